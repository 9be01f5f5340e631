//! On a real adapter, every WGSL function of the shading library matches its Rust f32 mirror
//! over a dense grid of inputs, within the case's stated tolerance (ulp, or absolute near 0).

use gbuffer_testkit::shading_cases::{
    cases, compute_harness, grid, output_components, ulp_distance, Output,
};

const POINTS_PER_FUNCTION: usize = 8192;

#[test]
fn wgsl_functions_match_their_rust_mirrors_on_the_adapter() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let mut failures = Vec::new();
    for case in cases() {
        let points = grid(&case, POINTS_PER_FUNCTION);
        let inputs: Vec<u32> = points.iter().flatten().copied().collect();
        let components = output_components(&case);
        let harness = compute_harness(&case);
        let outputs = gpu
            .run_compute(
                &harness,
                "harness_main",
                &inputs,
                &[points.len() * components],
                points.len() as u32,
            )
            .expect("the adapter runs the harness");
        let mut worst = 0u64;
        let mut case_failures = 0;
        for (index, point) in points.iter().enumerate() {
            let expected = (case.mirror)(point);
            let got = &outputs[0][index * components..][..components];
            for (component, (&want, &have)) in expected.iter().zip(got).enumerate() {
                let ok = match case.output {
                    Output::Unsigned => want == have,
                    Output::Floats(_) => {
                        let (want, have) = (f32::from_bits(want), f32::from_bits(have));
                        let distance = ulp_distance(want, have);
                        worst = worst.max(distance);
                        distance <= u64::from(case.ulps) || (want - have).abs() <= case.absolute
                    }
                };
                if !ok {
                    case_failures += 1;
                    if case_failures <= 3 {
                        let arguments: Vec<f32> =
                            point.iter().map(|&bits| f32::from_bits(bits)).collect();
                        failures.push(format!(
                            "{} [{component}] at {arguments:?}: mirror {}, adapter {}",
                            case.call,
                            f32::from_bits(want),
                            f32::from_bits(have)
                        ));
                    }
                }
            }
        }
        eprintln!(
            "{:<40} {:>6} points, worst {worst} ulp (allowed {})",
            case.name(),
            points.len(),
            case.ulps
        );
    }
    assert!(
        failures.is_empty(),
        "on {}:\n{}",
        gpu.describe(),
        failures.join("\n")
    );
}
