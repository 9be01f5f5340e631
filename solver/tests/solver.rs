//! The solver's promises: never over budget, always a layout when one exists (and the unmet
//! requirement named when none does), deterministic, predicted errors that bound the measured
//! ones, and WGSL that naga accepts.

use gbuffer::glam::Vec3;
use gbuffer_core::Named;
use gbuffer_solver::quantity::{Kind, Quantity};
use gbuffer_solver::representation::Representation;
use gbuffer_solver::texel::texel_wgsl;
use gbuffer_solver::{
    solve, Feature, Features, MaterialModel, Precision, SceneDescription, Setting, SolveError,
};
use rand::rngs::SmallRng;
use rand::{Rng, SeedableRng};

fn random_scene(random: &mut SmallRng, index: usize) -> SceneDescription {
    let features: Features = Feature::ALL
        .iter()
        .copied()
        .filter(|_| random.random_bool(0.5))
        .collect();
    SceneDescription {
        name: format!("Random{index}"),
        model: if random.random_bool(0.5) {
            MaterialModel::Metallic
        } else {
            MaterialModel::Specular
        },
        features,
        precision: Precision {
            normal_degrees: 10f64.powf(random.random_range(-2.5..1.0)),
            colour_steps: 1 << random.random_range(2..=10),
            material_steps: random.random_range(2..=2048),
            hdr_max: 10f64.powf(random.random_range(0.0..4.0)),
            hdr_min: 10f64.powf(random.random_range(-4.0..-1.0)),
            hdr_relative: 10f64.powf(random.random_range(-3.5..-1.0)),
        },
        budget: 32 * random.random_range(1..=8),
    }
}

/// Values spread over a quantity's domain, as the f32 the shader sees.
fn samples(quantity: Quantity, precision: &Precision) -> Vec<Vec3> {
    let mut random = SmallRng::seed_from_u64(7);
    (0..4000)
        .map(|_| match quantity.kind() {
            Kind::Direction => {
                let z: f32 = random.random_range(-1.0..=1.0);
                let angle: f32 = random.random_range(0.0..std::f32::consts::TAU);
                let radius = (1.0 - z * z).max(0.0).sqrt();
                Vec3::new(radius * angle.cos(), radius * angle.sin(), z).normalize()
            }
            Kind::Hdr => {
                let brightest = precision.hdr_max * random.random_range(0.0..=1.0f64).powi(4);
                Vec3::new(
                    random.random_range(0.0..=1.0),
                    random.random_range(0.0..=1.0),
                    1.0,
                ) * brightest as f32
            }
            _ => Vec3::new(
                random.random_range(0.0..=1.0),
                random.random_range(0.0..=1.0),
                random.random_range(0.0..=1.0),
            ),
        })
        .collect()
}

/// The largest error of an representation's CPU round trip, in the quantity's unit.
fn measured_error(
    quantity: Quantity,
    representation: Representation,
    precision: &Precision,
) -> f64 {
    samples(quantity, precision)
        .into_iter()
        .map(|value| {
            let back = representation.round_trip(quantity, value);
            match quantity.kind() {
                Kind::Direction => {
                    // In f64: acos of an f32 dot product near 1 would add 0.02 degrees.
                    let (value, back) = (value.as_dvec3(), back.as_dvec3().normalize());
                    value
                        .cross(back)
                        .length()
                        .atan2(value.dot(back))
                        .to_degrees()
                }
                Kind::Hdr => {
                    let floor = f64::from(value.max_element()).max(precision.hdr_min);
                    f64::from((back - value).abs().max_element()) / floor
                }
                Kind::Colour => f64::from((back - value).abs().max_element()),
                Kind::Scalar => f64::from((back.x - value.x).abs()),
                Kind::Distance => 0.0,
            }
        })
        .fold(0.0, f64::max)
}

#[test]
fn random_scenes_are_solved_within_budget_and_precision_or_refused_with_a_reason() {
    let mut random = SmallRng::seed_from_u64(2026);
    let (mut solved, mut refused) = (0, 0);
    for index in 0..300 {
        let scene = random_scene(&mut random, index);
        match solve(&scene) {
            Ok(solution) => {
                solved += 1;
                assert!(solution.layout.bits() <= scene.budget, "{solution}");
                assert!(solution.layout.check().is_empty(), "{solution}");
                for placement in &solution.placements {
                    assert!(
                        placement.predicted_error <= placement.allowed_error,
                        "{solution}"
                    );
                }
            }
            Err(SolveError::NothingStored) => {
                assert!(!scene.features.iter().any(|feature| !matches!(
                    feature,
                    Feature::NormalMaps
                        | Feature::Metals
                        | Feature::DielectricSpecular
                        | Feature::Decals
                        | Feature::FullyRough
                )))
            }
            Err(SolveError::Unmet { message, .. }) => {
                refused += 1;
                assert!(!message.is_empty());
            }
            Err(error) => panic!("{}: {error}", scene.name),
        }
    }
    assert!(
        solved > 50 && refused > 10,
        "solved {solved}, refused {refused}"
    );
}

#[test]
fn a_requirement_met_by_some_layout_is_always_met() {
    // Satisfiable by construction: a random representation per quantity, laid out one quantity per
    // word (an upper bound on what the solver needs), and precision set to exactly what those
    // representations achieve.
    let mut random = SmallRng::seed_from_u64(11);
    for index in 0..200 {
        let mut scene = random_scene(&mut random, index);
        scene.budget = 256;
        let stored = gbuffer_solver::quantity::stored_quantities(&scene);
        if stored.is_empty() {
            continue;
        }
        let mut words = 0;
        for entry in &stored {
            let catalogue = Representation::catalogue(entry.quantity, &scene.precision);
            let representation = catalogue[random.random_range(0..catalogue.len())];
            words += representation.bits(entry.quantity).div_ceil(32);
            let error = representation.predicted_error(entry.quantity, &scene.precision);
            let precision = &mut scene.precision;
            match entry.quantity.kind() {
                Kind::Direction => precision.normal_degrees = error,
                Kind::Colour => precision.colour_steps = (0.5 / error + 1.0).round() as u32,
                Kind::Scalar => {
                    precision.material_steps = precision
                        .material_steps
                        .min((0.5 / error + 1.0).round() as u32)
                }
                Kind::Hdr => {
                    precision.hdr_relative = error;
                    precision.hdr_max = precision.hdr_max.min(representation.hdr_max());
                }
                Kind::Distance => {}
            }
        }
        scene.budget = 32 * words;
        let solution = solve(&scene).unwrap_or_else(|error| {
            panic!(
                "{} should be satisfiable in {words} words: {error}",
                scene.name
            )
        });
        assert!(solution.layout.words() as u32 <= words);
    }
}

#[test]
fn the_unmet_requirement_is_named() {
    let too_fine = SceneDescription::new("Fine").normal_degrees(0.0001);
    match solve(&too_fine) {
        Err(SolveError::Unmet { setting, message }) => {
            assert_eq!(setting, Setting::NormalDegrees);
            assert!(message.contains("octahedral, 2 x 16 bits"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    // Precise normals fit 128 bits alone, not with everything else in 64.
    let tight = SceneDescription::new("Tight")
        .normal_degrees(0.01)
        .budget(64);
    match solve(&tight) {
        Err(SolveError::Unmet { setting, .. }) => {
            assert!(matches!(setting, Setting::NormalDegrees | Setting::Budget))
        }
        other => panic!("{other:?}"),
    }
    // Past binary16's range only the scaled representations reach, and they are too coarse.
    let bright = SceneDescription::new("Bright").hdr(1e6, 0.01, 0.01);
    match solve(&bright) {
        Err(SolveError::Unmet { setting, message }) => {
            assert_eq!(setting, Setting::HdrRelative);
            assert!(
                message.contains("the most precise representation"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    let everything = SceneDescription::new("Everything")
        .model(MaterialModel::Specular)
        .features(
            Feature::ALL
                .iter()
                .copied()
                .filter(|f| *f != Feature::FullyRough),
        )
        .budget(32);
    match solve(&everything) {
        Err(SolveError::Unmet { setting, message }) => {
            assert_eq!(setting, Setting::Budget);
            assert!(
                message.contains("depth (for point_lights, decals)"),
                "{message}"
            );
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(
        solve(&SceneDescription::new("Dark").features([Feature::Metals])),
        Err(SolveError::NothingStored)
    );
}

#[test]
fn solving_is_deterministic() {
    let mut random = SmallRng::seed_from_u64(5);
    for index in 0..40 {
        let scene = random_scene(&mut random, index);
        let first = solve(&scene);
        assert_eq!(first, solve(&scene));
        if let Ok(solution) = first {
            assert_eq!(texel_wgsl(&solution), texel_wgsl(&solve(&scene).unwrap()));
        }
    }
}

#[test]
fn predicted_errors_bound_the_measured_round_trips() {
    let precision = Precision {
        hdr_max: 64.0,
        hdr_min: 0.01,
        ..Precision::default()
    };
    for quantity in [
        Quantity::Light,
        Quantity::Normal,
        Quantity::BaseColour,
        Quantity::Roughness,
    ] {
        for representation in Representation::catalogue(quantity, &precision) {
            let predicted = representation.predicted_error(quantity, &precision);
            let measured = measured_error(quantity, representation, &precision);
            // f32 arithmetic adds about 1e-7 to the exact bounds.
            assert!(
                measured <= predicted * 1.0001 + 1e-6,
                "{quantity:?} {representation}: measured {measured} > predicted {predicted}"
            );
            // And the bounds are not vacuous.
            if predicted > 1e-3 && predicted < 0.5 {
                assert!(
                    measured > predicted / 8.0,
                    "{quantity:?} {representation}: measured {measured} far below predicted {predicted}"
                );
            }
        }
    }
}

#[test]
fn solved_layouts_are_layouts_of_the_vocabulary_written_out_and_read_back() {
    let mut random = SmallRng::seed_from_u64(7);
    let mut checked = 0;
    for index in 0..150 {
        let scene = random_scene(&mut random, index);
        let Ok(solution) = solve(&scene) else {
            continue;
        };
        // The layout file reads back as the solved layout, so `gbuffer codegen` of it gives
        // the WGSL, GLSL and mirror of the solver's own layout.
        let text = solution.layout_file();
        let file = gbuffer_layout_file::parse_layout(&text, std::path::Path::new("solved.toml"))
            .unwrap_or_else(|errors| panic!("{text}\n{errors:?}"));
        assert_eq!(file.layout, solution.layout, "{text}");
        // Each quantity is one field, or one per piece, as its representation stores it.
        for placement in &solution.placements {
            let pieces = placement.representation.pieces(placement.quantity);
            assert_eq!(pieces.len(), placement.fields.len());
            let mut components = 0;
            for (piece, &field) in pieces.iter().zip(&placement.fields) {
                let field = &solution.layout.fields[field];
                assert!(field.name.starts_with(placement.quantity.name()));
                assert_eq!((field.storage, field.ty), (piece.storage, piece.ty));
                components += field.ty.components;
            }
            assert_eq!(components, placement.quantity.components());
        }
        // The derive source declares the same fields with the same attributes.
        let source = solution.derive_source();
        for field in &solution.layout.fields {
            assert!(
                source.contains(&format!("pub {}: {},", field.name, field.ty.rust_name())),
                "{source}"
            );
        }
        checked += 1;
    }
    assert!(checked > 30, "only {checked} scenes solved");
}

#[test]
fn every_solved_layout_generates_valid_wgsl() {
    let mut random = SmallRng::seed_from_u64(99);
    let mut checked = 0;
    for index in 0..120 {
        let scene = random_scene(&mut random, index);
        let Ok(solution) = solve(&scene) else {
            continue;
        };
        let source = texel_wgsl(&solution);
        if let Err(problem) = gbuffer_validator::validate_wgsl(&source) {
            panic!("{solution}\n{problem}\n{}\n{source}", problem.detail);
        }
        checked += 1;
    }
    assert!(checked > 30, "only {checked} scenes solved");
}
