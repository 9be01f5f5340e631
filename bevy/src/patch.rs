//! Patches of Bevy 0.20.1's lighting modules, applied to their text once loaded.
//!
//! Bevy's forward renderer specialises each material's pipeline: a material without
//! anisotropy is shaded without STANDARD_MATERIAL_ANISOTROPY, by the isotropic lobe. Bevy's
//! deferred lighting pass is one pipeline for every pixel, so a layout that holds anisotropy
//! turns the def on for all of them, and under it Bevy's anisotropic lobe at strength 0 is not
//! the isotropic one (it squares the roughness the isotropic lobe takes as alpha once more, and
//! bends the environment map's normal). The patches return early to Bevy's isotropic path where
//! the strength is 0, so such pixels shade as the forward renderer shades them.

use std::fmt;

use bevy::shader::{Shader, Source};

/// Text inserted after a line of a Bevy shader module.
#[derive(Clone, Copy, Debug)]
pub struct Patch {
    /// The module's asset path.
    pub path: &'static str,
    /// The text to insert after (it occurs once).
    pub after: &'static str,
    /// The text inserted.
    pub insert: &'static str,
}

/// The patches for a layout that holds anisotropy.
pub const ISOTROPIC_WITHOUT_ANISOTROPY: [Patch; 2] = [
    Patch {
        path: "embedded://bevy_pbr/render/pbr_lighting.wesl",
        after: "    specular_intensity: f32,\n) -> vec3<f32> {\n    // Unpack.\n    let NdotV = (*input).layers[LAYER_BASE].NdotV;\n    let V = (*input).V;",
        insert: "\n    // gbuffer-bevy: without anisotropy, Bevy's isotropic lobe, as forward.\n    if ((*input).anisotropy == 0.0) {\n        return specular(input, derived_input, roughness, specular_intensity);\n    }",
    },
    Patch {
        path: "embedded://bevy_pbr/render/pbr_functions.wesl",
        after: "fn bend_normal_for_anisotropy(lighting_input: ptr<function, lighting::LightingInput>) {",
        insert: "\n    // gbuffer-bevy: without anisotropy, the normal unbent, as forward.\n    if ((*lighting_input).anisotropy == 0.0) {\n        return;\n    }",
    },
];

/// A patch that does not apply: Bevy's text is not the 0.20.1 text it was written for.
#[derive(Debug)]
pub struct PatchError(&'static str);

impl fmt::Display for PatchError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            out,
            "GBufferPlugin: {} is not Bevy 0.20.1's (the text the anisotropy patch follows is not \
             in it once)",
            self.0
        )
    }
}

impl Patch {
    /// `shader` with the patch applied.
    pub fn apply(&self, shader: &Shader) -> Result<Shader, PatchError> {
        let Source::Wesl(source) = &shader.source else {
            return Err(PatchError(self.path));
        };
        if source.matches(self.after).count() != 1 {
            return Err(PatchError(self.path));
        }
        let patched = source.replacen(self.after, &format!("{}{}", self.after, self.insert), 1);
        let mut shader = shader.clone();
        shader.source = Source::Wesl(patched.into());
        Ok(shader)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_patch_goes_after_its_text_once_or_names_the_module() {
        let patch = ISOTROPIC_WITHOUT_ANISOTROPY[1];
        let source = format!("fn a() {{}}\n{}\n    let N = 1;\n}}\n", patch.after);
        let shader = Shader::from_wesl(source, "test.wesl");
        let Source::Wesl(patched) = patch.apply(&shader).unwrap().source else {
            panic!("WESL stays WESL");
        };
        assert!(patched.contains(&format!("{}{}\n    let N = 1;", patch.after, patch.insert)));
        // Bevy's text changed (or repeated): the plugin says which module, not a silent no-op.
        let other = Shader::from_wesl("fn a() {}\n", "test.wesl");
        let error = patch.apply(&other).unwrap_err().to_string();
        assert!(
            error.contains("embedded://bevy_pbr/render/pbr_functions.wesl is not Bevy 0.20.1's")
        );
        let twice = Shader::from_wesl(format!("{0}\n{0}\n", patch.after), "test.wesl");
        assert!(patch.apply(&twice).is_err());
    }
}
