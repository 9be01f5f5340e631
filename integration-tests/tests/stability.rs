//! Numerical stability at the extremes, in f32 on the CPU and on the adapter, and in f16 for
//! the mobile forms (`shading::half_precision` on the CPU, `mobile_half.wgsl` on an adapter
//! with SHADER_F16).
//!
//! The extremes: roughness 0, 1e-4, the documented minimum and 1; n.v and n.l of -1, 0, 1e-7
//! and 1; HDR values up to and past each format's largest; denormals; NaN and infinities.
//! Finite input in a function's domain must give finite output in its physical range; the
//! composites, which clamp (MIN_ROUGHNESS, MIN_N_DOT_V, the diffuse share, the fit's dip
//! below 0; in f16 MIN_ROUGHNESS_HALF, MIN_N_DOT_V_HALF, MAX_RADIANCE_HALF), must stay finite
//! for any finite input, and each clamp is shown to be needed.

use gbuffer::glam::{DVec3, Vec3};
use gbuffer::layout::{Encoding, Format, ScalarKind};
use gbuffer_core::Named;
use gbuffer_gpu::values::{float_edges, sint_edges, uint_edges};
use gbuffer_shading::half_precision::{self as h, Half, Half3};
use gbuffer_shading::mirror as m;
use gbuffer_testkit::shading_cases::{
    cases, compute_harness, output_components, Argument, Case, Output,
};

/// Edge values of an argument's domain, each as its components' bits.
fn edges(argument: Argument) -> Vec<Vec<u32>> {
    let bits = |values: &[f32]| {
        values
            .iter()
            .map(|value| value.to_bits())
            .collect::<Vec<u32>>()
    };
    match argument {
        Argument::Scalar { low, high } => {
            let mut values = vec![
                low,
                f32::from_bits(low.to_bits() + 1),
                (low + high) / 2.0,
                high,
            ];
            if low == 0.0 {
                values.extend([1e-40, 1e-7]);
            }
            values.iter().map(|&value| bits(&[value])).collect()
        }
        Argument::Colour { scale } => {
            let mut colours = vec![
                [0.0; 3],
                [1e-40; 3],
                [scale; 3],
                [scale, 0.0, 0.0],
                [0.0, 1e-7, scale],
            ];
            if scale >= 6.0 {
                colours.push([65504.0; 3]);
            }
            colours.iter().map(|colour| bits(colour)).collect()
        }
        Argument::Pair { low, high } => [
            [low, low],
            [low, high],
            [high, low],
            [high, high],
            [(low + high) / 2.0, high],
        ]
        .iter()
        .map(|pair| bits(pair))
        .collect(),
        Argument::Direction => extreme_directions()
            .iter()
            .map(|direction| bits(&direction.to_array()))
            .collect(),
        Argument::Tangent => extreme_directions()
            .iter()
            .flat_map(|direction| [1.0, -1.0].map(|sign| bits(&direction.extend(sign).to_array())))
            .collect(),
        Argument::Rgbm => argument.samples(16),
        Argument::Unsigned { low, high } => vec![vec![low], vec![high]],
    }
}

/// Axis directions both ways, a diagonal, and directions grazing a plane at 1e-7.
fn extreme_directions() -> Vec<Vec3> {
    vec![
        Vec3::X,
        -Vec3::X,
        Vec3::Y,
        -Vec3::Y,
        Vec3::Z,
        -Vec3::Z,
        Vec3::ONE.normalize(),
        Vec3::new(1.0, 0.0, 1e-7).normalize(),
        Vec3::new(0.0, -1.0, 1e-7).normalize(),
    ]
}

/// Every combination of the arguments' edges, thinned evenly to at most `limit` points.
fn edge_grid(case: &Case, limit: usize) -> Vec<Vec<u32>> {
    let mut points: Vec<Vec<u32>> = vec![Vec::new()];
    for &argument in case.arguments {
        let values = edges(argument);
        points = points
            .iter()
            .flat_map(|point| {
                values
                    .iter()
                    .map(move |value| [point.clone(), value.clone()].concat())
            })
            .collect();
    }
    let step = points.len().div_ceil(limit);
    points.into_iter().step_by(step).collect()
}

/// The physical range of a function's outputs (for finite input in its domain).
fn physical_range(name: &str) -> (f32, f32) {
    match name {
        "srgb_to_linear"
        | "linear_to_srgb"
        | "gamma_2_2_to_linear"
        | "linear_to_gamma_2_2"
        | "pseudo_gamma_to_linear"
        | "linear_to_pseudo_gamma" => (0.0, 1.0),
        "rgbm_encode"
        | "rgbm_squared_encode"
        | "scale_hdr_to_unit"
        | "f_schlick"
        | "f_schlick_roughness"
        | "hammersley"
        | "normal_to_unorm" => (0.0, 1.0),
        "metallic_workflow"
        | "specular_workflow"
        | "tonemap_reinhard"
        | "tonemap_aces_fitted"
        | "diffuse_share" => (0.0, 1.0),
        "lambert_diffuse" => (0.0, std::f32::consts::FRAC_1_PI * 1.000_001),
        "dielectric_f0_from_specular" => (0.0, 0.08),
        "rgb9e5_decode" => (0.0, 65408.0),
        // The fit dips to -0.0024 at f0 = 0 and full roughness (Karis's 0.4524 f0 - 0.0024).
        "env_brdf_approx" | "env_brdf_approx_nonmetal" => (-0.0025, 1.05),
        // A quasi-Monte Carlo estimate: its excess over 1 is the integration error.
        "integrate_env_brdf" => (0.0, 1.001),
        "importance_sample_ggx"
        | "octahedral_encode"
        | "octahedral_decode"
        | "unorm_to_normal"
        | "reconstruct_tangent_z"
        | "tangent_to_world"
        | "half_vector_of" => (-1.0, 1.0),
        _ => (0.0, f32::INFINITY),
    }
}

/// Whether a point lies outside the function's documented domain, where it may be non-finite.
fn outside_domain(case: &Case, point: &[u32]) -> bool {
    let value = |index: usize| f32::from_bits(point[index]);
    match case.name() {
        // A zero result vector has no direction.
        "tangent_to_world" => {
            let (tangent_normal, normal) = (
                Vec3::new(value(0), value(1), value(2)),
                Vec3::new(value(3), value(4), value(5)),
            );
            let tangent = Vec3::new(value(6), value(7), value(8));
            let bitangent = normal.cross(tangent) * value(9);
            (tangent * tangent_normal.x + bitangent * tangent_normal.y + normal * tangent_normal.z)
                .length()
                < 1e-3
        }
        "unorm_to_normal" => {
            (Vec3::new(value(0), value(1), value(2)) * 2.0 - Vec3::ONE).length() < 1e-3
        }
        // pow of a denormal underflows in f32 on some paths; the domain is [0, 1] anyway.
        _ => false,
    }
}

fn check_outputs(
    case: &Case,
    point: &[u32],
    outputs: &[u32],
    place: &str,
    failures: &mut Vec<String>,
) {
    if case.output == Output::Unsigned || outside_domain(case, point) {
        return;
    }
    let (low, high) = physical_range(case.name());
    for &bits in outputs {
        let value = f32::from_bits(bits);
        if !value.is_finite() || value < low || value > high {
            let arguments: Vec<f32> = point.iter().map(|&bits| f32::from_bits(bits)).collect();
            failures.push(format!(
                "{place}: {} at {arguments:?} gives {value} (range {low}..{high})",
                case.call
            ));
            return;
        }
    }
}

#[test]
fn every_function_is_finite_and_in_range_at_its_domain_edges_on_cpu_and_adapter() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let mut failures = Vec::new();
    for case in cases() {
        let points = edge_grid(&case, 20_000);
        let components = output_components(&case);
        let inputs: Vec<u32> = points.iter().flatten().copied().collect();
        let adapter = gpu
            .run_compute(
                &compute_harness(&case),
                "harness_main",
                &inputs,
                &[points.len() * components],
                points.len() as u32,
            )
            .expect("the adapter runs the harness");
        for (index, point) in points.iter().enumerate() {
            check_outputs(&case, point, &(case.mirror)(point), "CPU", &mut failures);
            check_outputs(
                &case,
                point,
                &adapter[0][index * components..][..components],
                "adapter",
                &mut failures,
            );
        }
    }
    failures.truncate(20);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The extreme surfaces for the composites: roughness 0 to 1, n.v and n.l from -1 to 1 with
/// 1e-7, and colours up to f16's largest.
fn composite_extremes() -> Vec<(Vec3, Vec3, Vec3, f32, Vec3)> {
    let cosines = [-1.0f32, 0.0, 1e-7, 1.0];
    let direction = |cosine: f32, azimuth: f32| {
        let sine = (1.0 - cosine * cosine).max(0.0).sqrt();
        Vec3::new(sine * azimuth.cos(), sine * azimuth.sin(), cosine)
    };
    let mut extremes = Vec::new();
    for n_dot_v in cosines {
        for n_dot_l in cosines {
            for roughness in [0.0, 1e-4, m::constants::MIN_ROUGHNESS, 1.0] {
                for colour in [Vec3::ZERO, Vec3::ONE, Vec3::splat(65504.0)] {
                    extremes.push((
                        direction(n_dot_v, 0.0),
                        direction(n_dot_l, 0.0),
                        direction(n_dot_l, 2.0),
                        roughness,
                        colour,
                    ));
                }
            }
        }
    }
    extremes
}

#[test]
fn composites_stay_finite_for_any_finite_input_and_their_clamps_are_needed() {
    for (view, light, other_light, roughness, colour) in composite_extremes() {
        for light in [light, other_light] {
            let accurate = m::shading::shade_directional(
                Vec3::Z,
                view,
                light,
                colour,
                Vec3::ONE,
                Vec3::splat(0.04),
                roughness,
                gbuffer::glam::Vec2::new(0.9, 0.05),
            );
            let mobile = m::shading::shade_directional_mobile(
                Vec3::Z,
                view,
                light,
                colour,
                Vec3::ONE,
                Vec3::splat(0.04),
                roughness,
            );
            let ibl = m::shading::shade_ibl_mobile(
                Vec3::ONE,
                Vec3::ZERO,
                roughness,
                view.z,
                colour,
                colour,
            );
            for (name, value) in [
                ("shade_directional", accurate),
                ("shade_directional_mobile", mobile),
                ("shade_ibl_mobile", ibl),
            ] {
                assert!(value.is_finite() && value.cmpge(Vec3::ZERO).all(), "{name}: view {view}, light {light}, roughness {roughness}, colour {colour}: {value}");
            }
        }
    }
    // Without MIN_ROUGHNESS and MIN_N_DOT_V the terms they guard are not finite.
    assert!(
        m::microfacet::d_ggx(1.0, 0.0).is_nan(),
        "GGX at roughness 0 facing the light is 0 / 0"
    );
    assert!(
        (Vec3::Z + -Vec3::Z).normalize().is_nan(),
        "the half vector of opposite view and light"
    );
    assert!(
        m::microfacet::v_smith_ggx_correlated(0.0, 0.0, 0.5).is_infinite(),
        "visibility at n.v = n.l = 0 divides by 0"
    );
    assert!(
        m::mobile::d_approx(0.0, 1.0).is_nan(),
        "D_Approx at roughness 0 is infinity times 0"
    );
    // And the fit's dip below 0, clamped in the composites, is there in the function itself.
    assert!(m::mobile::env_brdf_approx(Vec3::ZERO, 1.0, 1.0).x < 0.0);
}

#[test]
fn composites_stay_finite_on_the_adapter() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let case = cases()
        .into_iter()
        .find(|case| case.name() == "shade_directional_mobile")
        .expect("the mobile composite has a case");
    let points: Vec<Vec<u32>> = composite_extremes()
        .into_iter()
        .map(|(view, light, _, roughness, colour)| {
            [Vec3::Z, view, light, colour, Vec3::ONE, Vec3::splat(0.04)]
                .iter()
                .flat_map(|vector| vector.to_array())
                .chain([roughness])
                .map(f32::to_bits)
                .collect()
        })
        .collect();
    let inputs: Vec<u32> = points.iter().flatten().copied().collect();
    let outputs = gpu
        .run_compute(
            &compute_harness(&case),
            "harness_main",
            &inputs,
            &[points.len() * 3],
            points.len() as u32,
        )
        .expect("the adapter runs the harness");
    for (index, value) in outputs[0].chunks(3).enumerate() {
        let value = Vec3::from_array([value[0], value[1], value[2]].map(f32::from_bits));
        assert!(
            value.is_finite() && value.cmpge(Vec3::ZERO).all(),
            "point {index}: {value}"
        );
    }
}

#[test]
fn packing_gives_finite_output_in_the_formats_range_for_finite_input() {
    for &format in Format::ALL {
        match format.scalar_kind() {
            ScalarKind::Float => {
                for value in float_edges().into_iter().filter(|value| value.is_finite()) {
                    let decoded = format.decode::<f32>(format.encode([value; 4]));
                    for (decoded, channel) in decoded.iter().zip(format.channels()) {
                        let largest = match channel.encoding {
                            Encoding::Float32 => f32::MAX,
                            Encoding::Half => 65504.0,
                            // 11 bits: 6 of mantissa; 10 bits: 5.
                            Encoding::UnsignedFloat => {
                                if channel.bits == 11 {
                                    65024.0
                                } else {
                                    64512.0
                                }
                            }
                            _ => 1.0,
                        };
                        assert!(
                            decoded.is_finite() && decoded.abs() <= largest,
                            "{format}: {value:e} -> {decoded:e}"
                        );
                    }
                }
            }
            // Integers are always finite: their range is what matters, each channel clamped.
            ScalarKind::Uint => {
                for value in uint_edges() {
                    let decoded = format.decode::<u32>(format.encode([value; 4]));
                    for (decoded, channel) in decoded.iter().zip(format.channels()) {
                        assert_eq!(*decoded, value.min(channel.mask()), "{format}: {value}");
                    }
                }
            }
            ScalarKind::Sint => {
                for value in sint_edges() {
                    let decoded = format.decode::<i32>(format.encode([value; 4]));
                    for (decoded, channel) in decoded.iter().zip(format.channels()) {
                        let highest = (channel.mask() >> 1) as i32;
                        assert_eq!(
                            *decoded,
                            value.clamp(-highest - 1, highest),
                            "{format}: {value}"
                        );
                    }
                }
            }
            ScalarKind::Bool => unreachable!("no format holds booleans"),
        }
    }
}

// ---- half precision ----

/// The half-precision extremes: roughness from 0 (below MIN_ROUGHNESS_HALF) to 1, n.v from -1
/// to 1, colours up to 65504.
fn half_extremes() -> Vec<(Vec3, Vec3, f32, Vec3)> {
    composite_extremes()
        .into_iter()
        .map(|(view, light, _, roughness, colour)| (view, light, roughness, colour))
        .chain([(Vec3::Z, Vec3::Z, 0.065, Vec3::splat(65504.0))])
        .collect()
}

fn half_mobile(view: Vec3, light: Vec3, roughness: f32, colour: Vec3) -> Half3 {
    let half = h::half3;
    h::shade_directional_mobile_half(
        half(Vec3::Z),
        half(view),
        half(light),
        half(colour),
        half(Vec3::ONE),
        half(Vec3::splat(0.04)),
        Half::new(roughness),
    )
}

#[test]
fn half_precision_forms_stay_finite_on_the_cpu_and_their_clamps_are_needed() {
    let maximum = 65504.0;
    for (view, light, roughness, colour) in half_extremes() {
        let value = half_mobile(view, light, roughness, colour).map(Half::to_f32);
        assert!(
            value
                .iter()
                .all(|channel| channel.is_finite() && (0.0..=maximum).contains(channel)),
            "view {view}, light {light}, roughness {roughness}, colour {colour}: {value:?}"
        );
        for n_dot_v in [-1.0, 0.0, 1e-7, 1.0] {
            let fit = h::env_brdf_approx_half(
                h::half3(Vec3::new(0.0, 0.04, 1.0)),
                Half::new(roughness),
                Half::new(n_dot_v),
            )
            .map(Half::to_f32);
            assert!(
                fit.iter().all(|channel| (-0.0025..=1.05).contains(channel)),
                "{fit:?}"
            );
        }
    }
    // At the f32 form's minimum roughness, D_Approx's 1 / alpha^2 overflows f16.
    let alpha = Half::new(m::constants::MIN_ROUGHNESS) * Half::new(m::constants::MIN_ROUGHNESS);
    assert!(!(Half::ONE / (alpha * alpha)).is_finite());
    // A bright light on a smooth surface passes f16's range unless the radiance saturates.
    let unclamped = Half::new(56_000.0) * Half::new(10.0 * std::f32::consts::FRAC_1_PI);
    assert!(!unclamped.is_finite());
}

#[test]
fn half_precision_forms_run_on_an_f16_adapter_and_agree_with_their_mirror() {
    let Some(gpu) =
        gbuffer_testkit::gpu_with(Some(wgpu::Limits::default()), wgpu::Features::SHADER_F16)
    else {
        return;
    };
    if !gpu.device.features().contains(wgpu::Features::SHADER_F16) {
        eprintln!(
            "{} has no SHADER_F16: the f16 forms were checked on the CPU only",
            gpu.describe()
        );
        return;
    }
    let extremes = half_extremes();
    let library = gbuffer_shading::compose(&["mobile_half"]).unwrap();
    let shader = format!(
        "{library}\n\
         @group(0) @binding(0) var<storage, read> inputs: array<f32>;\n\
         @group(0) @binding(1) var<storage, read_write> outputs: array<f32>;\n\
         @group(0) @binding(2) var<uniform> count: vec4<u32>;\n\
         @compute @workgroup_size(64)\n\
         fn harness_main(@builtin(global_invocation_id) id: vec3<u32>) {{\n\
         \x20   if id.x >= count.x {{ return; }}\n\
         \x20   let base = id.x * 10u;\n\
         \x20   let view = vec3<f16>(vec3<f32>(inputs[base], inputs[base + 1u], inputs[base + 2u]));\n\
         \x20   let light = vec3<f16>(vec3<f32>(inputs[base + 3u], inputs[base + 4u], inputs[base + 5u]));\n\
         \x20   let colour = vec3<f16>(vec3<f32>(inputs[base + 6u], inputs[base + 7u], inputs[base + 8u]));\n\
         \x20   let value = shade_directional_mobile_half(vec3<f16>(0.0h, 0.0h, 1.0h), view, light, colour, vec3<f16>(1.0h), vec3<f16>(0.04h), f16(inputs[base + 9u]));\n\
         \x20   outputs[id.x * 3u] = f32(value.x);\n\
         \x20   outputs[id.x * 3u + 1u] = f32(value.y);\n\
         \x20   outputs[id.x * 3u + 2u] = f32(value.z);\n\
         }}\n"
    );
    let inputs: Vec<u32> = extremes
        .iter()
        .flat_map(|(view, light, roughness, colour)| {
            view.to_array()
                .into_iter()
                .chain(light.to_array())
                .chain(colour.to_array())
                .chain([*roughness])
        })
        .map(f32::to_bits)
        .collect();
    let outputs = gpu
        .run_compute(
            &shader,
            "harness_main",
            &inputs,
            &[extremes.len() * 3],
            extremes.len() as u32,
        )
        .expect("the adapter runs the harness");
    for (index, (view, light, roughness, colour)) in extremes.iter().enumerate() {
        let adapter = Vec3::from_array(
            [0, 1, 2].map(|channel| f32::from_bits(outputs[0][index * 3 + channel])),
        );
        let mirror = DVec3::from_array(
            half_mobile(*view, *light, *roughness, *colour)
                .map(|channel| f64::from(channel.to_f32())),
        );
        assert!(
            adapter.is_finite()
                && adapter.cmpge(Vec3::ZERO).all()
                && adapter.max_element() <= 65504.0,
            "{view} {light} {roughness} {colour}: {adapter}"
        );
        // f16 keeps 11 bits, and the adapter may fuse or widen: agreement to 2^-6 relative.
        let tolerance = 2f64.powi(-6) * mirror.max_element().max(1.0);
        assert!(
            (adapter.as_dvec3() - mirror).abs().max_element() <= tolerance,
            "{view} {light} {roughness} {colour}: adapter {adapter}, mirror {mirror}"
        );
    }
}
