//! The hostile-input property test: mutated layout files, scene descriptions and shaders go
//! through the entry points the commands use (`read_layout_file`, `generate` and
//! `write_all` for `codegen`; `read_and_solve` for `solve`; `check_file` for `validate`), and
//! each must end in a result or an error, never a panic: a syntax or model error placed at a
//! `file:line:col`, and nothing written after a failure. CI runs a few dozen cases a kind;
//! `GBUFFER_FUZZ_CASES=N` runs N.

use std::path::Path;

use gbuffer_build::output::{generate, Output};
use gbuffer_build::staging::write_all;
use gbuffer_layout_file::{read_layout_file, FileError};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

use crate::workspace;

/// Cases per kind of input.
fn cases() -> u32 {
    std::env::var("GBUFFER_FUZZ_CASES")
        .ok()
        .and_then(|text| text.parse().ok())
        .unwrap_or(48)
}

/// Pieces a mutation inserts: each format's syntax, names the languages reserve, and numbers
/// at the edges.
const PIECES: &[&str] = &[
    "\"",
    "[[fields]]\n",
    "[",
    "]",
    "=",
    "\n",
    "{",
    "}",
    "(",
    ")",
    ";",
    "in",
    "dyn",
    "fn",
    "__x",
    "4294967296",
    "-1",
    "1e39",
    "nan",
    "0x",
    "bits = 33",
    "format = \"rgba8\"",
    "type = \"Vec4\"",
    "encoding = \"half\"",
    "#include \"x.wgsl\"",
    "#include <gbuffer/nope>",
    "+1.0",
    "vec4<f32>(",
    "\u{0}",
    "é",
    "\\",
    "'''",
];

/// One edit of a text: remove a range, repeat a range, insert a piece, or swap a byte.
#[derive(Clone, Debug)]
enum Edit {
    Remove(usize, usize),
    Repeat(usize, usize, usize),
    Insert(usize, usize),
}

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    let edit = prop_oneof![
        (any::<usize>(), 0usize..64).prop_map(|(at, length)| Edit::Remove(at, length)),
        (any::<usize>(), 1usize..64, 1usize..20)
            .prop_map(|(at, length, times)| Edit::Repeat(at, length, times)),
        (any::<usize>(), 0..PIECES.len()).prop_map(|(at, piece)| Edit::Insert(at, piece)),
    ];
    prop::collection::vec(edit, 1..6)
}

/// `text` with `edits` applied, at character boundaries.
fn mutate(text: &str, edits: &[Edit]) -> String {
    let mut characters: Vec<char> = text.chars().collect();
    for edit in edits {
        let length = characters.len().max(1);
        match *edit {
            Edit::Remove(at, count) => {
                let start = at % length;
                let end = (start + count).min(characters.len());
                characters.drain(start.min(end)..end);
            }
            Edit::Repeat(at, count, times) => {
                let start = at % length;
                let end = (start + count).min(characters.len());
                let run: Vec<char> = characters[start.min(end)..end].to_vec();
                for _ in 0..times {
                    characters.splice(end..end, run.iter().copied());
                }
            }
            Edit::Insert(at, piece) => {
                let at = at % (characters.len() + 1);
                characters.splice(at..at, PIECES[piece].chars());
            }
        }
    }
    characters.into_iter().collect()
}

/// Whether `message` places itself at `path:line:col`.
fn located(message: &str, path: &Path) -> bool {
    let prefix = format!("{}:", path.display());
    message.lines().any(|line| {
        line.strip_prefix(&prefix).is_some_and(|rest| {
            let mut parts = rest.splitn(3, ':');
            parts.next().is_some_and(|line| line.parse::<u32>().is_ok())
                && parts
                    .next()
                    .is_some_and(|column| column.parse::<u32>().is_ok())
        })
    })
}

/// Runs `check` on mutations of each of `seeds`.
fn fuzz(seeds: &[std::path::PathBuf], check: impl Fn(&Path, &str)) {
    let texts: Vec<String> = seeds
        .iter()
        .map(|path| std::fs::read_to_string(path).unwrap())
        .collect();
    let mut runner = TestRunner::new(Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(&(0..texts.len(), edits()), |(seed, edits)| {
            let folder = tempfile::tempdir().unwrap();
            let extension = seeds[seed].extension().unwrap();
            let path = folder.path().join("input").with_extension(extension);
            let text = mutate(&texts[seed], &edits);
            std::fs::write(&path, &text).unwrap();
            check(&path, &text);
            Ok(())
        })
        .unwrap();
}

fn seeds(folder: &str) -> Vec<std::path::PathBuf> {
    let mut paths: Vec<_> = std::fs::read_dir(workspace().join(folder))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    paths.sort();
    paths
}

#[test]
fn mutated_layout_files_fail_cleanly_and_write_nothing() {
    fuzz(&seeds("codegen/layouts"), |path, _| {
        let out = path.with_file_name("out");
        match read_layout_file(path) {
            Ok(file) => {
                let files = generate(&file.layout, file.conversions, &Output::ALL)
                    .expect("a checked layout generates");
                let named: Vec<_> = files
                    .into_iter()
                    .map(|file| ("input".to_string(), file))
                    .collect();
                write_all(&out, &named, |_| Ok(())).expect("the outputs are written");
            }
            Err(FileError::Io { .. }) => panic!("the file was written"),
            Err(error) => {
                assert!(located(&error.to_string(), path), "unplaced: {error}");
                assert!(!out.exists());
            }
        }
    });
}

#[test]
fn mutated_scenes_fail_cleanly() {
    fuzz(&seeds("solver/scenes"), |path, _| {
        if let Err(error) = gbuffer_solver::file::read_and_solve(path) {
            let message = error.to_string();
            assert!(
                located(&message, path) || message.contains("cannot"),
                "unplaced: {message}"
            );
        }
    });
}

#[test]
fn mutated_shaders_fail_cleanly() {
    let shaders = vec![
        workspace().join("validator/examples/shaders/lighting.wgsl"),
        workspace().join("validator/examples/shaders/broken.wgsl"),
    ];
    fuzz(&shaders, |path, _| {
        for problem in gbuffer_validator::check_file(path, false, &[]) {
            if problem.stage == gbuffer_validator::Stage::Parse {
                assert!(problem.location.is_some(), "unplaced: {problem}");
            }
        }
    });
}
