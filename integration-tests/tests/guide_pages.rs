//! The guide's pages held to what they describe: the symbols page to the files its layout
//! generates (each declaration it shows is in the file it names, and every function a shader
//! may call is on the page), and the guide's user part to its promise of naming no CI step, test
//! machinery or measurement protocol (those belong to "Working on gbuffer").

use std::collections::BTreeMap;
use std::path::Path;

use gbuffer_build::output::{generate, Output};
use gbuffer_layout_file::parse_layout;

const BOOK: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../book/src");

fn read(path: &str) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|error| panic!("{path}: {error}"))
}

/// Runs of whitespace as one space, so that a declaration matches however it is indented.
fn squeezed(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The page's sections (`### ` headings, each naming one file or more in backticks) and the
/// fenced blocks under each, in order.
fn sections(page: &str) -> Vec<(Vec<String>, Vec<String>)> {
    let mut sections: Vec<(Vec<String>, Vec<String>)> = Vec::new();
    let mut block: Option<String> = None;
    for line in page.lines() {
        if let Some(open) = &mut block {
            if line == "```" {
                let text = block.take().unwrap();
                if let Some((_, blocks)) = sections.last_mut() {
                    blocks.push(text);
                }
            } else {
                open.push_str(line);
                open.push('\n');
            }
        } else if line.starts_with("```") {
            block = Some(String::new());
        } else if let Some(heading) = line.strip_prefix("### ") {
            let names = heading
                .split('`')
                .skip(1)
                .step_by(2)
                .map(String::from)
                .collect();
            sections.push((names, Vec::new()));
        }
    }
    sections
}

/// The names of the functions a GLSL or WGSL text defines (`... name(...) {` at a line's
/// start, or WGSL's `fn name(`).
fn defined_functions(text: &str) -> Vec<String> {
    text.lines()
        .filter(|line| !line.starts_with(' ') && line.trim_end().ends_with('{'))
        .filter_map(|line| {
            let head = line.split('(').next()?;
            let name = head.split_whitespace().last()?;
            (line.contains('(') && !head.contains('=')).then(|| name.to_string())
        })
        .collect()
}

#[test]
fn the_symbols_page_declares_what_the_outputs_declare() {
    let page = read(&format!("{BOOK}/symbols.md"));
    let toml = page
        .split_once("```toml\n")
        .and_then(|(_, rest)| rest.split_once("```"))
        .expect("the page shows its layout in a ```toml block")
        .0;
    let file = parse_layout(toml, Path::new("symbols.md")).expect("the page's layout reads");
    let mut texts: BTreeMap<String, String> =
        generate(&file.layout, file.conversions, &Output::ALL)
            .expect("the page's layout generates")
            .into_iter()
            .map(|generated| (generated.name, generated.contents))
            .collect();
    texts.insert(
        "Surface::lighting_wgsl(0, 0)".into(),
        gbuffer::targets::lighting_wgsl(&file.layout, 0, 0),
    );

    let mut problems = Vec::new();
    let mut shown = String::new();
    for (names, blocks) in sections(&page) {
        if names.is_empty() || blocks.is_empty() {
            continue;
        }
        // One name, its blocks; several, a block each, in order.
        for (index, block) in blocks.iter().enumerate() {
            let name = &names[index.min(names.len() - 1)];
            let Some(text) = texts.get(name) else {
                problems.push(format!("`{name}`: not a file the layout generates"));
                continue;
            };
            let text = squeezed(text);
            for line in block.lines().filter(|line| !line.trim().is_empty()) {
                if !text.contains(&squeezed(line)) {
                    problems.push(format!("`{name}` does not declare `{}`", line.trim()));
                }
            }
            shown.push_str(block);
        }
    }
    // Every function a shader calls is on the page; the layout's own helpers carry its prefix.
    for (name, text) in &texts {
        if !(name.ends_with(".wgsl") || name.ends_with(".glsl")) {
            continue;
        }
        for function in defined_functions(text) {
            if !function.starts_with("surface_") && !shown.contains(&format!("{function}(")) {
                problems.push(format!(
                    "`{name}` defines `{function}`, which the page omits"
                ));
            }
        }
    }
    // The Rust table's items are the traits' items, as the API record lists them (gbuffer-runtime
    // defines the traits, which the facade re-exports at `gbuffer::`).
    let api = read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../api/gbuffer-runtime.txt"
    ));
    let rust = page
        .split_once("## Rust")
        .expect("the page has a Rust section")
        .1;
    for item in rust
        .split('`')
        .filter_map(|span| span.strip_prefix("Surface::"))
    {
        let item = item.split('(').next().unwrap();
        if !["GBufferLayout", "GBufferTargets"]
            .iter()
            .any(|trait_| api.contains(&format!("gbuffer_runtime::{trait_}::{item}")))
        {
            problems.push(format!(
                "`Surface::{item}` is not an item of the derive's traits"
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

/// What names CI, the tests' machinery or the measurement protocol, which the user part of
/// the guide leaves to "Working on gbuffer".
const MACHINERY: [&str; 9] = [
    " CI ",
    "CI's",
    ".ci/",
    "CI=true",
    "GBUFFER_TIMING",
    "protocol",
    "gpu-results.sh",
    "LP_NATIVE_VECTOR_WIDTH",
    "driver bug",
];

#[test]
fn the_users_part_of_the_guide_names_no_ci_or_measurement_machinery() {
    let summary = read(&format!("{BOOK}/SUMMARY.md"));
    let users_part = summary
        .split_once("# Working on gbuffer")
        .expect("SUMMARY.md has a part \"Working on gbuffer\"")
        .0;
    let chapters: Vec<&str> = users_part
        .split("](")
        .skip(1)
        .filter_map(|rest| rest.split_once(')').map(|(chapter, _)| chapter))
        .collect();
    assert!(chapters.len() >= 10, "the user part lists {chapters:?}");
    let mut found = Vec::new();
    for chapter in chapters {
        let text = read(&format!("{BOOK}/{chapter}"));
        let mut comment = false;
        for (number, line) in text.lines().enumerate() {
            // An HTML comment (a figure's source for .ci/check-figures) is not shown.
            if line.trim_start().starts_with("<!--") {
                comment = !line.contains("-->");
                continue;
            }
            if comment {
                comment = !line.contains("-->");
                continue;
            }
            let padded = format!(" {} ", line.replace(['(', ')', ',', '.', ':', ';'], " "));
            for word in MACHINERY {
                let hit = if word.starts_with(' ') {
                    padded.contains(word)
                } else {
                    line.contains(word)
                };
                if hit {
                    found.push(format!("{chapter}:{}: {}", number + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "the user part names the machinery:\n{}",
        found.join("\n")
    );
}
