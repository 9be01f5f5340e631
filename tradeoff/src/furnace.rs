//! The white furnace: how much light a BRDF reflects under a uniform white environment.

use gbuffer::glam::DVec3;
use gbuffer::shading::reference as r;
use std::f64::consts::{FRAC_PI_2, TAU};

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
