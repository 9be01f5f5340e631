//! A function: its signature, its locals and its statements, with the temporaries naga's
//! writer would hold values in.

use std::collections::{HashMap, HashSet};
use std::fmt::Write;

use naga::proc::NameKey;
use naga::valid::FunctionInfo;
use naga::{Block, Expression, Function, Handle, Statement, TypeInner};

use crate::items::ItemKind;

use super::{FromVersion310, FunctionContext, Printer, INDENT};

impl Printer<'_> {
    pub(super) fn function(
        &mut self,
        handle: Handle<Function>,
        function: &Function,
        wrap: Option<&FromVersion310>,
    ) -> Result<(), String> {
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
            let _ = write!(body, "{INDENT}{} = ", self.declaration(local.ty, name)?);
            match local.init {
                Some(init) => self.expression(&mut body, init, &context)?,
                None => self.zero_value(&mut body, local.ty)?,
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
        self.record(ItemKind::Function, function.name.as_deref(), name, out);
        Ok(())
    }

    pub(super) fn block(
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

    pub(super) fn statement(
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
                self.arguments(out, arguments, context)?;
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
}

/// The expressions written into temporaries: those used at least twice, and loads (a load
/// read later could see a later store); never a pointer's access, which GLSL cannot hold.
pub(super) fn baked_expressions(
    function: &Function,
    info: &FunctionInfo,
) -> HashSet<Handle<Expression>> {
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
