//! The white furnace: under a uniform white environment, the full BRDF (diffuse plus
//! specular) of `shade_directional` reflects at most what it receives, per roughness, view
//! angle and material; and how much single-scattering GGX loses at high roughness.
//! `cargo test -p gbuffer-integration-tests --test white_furnace -- --nocapture` prints the energies.

use gbuffer_shading::reference as r;
use gbuffer_tradeoff::furnace::{accurate, furnace};
use std::f64::consts::PI;

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
