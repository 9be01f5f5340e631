//! The solver's layouts are layouts of the vocabulary users write: two presets' solutions,
//! written by `gbuffer solve --out` as derive source and layout files, are checked in beside
//! this test (`tests/solved/`), compiled here through the derive, and must still be what the
//! solver writes; the derived layouts equal the solved ones, and their WGSL is the codegen's
//! of the layout files.
//!
//! Regenerate with `cargo run -p gbuffer-cli -- solve solver/scenes/mobile-metallic.toml
//! solver/scenes/desktop-256.toml --out integration-tests/solved` (then delete the other outputs).

use gbuffer::GBufferLayout;
use gbuffer_build::output::{generate, Output};
use gbuffer_core::Conversions;
use gbuffer_layout_file::read_layout_file;
use gbuffer_testkit::workspace;

mod mobile {
    include!("../solved/mobile_metallic_scene.derive.rs");
}

mod desktop {
    include!("../solved/desktop_specular_scene.derive.rs");
}

fn check<L: GBufferLayout>(preset: &str) {
    let symbols = L::layout().symbols();
    let solution =
        gbuffer_solver::file::read_and_solve(&workspace().join("solver/scenes").join(preset))
            .unwrap();
    let folder = workspace().join("integration-tests/solved");
    let read = |name: String| std::fs::read_to_string(folder.join(name)).unwrap();
    assert_eq!(
        read(symbols.file("derive.rs")),
        solution.derive_source(),
        "the checked-in derive source is stale: regenerate it (see the module's doc)"
    );
    assert_eq!(
        read(symbols.file("layout.toml")),
        solution.layout_file(),
        "the checked-in layout file is stale: regenerate it (see the module's doc)"
    );
    // The derive accepts the source and describes the solved layout.
    assert_eq!(L::layout(), solution.layout);
    // The layout file gives the same layout and, through codegen, the derive's WGSL.
    let file = read_layout_file(&folder.join(symbols.file("layout.toml"))).unwrap();
    assert_eq!(file.layout, solution.layout);
    let generated = generate(&file.layout, Conversions::Exact, &[Output::Wgsl]).unwrap();
    assert_eq!(generated[0].contents, format!("{}\n", L::WGSL));
}

#[test]
fn solved_layouts_compile_as_derives_and_read_back_as_layout_files() {
    check::<mobile::MobileMetallicScene>("mobile-metallic.toml");
    check::<desktop::DesktopSpecularScene>("desktop-256.toml");
}
