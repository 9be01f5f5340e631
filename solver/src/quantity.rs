//! What a G-buffer must store for a scene: each quantity, and the features that need it. A
//! quantity nobody reads is not stored.

use crate::description::{Feature, MaterialModel, SceneDescription};

/// A value the G-buffer pass writes and the lighting pass reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Quantity {
    /// Light accumulation: emissive light, light maps and diffuse image-based light, HDR.
    Light,
    /// Distance from the eye along the pixel's ray, for positions.
    Depth,
    /// The shading normal, a unit vector.
    Normal,
    /// Perceptual roughness, 0 to 1.
    Roughness,
    /// Metallic model: the base colour.
    BaseColour,
    /// Metallic model: metalness.
    Metallic,
    /// UE4's dielectric "Specular" parameter (f0 = 0.08 specular): in the metallic model, and in
    /// the specular model without metals (grey reflectance).
    Specular,
    /// Specular model: the diffuse albedo.
    Albedo,
    /// Specular model with metals: the reflectance at normal incidence, coloured.
    SpecularColour,
}

/// How a quantity's precision is measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// HDR colour: error relative to the brightest channel.
    Hdr,
    /// A 32-bit float, stored exactly.
    Distance,
    /// A unit vector: angular error.
    Direction,
    /// A colour in [0, 1]: levels per channel.
    Colour,
    /// A scalar in [0, 1]: levels.
    Scalar,
}

gbuffer_core::named!(
    /// The name of its member in the generated `...Values` struct.
    Quantity {
        Light => "light",
        Depth => "depth",
        Normal => "normal",
        Roughness => "roughness",
        BaseColour => "base_colour",
        Metallic => "metallic",
        Specular => "specular",
        Albedo => "albedo",
        SpecularColour => "specular_colour",
    }
);

impl Quantity {
    /// The kind of value it is, which sets the unit of its error.
    pub fn kind(self) -> Kind {
        match self {
            Quantity::Light => Kind::Hdr,
            Quantity::Depth => Kind::Distance,
            Quantity::Normal => Kind::Direction,
            Quantity::BaseColour | Quantity::Albedo | Quantity::SpecularColour => Kind::Colour,
            Quantity::Roughness | Quantity::Metallic | Quantity::Specular => Kind::Scalar,
        }
    }

    /// Its WGSL type.
    pub fn wgsl_type(self) -> &'static str {
        match self.kind() {
            Kind::Hdr | Kind::Direction | Kind::Colour => "vec3<f32>",
            Kind::Distance | Kind::Scalar => "f32",
        }
    }

    /// Scalar components.
    pub fn components(self) -> usize {
        match self.kind() {
            Kind::Hdr | Kind::Direction | Kind::Colour => 3,
            Kind::Distance | Kind::Scalar => 1,
        }
    }
}

/// A quantity the scene stores, and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Stored {
    /// The quantity.
    pub quantity: Quantity,
    /// The features that read it.
    pub needed_by: Vec<Feature>,
}

/// The quantities a scene stores, in [`Quantity`] order. The rules:
///
/// - light accumulation holds emissive light, light maps and diffuse image-based light;
/// - depth gives point lights their positions and decals their projection;
/// - normals and roughness serve the direct lights and the environment's specular reflection
///   (roughness is 1 everywhere on fully rough scenes);
/// - the diffuse colour serves the direct lights (image-based and baked diffuse light is
///   folded into the light accumulation by the G-buffer pass), the reflectance every specular
///   term;
/// - without metals (or in the metallic model) the dielectric reflectance is 0.04, or 0.08
///   specular with the dielectric specular parameter.
pub fn stored_quantities(scene: &SceneDescription) -> Vec<Stored> {
    let features = scene.features;
    let has = |feature| features.contains(feature);
    let lights_of = |candidates: &[Feature]| -> Vec<Feature> {
        candidates
            .iter()
            .copied()
            .filter(|feature| has(*feature))
            .collect()
    };
    // What reads the diffuse colour and what reads the reflectance.
    let diffuse_readers = lights_of(&[Feature::Sun, Feature::PointLights]);
    let mut specular_readers = diffuse_readers.clone();
    if features.environment_specular() {
        specular_readers.push(Feature::ImageBasedLighting);
    }
    let with_feature = |readers: &[Feature], feature: Feature| -> Vec<Feature> {
        if has(feature) && !readers.is_empty() {
            let mut needed_by = readers.to_vec();
            needed_by.push(feature);
            needed_by
        } else {
            Vec::new()
        }
    };

    let mut stored = vec![
        (
            Quantity::Light,
            lights_of(&[
                Feature::Emissive,
                Feature::ImageBasedLighting,
                Feature::LightMaps,
            ]),
        ),
        (
            Quantity::Depth,
            lights_of(&[Feature::PointLights, Feature::Decals]),
        ),
        (Quantity::Normal, specular_readers.clone()),
        (
            Quantity::Roughness,
            if has(Feature::FullyRough) {
                Vec::new()
            } else {
                specular_readers.clone()
            },
        ),
    ];
    match scene.model {
        MaterialModel::Metallic => {
            let mut base_colour_readers = diffuse_readers.clone();
            if has(Feature::Metals) {
                base_colour_readers.extend(&specular_readers);
                base_colour_readers.sort();
                base_colour_readers.dedup();
            }
            stored.push((Quantity::BaseColour, base_colour_readers));
            let mut metallic_readers = diffuse_readers.clone();
            metallic_readers.extend(&specular_readers);
            metallic_readers.sort();
            metallic_readers.dedup();
            stored.push((
                Quantity::Metallic,
                with_feature(&metallic_readers, Feature::Metals),
            ));
            stored.push((
                Quantity::Specular,
                with_feature(&specular_readers, Feature::DielectricSpecular),
            ));
        }
        MaterialModel::Specular => {
            stored.push((Quantity::Albedo, diffuse_readers.clone()));
            stored.push((
                Quantity::SpecularColour,
                with_feature(&specular_readers, Feature::Metals),
            ));
            let grey = if has(Feature::Metals) {
                Vec::new()
            } else {
                with_feature(&specular_readers, Feature::DielectricSpecular)
            };
            stored.push((Quantity::Specular, grey));
        }
    }
    stored
        .into_iter()
        .filter(|(_, needed_by)| !needed_by.is_empty())
        .map(|(quantity, needed_by)| Stored {
            quantity,
            needed_by,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quantities(scene: &SceneDescription) -> Vec<Quantity> {
        stored_quantities(scene)
            .into_iter()
            .map(|stored| stored.quantity)
            .collect()
    }

    #[test]
    fn the_reference_scene_stores_what_listing_2_2_does_but_depth() {
        use Quantity::*;
        let scene = SceneDescription::new("Reference");
        assert_eq!(
            quantities(&scene),
            [Light, Normal, Roughness, BaseColour, Metallic]
        );
    }

    #[test]
    fn unused_features_drop_their_quantities() {
        use Quantity::*;
        let dielectric = SceneDescription::new("Dielectric").without(Feature::Metals);
        assert_eq!(
            quantities(&dielectric),
            [Light, Normal, Roughness, BaseColour]
        );
        // Only baked light: the lighting pass reads the light accumulation alone.
        let baked = SceneDescription::new("Baked").features([Feature::LightMaps, Feature::Metals]);
        assert_eq!(quantities(&baked), [Light]);
        // Fully rough, lit by the sky only: the G-buffer pass folds everything into light.
        let rough = SceneDescription::new("Rough")
            .features([Feature::ImageBasedLighting, Feature::FullyRough]);
        assert_eq!(quantities(&rough), [Light]);
        // Point lights need positions.
        let points = SceneDescription::new("Points").features([Feature::PointLights]);
        assert_eq!(quantities(&points), [Depth, Normal, Roughness, BaseColour]);
    }

    #[test]
    fn the_specular_model_stores_grey_or_coloured_reflectance() {
        use Quantity::*;
        let scene = SceneDescription::new("Desktop")
            .model(MaterialModel::Specular)
            .with(Feature::DielectricSpecular);
        assert_eq!(
            quantities(&scene),
            [Light, Normal, Roughness, Albedo, SpecularColour]
        );
        let grey = scene.without(Feature::Metals);
        assert_eq!(
            quantities(&grey),
            [Light, Normal, Roughness, Albedo, Specular]
        );
    }

    #[test]
    fn each_quantity_says_which_features_read_it() {
        let scene = SceneDescription::new("Reference");
        let metallic = stored_quantities(&scene)
            .into_iter()
            .find(|stored| stored.quantity == Quantity::Metallic)
            .unwrap();
        assert_eq!(
            metallic.needed_by,
            [Feature::ImageBasedLighting, Feature::Sun, Feature::Metals]
        );
    }
}
