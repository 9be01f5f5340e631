//! The white furnace: under a uniform white environment, the full BRDF (diffuse plus
//! specular) of `shade_directional` reflects at most what it receives, per roughness, view
//! angle and material; and how much single-scattering GGX loses at high roughness.
//! `cargo test -p tests --test white_furnace -- --nocapture` prints the energies.

use shaderlib::glam::DVec3;
use shaderlib::shading::reference as r;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The light reflected towards `view` (at n.v) under a uniform white environment: the
/// integral over light directions of `brdf_times_cosine`, done over half vectors (where a
/// narrow lobe is narrow, on a grid crowding near the normal: theta = (pi / 2) s^3), with the
/// Jacobian d(light) = 4 (v.h) d(half).
fn furnace(n_dot_v: f64, brdf_times_cosine: impl Fn(DVec3, DVec3) -> f64) -> f64 {
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

/// The accurate directional form under white light of unit radiance.
fn accurate(roughness: f64, diffuse: f64, f0: f64, n_dot_v: f64) -> f64 {
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

#[test]
fn the_integrator_reproduces_known_integrals() {
    // A metal (f0 = 1) at roughness 1 (alpha = 1) seen head on: D = 1 / pi and V = 1 / (2 (n.l
    // + 1)), so the reflected energy is the integral of mu / (mu + 1) over [0, 1]: 1 - ln 2.
    let metal = furnace(1.0, |view, light| {
        r::microfacet::d_ggx((view + light).normalize().z, 1.0)
            * r::microfacet::v_smith_ggx_correlated(1.0, light.z, 1.0)
            * light.z
    });
    assert!((metal - (1.0 - 2f64.ln())).abs() < 1e-4, "{metal}");
    // Lambert alone reflects its albedo.
    let lambert = furnace(0.5, |_, light| light.z / PI);
    assert!((lambert - 1.0).abs() < 1e-4, "{lambert}");
}

#[test]
fn the_full_brdf_never_reflects_more_than_it_receives() {
    // (diffuse albedo, f0): white dielectrics at the range of UE4's specular, and metals.
    let materials = [
        (1.0, 0.0),
        (1.0, 0.02),
        (1.0, 0.04),
        (1.0, 0.08),
        (0.0, 0.5),
        (0.0, 1.0),
    ];
    let mut worst: f64 = 0.0;
    println!(
        "energy reflected under a white furnace (rows: roughness; columns: n.v 0.1, 0.5, 1.0)"
    );
    for roughness in [0.045, 0.1, 0.25, 0.5, 0.75, 1.0] {
        for (diffuse, f0) in materials {
            let energies: Vec<f64> = [0.1, 0.5, 1.0]
                .into_iter()
                .map(|n_dot_v| accurate(roughness, diffuse, f0, n_dot_v))
                .collect();
            println!("roughness {roughness:<5} diffuse {diffuse} f0 {f0:<4}: {energies:.4?}");
            worst = energies.into_iter().fold(worst, f64::max);
        }
    }
    println!("largest energy: {worst:.5}");
    assert!(
        worst <= 1.0 + 1e-3,
        "the BRDF reflects {worst} of the light it receives"
    );
}

#[test]
fn single_scattering_ggx_loses_energy_at_high_roughness() {
    // A white metal reflects all it scatters; single scattering drops what bounces twice.
    println!("single-scattering GGX, f0 = 1, seen head on: energy lost");
    let mut lost = Vec::new();
    for roughness in [0.25, 0.5, 0.75, 1.0] {
        let energy = accurate(roughness, 0.0, 1.0, 1.0);
        println!(
            "roughness {roughness}: reflects {energy:.4}, loses {:.1}%",
            100.0 * (1.0 - energy)
        );
        lost.push(1.0 - energy);
    }
    // The loss grows with roughness, to 1 - (1 - ln 2) = ln 2 at roughness 1.
    assert!(lost.windows(2).all(|pair| pair[1] > pair[0]), "{lost:?}");
    assert!((lost[3] - 2f64.ln()).abs() < 2e-3, "{lost:?}");
}
