//! The scene presets this package ships (`scenes/*.toml`), compiled in, so that a binary built
//! with them runs without the source tree: `gbuffer solve` of a preset's file and
//! [`solve_preset`] give the same layout.

use std::path::Path;

use crate::file::parse_and_solve;
use crate::solver::Solution;

/// The presets, name and scene file, in the order reports list them.
pub const PRESETS: [(&str, &str); 4] = [
    (
        "mobile-metallic",
        include_str!("../scenes/mobile-metallic.toml"),
    ),
    (
        "dielectric-only",
        include_str!("../scenes/dielectric-only.toml"),
    ),
    (
        "fully-rough-props",
        include_str!("../scenes/fully-rough-props.toml"),
    ),
    ("desktop-256", include_str!("../scenes/desktop-256.toml")),
];

/// A preset's scene file, solved; an unknown name is an error that lists the presets.
pub fn solve_preset(name: &str) -> Result<Solution, String> {
    let Some((_, source)) = PRESETS.iter().find(|(preset, _)| *preset == name) else {
        let names: Vec<&str> = PRESETS.iter().map(|(preset, _)| *preset).collect();
        return Err(format!(
            "no scene preset named `{name}`: {}",
            names.join(", ")
        ));
    };
    let path = Path::new("solver/scenes").join(format!("{name}.toml"));
    parse_and_solve(source, &path).map_err(|diagnostics| {
        let lines: Vec<String> = diagnostics.iter().map(ToString::to_string).collect();
        lines.join("\n")
    })
}
