//! GLSL ES declarations printed from naga's IR: the structs, constants and functions of a
//! validated module, for an include to paste into a user's shader.
//!
//! naga's own GLSL writer writes whole shaders only (a `#version`, default precision, an entry
//! point it requires) and keeps its names to itself, so an include would have to be cut out of
//! its text. This printer walks the module instead and writes what an include needs, at the
//! level each thing belongs to:
//! - **precision**: every declaration of a float or integer type says `highp`, so the include
//!   compiles under any default precision the user's preamble sets (or none) and never changes
//!   those defaults. It matters for the integers too: GLSL ES lets a fragment shader's default
//!   `int` be `mediump`, as narrow as 16 bits, and the packing needs all 32;
//! - **names**: naga's `Namer` with the words naga's writer reserves ([`super::keywords`]), so
//!   every item has the name naga's writer gives it in a whole shader (the renderer's and the
//!   user's shaders, translated by that writer, call them by it); [`Printed::names`] hands
//!   them to the hand-written parts of the include;
//! - **builtins from 3.10**: a function [`Printed`] is asked to wrap is written twice, under
//!   `#if __VERSION__ >= 310` as one call of the builtin GLSL ES 3.10 added for it, and after
//!   `#else` as translated.
//!
//! The form of each statement and expression is naga's writer's for GLSL ES 3.00 (same
//! parentheses, the same temporaries `_eN` for values used twice or returned by calls, the
//! same vector comparisons and selects), so the text reads as naga's translations elsewhere in
//! the project do. It prints what the generated WGSL uses; anything else is an error naming the
//! construct, never a guess.

use std::collections::{HashMap, HashSet};
use std::fmt::Write;

use naga::proc::{CaseInsensitiveKeywordSet, KeywordSet, NameKey, Namer};
use naga::valid::{FunctionInfo, ModuleInfo};
use naga::{
    ArraySize, BinaryOperator, Block, Expression, Function, Handle, Literal, MathFunction, Module,
    ScalarKind, Statement, Type, TypeInner,
};

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

/// What kind of declaration an item is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ItemKind {
    /// A struct type.
    Struct,
    /// A named constant.
    Constant,
    /// A texture a function samples (GLSL combines it with its sampler).
    Texture,
    /// A function.
    Function,
}

/// One printed declaration: its kind, its name in the WGSL and the name it was printed with.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Item {
    /// What it declares.
    pub kind: ItemKind,
    /// Its WGSL name.
    pub wgsl: String,
    /// Its GLSL name.
    pub glsl: String,
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
        &super::keywords::RESERVED_SET,
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
    let mut blocks = Vec::new();
    let declarations = printer.structs_and_constants()?;
    if !declarations.is_empty() {
        blocks.push(declarations);
    }
    blocks.extend(printer.textures(&functions, choice)?);
    for &handle in &functions {
        let function = &module.functions[handle];
        let wrap = choice
            .from_310
            .iter()
            .find(|wrap| function.name.as_deref() == Some(wrap.function));
        blocks.push(printer.function(handle, function, wrap)?);
    }
    Ok(Printed {
        text: blocks.join("\n"),
        items: printer.items,
        names: printer.names,
        texture_bindings: printer.texture_bindings,
    })
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

impl Printer<'_> {
    fn structs_and_constants(&mut self) -> Result<String, String> {
        let mut out = String::new();
        for (handle, ty) in self.module.types.iter() {
            let TypeInner::Struct { ref members, .. } = ty.inner else {
                continue;
            };
            let Some(name) =
                self.chosen(ItemKind::Struct, ty.name.as_deref(), NameKey::Type(handle))
            else {
                continue;
            };
            let _ = writeln!(out, "struct {name} {{");
            for (index, member) in members.iter().enumerate() {
                let name = &self.names[&NameKey::StructMember(handle, index as u32)];
                let _ = writeln!(out, "{INDENT}{};", self.declaration(member.ty, name)?);
            }
            out.push_str("};\n");
        }
        for (handle, constant) in self.module.constants.iter() {
            let Some(name) = constant.name.as_deref().and_then(|wgsl| {
                self.chosen(ItemKind::Constant, Some(wgsl), NameKey::Constant(handle))
            }) else {
                continue;
            };
            let mut init = String::new();
            self.const_expression(&mut init, constant.init)?;
            let _ = writeln!(
                out,
                "const {} = {init};",
                self.declaration(constant.ty, &name)?
            );
        }
        Ok(out)
    }

    /// The GLSL name of a struct or constant to print, recorded as an item; `None` for one
    /// the choice leaves out.
    fn chosen(&mut self, kind: ItemKind, wgsl: Option<&str>, key: NameKey) -> Option<String> {
        if wgsl.is_some_and(|wgsl| self.leave_out.contains(&wgsl)) {
            return None;
        }
        let glsl = self.names[&key].clone();
        self.items.push(Item {
            kind,
            wgsl: wgsl.unwrap_or_default().to_string(),
            glsl: glsl.clone(),
        });
        Some(glsl)
    }

    /// The textures `functions` sample, one declaration each: GLSL has no separate samplers,
    /// a sampler uniform is the texture and the sampler state together. Named as naga's
    /// writer names a resource (`_group_0_binding_5_fs`), which a host without binding
    /// qualifiers sets by name.
    fn textures(
        &mut self,
        functions: &[Handle<Function>],
        choice: &Choice,
    ) -> Result<Vec<String>, String> {
        let mut blocks = Vec::new();
        let suffix = match choice.entry_point {
            Some((naga::ShaderStage::Vertex, _)) => "vs",
            Some((naga::ShaderStage::Compute, _)) => "cs",
            _ => "fs",
        };
        for (handle, global) in self.module.global_variables.iter() {
            if !functions
                .iter()
                .any(|function| !self.info[*function][handle].is_empty())
            {
                continue;
            }
            let TypeInner::Image {
                dim: naga::ImageDimension::D2,
                arrayed: false,
                class: naga::ImageClass::Sampled { kind, multi: false },
            } = self.module.types[global.ty].inner
            else {
                if let TypeInner::Sampler { .. } = self.module.types[global.ty].inner {
                    continue;
                }
                return Err(format!(
                    "the GLSL printer declares 2D sampled textures only, not `{}`",
                    global.name.as_deref().unwrap_or("a global")
                ));
            };
            let binding = global.binding.ok_or("a texture without a binding")?;
            let name = format!(
                "_group_{}_binding_{}_{suffix}",
                binding.group, binding.binding
            );
            let prefix = value_type(&TypeInner::Vector {
                size: naga::VectorSize::Quad,
                scalar: naga::Scalar { kind, width: 4 },
            })?;
            let sampler = format!("{}sampler2D", prefix.trim_end_matches("vec4"));
            let layout = match choice.binding_qualifiers {
                true => format!("layout(binding = {}) ", binding.binding),
                false => String::new(),
            };
            blocks.push(format!("{layout}uniform highp {sampler} {name};\n"));
            self.names
                .insert(NameKey::GlobalVariable(handle), name.clone());
            self.items.push(Item {
                kind: ItemKind::Texture,
                wgsl: global.name.clone().unwrap_or_default(),
                glsl: name.clone(),
            });
            self.texture_bindings.push((name, binding));
        }
        Ok(blocks)
    }

    /// `highp T name[N]`: a type and a name as a declaration writes them.
    fn declaration(&self, ty: Handle<Type>, name: &str) -> Result<String, String> {
        Ok(format!(
            "{}{} {name}{}",
            self.precision(&self.module.types[ty].inner),
            self.type_name(ty)?,
            self.array_size(ty)
        ))
    }

    /// `highp ` for a type a precision qualifier applies to (float and integer scalars,
    /// vectors and matrices, and arrays of them), else nothing.
    fn precision(&self, inner: &TypeInner) -> &'static str {
        match *inner {
            TypeInner::Scalar(scalar)
            | TypeInner::Vector { scalar, .. }
            | TypeInner::Matrix { scalar, .. }
                if scalar.kind != ScalarKind::Bool =>
            {
                "highp "
            }
            TypeInner::Array { base, .. } => self.precision(&self.module.types[base].inner),
            _ => "",
        }
    }

    /// A type's name without its array sizes, which GLSL writes after the declared name.
    fn type_name(&self, ty: Handle<Type>) -> Result<String, String> {
        match self.module.types[ty].inner {
            TypeInner::Struct { .. } => Ok(self.names[&NameKey::Type(ty)].clone()),
            TypeInner::Array { base, .. } | TypeInner::Pointer { base, .. } => self.type_name(base),
            ref inner => value_type(inner),
        }
    }

    /// `[N]` for each array level of `ty`, outermost first; nothing for other types.
    fn array_size(&self, ty: Handle<Type>) -> String {
        let mut out = String::new();
        let mut ty = ty;
        while let TypeInner::Array { base, size, .. } = self.module.types[ty].inner {
            match size {
                ArraySize::Constant(count) => {
                    let _ = write!(out, "[{count}]");
                }
                ArraySize::Pending(_) | ArraySize::Dynamic => out.push_str("[]"),
            }
            ty = base;
        }
        out
    }

    fn function(
        &mut self,
        handle: Handle<Function>,
        function: &Function,
        wrap: Option<&FromVersion310>,
    ) -> Result<String, String> {
        let module_info = self.info;
        let info = &module_info[handle];
        let mut context = FunctionContext {
            handle,
            function,
            info,
            baked: baked_expressions(function, info),
            named: HashMap::new(),
        };
        let name = self.names[&NameKey::Function(handle)].clone();
        self.items.push(Item {
            kind: ItemKind::Function,
            wgsl: function.name.clone().unwrap_or_default(),
            glsl: name.clone(),
        });
        let result = match function.result {
            Some(ref result) => format!(
                "{}{}{}",
                self.precision(&self.module.types[result.ty].inner),
                self.type_name(result.ty)?,
                self.array_size(result.ty)
            ),
            None => "void".to_string(),
        };
        let mut parameters = Vec::new();
        for (index, argument) in function.arguments.iter().enumerate() {
            let name = &self.names[&NameKey::FunctionArgument(handle, index as u32)];
            parameters.push(match self.module.types[argument.ty].inner {
                TypeInner::Pointer { base, .. } => {
                    format!("inout {}", self.declaration(base, name)?)
                }
                _ => self.declaration(argument.ty, name)?,
            });
        }
        let header = format!("{result} {name}({}) {{", parameters.join(", "));
        let mut body = String::new();
        for (local_handle, local) in function.local_variables.iter() {
            let name = &self.names[&NameKey::FunctionLocal(handle, local_handle)];
            let _ = write!(body, "{INDENT}{}", self.declaration(local.ty, name)?);
            match local.init {
                Some(init) => {
                    body.push_str(" = ");
                    self.expression(&mut body, init, &context)?;
                }
                None => {
                    body.push_str(" = ");
                    self.zero_value(&mut body, local.ty)?;
                }
            }
            body.push_str(";\n");
        }
        self.block(&mut body, &function.body, &mut context, 1)?;

        let mut out = String::new();
        if let Some(wrap) = wrap {
            let [_] = function.arguments[..] else {
                return Err(format!(
                    "`{name}` takes {} parameters, and `{}` one",
                    function.arguments.len(),
                    wrap.builtin
                ));
            };
            let parameter = &self.names[&NameKey::FunctionArgument(handle, 0)];
            let _ = writeln!(out, "#if __VERSION__ >= 310");
            let _ = writeln!(out, "{header}");
            let _ = writeln!(out, "{INDENT}return {}({parameter});", wrap.builtin);
            let _ = writeln!(out, "}}");
            let _ = writeln!(out, "#else");
        }
        let _ = writeln!(out, "{header}");
        out.push_str(&body);
        out.push_str("}\n");
        if wrap.is_some() {
            out.push_str("#endif\n");
        }
        Ok(out)
    }

    fn block(
        &mut self,
        out: &mut String,
        block: &Block,
        context: &mut FunctionContext,
        level: usize,
    ) -> Result<(), String> {
        for statement in block.iter() {
            self.statement(out, statement, context, level)?;
        }
        Ok(())
    }

    fn statement(
        &mut self,
        out: &mut String,
        statement: &Statement,
        context: &mut FunctionContext,
        level: usize,
    ) -> Result<(), String> {
        let indent = INDENT.repeat(level);
        match *statement {
            // An expression is evaluated where it is emitted: one used more than once, a call's
            // result or a `let` is written into its own temporary there.
            Statement::Emit(ref range) => {
                for handle in range.clone() {
                    if context.ty(self.module, handle).pointer_space().is_some() {
                        continue;
                    }
                    let name = if let Some(name) = context.function.named_expressions.get(&handle) {
                        self.namer.call(name)
                    } else if context.baked.contains(&handle) {
                        format!("_e{}", handle.index())
                    } else {
                        continue;
                    };
                    let mut value = String::new();
                    self.expression(&mut value, handle, context)?;
                    let declared = self.value_declaration(context, handle, &name)?;
                    let _ = writeln!(out, "{indent}{declared} = {value};");
                    context.named.insert(handle, name);
                }
            }
            Statement::Block(ref block) => {
                let _ = writeln!(out, "{indent}{{");
                self.block(out, block, context, level + 1)?;
                let _ = writeln!(out, "{indent}}}");
            }
            Statement::If {
                condition,
                ref accept,
                ref reject,
            } => {
                let _ = write!(out, "{indent}if (");
                self.expression(out, condition, context)?;
                out.push_str(") {\n");
                self.block(out, accept, context, level + 1)?;
                if !reject.is_empty() {
                    let _ = writeln!(out, "{indent}}} else {{");
                    self.block(out, reject, context, level + 1)?;
                }
                let _ = writeln!(out, "{indent}}}");
            }
            // A loop with a continuing block runs it at the top of every iteration but the
            // first, behind a flag.
            Statement::Loop {
                ref body,
                ref continuing,
                break_if,
            } => {
                if !continuing.is_empty() || break_if.is_some() {
                    let gate = self.namer.call("loop_init");
                    let inner = INDENT.repeat(level + 1);
                    let _ = writeln!(out, "{indent}bool {gate} = true;");
                    let _ = writeln!(out, "{indent}while(true) {{");
                    let _ = writeln!(out, "{inner}if (!{gate}) {{");
                    self.block(out, continuing, context, level + 2)?;
                    if let Some(condition) = break_if {
                        let _ = write!(out, "{inner}{INDENT}if (");
                        self.expression(out, condition, context)?;
                        let _ = writeln!(
                            out,
                            ") {{\n{inner}{INDENT}{INDENT}break;\n{inner}{INDENT}}}"
                        );
                    }
                    let _ = writeln!(out, "{inner}}}");
                    let _ = writeln!(out, "{inner}{gate} = false;");
                } else {
                    let _ = writeln!(out, "{indent}while(true) {{");
                }
                self.block(out, body, context, level + 1)?;
                let _ = writeln!(out, "{indent}}}");
            }
            Statement::Break => {
                let _ = writeln!(out, "{indent}break;");
            }
            Statement::Continue => {
                let _ = writeln!(out, "{indent}continue;");
            }
            Statement::Return { value } => {
                let _ = write!(out, "{indent}return");
                if let Some(value) = value {
                    out.push(' ');
                    self.expression(out, value, context)?;
                }
                out.push_str(";\n");
            }
            Statement::Store { pointer, value } => {
                out.push_str(&indent);
                self.expression(out, pointer, context)?;
                out.push_str(" = ");
                self.expression(out, value, context)?;
                out.push_str(";\n");
            }
            Statement::Call {
                function,
                ref arguments,
                result,
            } => {
                out.push_str(&indent);
                if let Some(result) = result {
                    let name = format!("_e{}", result.index());
                    let ty = self.module.functions[function]
                        .result
                        .as_ref()
                        .map(|result| result.ty)
                        .ok_or("a call's result names a function that returns nothing")?;
                    let _ = write!(out, "{} = ", self.declaration(ty, &name)?);
                    context.named.insert(result, name);
                }
                let _ = write!(out, "{}(", self.names[&NameKey::Function(function)]);
                for (index, argument) in arguments.iter().enumerate() {
                    if index > 0 {
                        out.push_str(", ");
                    }
                    self.expression(out, *argument, context)?;
                }
                out.push_str(");\n");
            }
            ref other => {
                return Err(format!(
                    "the GLSL printer has no form for the statement {other:?} in `{}`",
                    self.names[&NameKey::Function(context.handle)]
                ))
            }
        }
        Ok(())
    }

    /// The declaration of a temporary holding expression `handle`.
    fn value_declaration(
        &self,
        context: &FunctionContext,
        handle: Handle<Expression>,
        name: &str,
    ) -> Result<String, String> {
        match context.info[handle].ty {
            naga::proc::TypeResolution::Handle(ty) => self.declaration(ty, name),
            naga::proc::TypeResolution::Value(ref inner) => Ok(format!(
                "{}{} {name}",
                self.precision(inner),
                value_type(inner)?
            )),
        }
    }

    fn zero_value(&self, out: &mut String, ty: Handle<Type>) -> Result<(), String> {
        match self.module.types[ty].inner {
            TypeInner::Scalar(scalar) => out.push_str(zero_scalar(scalar.kind)?),
            ref inner @ (TypeInner::Vector { scalar, .. } | TypeInner::Matrix { scalar, .. }) => {
                let _ = write!(out, "{}({})", value_type(inner)?, zero_scalar(scalar.kind)?);
            }
            TypeInner::Array {
                base,
                size: ArraySize::Constant(count),
                ..
            } => {
                let _ = write!(out, "{}{}(", self.type_name(base)?, self.array_size(ty));
                for index in 0..count.get() {
                    if index > 0 {
                        out.push_str(", ");
                    }
                    self.zero_value(out, base)?;
                }
                out.push(')');
            }
            TypeInner::Struct { ref members, .. } => {
                let _ = write!(out, "{}(", self.names[&NameKey::Type(ty)]);
                for (index, member) in members.iter().enumerate() {
                    if index > 0 {
                        out.push_str(", ");
                    }
                    self.zero_value(out, member.ty)?;
                }
                out.push(')');
            }
            ref other => return Err(format!("the GLSL printer has no zero value of {other:?}")),
        }
        Ok(())
    }

    /// A constant's initializer, in the module's global expressions.
    fn const_expression(&self, out: &mut String, handle: Handle<Expression>) -> Result<(), String> {
        match self.module.global_expressions[handle] {
            Expression::Literal(literal) => out.push_str(&literal_text(literal)?),
            Expression::Constant(constant) => self.constant(out, constant)?,
            Expression::ZeroValue(ty) => self.zero_value(out, ty)?,
            Expression::Compose { ty, ref components } => {
                let _ = write!(out, "{}{}(", self.type_name(ty)?, self.array_size(ty));
                for (index, component) in components.iter().enumerate() {
                    if index > 0 {
                        out.push_str(", ");
                    }
                    self.const_expression(out, *component)?;
                }
                out.push(')');
            }
            Expression::Splat { value, .. } => {
                let inner = self.info[handle].inner_with(&self.module.types);
                let _ = write!(out, "{}(", value_type(inner)?);
                self.const_expression(out, value)?;
                out.push(')');
            }
            ref other => {
                return Err(format!(
                    "the GLSL printer has no form for the constant expression {other:?}"
                ))
            }
        }
        Ok(())
    }

    /// A named constant by its name, an unnamed one by its value.
    fn constant(&self, out: &mut String, handle: Handle<naga::Constant>) -> Result<(), String> {
        let constant = &self.module.constants[handle];
        match constant.name {
            Some(_) => out.push_str(&self.names[&NameKey::Constant(handle)]),
            None => self.const_expression(out, constant.init)?,
        }
        Ok(())
    }

    fn expression(
        &self,
        out: &mut String,
        handle: Handle<Expression>,
        context: &FunctionContext,
    ) -> Result<(), String> {
        if let Some(name) = context.named.get(&handle) {
            out.push_str(name);
            return Ok(());
        }
        let module = self.module;
        match context.function.expressions[handle] {
            Expression::Literal(literal) => out.push_str(&literal_text(literal)?),
            Expression::Constant(constant) => self.constant(out, constant)?,
            Expression::ZeroValue(ty) => self.zero_value(out, ty)?,
            Expression::Compose { ty, ref components } => {
                let _ = write!(out, "{}{}(", self.type_name(ty)?, self.array_size(ty));
                self.arguments(out, components, context)?;
                out.push(')');
            }
            Expression::Splat { value, .. } => {
                let _ = write!(out, "{}(", value_type(context.ty(module, handle))?);
                self.expression(out, value, context)?;
                out.push(')');
            }
            Expression::Access { base, index } => {
                self.expression(out, base, context)?;
                out.push('[');
                self.expression(out, index, context)?;
                out.push(']');
            }
            Expression::AccessIndex { base, index } => {
                self.expression(out, base, context)?;
                let resolution = &context.info[base].ty;
                let (inner, ty) = match *resolution.inner_with(&module.types) {
                    TypeInner::Pointer { base, .. } => (&module.types[base].inner, Some(base)),
                    ref inner => (inner, resolution.handle()),
                };
                match *inner {
                    TypeInner::Vector { .. } => {
                        let _ = write!(out, ".{}", COMPONENTS[index as usize]);
                    }
                    TypeInner::Matrix { .. } | TypeInner::Array { .. } => {
                        let _ = write!(out, "[{index}]");
                    }
                    TypeInner::Struct { .. } => {
                        let ty = ty.ok_or("a struct member of a struct without a type")?;
                        let _ = write!(out, ".{}", self.names[&NameKey::StructMember(ty, index)]);
                    }
                    ref other => return Err(format!("the GLSL printer cannot index {other:?}")),
                }
            }
            Expression::Swizzle {
                size,
                vector,
                pattern,
            } => {
                self.expression(out, vector, context)?;
                out.push('.');
                for component in &pattern[..size as usize] {
                    out.push(COMPONENTS[*component as usize]);
                }
            }
            Expression::FunctionArgument(index) => {
                out.push_str(&self.names[&NameKey::FunctionArgument(context.handle, index)]);
            }
            Expression::GlobalVariable(global) => {
                out.push_str(&self.names[&NameKey::GlobalVariable(global)]);
            }
            Expression::ImageSample {
                image,
                coordinate,
                level,
                gather: None,
                array_index: None,
                offset: None,
                depth_ref: None,
                ..
            } => self.sample(out, image, coordinate, level, context)?,
            Expression::LocalVariable(local) => {
                out.push_str(&self.names[&NameKey::FunctionLocal(context.handle, local)]);
            }
            // GLSL has no pointers: a load reads the variable it points at.
            Expression::Load { pointer } => self.expression(out, pointer, context)?,
            Expression::Unary { op, expr } => {
                let operator = match op {
                    naga::UnaryOperator::Negate => "-",
                    naga::UnaryOperator::LogicalNot => match *context.ty(module, expr) {
                        TypeInner::Vector { .. } => "not",
                        _ => "!",
                    },
                    naga::UnaryOperator::BitwiseNot => "~",
                };
                let _ = write!(out, "{operator}(");
                self.expression(out, expr, context)?;
                out.push(')');
            }
            Expression::Binary { op, left, right } => {
                self.binary(out, op, left, right, context)?;
            }
            // A vector select is `mix` with a boolean vector, which picks its second argument
            // where the condition holds.
            Expression::Select {
                condition,
                accept,
                reject,
            } => {
                if let TypeInner::Vector { .. } = *context.ty(module, condition) {
                    out.push_str("mix(");
                    self.expression(out, reject, context)?;
                    out.push_str(", ");
                    self.expression(out, accept, context)?;
                    out.push_str(", ");
                    self.expression(out, condition, context)?;
                } else {
                    out.push('(');
                    self.expression(out, condition, context)?;
                    out.push_str(" ? ");
                    self.expression(out, accept, context)?;
                    out.push_str(" : ");
                    self.expression(out, reject, context)?;
                }
                out.push(')');
            }
            Expression::Relational { fun, argument } => {
                let name = match fun {
                    naga::RelationalFunction::IsInf => "isinf",
                    naga::RelationalFunction::IsNan => "isnan",
                    naga::RelationalFunction::All => "all",
                    naga::RelationalFunction::Any => "any",
                };
                let _ = write!(out, "{name}(");
                self.expression(out, argument, context)?;
                out.push(')');
            }
            Expression::Math {
                fun,
                arg,
                arg1,
                arg2,
                arg3,
            } => {
                let arguments: Vec<_> = [Some(arg), arg1, arg2, arg3]
                    .into_iter()
                    .flatten()
                    .collect();
                self.math(out, fun, &arguments, context)?;
            }
            Expression::As {
                expr,
                kind,
                convert,
            } => self.cast(out, expr, kind, convert, context)?,
            ref other => {
                return Err(format!(
                    "the GLSL printer has no form for the expression {other:?} in `{}`",
                    self.names[&NameKey::Function(context.handle)]
                ))
            }
        }
        Ok(())
    }

    /// A 2D texture's sample: `texture` at the level the derivatives choose, `textureLod`
    /// at one given.
    fn sample(
        &self,
        out: &mut String,
        image: Handle<Expression>,
        coordinate: Handle<Expression>,
        level: naga::SampleLevel,
        context: &FunctionContext,
    ) -> Result<(), String> {
        let function = match level {
            naga::SampleLevel::Auto | naga::SampleLevel::Bias(_) => "texture",
            naga::SampleLevel::Zero | naga::SampleLevel::Exact(_) => "textureLod",
            naga::SampleLevel::Gradient { .. } => {
                return Err("the GLSL printer has no form for a sample by gradients".into())
            }
        };
        let _ = write!(out, "{function}(");
        self.expression(out, image, context)?;
        out.push_str(", vec2(");
        self.expression(out, coordinate, context)?;
        out.push(')');
        match level {
            naga::SampleLevel::Zero => out.push_str(", 0.0"),
            naga::SampleLevel::Exact(value) | naga::SampleLevel::Bias(value) => {
                out.push_str(", ");
                self.expression(out, value, context)?;
            }
            _ => {}
        }
        out.push(')');
        Ok(())
    }

    fn arguments(
        &self,
        out: &mut String,
        arguments: &[Handle<Expression>],
        context: &FunctionContext,
    ) -> Result<(), String> {
        for (index, argument) in arguments.iter().enumerate() {
            if index > 0 {
                out.push_str(", ");
            }
            self.expression(out, *argument, context)?;
        }
        Ok(())
    }

    /// A binary operation in parentheses, or the function GLSL has for it: vectors compare
    /// through `lessThan` and its kin, and a float remainder is WGSL's truncated one.
    fn binary(
        &self,
        out: &mut String,
        op: BinaryOperator,
        left: Handle<Expression>,
        right: Handle<Expression>,
        context: &FunctionContext,
    ) -> Result<(), String> {
        use BinaryOperator as Op;
        let left_type = context.ty(self.module, left);
        let right_type = context.ty(self.module, right);
        let vectors = matches!(left_type, TypeInner::Vector { .. })
            && matches!(right_type, TypeInner::Vector { .. });
        let kind = left_type.scalar_kind();
        let comparison = match op {
            Op::Less => Some("lessThan"),
            Op::LessEqual => Some("lessThanEqual"),
            Op::Greater => Some("greaterThan"),
            Op::GreaterEqual => Some("greaterThanEqual"),
            Op::Equal => Some("equal"),
            Op::NotEqual => Some("notEqual"),
            _ => None,
        };
        let floats =
            kind == Some(ScalarKind::Float) || right_type.scalar_kind() == Some(ScalarKind::Float);
        match (vectors, comparison) {
            (true, Some(function)) => {
                let _ = write!(out, "{function}(");
                self.expression(out, left, context)?;
                out.push_str(", ");
                self.expression(out, right, context)?;
                out.push(')');
            }
            _ if op == Op::Modulo && floats => {
                // `e1 - e2 * trunc(e1 / e2)`
                out.push('(');
                self.expression(out, left, context)?;
                out.push_str(" - ");
                self.expression(out, right, context)?;
                out.push_str(" * trunc(");
                self.expression(out, left, context)?;
                out.push_str(" / ");
                self.expression(out, right, context)?;
                out.push_str("))");
            }
            _ if vectors
                && kind == Some(ScalarKind::Bool)
                && matches!(op, Op::And | Op::InclusiveOr) =>
            {
                return Err(
                    "the GLSL printer has no form for a logical operation on boolean vectors"
                        .into(),
                );
            }
            _ => {
                let op = match (op, kind) {
                    (Op::And, Some(ScalarKind::Bool)) => Op::LogicalAnd,
                    (Op::InclusiveOr, Some(ScalarKind::Bool)) => Op::LogicalOr,
                    (op, _) => op,
                };
                out.push('(');
                self.expression(out, left, context)?;
                let _ = write!(out, " {} ", operator_text(op));
                self.expression(out, right, context)?;
                out.push(')');
            }
        }
        Ok(())
    }

    /// A WGSL builtin as the GLSL ES 3.00 function of the same meaning.
    fn math(
        &self,
        out: &mut String,
        fun: MathFunction,
        arguments: &[Handle<Expression>],
        context: &FunctionContext,
    ) -> Result<(), String> {
        use MathFunction as Mf;
        let kind = context.ty(self.module, arguments[0]).scalar_kind();
        let name = match fun {
            Mf::Abs if kind == Some(ScalarKind::Float) || kind == Some(ScalarKind::Sint) => "abs",
            Mf::Min => "min",
            Mf::Max => "max",
            // GLSL's clamp is undefined where the bounds cross, and may then be a median of
            // three: WGSL's integer clamp must be min and max.
            Mf::Clamp if kind != Some(ScalarKind::Float) => {
                out.push_str("min(max(");
                self.expression(out, arguments[0], context)?;
                out.push_str(", ");
                self.expression(out, arguments[1], context)?;
                out.push_str("), ");
                self.expression(out, arguments[2], context)?;
                out.push(')');
                return Ok(());
            }
            Mf::Clamp => "clamp",
            Mf::Saturate => {
                out.push_str("clamp(");
                self.expression(out, arguments[0], context)?;
                match *context.ty(self.module, arguments[0]) {
                    TypeInner::Vector { size, .. } => {
                        let _ = write!(out, ", vec{0}(0.0), vec{0}(1.0))", size as u8);
                    }
                    _ => out.push_str(", 0.0, 1.0)"),
                }
                return Ok(());
            }
            Mf::Cos => "cos",
            Mf::Sin => "sin",
            Mf::Tan => "tan",
            Mf::Acos => "acos",
            Mf::Asin => "asin",
            Mf::Atan => "atan",
            Mf::Atan2 => "atan",
            Mf::Ceil => "ceil",
            Mf::Floor => "floor",
            Mf::Round => "roundEven",
            Mf::Fract => "fract",
            Mf::Trunc => "trunc",
            Mf::Exp => "exp",
            Mf::Exp2 => "exp2",
            Mf::Log => "log",
            Mf::Log2 => "log2",
            Mf::Pow => "pow",
            Mf::Dot if kind == Some(ScalarKind::Float) => "dot",
            Mf::Cross => "cross",
            Mf::Distance => "distance",
            Mf::Length => "length",
            Mf::Normalize => "normalize",
            Mf::FaceForward => "faceforward",
            Mf::Reflect => "reflect",
            Mf::Refract => "refract",
            Mf::Sign => "sign",
            // GLSL ES 3.00 has no `fma`: a product and a sum.
            Mf::Fma => {
                out.push('(');
                self.expression(out, arguments[0], context)?;
                out.push_str(" * ");
                self.expression(out, arguments[1], context)?;
                out.push_str(" + ");
                self.expression(out, arguments[2], context)?;
                out.push(')');
                return Ok(());
            }
            Mf::Mix => "mix",
            Mf::Step => "step",
            Mf::SmoothStep => "smoothstep",
            Mf::Sqrt => "sqrt",
            Mf::InverseSqrt => "inversesqrt",
            Mf::Pack2x16float => "packHalf2x16",
            Mf::Unpack2x16float => "unpackHalf2x16",
            Mf::Pack2x16unorm => "packUnorm2x16",
            Mf::Unpack2x16unorm => "unpackUnorm2x16",
            Mf::Pack2x16snorm => "packSnorm2x16",
            Mf::Unpack2x16snorm => "unpackSnorm2x16",
            other => {
                return Err(format!(
                    "the GLSL printer has no GLSL ES 3.00 form for `{other:?}` in `{}`",
                    self.names[&NameKey::Function(context.handle)]
                ))
            }
        };
        let _ = write!(out, "{name}(");
        self.arguments(out, arguments, context)?;
        out.push(')');
        Ok(())
    }

    /// A conversion is a constructor of the target type; a bitcast is GLSL's function for it
    /// (`floatBitsToUint` and its kin), or a constructor between the integer kinds.
    fn cast(
        &self,
        out: &mut String,
        expr: Handle<Expression>,
        kind: ScalarKind,
        convert: Option<u8>,
        context: &FunctionContext,
    ) -> Result<(), String> {
        use ScalarKind as Sk;
        let inner = context.ty(self.module, expr);
        let source = inner
            .scalar_kind()
            .ok_or("a cast of a value with no scalar kind")?;
        let width = convert.unwrap_or(4);
        let target = |kind| -> Result<String, String> {
            let scalar = naga::Scalar { kind, width };
            match *inner {
                TypeInner::Vector { size, .. } => value_type(&TypeInner::Vector { size, scalar }),
                TypeInner::Matrix { columns, rows, .. } => value_type(&TypeInner::Matrix {
                    columns,
                    rows,
                    scalar,
                }),
                _ => value_type(&TypeInner::Scalar(scalar)),
            }
        };
        let function = match convert {
            Some(_) => target(kind)?,
            None => match (source, kind) {
                (a, b) if a == b => return self.expression(out, expr, context),
                (Sk::Float, Sk::Sint) => "floatBitsToInt".into(),
                (Sk::Float, Sk::Uint) => "floatBitsToUint".into(),
                (Sk::Sint, Sk::Float) => "intBitsToFloat".into(),
                (Sk::Uint, Sk::Float) => "uintBitsToFloat".into(),
                _ => target(kind)?,
            },
        };
        let _ = write!(out, "{function}(");
        self.expression(out, expr, context)?;
        out.push(')');
        Ok(())
    }
}

/// The expressions written into temporaries: those used at least twice, and loads (a load
/// read later could see a later store); never a pointer's access, which GLSL cannot hold.
fn baked_expressions(function: &Function, info: &FunctionInfo) -> HashSet<Handle<Expression>> {
    function
        .expressions
        .iter()
        .filter(|(handle, expression)| {
            let uses = info[*handle].ref_count;
            match expression {
                Expression::Access { .. } | Expression::AccessIndex { .. } => false,
                Expression::Load { .. }
                | Expression::ImageSample { .. }
                | Expression::ImageLoad { .. }
                | Expression::Derivative { .. } => uses >= 1,
                _ => uses >= 2,
            }
        })
        .map(|(handle, _)| handle)
        .collect()
}

/// A scalar, vector or matrix type's GLSL name.
fn value_type(inner: &TypeInner) -> Result<String, String> {
    let prefix = |scalar: naga::Scalar| match (scalar.kind, scalar.width) {
        (ScalarKind::Float, 4) => Ok(("", "float")),
        (ScalarKind::Sint, 4) => Ok(("i", "int")),
        (ScalarKind::Uint, 4) => Ok(("u", "uint")),
        (ScalarKind::Bool, _) => Ok(("b", "bool")),
        _ => Err(format!("GLSL ES has no {scalar:?}")),
    };
    match *inner {
        TypeInner::Scalar(scalar) => Ok(prefix(scalar)?.1.to_string()),
        TypeInner::Vector { size, scalar } => Ok(format!("{}vec{}", prefix(scalar)?.0, size as u8)),
        TypeInner::Matrix {
            columns,
            rows,
            scalar,
        } => Ok(format!(
            "{}mat{}x{}",
            prefix(scalar)?.0,
            columns as u8,
            rows as u8
        )),
        ref other => Err(format!(
            "the GLSL printer has no form for the type {other:?}"
        )),
    }
}

fn zero_scalar(kind: ScalarKind) -> Result<&'static str, String> {
    match kind {
        ScalarKind::Bool => Ok("false"),
        ScalarKind::Uint => Ok("0u"),
        ScalarKind::Float => Ok("0.0"),
        ScalarKind::Sint => Ok("0"),
        ScalarKind::AbstractInt | ScalarKind::AbstractFloat => {
            Err("an abstract type in a validated module".into())
        }
    }
}

/// A literal as GLSL writes it: a float always with its point (Rust's `Debug`), an unsigned
/// integer with its `u`.
fn literal_text(literal: Literal) -> Result<String, String> {
    match literal {
        Literal::F32(value) => Ok(format!("{value:?}")),
        Literal::U32(value) => Ok(format!("{value}u")),
        Literal::I32(value) => Ok(format!("{value}")),
        Literal::Bool(value) => Ok(format!("{value}")),
        other => Err(format!("GLSL ES has no literal {other:?}")),
    }
}

fn operator_text(op: BinaryOperator) -> &'static str {
    use BinaryOperator as Op;
    match op {
        Op::Add => "+",
        Op::Subtract => "-",
        Op::Multiply => "*",
        Op::Divide => "/",
        Op::Modulo => "%",
        Op::Equal => "==",
        Op::NotEqual => "!=",
        Op::Less => "<",
        Op::LessEqual => "<=",
        Op::Greater => ">",
        Op::GreaterEqual => ">=",
        Op::And => "&",
        Op::ExclusiveOr => "^",
        Op::InclusiveOr => "|",
        Op::LogicalAnd => "&&",
        Op::LogicalOr => "||",
        Op::ShiftLeft => "<<",
        Op::ShiftRight => ">>",
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::glsl::naga_glsl;

    fn printed(wgsl: &str, from_310: &[FromVersion310]) -> String {
        let (module, info) = naga_glsl::validate(wgsl, naga_glsl::GENERATED_CODE_CAPABILITIES)
            .unwrap_or_else(|error| panic!("{error}"));
        let choice = Choice {
            from_310,
            ..Choice::default()
        };
        print(&module, &info, &choice).unwrap().text
    }

    #[test]
    fn declarations_say_highp_and_values_used_twice_are_held() {
        let wgsl = "
struct Texel { colour: vec3<f32>, flags: u32, }
const WORDS: u32 = 2u;
fn brighter(c: vec3<f32>) -> vec3<f32> {
    let doubled = c * 2.0;
    return select(c, doubled, c < vec3(0.5));
}
fn pack(t: Texel) -> array<u32, 2> {
    let c = brighter(t.colour);
    let bits = bitcast<vec3<u32>>(c);
    return array<u32, 2>(bits.x ^ bits.y, t.flags % WORDS);
}
";
        let expected = "\
struct Texel {
    highp vec3 colour;
    highp uint flags;
};
const highp uint WORDS = 2u;

highp vec3 brighter(highp vec3 c) {
    highp vec3 doubled = (c * 2.0);
    return mix(c, doubled, lessThan(c, vec3(0.5)));
}

highp uint[2] pack(Texel t) {
    highp vec3 _e2 = brighter(t.colour);
    highp uvec3 bits = floatBitsToUint(_e2);
    return uint[2]((bits.x ^ bits.y), (t.flags % WORDS));
}
";
        assert_eq!(printed(wgsl, &[]), expected);
    }

    #[test]
    fn a_wrapped_function_calls_the_builtin_from_310_and_is_translated_before() {
        let wgsl = "
fn encode(c: vec4<f32>) -> u32 {
    let codes = vec4<u32>(round(clamp(c, vec4(0.0), vec4(1.0)) * 255.0));
    return codes.x | (codes.y << 8u) | (codes.z << 16u) | (codes.w << 24u);
}
";
        let wrap = FromVersion310 {
            function: "encode",
            builtin: "packUnorm4x8",
        };
        let expected = "\
#if __VERSION__ >= 310
highp uint encode(highp vec4 c) {
    return packUnorm4x8(c);
}
#else
highp uint encode(highp vec4 c) {
    highp uvec4 codes = uvec4(roundEven((clamp(c, vec4(0.0), vec4(1.0)) * 255.0)));
    return (((codes.x | (codes.y << 8u)) | (codes.z << 16u)) | (codes.w << 24u));
}
#endif
";
        assert_eq!(printed(wgsl, &[wrap]), expected);
    }

    #[test]
    fn an_entry_point_gets_what_it_reaches_less_what_is_left_out() {
        let wgsl = "
struct Texel { colour: vec3<f32>, }
@group(0) @binding(1) var lut: texture_2d<f32>;
@group(0) @binding(2) var lut_sampler: sampler;
@group(0) @binding(3) var unused: texture_2d<f32>;
fn from_include(t: Texel) -> vec3<f32> { return t.colour; }
fn looked_up(x: f32) -> f32 { return textureSampleLevel(lut, lut_sampler, vec2(x, 0.5), 0.0).x; }
fn lit(t: Texel) -> vec3<f32> { return from_include(t) * looked_up(t.colour.x); }
fn unreached() -> vec4<f32> { return textureSampleLevel(unused, lut_sampler, vec2(0.0), 0.0); }
@fragment
fn entry() -> @location(0) vec4<f32> { return vec4(lit(Texel(vec3(1.0))), 1.0); }
";
        let (module, info) =
            naga_glsl::validate(wgsl, naga_glsl::GENERATED_CODE_CAPABILITIES).unwrap();
        let choice = Choice {
            entry_point: Some((naga::ShaderStage::Fragment, "entry")),
            leave_out: &["Texel", "from_include"],
            from_310: &[],
            binding_qualifiers: true,
        };
        let printed = print(&module, &info, &choice).unwrap();
        let expected = "\
layout(binding = 1) uniform highp sampler2D _group_0_binding_1_fs;

highp float looked_up(highp float x) {
    highp vec4 _e6 = textureLod(_group_0_binding_1_fs, vec2(vec2(x, 0.5)), 0.0);
    return _e6.x;
}

highp vec3 lit(Texel t_1) {
    highp vec3 _e1 = from_include(t_1);
    highp float _e4 = looked_up(t_1.colour.x);
    return (_e1 * _e4);
}
";
        assert_eq!(printed.text, expected);
        let kinds: Vec<(ItemKind, &str)> = printed
            .items
            .iter()
            .map(|item| (item.kind, item.wgsl.as_str()))
            .collect();
        assert_eq!(
            kinds,
            [
                (ItemKind::Texture, "lut"),
                (ItemKind::Function, "looked_up"),
                (ItemKind::Function, "lit")
            ]
        );
        let webgl = Choice {
            binding_qualifiers: false,
            ..choice
        };
        let printed = print(&module, &info, &webgl).unwrap();
        assert!(printed
            .text
            .starts_with("uniform highp sampler2D _group_0_binding_1_fs;\n"));
    }

    /// GLSL ES 3.20's built-in functions (section 8), which neither keyword list of the test
    /// holds by construction, and names naga changes for other reasons.
    const BUILTINS_AND_ODD_NAMES: [&str; 64] = [
        "radians",
        "degrees",
        "sin",
        "cos",
        "tan",
        "asin",
        "acos",
        "atan",
        "pow",
        "exp",
        "log",
        "exp2",
        "log2",
        "sqrt",
        "inversesqrt",
        "abs",
        "sign",
        "floor",
        "trunc",
        "round",
        "roundEven",
        "ceil",
        "fract",
        "mod",
        "modf",
        "min",
        "max",
        "clamp",
        "mix",
        "step",
        "smoothstep",
        "isnan",
        "isinf",
        "floatBitsToUint",
        "uintBitsToFloat",
        "fma",
        "frexp",
        "ldexp",
        "packUnorm4x8",
        "unpackHalf2x16",
        "length",
        "distance",
        "dot",
        "cross",
        "normalize",
        "reflect",
        "refract",
        "transpose",
        "inverse",
        "lessThan",
        "equal",
        "any",
        "not",
        "bitfieldExtract",
        "findMSB",
        "texture",
        "textureLod",
        "texelFetch",
        "dFdx",
        "barrier",
        "main",
        "gl_thing",
        "a__b",
        "target0",
    ];

    /// naga's GLSL writer is the reference: the renderer's and the user's shaders, which it
    /// translates, call the includes' items by the names it gives. For every word either list
    /// reserves that WGSL allows as a name, a struct member so named is printed with the name
    /// naga's writer gives it.
    #[test]
    fn names_are_the_ones_nagas_writer_gives() {
        let mut words: Vec<&str> = super::super::keywords::RESERVED
            .iter()
            .chain(gbuffer_core::naming::GLSL_RESERVED)
            .copied()
            .chain(BUILTINS_AND_ODD_NAMES)
            .filter(|word| gbuffer_core::naming::check_identifier(word).is_ok())
            .collect();
        words.sort();
        words.dedup();
        let members: String = words
            .iter()
            .map(|word| format!("    {word}: f32,\n"))
            .collect();
        let wgsl = format!(
            "struct Probe {{\n{members}}}\n\
             @fragment\nfn probe_entry() -> @location(0) vec4<f32> {{\n    \
             var p: Probe;\n    return vec4<f32>(p.{});\n}}\n",
            words[0]
        );
        let (module, info) =
            naga_glsl::validate(&wgsl, naga_glsl::GENERATED_CODE_CAPABILITIES).unwrap();
        let options =
            naga_glsl::options_keeping_bindings(&module, naga::back::glsl::Version::new_gles(300));
        let (naga_text, _) = naga_glsl::write(
            (&module, &info),
            naga::ShaderStage::Fragment,
            "probe_entry",
            &options,
        )
        .unwrap();
        let ours = print(&module, &info, &Choice::default()).unwrap();
        let (_, names) = ours.struct_names(&module, "Probe").unwrap();
        // naga writes the struct first, a member a line: `    float name;`.
        let nagas: Vec<&str> = naga_text
            .lines()
            .skip_while(|line| !line.starts_with("struct Probe"))
            .skip(1)
            .take(words.len())
            .map(|line| {
                line.trim()
                    .trim_start_matches("float ")
                    .trim_end_matches(';')
            })
            .collect();
        assert!(words.len() > 300, "{} words", words.len());
        for ((word, ours), nagas) in words.iter().zip(&names).zip(&nagas) {
            assert_eq!(ours, nagas, "`{word}`");
        }
    }

    #[test]
    fn what_it_cannot_print_is_named() {
        let wgsl = "fn f(x: u32) -> u32 { return countLeadingZeros(x); }";
        let (module, info) =
            naga_glsl::validate(wgsl, naga_glsl::GENERATED_CODE_CAPABILITIES).unwrap();
        let error = print(&module, &info, &Choice::default()).unwrap_err();
        assert!(
            error.contains("CountLeadingZeros") && error.contains("`f`"),
            "{error}"
        );
    }
}
