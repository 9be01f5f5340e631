// Mirrors material.wgsl.

/// The colours a BRDF takes: Lambert's diffuse colour and the reflectance at normal incidence.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialColours {
    /// Lambert's diffuse colour.
    pub diffuse: Vec3,
    /// Reflectance at normal incidence.
    pub f0: Vec3,
}

/// Metallic workflow (Burley 2012). `mix` is spelled out as WGSL defines it.
pub fn metallic_workflow(base_colour: Vec3, metallic: Float, dielectric_f0: Float) -> MaterialColours {
    let diffuse = base_colour * (1.0 - metallic);
    let f0 = Vec3::splat(dielectric_f0) * (1.0 - metallic) + base_colour * metallic;
    MaterialColours { diffuse, f0 }
}

/// UE4's dielectric "Specular" parameter: f0 = 0.08 * specular.
pub fn dielectric_f0_from_specular(specular: Float) -> Float {
    0.08 * specular
}

/// Specular workflow (GPU Pro 7, Listing 2.1), diffuse scaled by 1 - max(f0).
pub fn specular_workflow(albedo: Vec3, specular_colour: Vec3) -> MaterialColours {
    let reflectivity = specular_colour.x.max(specular_colour.y).max(specular_colour.z);
    MaterialColours { diffuse: albedo * (1.0 - reflectivity), f0: specular_colour }
}
