//! The whole layouts' rows: every seed and engine layout's displayed colour through its
//! convention's round trip, against the unquantised surface.

use gbuffer_core::Layout;
use gbuffer_render::conventions::seed::{
    round_trip, Shading, Surface, SurfaceConvention, LIGHT_SCALE, SURFACE_WGSL,
};
use gbuffer_shading::{mirror as m, reference as r};
use glam::{DVec3, Vec2, Vec3};

use gbuffer_gpu::values::halton;

use super::{wgsl, Accumulator, Row};

/// The light the texel shows: the stored light plus a white sun, tone mapped and encoded as
/// sRGB, in 8-bit steps: what the error of a layout looks like on screen.
fn displayed(shading: &Shading) -> DVec3 {
    let view = DVec3::new(0.0, 0.6, 0.8);
    let sun = DVec3::new(0.3, -0.4, 0.866).normalize();
    let normal = shading.normal.as_dvec3().normalize();
    let roughness = f64::from(shading.roughness);
    // The split-sum albedo the diffuse term is scaled by, as a renderer's LUT gives it.
    let env_brdf =
        r::environment::integrate_env_brdf(roughness.max(0.045), normal.dot(view).max(1e-4), 64);
    let shaded = r::shading::shade_directional(
        normal,
        view,
        sun,
        DVec3::splat(3.0),
        shading.diffuse.as_dvec3(),
        shading.f0.as_dvec3(),
        roughness,
        env_brdf,
    );
    r::colour::linear_to_srgb(r::tonemap::tonemap_reinhard(
        shaded + shading.light.as_dvec3(),
    )) * 255.0
}

/// The surfaces the layouts store: normals facing the viewer, roughness, metallic 0 or 1, base
/// colour and stored light below the seed layouts' light scale, spread by Halton sequences.
fn surfaces() -> Vec<Surface> {
    (1..=1u32 << 14)
        .map(|index| {
            let direction = |a: f64, b: f64| {
                let z = a; // upper hemisphere facing the viewer
                let angle = std::f64::consts::TAU * b;
                let radius = (1.0 - z * z).sqrt();
                DVec3::new(radius * angle.cos(), radius * angle.sin(), z).as_vec3()
            };
            let metallic = if index % 3 == 0 { 1.0 } else { 0.0 };
            Surface {
                normal: direction(halton(index, 2), halton(index, 3)),
                roughness: halton(index, 5) as f32,
                metallic,
                base_colour: Vec3::new(
                    halton(index, 7) as f32,
                    halton(index, 11) as f32,
                    halton(index, 13) as f32,
                ),
                light: Vec3::new(
                    halton(index, 17) as f32,
                    halton(index, 19) as f32,
                    halton(index, 23) as f32,
                ) * LIGHT_SCALE,
                distance: 0.5,
                position: Vec3::new(1.0, 2.0, 3.0),
            }
        })
        .collect()
}

/// A layout's row: its name, model, WGSL, bits and the Rust mirror of its convention.
struct LayoutRow {
    name: &'static str,
    layout: Layout,
    wgsl: &'static str,
    decode_wgsl: &'static str,
    bits: u32,
    round_trip: fn(&Surface) -> Shading,
}

impl LayoutRow {
    fn of<L: SurfaceConvention>(name: &'static str) -> LayoutRow {
        LayoutRow {
            name,
            layout: L::layout(),
            wgsl: L::WGSL,
            decode_wgsl: L::DECODE_WGSL,
            bits: L::BITS,
            round_trip: round_trip::<L>,
        }
    }
}

pub(crate) fn layout_rows() -> Vec<Row> {
    use gbuffer_render::coarse::CoarseNormals;
    use gbuffer_runtime::engine_layouts::{BevyDeferred, HdrpLit};
    use gbuffer_runtime::seed_layouts::{
        ArmTileBlock, FutureMetallic, FutureSpecular, MobileMetallic,
    };
    // Each layout by its own convention (`gbuffer_render::conventions::seed`,
    // `gbuffer_render::conventions::engine`), as the renderer stores it.
    let layouts = [
        LayoutRow::of::<MobileMetallic>("Listing 2.2 (MobileMetallic)"),
        LayoutRow::of::<ArmTileBlock>("Arm tile block (ArmTileBlock)"),
        LayoutRow::of::<FutureMetallic>("Listing 2.7 (FutureMetallic)"),
        LayoutRow::of::<FutureSpecular>("Listing 2.8 (FutureSpecular)"),
        LayoutRow::of::<BevyDeferred>("Bevy, WebGL2 (BevyDeferred)"),
        LayoutRow::of::<HdrpLit>("HDRP Lit (HdrpLit)"),
        LayoutRow::of::<CoarseNormals>("2 x 8-bit normals (CoarseNormals)"),
    ];
    let surfaces = surfaces();
    layouts
        .into_iter()
        .map(|seed| {
            let round_trip = seed.round_trip;
            let mut errors = Accumulator::default();
            for surface in &surfaces {
                let difference =
                    displayed(&round_trip(surface)) - displayed(&Shading::of(surface));
                errors.add(difference.abs().max_element());
            }
            let unpack = seed.layout.symbols().unpack();
            let words = seed.layout.words();
            // The words come from the input's bits: the cost measured is unpack, decode, shade.
            let lanes: Vec<String> = (0..words).map(|word| format!("bitcast<u32>(x[{}]) ^ {word}u", word % 4)).collect();
            let body = format!(
                "{layout_wgsl}\n{SURFACE_WGSL}\n{decode_wgsl}\n\n\
                 fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n\
                 \x20   let s = decode_texel({unpack}(array<u32, {words}>({lanes})));\n\
                 \x20   let shaded = shade_directional(s.normal, vec3<f32>(0.0, 0.6, 0.8), vec3<f32>(0.3, -0.4, 0.866), vec3<f32>(3.0), s.diffuse, s.f0, s.roughness, vec2<f32>(0.6, 0.1));\n\
                 \x20   return vec4<f32>(linear_to_srgb(tonemap_reinhard(shaded + s.light)), x.w);\n\
                 }}\n",
                layout_wgsl = seed.wgsl,
                decode_wgsl = seed.decode_wgsl,
                lanes = lanes.join(", "),
            );
            Row {
                family: "whole layout",
                name: seed.name.to_string(),
                bits: Some(seed.bits),
                domain: format!("16384 surfaces (normals facing the viewer, roughness, metallic 0/1, base colour, stored light < {LIGHT_SCALE}), sun and stored light, Reinhard, sRGB"),
                unit: "8-bit sRGB steps",
                errors: errors.finish(),
                wgsl: wgsl(&["shading", "material", "colour", "tonemap", "normals", "hdr", "constants"], &body),
                lut_size: None,
                cpu: Box::new(move |x| {
                    let surface = Surface {
                        normal: (x.truncate() * 2.0 - Vec3::splat(0.999)).normalize(),
                        roughness: x.w,
                        metallic: x.z,
                        base_colour: Vec3::splat(x.y),
                        light: Vec3::splat(x.x),
                        ..Surface::default()
                    };
                    let s = round_trip(&surface);
                    let shaded = m::shading::shade_directional(s.normal, Vec3::new(0.0, 0.6, 0.8), Vec3::new(0.3, -0.4, 0.866), Vec3::splat(3.0), s.diffuse, s.f0, s.roughness, Vec2::new(0.6, 0.1));
                    m::colour::linear_to_srgb(m::tonemap::tonemap_reinhard(shaded + s.light)).extend(x.w)
                }),
                plot: None,
            }
        })
        .collect()
}
