//! Expressions as GLSL ES 3.00 writes them: fully parenthesised operations, the functions GLSL
//! has for vector comparisons and selects, WGSL's builtins by their GLSL names.

use std::fmt::Write;

use naga::proc::NameKey;
use naga::{BinaryOperator, Expression, Handle, Literal, MathFunction, ScalarKind, TypeInner};

use super::declarations::value_type;
use super::{FunctionContext, Printer, COMPONENTS};

impl Printer<'_> {
    /// A constant's initializer, in the module's global expressions.
    pub(super) fn const_expression(
        &self,
        out: &mut String,
        handle: Handle<Expression>,
    ) -> Result<(), String> {
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
    pub(super) fn constant(
        &self,
        out: &mut String,
        handle: Handle<naga::Constant>,
    ) -> Result<(), String> {
        let constant = &self.module.constants[handle];
        match constant.name {
            Some(_) => out.push_str(&self.names[&NameKey::Constant(handle)]),
            None => self.const_expression(out, constant.init)?,
        }
        Ok(())
    }

    pub(super) fn expression(
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
    pub(super) fn sample(
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

    pub(super) fn arguments(
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

    /// `pieces[0] operands[0] pieces[1] ... operands[n - 1] pieces[n]`: a GLSL form of an
    /// operation that takes its operands in a fixed frame (`min(max(x, low), high)`).
    fn interleaved(
        &self,
        out: &mut String,
        pieces: &[&str],
        operands: &[Handle<Expression>],
        context: &FunctionContext,
    ) -> Result<(), String> {
        for (piece, operand) in pieces.iter().zip(operands) {
            out.push_str(piece);
            self.expression(out, *operand, context)?;
        }
        out.push_str(pieces[operands.len()]);
        Ok(())
    }

    /// A binary operation in parentheses, or the function GLSL has for it: vectors compare
    /// through `lessThan` and its kin, and a float remainder is WGSL's truncated one.
    pub(super) fn binary(
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
                // WGSL's remainder truncates: `e1 - e2 * trunc(e1 / e2)`.
                let pieces = ["(", " - ", " * trunc(", " / ", "))"];
                self.interleaved(out, &pieces, &[left, right, left, right], context)?;
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
    pub(super) fn math(
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
                let pieces = ["min(max(", ", ", "), ", ")"];
                return self.interleaved(out, &pieces, arguments, context);
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
            Mf::Fma => return self.interleaved(out, &["(", " * ", " + ", ")"], arguments, context),
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
    pub(super) fn cast(
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
