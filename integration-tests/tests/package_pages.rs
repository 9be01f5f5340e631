//! Each published package's front page (its crate documentation, which docs.rs shows first, or
//! for the command line, a binary, its README, which crates.io shows) says what the package is
//! for, names the guide and lists its feature flags, exactly those its Cargo.toml declares; its
//! docs are built on docs.rs with every feature, so the feature-gated API is documented.

use std::collections::BTreeSet;
use std::path::Path;

/// The packages published for users: folder and front page. The Bevy plugin is a workspace of
/// its own, but its files are read here all the same.
const PUBLISHED: &[(&str, &str)] = &[
    ("gbuffer", "src/lib.rs"),
    ("core", "src/lib.rs"),
    ("files", "src/lib.rs"),
    ("layout-file", "src/lib.rs"),
    ("shading", "src/lib.rs"),
    ("translate", "src/lib.rs"),
    ("macros", "src/lib.rs"),
    ("runtime", "src/lib.rs"),
    ("codegen", "src/lib.rs"),
    ("build", "src/lib.rs"),
    ("validator", "src/lib.rs"),
    ("solver", "src/lib.rs"),
    ("cost", "src/lib.rs"),
    ("gpu", "src/lib.rs"),
    ("render", "src/lib.rs"),
    ("tradeoff", "src/lib.rs"),
    ("cli", "README.md"),
    ("bevy", "src/lib.rs"),
];

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|error| panic!("{}: {error}", path.display()))
}

/// A front page's text: a crate's `//!` lines, or a README as it is.
fn front_page(folder: &Path, page: &str) -> String {
    let text = read(&folder.join(page));
    if !page.ends_with(".rs") {
        return text;
    }
    text.lines()
        .filter_map(|line| line.trim_start().strip_prefix("//!"))
        .map(|line| line.strip_prefix(' ').unwrap_or(line))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The lines of a Cargo.toml's `[section]`, up to the next section.
fn section<'a>(manifest: &'a str, name: &str) -> Vec<&'a str> {
    manifest
        .lines()
        .skip_while(|line| line.trim() != format!("[{name}]"))
        .skip(1)
        .take_while(|line| !line.starts_with('['))
        .filter(|line| !line.trim().is_empty() && !line.trim_start().starts_with('#'))
        .collect()
}

/// The features a Cargo.toml declares, but `default`, and those `default` turns on.
fn features(manifest: &str) -> (BTreeSet<String>, BTreeSet<String>) {
    let mut declared = BTreeSet::new();
    let mut default = BTreeSet::new();
    for line in section(manifest, "features") {
        let (name, value) = line.split_once('=').expect("a feature is `name = [...]`");
        let name = name.trim();
        if name == "default" {
            default.extend(
                value
                    .trim()
                    .trim_matches(['[', ']'])
                    .split(',')
                    .map(|feature| feature.trim().trim_matches('"').to_string())
                    .filter(|feature| !feature.is_empty()),
            );
        } else {
            declared.insert(name.to_string());
        }
    }
    (declared, default)
}

/// The features a front page's "Feature flags" section lists (a bullet each, "- `name`: ..."),
/// with whether the bullet says the feature is on by default; `None` without the section.
fn listed_features(page: &str) -> Option<Vec<(String, bool)>> {
    let start = page.lines().position(|line| {
        line.starts_with('#') && line.trim_start_matches('#').trim() == "Feature flags"
    })?;
    let listed = page
        .lines()
        .skip(start + 1)
        .take_while(|line| !line.starts_with('#'))
        .filter_map(|line| {
            let name = line.strip_prefix("- `")?.split_once('`')?.0;
            Some((name.to_string(), line.contains("on by default")))
        })
        .collect();
    Some(listed)
}

#[test]
fn every_front_page_lists_its_packages_feature_flags() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for (folder, page) in PUBLISHED {
        let folder = root.join(folder);
        let manifest = read(&folder.join("Cargo.toml"));
        let text = front_page(&folder, page);
        let (declared, default) = features(&manifest);
        match listed_features(&text) {
            None => assert!(
                declared.is_empty(),
                "{}/{page} has no \"Feature flags\" section, and Cargo.toml declares {declared:?}",
                folder.display()
            ),
            Some(listed) => {
                let names: BTreeSet<String> = listed.iter().map(|(name, _)| name.clone()).collect();
                assert_eq!(
                    names,
                    declared,
                    "{}/{page}: the features listed, and those Cargo.toml declares",
                    folder.display()
                );
                for (name, said_default) in &listed {
                    assert_eq!(
                        *said_default,
                        default.contains(name),
                        "{}/{page}: `{name}` is {}on by default, and its bullet says otherwise",
                        folder.display(),
                        if default.contains(name) { "" } else { "not " }
                    );
                }
            }
        }
    }
}

#[test]
fn every_front_page_says_what_its_package_is_for_and_names_the_guide() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for (folder, page) in PUBLISHED {
        let folder = root.join(folder);
        let text = front_page(&folder, page);
        let first = text
            .lines()
            .find(|line| !line.is_empty() && !line.starts_with('#'))
            .unwrap_or_default();
        assert!(
            first.split_whitespace().count() >= 5,
            "{}/{page}: the first line says what the package is for, not {first:?}",
            folder.display()
        );
        // The facade's page says where the guide is, under "The guide"; every other package's
        // links there.
        let names_the_guide = if folder.ends_with("gbuffer") {
            text.lines().any(|line| line == "# The guide")
        } else {
            text.contains("](https://docs.rs/gbuffer#the-guide)")
        };
        assert!(
            names_the_guide,
            "{}/{page}: the front page links the guide (https://docs.rs/gbuffer#the-guide)",
            folder.display()
        );
    }
}

#[test]
fn every_library_is_documented_with_all_its_features_on_docs_rs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for (folder, page) in PUBLISHED {
        if !page.ends_with(".rs") {
            continue;
        }
        let manifest = read(&root.join(folder).join("Cargo.toml"));
        let docs_rs = section(&manifest, "package.metadata.docs.rs");
        assert!(
            docs_rs.contains(&"all-features = true"),
            "{folder}/Cargo.toml: docs.rs documents the feature-gated API"
        );
        // A package with features labels each gated item with its feature there.
        if !features(&manifest).0.is_empty() && folder != &"cli" {
            assert!(
                docs_rs.contains(&r#"rustdoc-args = ["--cfg", "docsrs"]"#),
                "{folder}/Cargo.toml: docs.rs builds with --cfg docsrs"
            );
            let source = read(&root.join(folder).join(page));
            assert!(
                source.contains("#![cfg_attr(docsrs, feature(doc_cfg))]"),
                "{folder}/{page}: docs.rs labels what each feature turns on"
            );
        }
    }
}

/// The facade's front page names every encoding a bit field can take, as the derive spells it.
#[test]
fn the_facades_front_page_names_every_encoding() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let page = front_page(&root.join("gbuffer"), "src/lib.rs");
    let sentence = page
        .split_once("The encodings are ")
        .and_then(|(_, rest)| rest.split_once("([`layout::Encoding`])"))
        .expect("the front page lists the encodings: \"The encodings are ...\"")
        .0;
    let listed: Vec<&str> = sentence
        .split('`')
        .skip(1)
        .step_by(2)
        .map(|name| name.split('(').next().unwrap())
        .collect();
    assert_eq!(listed, gbuffer_core::Encoding::names());
}

/// The guide's feature flags page lists every feature of every published package, with its
/// default, and nothing else.
#[test]
fn the_guides_feature_page_lists_every_feature() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let page = read(&root.join("book/src/feature-flags.md"));
    let listed: BTreeSet<(String, String, bool)> = page
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.strip_prefix("| `")?.split(" | ").collect();
            let package = cells.first()?.strip_suffix('`')?;
            let feature = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            let default = match *cells.get(2)? {
                "yes" => true,
                "no" => false,
                other => panic!("{package} `{feature}`: on by default is yes or no, not {other}"),
            };
            Some((package.to_string(), feature.to_string(), default))
        })
        .collect();
    let mut declared = BTreeSet::new();
    for (folder, _) in PUBLISHED {
        let manifest = read(&root.join(folder).join("Cargo.toml"));
        let package = section(&manifest, "package")
            .iter()
            .find_map(|line| line.strip_prefix("name = \""))
            .and_then(|name| name.strip_suffix('"'))
            .unwrap_or_else(|| panic!("{folder}/Cargo.toml names its package"))
            .to_string();
        let (features, default) = features(&manifest);
        for feature in features {
            let on = default.contains(&feature);
            declared.insert((package.clone(), feature, on));
        }
    }
    assert_eq!(
        listed, declared,
        "book/src/feature-flags.md, and the packages' Cargo.toml"
    );
}
