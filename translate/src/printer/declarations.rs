//! The declarations outside functions (structs, constants, textures) and how a declaration
//! writes a type: `highp` where a precision qualifier applies, GLSL's array sizes after the name.

use std::fmt::Write;

use naga::proc::NameKey;
use naga::{ArraySize, Expression, Function, Handle, ScalarKind, Type, TypeInner};

use crate::items::ItemKind;

use super::{Choice, FunctionContext, Item, Printer, INDENT};

impl Printer<'_> {
    /// Every struct and named constant the choice does not leave out.
    pub(super) fn structs_and_constants(&mut self) -> Result<(), String> {
        for (handle, ty) in self.module.types.iter() {
            let TypeInner::Struct { ref members, .. } = ty.inner else {
                continue;
            };
            if self.left_out(ty.name.as_deref()) {
                continue;
            }
            let name = self.names[&NameKey::Type(handle)].clone();
            let mut text = format!("struct {name} {{\n");
            for (index, member) in members.iter().enumerate() {
                let name = &self.names[&NameKey::StructMember(handle, index as u32)];
                let _ = writeln!(text, "{INDENT}{};", self.declaration(member.ty, name)?);
            }
            text.push_str("};\n");
            self.record(ItemKind::Struct, ty.name.as_deref(), name, text);
        }
        for (handle, constant) in self.module.constants.iter() {
            if constant.name.is_none() || self.left_out(constant.name.as_deref()) {
                continue;
            }
            let name = self.names[&NameKey::Constant(handle)].clone();
            let mut init = String::new();
            self.const_expression(&mut init, constant.init)?;
            let text = format!(
                "const {} = {init};\n",
                self.declaration(constant.ty, &name)?
            );
            self.record(ItemKind::Constant, constant.name.as_deref(), name, text);
        }
        Ok(())
    }

    /// Whether the choice leaves out the item of this WGSL name.
    pub(super) fn left_out(&self, wgsl: Option<&str>) -> bool {
        wgsl.is_some_and(|wgsl| self.leave_out.contains(&wgsl))
    }

    /// Records a printed item.
    pub(super) fn record(
        &mut self,
        kind: ItemKind,
        wgsl: Option<&str>,
        glsl: String,
        text: String,
    ) {
        self.items.push(Item {
            kind,
            wgsl: wgsl.map(str::to_string),
            glsl,
            text,
        });
    }

    /// The textures `functions` sample, one declaration each: GLSL has no separate samplers,
    /// a sampler uniform is the texture and the sampler state together. Named as naga's
    /// writer names a resource (`_group_0_binding_5_fs`), which a host without binding
    /// qualifiers sets by name.
    pub(super) fn textures(
        &mut self,
        functions: &[Handle<Function>],
        choice: &Choice,
    ) -> Result<(), String> {
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
            let sampler = match kind {
                ScalarKind::Float => "sampler2D",
                ScalarKind::Sint => "isampler2D",
                ScalarKind::Uint => "usampler2D",
                other => return Err(format!("GLSL has no texture of {other:?}")),
            };
            let layout = match choice.binding_qualifiers {
                true => format!("layout(binding = {}) ", binding.binding),
                false => String::new(),
            };
            let text = format!("{layout}uniform highp {sampler} {name};\n");
            self.names
                .insert(NameKey::GlobalVariable(handle), name.clone());
            self.texture_bindings.push((name.clone(), binding));
            self.record(ItemKind::Texture, global.name.as_deref(), name, text);
        }
        Ok(())
    }

    /// `highp T name[N]`: a type and a name as a declaration writes them.
    pub(super) fn declaration(&self, ty: Handle<Type>, name: &str) -> Result<String, String> {
        Ok(format!(
            "{}{} {name}{}",
            self.precision(&self.module.types[ty].inner),
            self.type_name(ty)?,
            self.array_size(ty)
        ))
    }

    /// `highp ` for a type a precision qualifier applies to (float and integer scalars,
    /// vectors and matrices, and arrays of them), else nothing.
    pub(super) fn precision(&self, inner: &TypeInner) -> &'static str {
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
    pub(super) fn type_name(&self, ty: Handle<Type>) -> Result<String, String> {
        match self.module.types[ty].inner {
            TypeInner::Struct { .. } => Ok(self.names[&NameKey::Type(ty)].clone()),
            TypeInner::Array { base, .. } | TypeInner::Pointer { base, .. } => self.type_name(base),
            ref inner => value_type(inner),
        }
    }

    /// `[N]` for each array level of `ty`, outermost first; nothing for other types.
    pub(super) fn array_size(&self, ty: Handle<Type>) -> String {
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

    /// The declaration of a temporary holding expression `handle`.
    pub(super) fn value_declaration(
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

    pub(super) fn zero_value(&self, out: &mut String, ty: Handle<Type>) -> Result<(), String> {
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
}

/// A scalar, vector or matrix type's GLSL name.
pub(super) fn value_type(inner: &TypeInner) -> Result<String, String> {
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
