//! Which of Bevy's G-buffer quantities a layout's field holds: by the field's name (the names
//! Bevy's own `PbrInput` and deferred shaders use) or as the plugin is told
//! ([`crate::GBufferPlugin::with_field`]), each checked against the field's type; and what the
//! lighting reads where the layout stores no such quantity (the value Bevy's `pbr_input_new`
//! starts from, or its deferred shader's own default).

use std::fmt;

use gbuffer::layout::{Encoding, Field, FieldType, Layout, ScalarKind, Storage};

/// A quantity of Bevy's `PbrInput` that a layout's field can hold: Bevy's own G-buffer's, and
/// those Bevy's G-buffer drops (coloured reflectance and occlusion, anisotropy, the clearcoat
/// normal, diffuse transmission, whether the mesh is lightmapped).
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
    /// Bevy's `reflectance`, monochrome: the Rec. 709 luminance of `PbrInput`'s, as Bevy's own
    /// G-buffer keeps it (`f32`; f0 = 0.16 reflectance²).
    Reflectance,
    /// `PbrInput`'s coloured reflectance, Bevy's `reflectance` times its `specular_tint`
    /// (`vec3`): the specular tint Bevy's own G-buffer drops.
    ReflectanceColor,
    /// Diffuse occlusion, monochrome: the Rec. 709 luminance of `PbrInput`'s (`f32`).
    DiffuseOcclusion,
    /// `PbrInput`'s coloured diffuse occlusion (`vec3`).
    DiffuseOcclusionColor,
    /// Emissive light, with the light map's light added as Bevy does (`vec3`, HDR).
    Emissive,
    /// The world-space unit normal (`vec3`).
    Normal,
    /// Bevy's deferred flags (`u32`, 3 bits: unlit, fog, shadow receiver).
    Flags,
    /// Clearcoat strength (`f32`).
    Clearcoat,
    /// Clearcoat perceptual roughness (`f32`).
    ClearcoatPerceptualRoughness,
    /// The clearcoat layer's world-space unit normal, with its normal map (`vec3`); Bevy's own
    /// G-buffer reads the base normal in its place.
    ClearcoatNormal,
    /// Anisotropy strength (`f32`, 0 to 1): `PbrInput`'s `anisotropy_strength`.
    AnisotropyStrength,
    /// The world-space unit direction of anisotropy, `PbrInput`'s `anisotropy_T` (`vec3`); the
    /// bitangent is rebuilt as Bevy builds it, `normalize(cross(N, T))`.
    AnisotropyTangent,
    /// Diffuse transmission (`f32`, 0 to 1).
    DiffuseTransmission,
    /// The thickness diffuse transmission's back lobe sits behind the surface (`f32`, world
    /// units, 0 up).
    Thickness,
    /// Whether the mesh has a light map (`u32`, 1 bit), so that an ambient light with
    /// `affects_lightmapped_meshes: false` leaves it out, as Bevy's forward renderer does.
    Lightmapped,
    /// Depth, `frag_coord.z` (`f32`), as Bevy's WebGL2 G-buffer keeps it; the lighting reads
    /// depth from the depth prepass.
    Depth,
}

/// What values a quantity takes, which decides the encodings that can hold it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Values {
    /// In [0, 1] (colours, roughness, occlusion, depth...).
    Unit,
    /// A unit vector: signed components.
    Direction,
    /// Light or a length: 0 up, unbounded.
    Unbounded,
    /// Integer bits.
    Bits,
}

impl Values {
    /// Whether `encoding` holds these values: a direction needs signed components, light and
    /// lengths need more than [0, 1], bits need an integer.
    pub fn held_by(self, encoding: Encoding) -> bool {
        use Encoding as E;
        match self {
            Values::Unit => !matches!(encoding, E::Uint | E::Sint | E::Bool | E::Octahedral),
            // A direction is a `Vec3` in one 32-bit word: `half` and `float32` would take 48
            // and 96 bits, so no layout can give it them.
            Values::Direction => matches!(encoding, E::Octahedral | E::Snorm),
            Values::Unbounded => matches!(
                encoding,
                E::Half | E::Float32 | E::UnsignedFloat | E::Rgb9e5 | E::Rgbm(_) | E::LogLuminance
            ),
            Values::Bits => encoding == E::Uint,
        }
    }

    /// The encodings that hold these values, for messages.
    pub fn encodings(self) -> &'static str {
        match self {
            Values::Unit => "unorm, snorm or a float encoding",
            Values::Direction => "octahedral or snorm",
            Values::Unbounded => {
                "a float encoding (rgb9e5, unsigned_float, half, float32, rgbm, log_luminance)"
            }
            Values::Bits => "uint",
        }
    }
}

impl Quantity {
    /// Every quantity.
    pub const ALL: [Quantity; 20] = [
        Quantity::BaseColor,
        Quantity::BaseColorRoughness,
        Quantity::PerceptualRoughness,
        Quantity::Metallic,
        Quantity::Reflectance,
        Quantity::ReflectanceColor,
        Quantity::DiffuseOcclusion,
        Quantity::DiffuseOcclusionColor,
        Quantity::Emissive,
        Quantity::Normal,
        Quantity::Flags,
        Quantity::Clearcoat,
        Quantity::ClearcoatPerceptualRoughness,
        Quantity::ClearcoatNormal,
        Quantity::AnisotropyStrength,
        Quantity::AnisotropyTangent,
        Quantity::DiffuseTransmission,
        Quantity::Thickness,
        Quantity::Lightmapped,
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
            Quantity::ReflectanceColor => &["reflectance_color"],
            Quantity::DiffuseOcclusion => &["diffuse_occlusion", "occlusion"],
            Quantity::DiffuseOcclusionColor => &["diffuse_occlusion_color", "occlusion_color"],
            Quantity::Emissive => &["emissive"],
            Quantity::Normal => &["normal"],
            Quantity::Flags => &["flags"],
            Quantity::Clearcoat => &["clearcoat"],
            Quantity::ClearcoatPerceptualRoughness => &["clearcoat_perceptual_roughness"],
            Quantity::ClearcoatNormal => &["clearcoat_normal"],
            Quantity::AnisotropyStrength => &["anisotropy_strength"],
            Quantity::AnisotropyTangent => &["anisotropy_tangent"],
            Quantity::DiffuseTransmission => &["diffuse_transmission"],
            Quantity::Thickness => &["thickness"],
            Quantity::Lightmapped => &["lightmapped"],
            Quantity::Depth => &["depth"],
        }
    }

    /// The type a field holding it must have.
    pub fn field_type(self) -> FieldType {
        match self {
            Quantity::BaseColor
            | Quantity::ReflectanceColor
            | Quantity::DiffuseOcclusionColor
            | Quantity::Emissive
            | Quantity::Normal
            | Quantity::ClearcoatNormal
            | Quantity::AnisotropyTangent => FieldType::new(ScalarKind::Float, 3),
            Quantity::BaseColorRoughness => FieldType::new(ScalarKind::Float, 4),
            Quantity::Flags | Quantity::Lightmapped => FieldType::new(ScalarKind::Uint, 1),
            _ => FieldType::new(ScalarKind::Float, 1),
        }
    }

    /// The values it takes.
    pub fn values(self) -> Values {
        match self {
            Quantity::Normal | Quantity::ClearcoatNormal | Quantity::AnisotropyTangent => {
                Values::Direction
            }
            Quantity::Emissive | Quantity::Thickness => Values::Unbounded,
            Quantity::Flags | Quantity::Lightmapped => Values::Bits,
            _ => Values::Unit,
        }
    }

    /// The quantities a field holding this one stores too: base colour and roughness for
    /// `base_color_roughness`, the monochrome form for a coloured one.
    pub fn covers(self) -> &'static [Quantity] {
        match self {
            Quantity::BaseColorRoughness => &[Quantity::BaseColor, Quantity::PerceptualRoughness],
            Quantity::ReflectanceColor => &[Quantity::Reflectance],
            Quantity::DiffuseOcclusionColor => &[Quantity::DiffuseOcclusion],
            _ => &[],
        }
    }

    /// The quantity it cannot be read without: the two halves of anisotropy.
    pub fn partner(self) -> Option<Quantity> {
        match self {
            Quantity::AnisotropyStrength => Some(Quantity::AnisotropyTangent),
            Quantity::AnisotropyTangent => Some(Quantity::AnisotropyStrength),
            _ => None,
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
    /// A field whose encoding cannot hold its quantity's values (a normal in unorm, light in
    /// unorm...).
    WrongEncoding {
        /// The layout.
        layout: String,
        /// The field.
        field: String,
        /// Its quantity.
        quantity: Quantity,
        /// Its encoding's name.
        encoding: &'static str,
    },
    /// A quantity stored without the one it is read with (anisotropy's strength without its
    /// direction, or the other way).
    Incomplete {
        /// The layout.
        layout: String,
        /// The field.
        field: String,
        /// Its quantity.
        quantity: Quantity,
        /// The quantity no field holds.
        missing: Quantity,
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
            MappingError::WrongEncoding {
                layout,
                field,
                quantity,
                encoding,
            } => write!(
                out,
                "layout `{layout}`, field `{field}`: `{encoding}` cannot hold `{quantity}`; use {}",
                quantity.values().encodings()
            ),
            MappingError::Incomplete {
                layout,
                field,
                quantity,
                missing,
            } => write!(
                out,
                "layout `{layout}`, field `{field}`: `{quantity}` is read with `{missing}`, which \
                 no field holds"
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
/// then the field's name. Checks the width, each field's type and encoding, that no quantity
/// is stored twice, that the normal is there and that anisotropy has both halves.
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
        let encoding = encoding(field);
        if !quantity.values().held_by(encoding) {
            return Err(MappingError::WrongEncoding {
                layout: name(),
                field: field.name.clone(),
                quantity,
                encoding: encoding.name(),
            });
        }
        let with_covered =
            |quantity: Quantity| std::iter::once(quantity).chain(quantity.covers().iter().copied());
        let taken = mapped
            .iter()
            .flat_map(|(_, earlier)| with_covered(*earlier))
            .any(|earlier| with_covered(quantity).any(|stored| stored == earlier));
        if taken {
            return Err(MappingError::Repeated {
                layout: name(),
                field: field.name.clone(),
                quantity,
            });
        }
        mapped.push((field.name.clone(), quantity));
    }
    let holds = |wanted: Quantity| mapped.iter().any(|(_, quantity)| *quantity == wanted);
    if !holds(Quantity::Normal) {
        return Err(MappingError::NoNormal { layout: name() });
    }
    for (field, quantity) in &mapped {
        if let Some(missing) = quantity.partner().filter(|partner| !holds(*partner)) {
            return Err(MappingError::Incomplete {
                layout: name(),
                field: field.clone(),
                quantity: *quantity,
                missing,
            });
        }
    }
    Ok(mapped)
}

/// A field's encoding: its bit field's, or its word format's channels'.
fn encoding(field: &Field) -> Encoding {
    match field.storage {
        Storage::Bits(bit_field) => bit_field.encoding,
        Storage::Word(format) => format.channels()[0].encoding,
    }
}
