//! What a scene is made of: its material model, the features it uses, the precision each stored
//! quantity needs and the bits of tile memory it may use. Build one in Rust with the builder
//! methods below, or read it from a scene file ([`crate::file`]).

use std::fmt;

use gbuffer_core::Named;

/// How materials give the BRDF its colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MaterialModel {
    /// Base colour and metallic (Burley 2012): GPU Pro 7 Listing 2.2.
    Metallic,
    /// Diffuse albedo and specular colour: GPU Pro 7 Listings 2.1 and 2.8.
    Specular,
}

// Both models, in the order scene files list them.
gbuffer_core::named!(
    /// The name in scene files.
    MaterialModel {
        Metallic => "metallic",
        Specular => "specular",
    }
);

/// Something a scene may use. Each one brings what only it needs: stored quantities, terms of
/// the lighting shader, work in the G-buffer pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Feature {
    /// Metallic surfaces: coloured reflectance, no diffuse.
    Metals,
    /// A per-material dielectric reflectance (UE4's "Specular"); without it f0 is 0.04.
    DielectricSpecular,
    /// Tangent-space normal maps perturb the geometric normal in the G-buffer pass.
    NormalMaps,
    /// Emissive surfaces add their light to the light accumulation.
    Emissive,
    /// Image-based light: the sky's diffuse irradiance and its prefiltered specular reflection.
    ImageBasedLighting,
    /// Baked diffuse light maps, added to the light accumulation.
    LightMaps,
    /// One directional light.
    Sun,
    /// Point lights, shaded at the position reconstructed from depth.
    PointLights,
    /// Deferred decals, projected onto the depth the G-buffer keeps.
    Decals,
    /// Every surface is fully rough (roughness 1): no roughness is stored and the lighting
    /// folds the specular reflection of image-based light into diffuse (seed 001).
    FullyRough,
}

// Every feature, in the order reports list them.
gbuffer_core::named!(
    /// The key in a scene file's `[features]` table.
    Feature {
        Metals => "metals",
        DielectricSpecular => "dielectric_specular",
        NormalMaps => "normal_maps",
        Emissive => "emissive",
        ImageBasedLighting => "image_based_lighting",
        LightMaps => "light_maps",
        Sun => "sun",
        PointLights => "point_lights",
        Decals => "decals",
        FullyRough => "fully_rough",
    }
);

impl Feature {
    fn bit(self) -> u16 {
        1 << self as u16
    }
}

impl fmt::Display for Feature {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        out.write_str(self.name())
    }
}

/// A set of features.
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
pub struct Features(u16);

impl Features {
    /// No feature.
    pub const NONE: Features = Features(0);

    /// Everything the reference renderer's scene shows: metals, normal maps, image-based
    /// light, light maps and the sun.
    pub fn reference_scene() -> Features {
        Features::from_iter([
            Feature::Metals,
            Feature::NormalMaps,
            Feature::ImageBasedLighting,
            Feature::LightMaps,
            Feature::Sun,
        ])
    }

    /// Whether the set has `feature`.
    pub fn contains(self, feature: Feature) -> bool {
        self.0 & feature.bit() != 0
    }

    /// The set with `feature` added.
    pub fn with(self, feature: Feature) -> Features {
        Features(self.0 | feature.bit())
    }

    /// The set without `feature`.
    pub fn without(self, feature: Feature) -> Features {
        Features(self.0 & !feature.bit())
    }

    /// The features in the set, in [`Feature::ALL`] order.
    pub fn iter(self) -> impl Iterator<Item = Feature> {
        Feature::ALL
            .iter()
            .copied()
            .filter(move |feature| self.contains(*feature))
    }

    /// Direct lights: the sun or point lights.
    pub fn direct_light(self) -> bool {
        self.contains(Feature::Sun) || self.contains(Feature::PointLights)
    }

    /// The specular reflection of the environment map: image-based light on surfaces that are
    /// not all fully rough.
    pub fn environment_specular(self) -> bool {
        self.contains(Feature::ImageBasedLighting) && !self.contains(Feature::FullyRough)
    }
}

impl FromIterator<Feature> for Features {
    fn from_iter<I: IntoIterator<Item = Feature>>(features: I) -> Self {
        features.into_iter().fold(Features::NONE, Features::with)
    }
}

impl fmt::Debug for Features {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        out.debug_set().entries(self.iter()).finish()
    }
}

/// The precision each stored quantity needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precision {
    /// The largest angle, in degrees, between a normal and the normal read back.
    pub normal_degrees: f64,
    /// Distinct levels per channel of base colour, albedo and specular colour, in the [0, 1]
    /// space they are stored in: 256 is what 8 bits give.
    pub colour_steps: u32,
    /// Distinct levels of roughness, metallic and the dielectric specular parameter.
    pub material_steps: u32,
    /// The largest light accumulation value that must be stored without clipping.
    pub hdr_max: f64,
    /// Below this brightness an absolute error of `hdr_relative * hdr_min` is enough.
    pub hdr_min: f64,
    /// The largest error of a light accumulation channel relative to the pixel's brightest
    /// channel (or to `hdr_min`, when that is larger).
    pub hdr_relative: f64,
}

impl Default for Precision {
    /// What the mobile layout of GPU Pro 7 (Listing 2.2) achieves, roughly: half a degree,
    /// 8-bit colours and material parameters, light up to 8 within 2% down to 1/64.
    fn default() -> Self {
        Precision {
            normal_degrees: 0.5,
            colour_steps: 256,
            material_steps: 256,
            hdr_max: 8.0,
            hdr_min: 1.0 / 64.0,
            hdr_relative: 0.02,
        }
    }
}

/// The bits a scene may use when its description names none: PowerVR and Mali tile storage.
pub const DEFAULT_BUDGET: u32 = gbuffer_core::DEFAULT_BUDGET;

/// A scene: what it uses and how precisely, and how much tile memory it may take.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneDescription {
    /// The name of the layout solved for it, UpperCamelCase.
    pub name: String,
    /// How materials are described: metallic or specular.
    pub model: MaterialModel,
    /// What the scene uses.
    pub features: Features,
    /// How precisely it must be stored.
    pub precision: Precision,
    /// Bits of tile memory per pixel: a positive multiple of 32.
    pub budget: u32,
}

/// Which setting of a description a problem is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    /// The layout name.
    Name,
    /// The bit budget.
    Budget,
    /// The normal's allowed error, degrees.
    NormalDegrees,
    /// Steps per colour channel.
    ColourSteps,
    /// Steps of roughness and metallic.
    MaterialSteps,
    /// The brightest light stored.
    HdrMax,
    /// The dimmest light stored within the relative error.
    HdrMin,
    /// The relative error allowed in light.
    HdrRelative,
}

impl Setting {
    /// The key in a scene file.
    pub fn key(self) -> &'static str {
        match self {
            Setting::Name => "name",
            Setting::Budget => "budget",
            Setting::NormalDegrees => "normal_degrees",
            Setting::ColourSteps => "colour_steps",
            Setting::MaterialSteps => "material_steps",
            Setting::HdrMax => "hdr_max",
            Setting::HdrMin => "hdr_min",
            Setting::HdrRelative => "hdr_relative",
        }
    }
}

/// One problem with a description.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DescriptionError {
    /// The setting it is about.
    pub setting: Setting,
    /// What is wrong with it.
    pub message: String,
}

impl SceneDescription {
    /// A scene of the metallic model with the reference scene's features, the default
    /// precision and a 128-bit budget.
    pub fn new(name: &str) -> Self {
        SceneDescription {
            name: name.to_string(),
            model: MaterialModel::Metallic,
            features: Features::reference_scene(),
            precision: Precision::default(),
            budget: DEFAULT_BUDGET,
        }
    }

    /// The material model.
    pub fn model(mut self, model: MaterialModel) -> Self {
        self.model = model;
        self
    }

    /// Exactly these features.
    pub fn features(mut self, features: impl IntoIterator<Item = Feature>) -> Self {
        self.features = features.into_iter().collect();
        self
    }

    /// Adds a feature.
    pub fn with(mut self, feature: Feature) -> Self {
        self.features = self.features.with(feature);
        self
    }

    /// Removes a feature.
    pub fn without(mut self, feature: Feature) -> Self {
        self.features = self.features.without(feature);
        self
    }

    /// All precision settings at once.
    pub fn precision(mut self, precision: Precision) -> Self {
        self.precision = precision;
        self
    }

    /// The normal's allowed error, degrees.
    pub fn normal_degrees(mut self, degrees: f64) -> Self {
        self.precision.normal_degrees = degrees;
        self
    }

    /// Steps per colour channel.
    pub fn colour_steps(mut self, steps: u32) -> Self {
        self.precision.colour_steps = steps;
        self
    }

    /// Steps of roughness and metallic.
    pub fn material_steps(mut self, steps: u32) -> Self {
        self.precision.material_steps = steps;
        self
    }

    /// Light accumulation up to `max`, within `relative` of the brightest channel down to `min`.
    pub fn hdr(mut self, max: f64, min: f64, relative: f64) -> Self {
        self.precision.hdr_max = max;
        self.precision.hdr_min = min;
        self.precision.hdr_relative = relative;
        self
    }

    /// The bit budget: a positive multiple of 32.
    pub fn budget(mut self, bits: u32) -> Self {
        self.budget = bits;
        self
    }

    /// Every problem with the description; empty when the solver can take it.
    pub fn check(&self) -> Vec<DescriptionError> {
        let mut errors = Vec::new();
        let mut report =
            |setting, message: String| errors.push(DescriptionError { setting, message });
        if let Err(reason) = gbuffer_core::naming::check_identifier(&self.name) {
            report(
                Setting::Name,
                format!("scene name `{}` {reason}", self.name),
            );
        }
        if let Err(problem) = gbuffer_core::layout::check_budget(self.budget) {
            report(Setting::Budget, problem);
        }
        let precision = &self.precision;
        let positive = [
            (Setting::NormalDegrees, precision.normal_degrees),
            (Setting::HdrMax, precision.hdr_max),
            (Setting::HdrMin, precision.hdr_min),
            (Setting::HdrRelative, precision.hdr_relative),
        ];
        for (setting, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                report(
                    setting,
                    format!("{} must be a positive number, not {value}", setting.key()),
                );
            }
        }
        if precision.hdr_min >= precision.hdr_max {
            report(
                Setting::HdrMin,
                format!(
                    "hdr_min ({}) must be below hdr_max ({})",
                    precision.hdr_min, precision.hdr_max
                ),
            );
        }
        for (setting, steps) in [
            (Setting::ColourSteps, precision.colour_steps),
            (Setting::MaterialSteps, precision.material_steps),
        ] {
            if steps < 2 {
                report(
                    setting,
                    format!(
                        "{} must be at least 2 (one bit), not {steps}",
                        setting.key()
                    ),
                );
            }
        }
        errors
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn feature_names_round_trip() {
        for &feature in Feature::ALL {
            assert_eq!(Feature::from_name(feature.name()), Some(feature));
        }
        for &model in MaterialModel::ALL {
            assert_eq!(MaterialModel::from_name(model.name()), Some(model));
        }
    }

    #[test]
    fn the_builder_sets_what_it_names() {
        let scene = SceneDescription::new("Props")
            .without(Feature::Metals)
            .with(Feature::FullyRough)
            .normal_degrees(2.0)
            .budget(64);
        assert!(!scene.features.contains(Feature::Metals));
        assert!(scene.features.contains(Feature::FullyRough));
        assert!(scene.features.contains(Feature::Sun));
        assert!(!scene.features.environment_specular());
        assert_eq!((scene.precision.normal_degrees, scene.budget), (2.0, 64));
        assert!(scene.check().is_empty());
    }

    #[test]
    fn every_bad_setting_is_named() {
        let scene = SceneDescription::new("bad name")
            .budget(100)
            .normal_degrees(-1.0)
            .colour_steps(1)
            .hdr(1.0, 2.0, f64::NAN);
        let settings: Vec<Setting> = scene.check().into_iter().map(|e| e.setting).collect();
        assert_eq!(
            settings,
            [
                Setting::Name,
                Setting::Budget,
                Setting::NormalDegrees,
                Setting::HdrRelative,
                Setting::HdrMin,
                Setting::ColourSteps
            ]
        );
    }
}
