//! What the validator says of broken shaders, as golden files: each problem at the
//! `file:line:col` of the file the user wrote (an included file's own, when the mistake is
//! there), naga's labelled spans under their source lines, its notes, and no arena handles.
//! The shaders are in `tests/broken/`; the goldens in `tests/snapshots/`.

use std::path::{Path, PathBuf};

fn broken_shaders() -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir("tests/broken")
        .expect("tests/broken")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|path| {
            path.extension()
                .is_some_and(|extension| extension == "wgsl")
        })
        .collect();
    paths.sort();
    paths
}

#[test]
fn broken_shaders_get_placed_labelled_messages() {
    let paths = broken_shaders();
    assert!(paths.len() >= 12, "a dozen broken shaders");
    for path in paths {
        // The layouts some include live in codegen's folder: an include root of their own.
        let layouts = PathBuf::from("../codegen/layouts");
        let problems = gbuffer_validator::check_file(Path::new(&path), true, &[layouts]);
        assert!(!problems.is_empty(), "{} passed", path.display());
        let text: Vec<String> = problems.iter().map(ToString::to_string).collect();
        let text = text.join("\n\n");
        // naga prints arena handles as `[N]`; every one must have been named.
        assert!(
            !problems.iter().any(|problem| has_handle(&problem.message)
                || problem.notes.iter().any(|note| has_handle(note))
                || problem.labels.iter().any(|label| has_handle(&label.text))),
            "{}: a handle is left in\n{text}",
            path.display()
        );
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        insta::assert_snapshot!(name, text);
    }
}

/// Whether `text` has a `[digits]` handle.
fn has_handle(text: &str) -> bool {
    text.split('[').skip(1).any(|rest| {
        rest.split_once(']').is_some_and(|(inside, _)| {
            !inside.is_empty() && inside.bytes().all(|byte| byte.is_ascii_digit())
        })
    })
}
