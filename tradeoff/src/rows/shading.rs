//! The shading approximations' rows: the environment BRDF (LUT sizes and the analytic fit),
//! the specular lobe and the visibility term, each against the f64 reference.

use gbuffer_shading::env_brdf_lut::EnvBrdfLut;
use gbuffer_shading::{mirror as m, reference as r};
use glam::{DVec3, Vec3, Vec4};

use super::{wgsl, Accumulator, Row};
use crate::plot::Plot;

// ---- environment BRDF ----

const ENV_GRID: usize = 64;
const ENV_SAMPLES: u32 = 1024;

/// The reference split-sum (scale, bias) at the centre of cell (row: roughness, column: n.v).
fn env_reference() -> Vec<[f64; 2]> {
    (0..ENV_GRID * ENV_GRID)
        .map(|cell| {
            let (roughness, n_dot_v) = env_cell(cell);
            r::environment::integrate_env_brdf(roughness, n_dot_v, ENV_SAMPLES).to_array()
        })
        .collect()
}

fn env_cell(cell: usize) -> (f64, f64) {
    let centre = |index: usize| (index as f64 + 0.5) / ENV_GRID as f64;
    (centre(cell / ENV_GRID), centre(cell % ENV_GRID))
}

type EnvApproximation = Box<dyn Fn(f32, f32, f32) -> f32>;

/// An environment BRDF row: its name, the f0 values it covers, whether it holds for roughness 1
/// only, its CPU form, the WGSL of its reflectance and the LUT size it samples.
type EnvForm = (
    &'static str,
    &'static [f32],
    bool,
    EnvApproximation,
    &'static str,
    Option<usize>,
);

/// A lobe evaluated at (n.h, r.l, roughness).
type Lobe = fn(f32, f32, f32) -> f64;

/// A visibility form at (n.v, n.l, roughness).
type Visibility = fn(f32, f32, f32) -> f32;

pub(super) fn env_brdf_rows() -> Vec<Row> {
    let reference = env_reference();
    let lut_16 = EnvBrdfLut::bake(16, ENV_SAMPLES);
    let lut_32 = EnvBrdfLut::bake(32, ENV_SAMPLES);
    let lut_row = |lut: EnvBrdfLut| -> EnvApproximation {
        Box::new(move |f0, roughness, n_dot_v| {
            let scale_bias = lut.sample(roughness, n_dot_v);
            f0 * scale_bias.x + scale_bias.y
        })
    };
    // (name, f0 values, roughness fixed to 1?, approximation, WGSL of the reflectance, LUT size)
    let approximations: Vec<EnvForm> = vec![
        (
            "LUT 16x16, bilinear",
            &[0.04, 1.0],
            false,
            lut_row(lut_16),
            "lut_reflectance(f0, roughness, n_dot_v)",
            Some(16),
        ),
        (
            "LUT 32x32, bilinear",
            &[0.04, 1.0],
            false,
            lut_row(lut_32),
            "lut_reflectance(f0, roughness, n_dot_v)",
            Some(32),
        ),
        (
            "env_brdf_approx",
            &[0.04, 1.0],
            false,
            Box::new(|f0, roughness, n_dot_v| {
                m::mobile::env_brdf_approx(Vec3::splat(f0), roughness, n_dot_v).x
            }),
            "env_brdf_approx(vec3<f32>(f0), roughness, n_dot_v).x",
            None,
        ),
        (
            "env_brdf_approx_nonmetal",
            &[0.04],
            false,
            Box::new(|_, roughness, n_dot_v| {
                m::mobile::env_brdf_approx_nonmetal(roughness, n_dot_v)
            }),
            "env_brdf_approx_nonmetal(roughness, n_dot_v)",
            None,
        ),
        (
            "fully rough (0.45 f0)",
            &[0.04, 1.0],
            true,
            Box::new(|f0, _, _| 0.45 * f0),
            "0.45 * f0",
            None,
        ),
    ];
    approximations
        .into_iter()
        .map(|(name, f0s, fully_rough, approximate, reflectance, lut_size)| {
            let mut errors = Accumulator::default();
            let mut map = vec![0.0; ENV_GRID * ENV_GRID];
            for (cell, [scale, bias]) in reference.iter().enumerate() {
                let (roughness, n_dot_v) = env_cell(cell);
                if fully_rough && cell / ENV_GRID != ENV_GRID - 1 {
                    continue; // the shortcut is for roughness 1: the top row of the grid
                }
                for &f0 in f0s {
                    let exact = f64::from(f0) * scale + bias;
                    let error = (f64::from(approximate(f0, roughness as f32, n_dot_v as f32)) - exact).abs();
                    errors.add(error);
                    map[cell] = f64::max(map[cell], error);
                }
            }
            let lut_function = "fn lut_reflectance(f0: f32, roughness: f32, n_dot_v: f32) -> f32 {\n    let scale_bias = textureSampleLevel(lut_texture, lut_sampler, vec2<f32>(n_dot_v, roughness), 0.0).xy;\n    return f0 * scale_bias.x + scale_bias.y;\n}\n";
            let body = format!(
                "{}fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    let f0 = x.z;\n    let roughness = x.x;\n    let n_dot_v = max(x.y, 0.01);\n    return vec4<f32>({reflectance}, x.yzw);\n}}\n",
                if lut_size.is_some() { lut_function } else { "" }
            );
            let domain = if fully_rough {
                "roughness 1, n.v in (0, 1] (64 cells), f0 in {0.04, 1}".to_string()
            } else if f0s.len() == 1 {
                "roughness x n.v in (0, 1]^2 (64x64 cell centres), f0 0.04".to_string()
            } else {
                "roughness x n.v in (0, 1]^2 (64x64 cell centres), f0 in {0.04, 1}".to_string()
            };
            let plot = (name == "env_brdf_approx").then_some(Plot::Heatmap { width: ENV_GRID, height: ENV_GRID, values: map, x_label: "n.v", y_label: "roughness" });
            Row {
                family: "environment BRDF",
                name: name.to_string(),
                bits: None,
                domain,
                unit: "absolute",
                errors: errors.finish(),
                wgsl: wgsl(&["mobile"], &body),
                lut_size,
                cpu: Box::new(move |x| Vec4::new(approximate(x.z, x.x, x.y.max(0.01)), x.y, x.z, x.w)),
                plot,
            }
        })
        .collect()
}

// ---- specular lobe ----

pub(super) fn specular_lobe_rows() -> Vec<Row> {
    const GRID: usize = 64;
    const ANGLES: usize = 256;
    let lobes: [(&str, Lobe, &str); 2] = [
        (
            "GGX (f32)",
            |n_dot_h, _, roughness| f64::from(m::microfacet::d_ggx(n_dot_h, roughness)),
            "d_ggx(n_dot_h, roughness)",
        ),
        (
            "d_approx (spherical Gaussian)",
            |_, r_dot_l, roughness| {
                f64::from(m::mobile::d_approx(roughness, r_dot_l)) / std::f64::consts::PI
            },
            "d_approx(roughness, r_dot_l) * INV_PI",
        ),
    ];
    lobes
        .into_iter()
        .map(|(name, lobe, expression)| {
            let mut errors = Accumulator::default();
            let mut map = vec![0.0f64; GRID * GRID];
            for (cell, worst) in map.iter_mut().enumerate() {
                let roughness = 0.1 + 0.9 * (cell / GRID) as f64 / (GRID - 1) as f64;
                let n_dot_v = 0.05 + 0.95 * (cell % GRID) as f64 / (GRID - 1) as f64;
                let view = DVec3::new((1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v);
                let reflected = DVec3::new(-view.x, 0.0, view.z);
                // The lobe over light directions in the plane of incidence, against the GGX
                // peak at this view.
                let samples: Vec<(f64, f64)> = (0..ANGLES)
                    .map(|index| {
                        let angle = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * (index as f64 + 0.5) / ANGLES as f64;
                        let light = DVec3::new(angle.sin(), 0.0, angle.cos());
                        let half = (view + light).normalize();
                        let exact = r::microfacet::d_ggx(half.z, roughness);
                        (exact, lobe(half.z as f32, reflected.dot(light) as f32, roughness as f32))
                    })
                    .collect();
                let peak = samples.iter().map(|(exact, _)| *exact).fold(0.0, f64::max);
                for (exact, approximate) in samples {
                    let error = (approximate - exact).abs() / peak;
                    errors.add(error);
                    *worst = f64::max(*worst, error);
                }
            }
            let body = format!(
                "fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    let roughness = 0.1 + 0.9 * x.x;\n    let n_dot_h = x.y;\n    let r_dot_l = x.z;\n    return vec4<f32>({expression}, x.yzw);\n}}\n"
            );
            let plot = name.starts_with("d_approx").then_some(Plot::Heatmap { width: GRID, height: GRID, values: map, x_label: "n.v", y_label: "roughness" });
            Row {
                family: "specular lobe",
                name: name.to_string(),
                bits: None,
                domain: "roughness [0.1, 1] x n.v [0.05, 1] (64x64), light over the plane of incidence".into(),
                unit: "relative to the GGX peak",
                errors: errors.finish(),
                wgsl: wgsl(&["constants", "microfacet", "mobile"], &body),
                lut_size: None,
                cpu: Box::new(move |x| Vec4::new(lobe(x.y, x.z, 0.1 + 0.9 * x.x) as f32, x.y, x.z, x.w)),
                plot,
            }
        })
        .collect()
}

// ---- visibility ----

pub(super) fn visibility_rows() -> Vec<Row> {
    const GRID: usize = 32;
    let forms: [(&str, Visibility, &str); 2] = [
        (
            "height-correlated Smith (f32)",
            m::microfacet::v_smith_ggx_correlated,
            "v_smith_ggx_correlated",
        ),
        (
            "separable Schlick-GGX",
            m::microfacet::v_schlick_ggx,
            "v_schlick_ggx",
        ),
    ];
    forms
        .into_iter()
        .map(|(name, form, function)| {
            let mut errors = Accumulator::default();
            let axis = |index: usize, low: f64| low + (1.0 - low) * index as f64 / (GRID - 1) as f64;
            for point in 0..GRID * GRID * GRID {
                let (n_dot_v, n_dot_l, roughness) = (axis(point % GRID, 0.01), axis(point / GRID % GRID, 0.01), axis(point / (GRID * GRID), 0.045));
                let exact = r::microfacet::v_smith_ggx_correlated(n_dot_v, n_dot_l, roughness);
                let value = f64::from(form(n_dot_v as f32, n_dot_l as f32, roughness as f32));
                errors.add((value - exact).abs() / exact);
            }
            let body = format!(
                "fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    return vec4<f32>({function}(max(x.x, 0.01), max(x.y, 0.01), max(x.z, 0.045)) * 0.01, x.yzw);\n}}\n"
            );
            Row {
                family: "visibility",
                name: name.to_string(),
                bits: None,
                domain: "n.v, n.l [0.01, 1] x roughness [0.045, 1] (32^3)".into(),
                unit: "relative",
                errors: errors.finish(),
                wgsl: wgsl(&["microfacet"], &body),
                lut_size: None,
                cpu: Box::new(move |x| Vec4::new(form(x.x.max(0.01), x.y.max(0.01), x.z.max(0.045)) * 0.01, x.y, x.z, x.w)),
                plot: None,
            }
        })
        .collect()
}
