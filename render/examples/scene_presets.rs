//! The scene presets side by side: for each scene description in `solver/scenes/`, the bits
//! of its solved layout, the instructions of its specialised lighting pass, and its error
//! against the full model (the CPU reference). Prints a table and writes
//! `target/scene-presets/report.md`.
//!
//! `cargo run --release -p gbuffer-render --example scene_presets [-- --size 320x180] [--mobile]`

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use gbuffer_render::options::parse_size;
use gbuffer_render::presets::{lighting_cost, measure_preset, unspecialised_options};
use gbuffer_render::wgpu::Renderer;
use gbuffer_solver::lighting::{terms, Forms};
use gbuffer_solver::presets::PRESETS;

#[derive(Parser, Debug)]
#[command(name = "scene_presets", about)]
struct Arguments {
    /// Frame size for the error, WIDTHxHEIGHT (the CPU reference takes a while at large sizes).
    #[arg(long, default_value = "320x180", value_parser = parse_size)]
    size: (u32, u32),
    /// The mobile forms (D_Approx, EnvBRDFApprox) instead of GGX and the split-sum LUT.
    #[arg(long)]
    mobile: bool,
}

fn main() -> ExitCode {
    let arguments = Arguments::parse();
    let (width, height) = arguments.size;
    let forms = if arguments.mobile {
        Forms::MOBILE
    } else {
        Forms::ACCURATE
    };
    match run(forms, width, height) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("scene_presets: {error}");
            ExitCode::FAILURE
        }
    }
}

fn run(forms: Forms, width: u32, height: u32) -> Result<(), String> {
    let renderer = Renderer::new(&|message| eprintln!("{message}"))?;
    let baseline = lighting_cost(&unspecialised_options(forms, width, height))?;
    let mut table = String::new();
    let _ = writeln!(
        table,
        "| preset | layout | bits (budget) | r32ui words | lighting terms | lighting: naga expressions | lighting: SPIR-V instructions | PSNR vs full model | largest error |"
    );
    let _ = writeln!(table, "|---|---|---|---|---|---|---|---|---|");
    let _ = writeln!(
        table,
        "| unspecialised (Listing 2.2, every term) | MobileMetallic | 128 (128) | 0 | image-based light, light accumulation, sun | {} | {} | see `cargo bench -p gbuffer-render` | |",
        baseline.expressions, baseline.spirv_instructions
    );
    let mut details = String::new();
    for (preset, _) in PRESETS {
        eprintln!("{preset}...");
        let row = measure_preset(&renderer, preset, forms, width, height)?;
        let layout = &row.solution.layout;
        let _ = writeln!(
            table,
            "| {preset} | {} | {} ({}) | {} | {} | {} | {} | {:.2} dB | {} steps |",
            layout.name,
            layout.bits(),
            layout.budget,
            row.solution.custom_words(),
            terms(&row.solution).join(", "),
            row.lighting.expressions,
            row.lighting.spirv_instructions,
            row.psnr,
            row.largest_error
        );
        let _ = writeln!(details, "### {preset}\n\n```text\n{}```\n", row.solution);
    }
    println!("{table}");
    let report = format!(
        "# Scene presets\n\nAdapter: {} ({:?}). Frames {width}x{height}, {:?} direct light, {:?} image-based light. \
         PSNR is against the CPU reference of the same scene by the full model (every term, \
         accurate forms, f64, no packing). Lighting costs are of the lighting pass's fragment \
         shader (`lighting_main`), compacted by naga.\n\n{table}\n## Solved layouts\n\n{details}",
        renderer.adapter.name, renderer.adapter.backend, forms.sun, forms.ibl
    );
    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target/scene-presets");
    std::fs::create_dir_all(&folder).map_err(|error| error.to_string())?;
    let path = folder.join("report.md");
    std::fs::write(&path, report).map_err(|error| error.to_string())?;
    eprintln!("wrote {}", path.display());
    Ok(())
}
