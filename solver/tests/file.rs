//! Scene files: every preset reads and solves; every problem points at its line and column.

use std::path::Path;

use gbuffer_solver::file::{parse_and_solve, parse_scene};
use gbuffer_solver::{Feature, MaterialModel};

const SCENE: &str = r#"name = "Props"
model = "specular"
budget = 64

[features]
sun = true
metals = false
fully_rough = true

[precision]
normal_degrees = 4.0
colour_steps = 64
"#;

fn presets() -> Vec<std::path::PathBuf> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut files: Vec<_> = std::fs::read_dir(folder)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    files.sort();
    files
}

#[test]
fn a_scene_file_reads_into_its_description() {
    let scene = parse_scene(SCENE, Path::new("props.toml")).unwrap();
    assert_eq!(scene.model, MaterialModel::Specular);
    assert!(scene.features.contains(Feature::FullyRough));
    assert!(!scene.features.contains(Feature::Metals));
    assert_eq!((scene.budget, scene.precision.colour_steps), (64, 64));
    let solution = parse_and_solve(SCENE, Path::new("props.toml")).unwrap();
    assert!(solution.layout.bits() <= 64);
}

#[test]
fn every_preset_solves_within_its_budget() {
    let files = presets();
    assert_eq!(files.len(), 4);
    for path in files {
        let solution =
            gbuffer_solver::file::read_and_solve(&path).unwrap_or_else(|error| panic!("{error}"));
        assert!(solution.layout.bits() <= solution.scene.budget);
    }
}

#[test]
fn problems_point_at_their_key() {
    let unknown = SCENE.replace("sun = true", "sunlight = true");
    let errors = parse_scene(&unknown, Path::new("props.toml")).unwrap_err();
    assert_eq!((errors[0].line, errors[0].column), (6, 1));
    assert!(
        errors[0].message.contains("unknown feature `sunlight`"),
        "{}",
        errors[0]
    );

    let too_fine = SCENE.replace("normal_degrees = 4.0", "normal_degrees = 0.0001");
    let errors = parse_and_solve(&too_fine, Path::new("props.toml")).unwrap_err();
    assert_eq!(errors.len(), 1);
    assert_eq!(errors[0].line, 11, "{}", errors[0]);
    assert!(
        errors[0]
            .message
            .starts_with("`normal_degrees` cannot be met"),
        "{}",
        errors[0]
    );

    let bad = SCENE
        .replace("budget = 64", "budget = 60")
        .replace("\"specular\"", "\"glossy\"");
    let errors = parse_scene(&bad, Path::new("props.toml")).unwrap_err();
    let lines: Vec<usize> = errors.iter().map(|error| error.line).collect();
    assert_eq!(lines, [2, 3]);

    let syntax = parse_scene("name = \"Props\"\nbudget = [", Path::new("props.toml")).unwrap_err();
    assert_eq!(syntax[0].line, 2);
}
