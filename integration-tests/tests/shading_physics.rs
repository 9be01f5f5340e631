//! Physical properties of the shading library, on the f64 references (and the f32 mirrors
//! where the property is about their numbers).

use gbuffer::glam::{DVec2, DVec3, Vec3};
use gbuffer_shading::env_brdf_lut::EnvBrdfLut;
use gbuffer_shading::mirror as m;
use gbuffer_shading::reference as r;
use std::f64::consts::PI;

#[test]
fn fresnel_is_f0_at_normal_incidence_and_one_at_grazing() {
    for f0 in [0.0, 0.04, 0.5, 1.0] {
        let f0 = DVec3::new(f0, f0 * 0.5, 0.02);
        assert_eq!(r::microfacet::f_schlick(f0, 1.0), f0);
        assert_eq!(r::microfacet::f_schlick(f0, 0.0), DVec3::ONE);
        // Lagarde's form: f0 at normal incidence, 1 - roughness (or f0) at grazing.
        assert_eq!(r::microfacet::f_schlick_roughness(f0, 1.0, 0.3), f0);
        assert_eq!(r::microfacet::f_schlick_roughness(f0, 0.0, 0.0), DVec3::ONE);
        // Monotonic in the angle.
        let mut previous = f0;
        for step in (0..=100).rev() {
            let value = r::microfacet::f_schlick(f0, f64::from(step) / 100.0);
            assert!(value.cmpge(previous).all());
            previous = value;
        }
    }
}

/// The integral over the hemisphere of D(h) (n.h), by Simpson's rule in theta on a grid that
/// crowds near the pole, where a narrow lobe lives (theta = (pi / 2) s^3).
fn projected_ndf_integral(roughness: f64) -> f64 {
    let steps = 200_000;
    let integrand = |s: f64| {
        let theta = PI / 2.0 * s * s * s;
        let jacobian = PI / 2.0 * 3.0 * s * s;
        r::microfacet::d_ggx(theta.cos(), roughness) * theta.cos() * theta.sin() * jacobian
    };
    let h = 1.0 / steps as f64;
    let mut sum = integrand(0.0) + integrand(1.0);
    for index in 1..steps {
        sum += integrand(index as f64 * h) * if index % 2 == 1 { 4.0 } else { 2.0 };
    }
    2.0 * PI * sum * h / 3.0
}

#[test]
fn ggx_ndf_is_normalised() {
    for roughness in [0.05, 0.1, 0.25, 0.5, 0.75, 1.0] {
        let integral = projected_ndf_integral(roughness);
        assert!(
            (integral - 1.0).abs() < 1e-3,
            "roughness {roughness}: {integral}"
        );
    }
}

#[test]
fn environment_brdf_never_reflects_more_than_it_receives() {
    // scale + bias is the directional albedo of the specular lobe at f0 = 1: at most 1. The
    // quasi-Monte Carlo estimate carries an error that falls as 1 / samples (the worst excess
    // over this grid is 4.8e-5 at 1024 samples, 1.2e-5 at 4096, 3.0e-6 at 16384), so the
    // bound allows for the error at 4096 samples.
    const SAMPLES: u32 = 4096;
    const INTEGRATION_ERROR: f64 = 2.5e-5;
    for roughness_step in 0..=16 {
        for n_dot_v_step in 1..=16 {
            let (roughness, n_dot_v) = (
                f64::from(roughness_step) / 16.0,
                f64::from(n_dot_v_step) / 16.0,
            );
            let scale_bias = r::environment::integrate_env_brdf(roughness, n_dot_v, SAMPLES);
            assert!(
                scale_bias.min_element() >= 0.0,
                "{scale_bias} at roughness {roughness}, n.v {n_dot_v}"
            );
            assert!(
                scale_bias.x + scale_bias.y <= 1.0 + INTEGRATION_ERROR,
                "{scale_bias} at roughness {roughness}, n.v {n_dot_v}"
            );
        }
    }
}

#[test]
fn baked_lut_reproduces_the_integral_at_texel_centres_and_between() {
    let lut = EnvBrdfLut::bake(16, 256);
    let centre = (3.0 + 0.5) / 16.0;
    let exact = r::environment::integrate_env_brdf(centre, centre, 256);
    assert!(
        (lut.sample(centre as f32, centre as f32).as_dvec2() - exact)
            .abs()
            .max_element()
            < 1e-6
    );
    // Between texels the bilinear lookup stays within the neighbours' range.
    let between = lut.sample(0.5, 0.5);
    assert!(between.cmpge(gbuffer::glam::Vec2::ZERO).all() && between.x + between.y <= 1.0 + 1e-6);
}

#[test]
fn env_brdf_approx_at_full_roughness_and_normal_view_is_0_4524_f0_minus_0_0024() {
    for f0 in [0.0, 0.04, 0.5, 1.0] {
        let value = r::mobile::env_brdf_approx(DVec3::splat(f0), 1.0, 1.0);
        let expected = 0.4524 * f0 - 0.0024;
        assert!(
            (value - DVec3::splat(expected)).abs().max_element() < 1e-12,
            "f0 {f0}: {value}"
        );
        let mirror = m::mobile::env_brdf_approx(Vec3::splat(f0 as f32), 1.0, 1.0);
        assert!((mirror.x as f64 - expected).abs() < 1e-6);
    }
    // The non-metal form is "the same as" the general one at f0 = 0.04 (Karis 2014) up to
    // the fit's own terms: general - nonmetal = 0.0016 (1 - a004) - 0.00088 roughness, at most
    // 0.0016 in size over the domain.
    for roughness_step in 0..=10 {
        for n_dot_v_step in 0..=10 {
            let (roughness, n_dot_v) = (
                f64::from(roughness_step) / 10.0,
                f64::from(n_dot_v_step) / 10.0,
            );
            let general = r::mobile::env_brdf_approx(DVec3::splat(0.04), roughness, n_dot_v).x;
            let nonmetal = r::mobile::env_brdf_approx_nonmetal(roughness, n_dot_v);
            assert!(
                (general - nonmetal).abs() <= 0.0016 + 1e-12,
                "{general} vs {nonmetal}"
            );
        }
    }
}

/// The largest angle between a unit vector and its octahedral encoding quantized to `bits`
/// per component (stored as unorm of encoded * 0.5 + 0.5), over a dense sphere.
fn octahedral_quantized_error(bits: u32) -> f64 {
    let max_code = f64::from((1u32 << bits) - 1);
    let quantize = |value: f64| ((value * 0.5 + 0.5) * max_code).round() / max_code * 2.0 - 1.0;
    gbuffer_gpu::values::fibonacci_sphere(200_000)
        .into_iter()
        .map(|direction| {
            let direction = direction.as_dvec3().normalize();
            let encoded = r::normals::octahedral_encode(direction);
            let decoded =
                r::normals::octahedral_decode(DVec2::new(quantize(encoded.x), quantize(encoded.y)));
            direction.dot(decoded).clamp(-1.0, 1.0).acos()
        })
        .fold(0.0, f64::max)
}

#[test]
fn octahedral_round_trip_is_within_its_quantization_bound() {
    // Unquantized, the round trip is exact to rounding.
    for direction in gbuffer_gpu::values::fibonacci_sphere(10_000) {
        let direction = direction.as_dvec3().normalize();
        let back = r::normals::octahedral_decode(r::normals::octahedral_encode(direction));
        assert!((back - direction).length() < 1e-12, "{direction} -> {back}");
    }
    // Quantized: a code error of e = 1 / (2^bits - 1) per component moves the L1-normalized
    // point by at most sqrt(6) e, and normalizing (|p| >= 1 / sqrt 3) stretches that by at
    // most sqrt 3: the angle stays under sqrt(18) e.
    for bits in [8, 10, 12, 16] {
        let bound = 18f64.sqrt() / f64::from((1u32 << bits) - 1);
        let error = octahedral_quantized_error(bits);
        assert!(
            error <= bound,
            "{bits} bits: {:.4} degrees > bound {:.4}",
            error.to_degrees(),
            bound.to_degrees()
        );
        assert!(
            error > bound / 20.0,
            "{bits} bits: the error {error} is implausibly small: is quantization applied?"
        );
    }
}

#[test]
fn transfer_curves_invert_each_other() {
    for step in 0..=1000 {
        let value = DVec3::splat(f64::from(step) / 1000.0);
        let close = |a: DVec3, b: DVec3| (a - b).abs().max_element() < 1e-12;
        assert!(close(
            r::colour::srgb_to_linear(r::colour::linear_to_srgb(value)),
            value
        ));
        assert!(close(
            r::colour::gamma_2_2_to_linear(r::colour::linear_to_gamma_2_2(value)),
            value
        ));
        assert!(close(
            r::colour::pseudo_gamma_to_linear(r::colour::linear_to_pseudo_gamma(value)),
            value
        ));
        assert!(close(
            r::hdr::scale_unit_to_hdr(r::hdr::scale_hdr_to_unit(value * 4.0, 4.0), 4.0),
            value * 4.0
        ));
    }
}

/// RGBM through an rgba8 target: the reference round-trips within half a step of its 8-bit
/// channels, and the f32 mirror (the codec's exact encode) decodes like the reference.
#[test]
fn rgbm_round_trips_within_its_8_bit_steps_in_f64_and_f32() {
    for step in 0..=6000 {
        let colour = DVec3::new(f64::from(step) / 1000.0, f64::from(step) / 3000.0, 0.01);
        let encoded = r::hdr::rgbm_encode(colour, 6.0);
        // Quantize every channel to 8 bits as an rgba8 texture would (m is already on a step).
        let stored = (encoded * 255.0).round() / 255.0;
        let decoded = r::hdr::rgbm_decode(stored, 6.0);
        // A step of rgb is m * range / 255; half of it, plus nothing from m.
        let channel_step = stored.w * 6.0 / 255.0;
        let error = (decoded - colour).abs().max_element();
        assert!(error <= 0.5 * channel_step + 1e-12, "{colour} -> {decoded}");
        // The mirror may round a channel lying on a half code the other way: one step of the
        // multiplier's at most.
        let mirror =
            m::hdr::rgbm_decode(m::hdr::rgbm_encode(colour.as_vec3(), 6.0), 6.0).as_dvec3();
        let apart = (mirror - decoded).abs().max_element();
        assert!(
            apart <= channel_step * (1.0 + 1e-5),
            "{colour}: {mirror} vs {decoded}"
        );
    }
}

#[test]
fn tone_maps_stay_in_range_and_are_monotonic() {
    let mut previous = (DVec3::ZERO, DVec3::ZERO);
    for step in 0..=1000 {
        let value = DVec3::splat(f64::from(step) * 0.05);
        let (reinhard, aces) = (
            r::tonemap::tonemap_reinhard(value),
            r::tonemap::tonemap_aces_fitted(value),
        );
        for mapped in [reinhard, aces] {
            assert!(mapped.cmpge(DVec3::ZERO).all() && mapped.cmple(DVec3::ONE).all());
        }
        assert!(reinhard.cmpge(previous.0).all() && aces.cmpge(previous.1).all());
        previous = (reinhard, aces);
    }
}
