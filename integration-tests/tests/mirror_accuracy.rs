//! The f32 mirrors against the f64 references: the rounding error of every function over its
//! grid, printed as a table (`cargo test -p gbuffer-integration-tests --test mirror_accuracy -- --nocapture`).
//!
//! The worst cases are precision hazards of f32 itself, named in the functions' comments:
//! GGX's denominator cancels near n.h = 1 at low roughness (0.6% at roughness 0.045, and the
//! directional composites inherit it). The RGBM encoders are the codec's, whose channels are
//! 8-bit codes where the textbook f64 form leaves them unrounded: they are compared after
//! storing the reference's in 8 bits and decoding.

use gbuffer_testkit::shading_cases::{cases, grid, mirror_error};

#[test]
fn f32_mirrors_stay_close_to_the_f64_references() {
    const QUANTIZERS: [&str; 2] = ["rgbm_encode", "rgbm_squared_encode"];
    const RELATIVE_BOUND: f64 = 1e-2;
    let mut failures = Vec::new();
    println!(
        "{:<28} {:>12} {:>12} {:>12}",
        "function", "max abs", "max rel", "rms abs"
    );
    for case in cases() {
        let points = grid(&case, 8192);
        let Some(error) = mirror_error(&case, &points) else {
            continue;
        };
        println!(
            "{:<28} {:>12.3e} {:>12.3e} {:>12.3e}",
            case.call, error.max_absolute, error.max_relative, error.rms_absolute
        );
        if !QUANTIZERS.contains(&case.name()) && error.max_relative > RELATIVE_BOUND {
            failures.push(format!(
                "{}: relative error {:.3e}",
                case.call, error.max_relative
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
