//! naga's diagnostics in the words of the shader: the spans it labels, and its messages with
//! the arena handles they print (`Call to [0]`, `the type [2]`) replaced by what the handles
//! stand for in the module (`Call to `helper``, `the type `f32``, an expression's source).

use std::ops::Range;

use naga::common::wgsl::TypeContext as _;
use naga::{Handle, Module};

/// A span of the validated source with what naga says of it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Label {
    /// Byte range in the validated source.
    pub span: Range<usize>,
    /// What naga says of the span, with its handles named.
    pub text: String,
}

/// The function whose expressions a validation error's handles index, if any.
pub fn function_of<'module>(
    module: &'module Module,
    error: &naga::valid::ValidationError,
) -> Option<&'module naga::Function> {
    match error {
        naga::valid::ValidationError::Function { handle, .. } => Some(&module.functions[*handle]),
        naga::valid::ValidationError::EntryPoint { stage, name, .. } => module
            .entry_points
            .iter()
            .find(|entry| entry.stage == *stage && entry.name == *name)
            .map(|entry| &entry.function),
        _ => None,
    }
}

/// What the handles in naga's text refer to: the module, the source it came from and the
/// function whose expressions are meant.
pub struct Handles<'a> {
    /// The module the handles index.
    pub module: &'a Module,
    /// The source the module was parsed from.
    pub source: &'a str,
    /// The function whose expressions and locals the handles index (none: the module's).
    pub function: Option<&'a naga::Function>,
}

impl Handles<'_> {
    /// `text` with every `[N]` handle replaced by a name in backquotes where the words before
    /// it say which arena it indexes; handles it cannot place are left as they are.
    pub fn describe(&self, text: &str) -> String {
        let mut out = String::with_capacity(text.len());
        let mut rest = text;
        while let Some(open) = rest.find('[') {
            let (before, from_bracket) = rest.split_at(open);
            out.push_str(before);
            let handle = from_bracket[1..]
                .find(']')
                .and_then(|close| Some((close, from_bracket[1..1 + close].parse::<usize>().ok()?)));
            // `Some([N])`, naga's optional handle, reads as the handle alone.
            let optional = out.ends_with("Some(")
                && handle.is_some_and(|(close, _)| from_bracket[close + 2..].starts_with(')'));
            let context = if optional {
                &out[..out.len() - "Some(".len()]
            } else {
                out.as_str()
            };
            match handle.and_then(|(close, index)| Some((close, self.name(context, index)?))) {
                Some((close, name)) => {
                    if optional {
                        out.truncate(out.len() - "Some(".len());
                    }
                    out.push_str(&name);
                    rest = &from_bracket[close + 2 + usize::from(optional)..];
                }
                None => {
                    out.push('[');
                    rest = &from_bracket[1..];
                }
            }
        }
        out.push_str(rest);
        tidy(&out)
    }

    /// The name of handle `index` of the arena that the end of `before` names.
    fn name(&self, before: &str, index: usize) -> Option<String> {
        let word = before
            .trim_end()
            .rsplit([' ', ':', '('])
            .next()
            .unwrap_or("")
            .to_ascii_lowercase();
        let named = |name: Option<&String>| name.map(|name| format!("`{name}`"));
        match word.as_str() {
            "function" | "to" => named(
                self.module
                    .functions
                    .iter()
                    .find(|(handle, _)| handle.index() == index)?
                    .1
                    .name
                    .as_ref(),
            ),
            // "are not met by [t]": a type's alignment.
            "type" | "by" => {
                let handle = self
                    .module
                    .types
                    .iter()
                    .find(|(handle, _)| handle.index() == index)?
                    .0;
                Some(format!("`{}`", self.module.to_ctx().type_to_string(handle)))
            }
            "globalvariable" | "global" | "variable" => named(
                self.module
                    .global_variables
                    .iter()
                    .find(|(handle, _)| handle.index() == index)?
                    .1
                    .name
                    .as_ref(),
            ),
            "localvariable" | "local" => named(
                self.function?
                    .local_variables
                    .iter()
                    .find(|(handle, _)| handle.index() == index)?
                    .1
                    .name
                    .as_ref(),
            ),
            "expression" | "value" | "pointer" | "argument" | "result" | "index" | "base" => {
                let expressions = match self.function {
                    Some(function) => &function.expressions,
                    None => &self.module.global_expressions,
                };
                let handle: Handle<naga::Expression> = expressions
                    .iter()
                    .find(|(handle, _)| handle.index() == index)?
                    .0;
                let text = self.source.get(expressions.get_span(handle).to_range()?)?;
                Some(format!("`{}`", shorten(text)))
            }
            _ => None,
        }
    }
}

/// An expression's source on one line, cut at 48 characters.
fn shorten(text: &str) -> String {
    let one_line = text.split_whitespace().collect::<Vec<_>>().join(" ");
    match one_line.char_indices().nth(48) {
        Some((cut, _)) => format!("{}...", &one_line[..cut]),
        None => one_line,
    }
}

/// naga's wording around replaced handles: `naga::ir::Expression `x`` reads `expression `x``,
/// and `Function `f` 'f'` reads `Function `f``.
fn tidy(text: &str) -> String {
    let mut text = text.to_string();
    for (from, to) in [
        ("naga::ir::Expression ", "expression "),
        ("naga::ir::Function ", "function "),
        ("naga::ir::Type ", "type "),
        ("naga::ir::GlobalVariable ", "global "),
        ("naga::ir::LocalVariable ", "local "),
        ("naga::ir::Constant ", "constant "),
    ] {
        text = text.replace(from, to);
    }
    // `Function [h] 'name' is invalid` names the function twice once the handle is named.
    if let Some(start) = text.find("` '") {
        let name_start = text[..start].rfind('`').map(|at| at + 1);
        if let Some(name_start) = name_start {
            let name = text[name_start..start].to_string();
            text = text.replacen(&format!("`{name}` '{name}'"), &format!("`{name}`"), 1);
        }
    }
    text
}
