//! Which of Bevy's G-buffer quantities a layout's field holds: by the field's name (the names
//! Bevy's own `PbrInput` and deferred shaders use) or as the plugin is told
//! ([`crate::GBufferPlugin::with_field`]), each checked against the field's type; and what the
//! lighting reads where the layout stores no such quantity (the value Bevy's `pbr_input_new`
//! starts from, or its deferred shader's own default).

use std::fmt;

use gbuffer::layout::{FieldType, Layout, ScalarKind};

/// A quantity Bevy's deferred renderer stores in its G-buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Base colour, gamma 2.2 encoded as Bevy stores it (`vec3`).
    BaseColor,
    /// Base colour (gamma 2.2) and perceptual roughness in one `vec4`, as Bevy's first word.
    BaseColorRoughness,
    /// Perceptual roughness (`f32`).
    PerceptualRoughness,
    /// Metallic (`f32`).
    Metallic,
    /// Bevy's `reflectance`, monochrome (`f32`; f0 = 0.16 reflectance²).
    Reflectance,
    /// Diffuse occlusion, monochrome (`f32`).
    DiffuseOcclusion,
    /// Emissive light, with the light map's light added as Bevy does (`vec3`, HDR).
    Emissive,
    /// The world-space unit normal (`vec3`).
    Normal,
    /// Bevy's deferred flags (`u32`, 8 bits).
    Flags,
    /// Clearcoat strength (`f32`).
    Clearcoat,
    /// Clearcoat perceptual roughness (`f32`).
    ClearcoatPerceptualRoughness,
    /// Depth, `frag_coord.z` (`f32`), as Bevy's WebGL2 G-buffer keeps it; the lighting reads
    /// depth from the depth prepass.
    Depth,
}

impl Quantity {
    /// Every quantity.
    pub const ALL: [Quantity; 12] = [
        Quantity::BaseColor,
        Quantity::BaseColorRoughness,
        Quantity::PerceptualRoughness,
        Quantity::Metallic,
        Quantity::Reflectance,
        Quantity::DiffuseOcclusion,
        Quantity::Emissive,
        Quantity::Normal,
        Quantity::Flags,
        Quantity::Clearcoat,
        Quantity::ClearcoatPerceptualRoughness,
        Quantity::Depth,
    ];

    /// The field names that hold it without being told.
    pub fn names(self) -> &'static [&'static str] {
        match self {
            Quantity::BaseColor => &["base_color"],
            Quantity::BaseColorRoughness => &["base_color_roughness"],
            Quantity::PerceptualRoughness => &["perceptual_roughness", "roughness"],
            Quantity::Metallic => &["metallic"],
            Quantity::Reflectance => &["reflectance"],
            Quantity::DiffuseOcclusion => &["diffuse_occlusion", "occlusion"],
            Quantity::Emissive => &["emissive"],
            Quantity::Normal => &["normal"],
            Quantity::Flags => &["flags"],
            Quantity::Clearcoat => &["clearcoat"],
            Quantity::ClearcoatPerceptualRoughness => &["clearcoat_perceptual_roughness"],
            Quantity::Depth => &["depth"],
        }
    }

    /// The type a field holding it must have.
    pub fn field_type(self) -> FieldType {
        match self {
            Quantity::BaseColor | Quantity::Emissive | Quantity::Normal => {
                FieldType::new(ScalarKind::Float, 3)
            }
            Quantity::BaseColorRoughness => FieldType::new(ScalarKind::Float, 4),
            Quantity::Flags => FieldType::new(ScalarKind::Uint, 1),
            _ => FieldType::new(ScalarKind::Float, 1),
        }
    }

    /// The quantity a field of this name holds, if its name says.
    pub fn named(name: &str) -> Option<Quantity> {
        Quantity::ALL
            .into_iter()
            .find(|quantity| quantity.names().contains(&name))
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        out.write_str(self.names()[0])
    }
}

/// Why a layout cannot stand in for Bevy's G-buffer; its `Display` names the layout and the
/// field.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum MappingError {
    /// More than Bevy's one `Rgba32Uint` texel.
    TooWide {
        /// The layout.
        layout: String,
        /// Its bits.
        bits: u32,
    },
    /// A field whose name is none of Bevy's quantities, and which the plugin was not told about.
    UnknownField {
        /// The layout.
        layout: String,
        /// The field.
        field: String,
    },
    /// A field whose type cannot hold its quantity.
    WrongType {
        /// The layout.
        layout: String,
        /// The field.
        field: String,
        /// Its quantity.
        quantity: Quantity,
        /// Its type (`Vec3`, ...).
        found: &'static str,
    },
    /// Two fields holding one quantity (base colour or roughness counted in
    /// `base_color_roughness` too).
    Repeated {
        /// The layout.
        layout: String,
        /// The second field.
        field: String,
        /// The quantity.
        quantity: Quantity,
    },
    /// No field holds the normal, which Bevy's lighting cannot do without.
    NoNormal {
        /// The layout.
        layout: String,
    },
    /// [`crate::GBufferPlugin::with_field`] named a field the layout does not have.
    NoSuchField {
        /// The layout.
        layout: String,
        /// The name given.
        field: String,
    },
}

impl fmt::Display for MappingError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MappingError::TooWide { layout, bits } => write!(
                out,
                "layout `{layout}` takes {bits} bits; Bevy's G-buffer is one Rgba32Uint texel, \
                 128 bits"
            ),
            MappingError::UnknownField { layout, field } => {
                let names: Vec<&str> = Quantity::ALL
                    .iter()
                    .flat_map(|quantity| quantity.names().iter().copied())
                    .collect();
                write!(
                    out,
                    "layout `{layout}`, field `{field}`: not one of Bevy's G-buffer quantities \
                     ({}); name it so, or map it with GBufferPlugin::with_field",
                    names.join(", ")
                )
            }
            MappingError::WrongType {
                layout,
                field,
                quantity,
                found,
            } => write!(
                out,
                "layout `{layout}`, field `{field}`: holds `{quantity}`, which needs a `{}`, \
                 not a `{found}`",
                quantity.field_type().rust_name()
            ),
            MappingError::Repeated {
                layout,
                field,
                quantity,
            } => write!(
                out,
                "layout `{layout}`, field `{field}`: `{quantity}` is already stored by another \
                 field"
            ),
            MappingError::NoNormal { layout } => write!(
                out,
                "layout `{layout}` has no `normal` field (a Vec3): Bevy's lighting needs the normal"
            ),
            MappingError::NoSuchField { layout, field } => write!(
                out,
                "layout `{layout}` has no field `{field}` (named in GBufferPlugin::with_field)"
            ),
        }
    }
}

impl std::error::Error for MappingError {}

/// Each field of `layout` with the quantity it holds: `told` first (field name, quantity),
/// then the field's name. Checks the width, each field's type, that no quantity is stored
/// twice and that the normal is there.
pub fn map_fields(
    layout: &Layout,
    told: &[(String, Quantity)],
) -> Result<Vec<(String, Quantity)>, MappingError> {
    let name = || layout.name.clone();
    if layout.bits() > 128 {
        return Err(MappingError::TooWide {
            layout: name(),
            bits: layout.bits(),
        });
    }
    if let Some((field, _)) = told
        .iter()
        .find(|(field, _)| layout.fields.iter().all(|f| &f.name != field))
    {
        return Err(MappingError::NoSuchField {
            layout: name(),
            field: field.clone(),
        });
    }
    let mut mapped: Vec<(String, Quantity)> = Vec::new();
    for field in &layout.fields {
        let quantity = told
            .iter()
            .find(|(name, _)| *name == field.name)
            .map(|(_, quantity)| *quantity)
            .or_else(|| Quantity::named(&field.name))
            .ok_or_else(|| MappingError::UnknownField {
                layout: name(),
                field: field.name.clone(),
            })?;
        if field.ty != quantity.field_type() {
            return Err(MappingError::WrongType {
                layout: name(),
                field: field.name.clone(),
                quantity,
                found: field.ty.rust_name(),
            });
        }
        let covers = |quantity: Quantity| match quantity {
            Quantity::BaseColorRoughness => {
                vec![Quantity::BaseColor, Quantity::PerceptualRoughness]
            }
            other => vec![other],
        };
        let taken = mapped
            .iter()
            .flat_map(|(_, earlier)| covers(*earlier))
            .any(|earlier| covers(quantity).contains(&earlier));
        if taken {
            return Err(MappingError::Repeated {
                layout: name(),
                field: field.name.clone(),
                quantity,
            });
        }
        mapped.push((field.name.clone(), quantity));
    }
    if !mapped
        .iter()
        .any(|(_, quantity)| *quantity == Quantity::Normal)
    {
        return Err(MappingError::NoNormal { layout: name() });
    }
    Ok(mapped)
}
