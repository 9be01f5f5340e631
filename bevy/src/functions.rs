//! The module that stands in for Bevy 0.19's `bevy_pbr::pbr_deferred_functions`: the same
//! import path and functions, whose G-buffer is a layout's. `deferred_gbuffer_from_pbr_input`
//! computes Bevy's quantities as Bevy's own does (its Rec. 709 monochrome occlusion and
//! reflectance, the flags, gamma 2.2 base colour, unlit materials' colour in the emissive
//! slot, the light map's light added to the emissive) and packs them with the layout's own
//! `pack_<snake>`, so the words are the Rust mirror's; `pbr_input_from_deferred_gbuffer`
//! unpacks them with `unpack_<snake>` and rebuilds the `PbrInput` as Bevy does, with Bevy's
//! defaults for what the layout does not store. `deferred_output` is Bevy's.

use std::fmt::Write as _;

use gbuffer::layout::Layout;

use crate::quantity::Quantity;

/// The import path the module replaces.
pub const IMPORT_PATH: &str = "bevy_pbr::pbr_deferred_functions";

/// Bevy's imports, as its own module has them.
const IMPORTS: &str = "#import bevy_pbr::{
    pbr_types::{PbrInput, pbr_input_new, STANDARD_MATERIAL_FLAGS_UNLIT_BIT},
    pbr_deferred_types as deferred_types,
    pbr_functions,
    mesh_view_bindings::view,
    prepass_io::FragmentOutput,
    view_transformations::{position_ndc_to_world, frag_coord_to_ndc},
}

#ifdef MESHLET_MESH_MATERIAL_PASS
#import bevy_pbr::meshlet_visibility_buffer_resolve::VertexOutput
#else
#import bevy_pbr::prepass_io::VertexOutput
#endif

#ifdef MOTION_VECTOR_PREPASS
#import bevy_pbr::pbr_prepass_functions::calculate_motion_vector
#endif
";

/// `deferred_output`, as Bevy 0.19 writes the prepass's outputs.
const DEFERRED_OUTPUT: &str = "#ifdef PREPASS_PIPELINE
fn deferred_output(in: VertexOutput, pbr_input: PbrInput) -> FragmentOutput {
    var out: FragmentOutput;
    out.deferred = deferred_gbuffer_from_pbr_input(pbr_input);
    // Which lighting shader runs for the fragment.
    out.deferred_lighting_pass_id = pbr_input.material.deferred_lighting_pass_id;
#ifdef NORMAL_PREPASS
    out.normal = vec4(in.world_normal * 0.5 + vec3(0.5), 1.0);
#endif
#ifdef MOTION_VECTOR_PREPASS
#ifdef MESHLET_MESH_MATERIAL_PASS
    out.motion_vector = in.motion_vector;
#else
    out.motion_vector = calculate_motion_vector(in.world_position, in.previous_world_position);
#endif
#endif
    return out;
}
#endif
";

/// The value each quantity is stored from in `deferred_gbuffer_from_pbr_input`.
fn stored(quantity: Quantity) -> &'static str {
    match quantity {
        Quantity::BaseColor => "base_color_gamma",
        Quantity::BaseColorRoughness => "vec4(base_color_gamma, in.material.perceptual_roughness)",
        Quantity::PerceptualRoughness => "in.material.perceptual_roughness",
        Quantity::Metallic => "in.material.metallic",
        Quantity::Reflectance => "reflectance",
        Quantity::DiffuseOcclusion => "diffuse_occlusion",
        Quantity::Emissive => "emissive",
        Quantity::Normal => "normalize(in.N)",
        Quantity::Flags => "flags",
        Quantity::Clearcoat => "saturate(in.material.clearcoat)",
        Quantity::ClearcoatPerceptualRoughness => {
            "saturate(in.material.clearcoat_perceptual_roughness)"
        }
        Quantity::Depth => "in.frag_coord.z",
    }
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
        (None, _) => default.to_string(),
    }
}

/// The module's text for `layout` (whose WGSL is `layout_wgsl`), each field holding its
/// quantity in `mapping` ([`crate::quantity::map_fields`]).
pub fn deferred_functions_wgsl(
    layout: &Layout,
    layout_wgsl: &str,
    mapping: &[(String, Quantity)],
) -> String {
    let (name, snake, words) = (&layout.name, layout.snake_name(), layout.words());
    let mut stores = String::new();
    for (field, quantity) in mapping {
        let _ = writeln!(stores, "    texel.{field} = {};", stored(*quantity));
    }
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
#define_import_path {IMPORT_PATH}

{IMPORTS}
// The layout, as gbuffer generates it.
{layout_wgsl}

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

    var texel: {name};
{stores}    let words = pack_{snake}(texel);
    return vec4<u32>({packed});
}}

// Creates a PbrInput from the deferred G-buffer; what `{name}` does not store takes Bevy's
// default.
fn pbr_input_from_deferred_gbuffer(frag_coord: vec4<f32>, gbuffer: vec4<u32>) -> PbrInput {{
    var pbr = pbr_input_new();
    let texel = unpack_{snake}(array<u32, {words}>({channels}));

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
    return pbr;
}}

{DEFERRED_OUTPUT}",
        bits = layout.bits(),
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
