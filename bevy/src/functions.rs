//! The module that stands in for Bevy 0.20's `bevy_pbr::deferred::functions` (a WESL module,
//! `deferred/functions.wesl`): the same module path and functions, whose G-buffer is a
//! layout's. `deferred_gbuffer_from_pbr_input` computes Bevy's quantities as Bevy's own does (its
//! Rec. 709 monochrome occlusion and reflectance, the flags, gamma 2.2 base colour, unlit
//! materials' colour in the emissive slot, the light map's light added to the emissive) and
//! packs them with the layout's own `pack_<snake>`, so the words are the Rust mirror's;
//! `pbr_input_from_deferred_gbuffer` unpacks them with `unpack_<snake>` and rebuilds the
//! `PbrInput` as Bevy does, with Bevy's defaults for what the layout does not store.
//! `deferred_output` is Bevy's.
//!
//! The layout's WGSL is a WESL module of its own (`GBufferLayout::wesl_module`,
//! `gbuffer::<snake>`), which this one imports as Bevy's modules import each other. WESL is WGSL
//! with imports and conditional translation (`@if(DEF)` on a declaration or a statement, where
//! naga_oil had `#ifdef`).

use std::fmt::Write as _;

use gbuffer::layout::Layout;

use crate::quantity::Quantity;

/// The WESL module path the module replaces (Bevy's deferred lighting pass, its prepass's
/// `deferred_output` and its screen-space reflections import from it). Bevy 0.20 loads it from
/// [`asset_path`] of it, `embedded://bevy_pbr/deferred/functions.wesl`, where the plugin's
/// module takes its place.
pub const MODULE_PATH: &str = "bevy_pbr::deferred::functions";

/// Bevy's imports, as its own module has them (`package` is `bevy_pbr`), and the ambient
/// light's flags a lightmapped layout reads.
const IMPORTS: &str = "import package::{
    render::{
        pbr_types::{PbrInput, pbr_input_new, STANDARD_MATERIAL_FLAGS_UNLIT_BIT},
        pbr_functions,
        mesh_view_bindings::{view, lights},
        mesh_view_types,
        view_transformations::{position_ndc_to_world, frag_coord_to_ndc},
    },
    deferred::types as deferred_types,
    prepass::io::FragmentOutput,
};

@if(MESHLET_MESH_MATERIAL_PASS) import package::meshlet::visibility_buffer_resolve::VertexOutput;
@else import package::prepass::io::VertexOutput;

@if(MOTION_VECTOR_PREPASS)
    import package::render::pbr_prepass_functions::calculate_motion_vector;
";

/// `deferred_output`, as Bevy 0.20 writes the prepass's outputs.
const DEFERRED_OUTPUT: &str = "@if(PREPASS_PIPELINE)
fn deferred_output(in: VertexOutput, pbr_input: PbrInput) -> FragmentOutput {
    var out: FragmentOutput;
    out.deferred = deferred_gbuffer_from_pbr_input(pbr_input);
    // Which lighting shader runs for the fragment.
    out.deferred_lighting_pass_id = pbr_input.material.deferred_lighting_pass_id;
    @if(NORMAL_PREPASS)
    out.normal = vec4(in.world_normal * 0.5 + vec3(0.5), 1.0);
    @if(MOTION_VECTOR_PREPASS && MESHLET_MESH_MATERIAL_PASS)
    out.motion_vector = in.motion_vector;
    @if(MOTION_VECTOR_PREPASS && !MESHLET_MESH_MATERIAL_PASS)
    out.motion_vector = calculate_motion_vector(in.world_position, in.previous_world_position);
    return out;
}
";

/// The value each quantity is stored from in `deferred_gbuffer_from_pbr_input`.
fn stored(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::BaseColor => "base_color_gamma",
        Quantity::BaseColorRoughness => "vec4(base_color_gamma, in.material.perceptual_roughness)",
        Quantity::PerceptualRoughness => "in.material.perceptual_roughness",
        Quantity::Metallic => "in.material.metallic",
        Quantity::Reflectance => "reflectance",
        Quantity::ReflectanceColor => "in.material.reflectance",
        Quantity::DiffuseOcclusion => "diffuse_occlusion",
        Quantity::DiffuseOcclusionColor => "in.diffuse_occlusion",
        Quantity::Emissive => "emissive",
        Quantity::Normal => "normalize(in.N)",
        Quantity::Flags => "flags",
        Quantity::Clearcoat => "saturate(in.material.clearcoat)",
        Quantity::ClearcoatPerceptualRoughness => {
            "saturate(in.material.clearcoat_perceptual_roughness)"
        }
        Quantity::ClearcoatNormal => "clearcoat_normal",
        Quantity::AnisotropyStrength => "anisotropy_strength",
        Quantity::AnisotropyTangent => "anisotropy_tangent",
        Quantity::DiffuseTransmission => "saturate(in.material.diffuse_transmission)",
        Quantity::Thickness => "in.material.thickness",
        Quantity::Lightmapped => "lightmapped",
        Quantity::Depth => "in.frag_coord.z",
    }
}

/// What the prepass computes before storing, for the quantities Bevy's own module does not
/// store: each quantity's lines, emitted only when the layout holds it.
fn prepared(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::ClearcoatNormal => {
            "    // The clearcoat normal, with its normal map; Bevy leaves it zero where it
    // computes none.
    let clearcoat_normal = select(
        normalize(in.N),
        normalize(in.clearcoat_N),
        dot(in.clearcoat_N, in.clearcoat_N) > 0.0,
    );
"
        }
        Quantity::AnisotropyTangent => {
            "    // Anisotropy where the material has it (Bevy computes `anisotropy_T` only under
    // STANDARD_MATERIAL_ANISOTROPY, with tangents); elsewhere none, along a tangent of N (the
    // patched lighting shades strength 0 with Bevy's isotropic lobe).
    var anisotropy_strength = 0.0;
    var anisotropy_tangent = orthonormal_tangent(normalize(in.N));
    @if(STANDARD_MATERIAL_ANISOTROPY) {
        if (in.anisotropy_strength > 0.0 && dot(in.anisotropy_T, in.anisotropy_T) > 0.0) {
            anisotropy_strength = in.anisotropy_strength;
            anisotropy_tangent = in.anisotropy_T;
        }
    }
"
        }
        Quantity::Lightmapped => {
            "    // The prepass of a mesh with a light map is specialised with LIGHTMAP.
    var lightmapped = 0u;
    @if(LIGHTMAP)
    lightmapped = 1u;
"
        }
        _ => "",
    }
}

/// A unit vector perpendicular to `n`, emitted with the anisotropy it serves.
const ORTHONORMAL_TANGENT: &str = "
// A unit tangent of the unit vector n, continuous but at n.z = 0: the first vector of Duff et
// al. 2017, \"Building an Orthonormal Basis, Revisited\" (JCGT 6(1)), Listing 3.
fn orthonormal_tangent(n: vec3<f32>) -> vec3<f32> {
    let sign = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
}
";

/// The lines that set what `pbr_input_from_deferred_gbuffer` reads beyond Bevy's own
/// G-buffer, each quantity's only when the layout holds it; `N` is the unpacked normal.
fn read_back(quantity: Quantity, field: &str) -> String {
    match quantity {
        Quantity::ClearcoatNormal => format!("    pbr.clearcoat_N = normalize(texel.{field});\n"),
        Quantity::AnisotropyTangent => format!(
            "    // The bitangent as Bevy's fragment shader builds it, from the normal.
    pbr.anisotropy_T = normalize(texel.{field});
    pbr.anisotropy_B = normalize(cross(N, pbr.anisotropy_T));
"
        ),
        Quantity::AnisotropyStrength => format!("    pbr.anisotropy_strength = texel.{field};\n"),
        Quantity::DiffuseTransmission => {
            format!("    pbr.material.diffuse_transmission = texel.{field};\n")
        }
        Quantity::Thickness => format!("    pbr.material.thickness = texel.{field};\n"),
        Quantity::Lightmapped => format!(
            "    // Bevy's forward renderer leaves the ambient light out of a lightmapped mesh
    // when the light says so (under LIGHTMAP); here its occlusion does, which scales nothing
    // else that the forward renderer gives a lightmapped mesh (its environment map and
    // irradiance volumes give it no diffuse light).
    let ambient_flags = lights.ambient_light_flags;
    let affects = mesh_view_types::AMBIENT_LIGHT_FLAGS_AFFECTS_LIGHTMAPPED_MESHES_BIT;
    if (texel.{field} != 0u && (ambient_flags & affects) == 0u) {{
        pbr.diffuse_occlusion = vec3(0.0);
    }}
"
        ),
        _ => String::new(),
    }
}

/// The shader defs the deferred prepass and lighting pass need for what the layout holds,
/// beyond the STANDARD_MATERIAL_CLEARCOAT Bevy's deferred lighting pipeline always has: Bevy's
/// forward renderer specialises a material's pipeline with them, its deferred pipelines never
/// (its prepass not even with PBR_ANISOTROPY_TEXTURE_SUPPORTED, under which alone Bevy's
/// fragment shader computes anisotropy; this crate turns on the Cargo feature that binds the
/// texture it reads).
pub fn shader_defs(mapping: &[(String, Quantity)]) -> Vec<&'static str> {
    let mut defs = Vec::new();
    if holds(mapping, Quantity::AnisotropyStrength) {
        defs.push("STANDARD_MATERIAL_ANISOTROPY");
        defs.push("PBR_ANISOTROPY_TEXTURE_SUPPORTED");
    }
    if holds(mapping, Quantity::DiffuseTransmission) {
        defs.push("STANDARD_MATERIAL_DIFFUSE_TRANSMISSION");
        defs.push("STANDARD_MATERIAL_DIFFUSE_OR_SPECULAR_TRANSMISSION");
    }
    defs
}

/// Whether a field holds `quantity`.
pub fn holds(mapping: &[(String, Quantity)], quantity: Quantity) -> bool {
    field_of(mapping, quantity).is_some()
}

/// The field that holds `quantity`, if one does.
fn field_of(mapping: &[(String, Quantity)], quantity: Quantity) -> Option<&str> {
    mapping
        .iter()
        .find(|(_, stored)| *stored == quantity)
        .map(|(field, _)| field.as_str())
}

/// Where `quantity` is read back from: the texel's field, or `default` (what `pbr_input_new`
/// starts from: Bevy's own default).
fn read(mapping: &[(String, Quantity)], quantity: Quantity, default: &str) -> String {
    let field = |quantity| field_of(mapping, quantity);
    match (field(quantity), quantity) {
        (Some(field), _) => format!("texel.{field}"),
        (None, Quantity::BaseColor) => field(Quantity::BaseColorRoughness)
            .map_or_else(|| default.to_string(), |field| format!("texel.{field}.rgb")),
        (None, Quantity::PerceptualRoughness) => field(Quantity::BaseColorRoughness)
            .map_or_else(|| default.to_string(), |field| format!("texel.{field}.a")),
        // A coloured form read where the monochrome one is asked for: `vec3(x)` takes it whole.
        (None, Quantity::Reflectance) => field(Quantity::ReflectanceColor)
            .map_or_else(|| default.to_string(), |field| format!("texel.{field}")),
        (None, Quantity::DiffuseOcclusion) => field(Quantity::DiffuseOcclusionColor)
            .map_or_else(|| default.to_string(), |field| format!("texel.{field}")),
        (None, _) => default.to_string(),
    }
}

/// The asset path from which Bevy derives the module path `module_path` (`gbuffer::<snake>`):
/// `embedded://gbuffer/<snake>.wesl`; an embedded asset's path, as Bevy's own modules have.
pub fn asset_path(module_path: &str) -> String {
    format!("embedded://{}.wesl", module_path.replace("::", "/"))
}

/// The module's text for `layout`, each field holding its quantity in `mapping`
/// ([`crate::quantity::map_fields`]); it imports the layout's WESL module.
pub fn deferred_functions_wesl(layout: &Layout, mapping: &[(String, Quantity)]) -> String {
    let symbols = layout.symbols();
    let (name, words) = (symbols.texel(), layout.words());
    let (pack, unpack) = (symbols.pack(), symbols.unpack());
    let (mut prepare, mut stores, mut reads) = (String::new(), String::new(), String::new());
    for (field, quantity) in mapping {
        prepare.push_str(prepared(*quantity));
        let _ = writeln!(stores, "    texel.{field} = {};", stored(*quantity));
        reads.push_str(&read_back(*quantity, field));
    }
    let helpers = if holds(mapping, Quantity::AnisotropyTangent) {
        ORTHONORMAL_TANGENT
    } else {
        ""
    };
    let packed: Vec<String> = (0..4)
        .map(|word| {
            if word < words {
                format!("words[{word}]")
            } else {
                "0u".to_string()
            }
        })
        .collect();
    let channels = ["gbuffer.r", "gbuffer.g", "gbuffer.b", "gbuffer.a"];
    format!(
        "// Generated by gbuffer-bevy: Bevy's deferred G-buffer functions, with the G-buffer
// stored in the layout `{name}` ({bits} bits).
{IMPORTS}
// The layout's texel and its pack and unpack, from the module gbuffer generates for it.
import {module}::{{{name}, {pack}, {unpack}}};
{helpers}
// Creates the deferred G-buffer from a PbrInput: Bevy's quantities, packed as `{name}`.
fn deferred_gbuffer_from_pbr_input(in: PbrInput) -> vec4<u32> {{
    // Monochrome occlusion and reflectance, by Rec. 709 luminance, as Bevy stores them.
    let rec_709_coeffs = vec3<f32>(0.2126, 0.7152, 0.0722);
    let diffuse_occlusion = dot(in.diffuse_occlusion, rec_709_coeffs);
    let reflectance = dot(in.material.reflectance, rec_709_coeffs);
    let flags = deferred_types::deferred_flags_from_mesh_material_flags(in.flags, in.material.flags);
    var base_color_gamma = vec3(0.0);
    var emissive = in.material.emissive.rgb;
    if ((in.material.flags & STANDARD_MATERIAL_FLAGS_UNLIT_BIT) != 0u) {{
        // Unlit: the colour travels in the emissive slot.
        emissive = in.material.base_color.rgb;
    }} else {{
        base_color_gamma = pow(in.material.base_color.rgb, vec3(1.0 / 2.2));
    }}
    // The light map's light, times the diffuse colour, as Bevy adds it to the emissive.
    let diffuse_color = pbr_functions::calculate_diffuse_color(
        in.material.base_color.rgb,
        in.material.metallic,
        in.material.specular_transmission,
        in.material.diffuse_transmission,
    );
    emissive += in.lightmap_light * diffuse_color * view.exposure;
{prepare}
    var texel: {name};
{stores}    let words = {pack}(texel);
    return vec4<u32>({packed});
}}

// Creates a PbrInput from the deferred G-buffer; what `{name}` does not store takes Bevy's
// default.
fn pbr_input_from_deferred_gbuffer(frag_coord: vec4<f32>, gbuffer: vec4<u32>) -> PbrInput {{
    var pbr = pbr_input_new();
    let texel = {unpack}(array<u32, {words}>({channels}));

    let deferred_flags = deferred_types::mesh_material_flags_from_deferred_flags({flags});
    pbr.flags = deferred_flags.x;
    pbr.material.flags = deferred_flags.y;

    pbr.material.perceptual_roughness = {roughness};
    let emissive = {emissive};
    if ((pbr.material.flags & STANDARD_MATERIAL_FLAGS_UNLIT_BIT) != 0u) {{
        pbr.material.base_color = vec4(emissive, 1.0);
        pbr.material.emissive = vec4(vec3(0.0), 0.0);
    }} else {{
        pbr.material.base_color = vec4(pow({base_color}, vec3(2.2)), 1.0);
        pbr.material.emissive = vec4(emissive, 0.0);
    }}
    pbr.material.reflectance = vec3({reflectance});
    pbr.material.metallic = {metallic};
    pbr.material.clearcoat = {clearcoat};
    pbr.material.clearcoat_perceptual_roughness = {clearcoat_roughness};
    pbr.diffuse_occlusion = vec3({occlusion});

    let N = normalize(texel.{normal});
    let world_position = vec4(position_ndc_to_world(frag_coord_to_ndc(frag_coord)), 1.0);
    let is_orthographic = view.clip_from_view[3].w == 1.0;
    let V = pbr_functions::calculate_view(world_position, is_orthographic);

    pbr.frag_coord = frag_coord;
    pbr.world_normal = N;
    pbr.world_position = world_position;
    pbr.N = N;
    pbr.V = V;
    pbr.clearcoat_N = N;
    pbr.is_orthographic = is_orthographic;
{reads}    return pbr;
}}

{DEFERRED_OUTPUT}",
        bits = layout.bits(),
        module = symbols.module_path(),
        packed = packed.join(", "),
        channels = channels[..words].join(", "),
        flags = read(mapping, Quantity::Flags, "0u"),
        roughness = read(mapping, Quantity::PerceptualRoughness, "pbr.material.perceptual_roughness"),
        emissive = read(mapping, Quantity::Emissive, "vec3(0.0)"),
        base_color = read(mapping, Quantity::BaseColor, "vec3(1.0)"),
        reflectance = read(mapping, Quantity::Reflectance, "pbr.material.reflectance.r"),
        metallic = read(mapping, Quantity::Metallic, "pbr.material.metallic"),
        clearcoat = read(mapping, Quantity::Clearcoat, "pbr.material.clearcoat"),
        clearcoat_roughness = read(
            mapping,
            Quantity::ClearcoatPerceptualRoughness,
            "pbr.material.clearcoat_perceptual_roughness",
        ),
        occlusion = read(mapping, Quantity::DiffuseOcclusion, "pbr.diffuse_occlusion.r"),
        normal = field_of(mapping, Quantity::Normal).unwrap_or("normal"),
    )
}
