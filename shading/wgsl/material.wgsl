// material: from stored material parameters to the diffuse colour and f0 the BRDF needs.
// requires: constants

// The colours a BRDF takes: Lambert's diffuse colour and the reflectance at normal incidence.
struct MaterialColours {
    diffuse: vec3<f32>,
    f0: vec3<f32>,
}

// Metallic workflow (Burley 2012): metals have no diffuse and tint f0 with the base colour;
// dielectrics reflect dielectric_f0 (DIELECTRIC_F0, or from dielectric_f0_from_specular).
// Domain [0, 1]; a metallic between 0 and 1 (filtered masks) mixes both: the seed's halos.
fn metallic_workflow(base_colour: vec3<f32>, metallic: f32, dielectric_f0: f32) -> MaterialColours {
    let diffuse = base_colour * (1.0 - metallic);
    let f0 = mix(vec3<f32>(dielectric_f0), base_colour, metallic);
    return MaterialColours(diffuse, f0);
}

// UE4's dielectric "Specular" parameter (Karis 2013, after Burley): f0 = 0.08 * specular, so
// the default 0.5 gives 0.04. Domain [0, 1].
fn dielectric_f0_from_specular(specular: f32) -> f32 {
    return 0.08 * specular;
}

// Specular workflow (GPU Pro 7, Listing 2.1): f0 is the stored specular colour; the diffuse
// albedo is scaled by 1 - max(f0) so diffuse plus specular never exceed one.
fn specular_workflow(albedo: vec3<f32>, specular_colour: vec3<f32>) -> MaterialColours {
    let reflectivity = max(max(specular_colour.r, specular_colour.g), specular_colour.b);
    return MaterialColours(albedo * (1.0 - reflectivity), specular_colour);
}
