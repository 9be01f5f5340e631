//! GLSL ES declarations printed from naga's IR: the structs, constants, textures and functions
//! of a validated module (every one, or what an entry point reaches, less what a [`Choice`]
//! leaves out), for an include to paste into a user's shader or a hand-written `main` to call.
//!
//! naga's own GLSL writer writes whole shaders only (a `#version`, default precision, an entry
//! point it requires) and keeps its names to itself, so the declarations would have to be cut
//! out of its text. This printer walks the module instead, chooses the items there, and writes
//! each at the level it belongs to:
//! - **precision**: every declaration of a float or integer type says `highp`, so the include
//!   compiles under any default precision the user's preamble sets (or none) and never changes
//!   those defaults. It matters for the integers too: GLSL ES lets a fragment shader's default
//!   `int` be `mediump`, as narrow as 16 bits, and the packing needs all 32;
//! - **names**: naga's `Namer` with the words naga's writer reserves (`keywords.rs`), so
//!   every item has the name naga's writer gives it in a whole shader (the renderer's and the
//!   user's shaders, translated by that writer, call them by it); [`Printed::names`] hands
//!   them to the hand-written parts of the include;
//! - **builtins from 3.10**: a function [`Choice::from_310`] names is written twice, under
//!   `#if __VERSION__ >= 310` as one call of the builtin GLSL ES 3.10 added for it, and after
//!   `#else` as translated.
//!
//! The form of each statement and expression is naga's writer's for GLSL ES 3.00 (same
//! parentheses, the same temporaries `_eN` for values used twice or returned by calls, the
//! same vector comparisons and selects), so the text reads as naga's translations elsewhere in
//! the project do. It prints what the generated WGSL uses; anything else is an error naming the
//! construct, never a guess.

use std::collections::{HashMap, HashSet};

use naga::proc::{CaseInsensitiveKeywordSet, KeywordSet, NameKey, Namer};
use naga::valid::{FunctionInfo, ModuleInfo};
use naga::{Block, Expression, Function, Handle, Module, Statement, TypeInner};

use crate::items::ItemKind;

/// One level of indentation.
const INDENT: &str = "    ";

/// The vector components by index.
const COMPONENTS: [char; 4] = ['x', 'y', 'z', 'w'];

/// A function printed with a GLSL ES 3.10 builtin where the version has it.
#[derive(Clone, Copy, Debug)]
pub struct FromVersion310<'a> {
    /// The function's WGSL name.
    pub function: &'a str,
    /// The builtin its one parameter is passed to (`packUnorm4x8`).
    pub builtin: &'a str,
}

/// Which items to print, and how.
#[derive(Clone, Copy, Debug, Default)]
pub struct Choice<'a> {
    /// Print what this entry point reaches (the functions it calls, directly or not, and the
    /// textures they sample), not the entry point itself; with none, every function.
    pub entry_point: Option<(naga::ShaderStage, &'a str)>,
    /// WGSL names of structs, constants and functions not to print: a shader's include
    /// declares them.
    pub leave_out: &'a [&'a str],
    /// Functions to wrap with a GLSL ES 3.10 builtin.
    pub from_310: &'a [FromVersion310<'a>],
    /// Whether textures declare their binding (`layout(binding = N)`: GLSL ES 3.10 and GLSL
    /// 4.50 have it, WebGL's GLSL ES 3.00 does not).
    pub binding_qualifiers: bool,
}

/// One printed declaration: its kind, its name in the WGSL, the name it was printed with and
/// its text.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Item {
    /// What it declares.
    pub kind: ItemKind,
    /// Its WGSL name; none for an item an include writes by hand.
    pub wgsl: Option<String>,
    /// Its GLSL name.
    pub glsl: String,
    /// Its declaration, as it stands in the printed text (a function wrapped for GLSL ES 3.10
    /// with its `#if`).
    pub text: String,
}

/// The printed declarations, what they are and the names they were given.
#[derive(Debug)]
pub struct Printed {
    /// Structs and constants, then the textures, then the functions, a blank line between.
    pub text: String,
    /// The items of the text, in its order.
    pub items: Vec<Item>,
    /// The GLSL name of every type, struct member, constant, function and parameter.
    pub names: naga::FastHashMap<NameKey, String>,
    /// For each texture printed, its binding in the WGSL.
    pub texture_bindings: Vec<(String, naga::ResourceBinding)>,
}

impl Printed {
    /// The GLSL name of the struct named `wgsl_name` in `module`, and of its members.
    pub fn struct_names(&self, module: &Module, wgsl_name: &str) -> Option<(String, Vec<String>)> {
        let (handle, ty) = module
            .types
            .iter()
            .find(|(_, ty)| ty.name.as_deref() == Some(wgsl_name))?;
        let TypeInner::Struct { ref members, .. } = ty.inner else {
            return None;
        };
        let members = (0..members.len() as u32)
            .map(|index| self.names[&NameKey::StructMember(handle, index)].clone())
            .collect();
        Some((self.names[&NameKey::Type(handle)].clone(), members))
    }
}

/// Prints the structs, named constants, textures and functions of `module` that `choice`
/// picks (entry points are not declarations and are left out).
pub fn print(module: &Module, info: &ModuleInfo, choice: &Choice) -> Result<Printed, String> {
    let mut names = naga::FastHashMap::default();
    let mut namer = Namer::default();
    // The arguments naga's GLSL writer passes: its reserved words and prefixes.
    namer.reset(
        module,
        &keywords::RESERVED_SET,
        KeywordSet::empty(),
        CaseInsensitiveKeywordSet::empty(),
        &["gl_", "_group", "_immediates_binding_"],
        &mut names,
    );
    let functions = chosen_functions(module, choice)?;
    let mut printer = Printer {
        module,
        info,
        names,
        namer,
        items: Vec::new(),
        texture_bindings: Vec::new(),
        leave_out: choice.leave_out,
    };
    printer.structs_and_constants()?;
    printer.textures(&functions, choice)?;
    for &handle in &functions {
        let function = &module.functions[handle];
        let wrap = choice
            .from_310
            .iter()
            .find(|wrap| function.name.as_deref() == Some(wrap.function));
        printer.function(handle, function, wrap)?;
    }
    Ok(Printed {
        text: text_of(&printer.items),
        items: printer.items,
        names: printer.names,
        texture_bindings: printer.texture_bindings,
    })
}

/// The printed text of `items`: the structs and constants together, then each texture and
/// function, a blank line between.
fn text_of(items: &[Item]) -> String {
    let (declarations, others): (Vec<&Item>, Vec<&Item>) = items
        .iter()
        .partition(|item| matches!(item.kind, ItemKind::Struct | ItemKind::Constant));
    let declarations: String = declarations.iter().map(|item| item.text.as_str()).collect();
    let blocks = (!declarations.is_empty()).then_some(declarations.as_str());
    blocks
        .into_iter()
        .chain(others.iter().map(|item| item.text.as_str()))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The functions `choice` picks, in the module's order (a callee before its callers).
fn chosen_functions(module: &Module, choice: &Choice) -> Result<Vec<Handle<Function>>, String> {
    let left_out = |function: &Function| {
        function
            .name
            .as_deref()
            .is_some_and(|name| choice.leave_out.contains(&name))
    };
    let Some((stage, name)) = choice.entry_point else {
        return Ok(module
            .functions
            .iter()
            .filter(|(_, function)| !left_out(function))
            .map(|(handle, _)| handle)
            .collect());
    };
    let entry = module
        .entry_points
        .iter()
        .find(|entry| entry.stage == stage && entry.name == name)
        .ok_or_else(|| format!("the WGSL has no {stage:?} entry point `{name}`"))?;
    let mut reached = HashSet::new();
    let mut pending = vec![&entry.function];
    while let Some(function) = pending.pop() {
        for callee in calls(&function.body) {
            if reached.insert(callee) {
                pending.push(&module.functions[callee]);
            }
        }
    }
    Ok(module
        .functions
        .iter()
        .filter(|(handle, function)| reached.contains(handle) && !left_out(function))
        .map(|(handle, _)| handle)
        .collect())
}

/// The functions `block` calls, at any depth of its statements.
fn calls(block: &Block) -> Vec<Handle<Function>> {
    let mut found = Vec::new();
    for statement in block.iter() {
        match *statement {
            Statement::Call { function, .. } => found.push(function),
            Statement::Block(ref inner) => found.extend(calls(inner)),
            Statement::If {
                ref accept,
                ref reject,
                ..
            } => {
                found.extend(calls(accept));
                found.extend(calls(reject));
            }
            Statement::Loop {
                ref body,
                ref continuing,
                ..
            } => {
                found.extend(calls(body));
                found.extend(calls(continuing));
            }
            Statement::Switch { ref cases, .. } => {
                for case in cases {
                    found.extend(calls(&case.body));
                }
            }
            _ => {}
        }
    }
    found
}

struct Printer<'m> {
    module: &'m Module,
    info: &'m ModuleInfo,
    names: naga::FastHashMap<NameKey, String>,
    namer: Namer,
    /// The items printed so far.
    items: Vec<Item>,
    /// The textures printed so far, and their bindings.
    texture_bindings: Vec<(String, naga::ResourceBinding)>,
    /// WGSL names not to print.
    leave_out: &'m [&'m str],
}

/// What one function's expressions print as.
struct FunctionContext<'f> {
    handle: Handle<Function>,
    function: &'f Function,
    info: &'f FunctionInfo,
    /// Expressions written once into a temporary, then named by it.
    baked: HashSet<Handle<Expression>>,
    /// The temporaries and `let`s written so far.
    named: HashMap<Handle<Expression>, String>,
}

impl FunctionContext<'_> {
    fn ty<'a>(&'a self, module: &'a Module, expression: Handle<Expression>) -> &'a TypeInner {
        self.info[expression].ty.inner_with(&module.types)
    }
}

mod declarations;
mod expressions;
mod keywords;

pub use keywords::GLSL_RESERVED;
mod statements;
#[cfg(test)]
mod tests;
