//! The white furnace: how much light a BRDF reflects under a uniform white environment.

use std::f64::consts::{FRAC_PI_2, TAU};
use std::fmt::Write as _;

use gbuffer_shading::reference as r;
use glam::DVec3;

use crate::stdout::report_line;

/// The light reflected towards `view` (at n.v) under a uniform white environment: the
/// integral over light directions of `brdf_times_cosine`, done over half vectors (where a
/// narrow lobe is narrow, on a grid crowding near the normal: theta = (pi / 2) s^3), with the
/// Jacobian d(light) = 4 (v.h) d(half).
pub fn furnace(n_dot_v: f64, brdf_times_cosine: impl Fn(DVec3, DVec3) -> f64) -> f64 {
    let view = DVec3::new((1.0 - n_dot_v * n_dot_v).sqrt(), 0.0, n_dot_v);
    let (thetas, phis) = (1200, 256);
    let mut sum = 0.0;
    for i in 0..thetas {
        let s = (i as f64 + 0.5) / thetas as f64;
        let theta = FRAC_PI_2 * s * s * s;
        let d_theta = FRAC_PI_2 * 3.0 * s * s / thetas as f64;
        for j in 0..phis {
            let phi = TAU * (j as f64 + 0.5) / phis as f64;
            let half = DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            );
            let v_dot_h = view.dot(half);
            let light = 2.0 * v_dot_h * half - view;
            if light.z <= 0.0 || v_dot_h <= 0.0 {
                continue;
            }
            sum += brdf_times_cosine(view, light)
                * 4.0
                * v_dot_h
                * theta.sin()
                * d_theta
                * (TAU / phis as f64);
        }
    }
    sum
}

/// The energy the accurate directional form reflects under white light of unit radiance: the
/// `diffuse` albedo and `f0` of a grey material, seen at n.v.
pub fn accurate(roughness: f64, diffuse: f64, f0: f64, n_dot_v: f64) -> f64 {
    let env_brdf = r::environment::integrate_env_brdf(
        roughness.max(r::constants::MIN_ROUGHNESS),
        n_dot_v,
        2048,
    );
    furnace(n_dot_v, |view, light| {
        r::shading::shade_directional(
            DVec3::Z,
            view,
            light,
            DVec3::ONE,
            DVec3::splat(diffuse),
            DVec3::splat(f0),
            roughness,
            env_brdf,
        )
        .x
    })
}

/// The energy `shade_directional` reflects under a uniform white environment at one roughness.
pub(crate) struct FurnaceEnergy {
    pub(crate) roughness: f64,
    /// A white metal (f0 = 1) seen head on: what single scattering keeps.
    pub(crate) metal_head_on: f64,
    /// The same at n.v = 0.25.
    pub(crate) metal_grazing: f64,
    /// A white dielectric (albedo 1, f0 0.04), the largest over n.v in {0.1, 0.5, 1}.
    pub(crate) dielectric_max: f64,
}

/// The furnace's energies at the report's roughnesses.
pub(crate) fn white_furnace() -> Vec<FurnaceEnergy> {
    eprintln!("white furnace...");
    [0.045, 0.25, 0.5, 0.75, 1.0]
        .into_iter()
        .map(|roughness| FurnaceEnergy {
            roughness,
            metal_head_on: accurate(roughness, 0.0, 1.0, 1.0),
            metal_grazing: accurate(roughness, 0.0, 1.0, 0.25),
            dielectric_max: [0.1, 0.5, 1.0]
                .into_iter()
                .map(|n_dot_v| accurate(roughness, 1.0, 0.04, n_dot_v))
                .fold(0.0, f64::max),
        })
        .collect()
}

/// The furnace's table on standard output.
pub(crate) fn print_furnace(furnace: &[FurnaceEnergy]) {
    report_line!("\nwhite furnace (energy reflected of 1 received):");
    report_line!(
        "{:>9} {:>14} {:>14} {:>16}",
        "roughness",
        "metal n.v=1",
        "metal n.v=0.25",
        "white dielectric"
    );
    for energy in furnace {
        report_line!(
            "{:>9} {:>14.4} {:>14.4} {:>16.4}",
            energy.roughness,
            energy.metal_head_on,
            energy.metal_grazing,
            energy.dielectric_max
        );
    }
}

/// The furnace's section of `report.md`.
pub(crate) fn furnace_markdown(furnace: &[FurnaceEnergy]) -> String {
    let mut out = String::from("\n## White furnace\n\nThe energy `shade_directional` reflects under a uniform white environment (1 received). A white dielectric (albedo 1, f0 0.04; largest over n.v 0.1, 0.5, 1) stays at 1: its diffuse takes what the specular lobe leaves. A white metal (f0 1) shows what single-scattering GGX loses to the light that would bounce between microfacets.\n\n| roughness | metal, n.v = 1 | metal, n.v = 0.25 | white dielectric | single scattering loses (n.v = 1) |\n| ---: | ---: | ---: | ---: | ---: |\n");
    for energy in furnace {
        let _ = writeln!(
            out,
            "| {} | {:.4} | {:.4} | {:.4} | {:.1}% |",
            energy.roughness,
            energy.metal_head_on,
            energy.metal_grazing,
            energy.dielectric_max,
            100.0 * (1.0 - energy.metal_head_on)
        );
    }
    out
}

/// The furnace's entries of `report.json`.
pub(crate) fn furnace_json(furnace: &[FurnaceEnergy]) -> serde_json::Value {
    serde_json::json!(furnace
        .iter()
        .map(|energy| serde_json::json!({"roughness": energy.roughness, "metal_head_on": energy.metal_head_on, "metal_grazing": energy.metal_grazing, "white_dielectric_max": energy.dielectric_max}))
        .collect::<Vec<_>>())
}
