//! The reference deferred renderer, headless: renders the scene with a chosen G-buffer layout
//! and lighting forms to a PNG, and optionally compares it with the CPU reference.
//!
//! `cargo run --release --example deferred -- --layout mobile-metallic --size 1280x720 --out frame.png`
//! `cargo run --release --example deferred -- --scene examples/scenes/dielectric-only.toml --reference`

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use gbuffer_render::gbuffers::{GBuffer, SeedLayout};
use gbuffer_render::image::{compare, difference, write_png};
use gbuffer_render::reference;
use gbuffer_render::renderer::{IblForm, Options, Renderer, SunForm};

/// Renders the reference scene (spheres across roughness and metallic on a gold-and-stone
/// ground, a sun, image-based light and a light map) through a packed G-buffer layout and
/// full PBS lighting on wgpu, and writes it as a PNG.
#[derive(Parser, Debug)]
#[command(name = "deferred", about, long_about)]
struct Arguments {
    /// The G-buffer: a seed layout (mobile-metallic, specular-workflow, future-metallic,
    /// future-specular, arm-tile-block), packed into Rgba32Uint targets, or `classic`
    /// (separate Rgba16Float and Rgba8 targets, as without this library).
    #[arg(long, default_value = "mobile-metallic", conflicts_with = "scene")]
    layout: String,
    /// A scene description (TOML, see `gbuffer_scenes::file`): renders the scene it describes through
    /// the layout solved for it and a lighting pass with only its terms.
    #[arg(long, value_name = "SCENE.toml")]
    scene: Option<PathBuf>,
    /// Frame size, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720")]
    size: String,
    /// Where to write the PNG.
    #[arg(long, default_value = "frame.png")]
    out: PathBuf,
    /// Sun: `ggx` (GGX, correlated Smith, Schlick) or `approx` (D_Approx with EnvBRDFApprox).
    #[arg(long, default_value = "ggx")]
    sun: String,
    /// Image-based light: `lut` (split-sum LUT) or `approx` (EnvBRDFApprox).
    #[arg(long, default_value = "lut")]
    ibl: String,
    /// Also render the CPU reference: print PSNR and the largest error, and write
    /// `<out>.reference.png` and `<out>.difference.png` (differences x8).
    #[arg(long)]
    reference: bool,
}

fn parse(arguments: &Arguments) -> Result<Options, String> {
    let gbuffer = match &arguments.scene {
        Some(path) => {
            let solution =
                gbuffer_scenes::file::read_and_solve(path).map_err(|error| error.to_string())?;
            eprintln!("{solution}");
            Some(GBuffer::Solved(std::sync::Arc::new(solution)))
        }
        None => GBuffer::from_flag(&arguments.layout),
    };
    let gbuffer = gbuffer.ok_or_else(|| {
        let names: Vec<&str> = SeedLayout::ALL
            .iter()
            .map(|layout| layout.flag())
            .chain(["classic"])
            .collect();
        format!(
            "unknown layout `{}`: use one of {}",
            arguments.layout,
            names.join(", ")
        )
    })?;
    let (width, height) = arguments
        .size
        .split_once('x')
        .and_then(|(width, height)| Some((width.parse::<u32>().ok()?, height.parse::<u32>().ok()?)))
        .filter(|&(width, height)| width > 0 && height > 0 && width <= 8192 && height <= 8192)
        .ok_or_else(|| {
            format!(
                "bad size `{}`: write WIDTHxHEIGHT, e.g. 1280x720 (at most 8192 each)",
                arguments.size
            )
        })?;
    let sun = match arguments.sun.as_str() {
        "ggx" => SunForm::Ggx,
        "approx" => SunForm::Approx,
        other => return Err(format!("unknown sun form `{other}`: use ggx or approx")),
    };
    let ibl = match arguments.ibl.as_str() {
        "lut" => IblForm::Lut,
        "approx" => IblForm::Approx,
        other => return Err(format!("unknown IBL form `{other}`: use lut or approx")),
    };
    Ok(Options {
        gbuffer,
        sun,
        ibl,
        width,
        height,
    })
}

fn main() -> ExitCode {
    let arguments = Arguments::parse();
    let options = match parse(&arguments) {
        Ok(options) => options,
        Err(message) => {
            eprintln!("deferred: {message}");
            return ExitCode::from(2);
        }
    };
    let progress = |message: &str| eprintln!("{message}");
    let run = || -> Result<(), String> {
        let renderer = Renderer::new(&progress)?;
        eprintln!(
            "rendering {}x{} with {} ({} bytes per pixel)...",
            options.width,
            options.height,
            options.gbuffer.name(),
            options.gbuffer.bytes_per_pixel()
        );
        let frame = renderer.render(&options)?;
        write_png(&arguments.out, &frame)
            .map_err(|error| format!("{}: {error}", arguments.out.display()))?;
        eprintln!("wrote {}", arguments.out.display());
        if arguments.reference {
            eprintln!("rendering the CPU reference...");
            let reference = reference::render(
                options.width,
                options.height,
                options.gbuffer.features(),
                &|done| eprintln!("  reference {:.0}%", done * 100.0),
            );
            let comparison = compare(&frame, &reference);
            println!(
                "PSNR {:.2} dB, largest error {} steps (against the CPU reference)",
                comparison.psnr, comparison.max_error
            );
            let with_suffix = |suffix: &str| arguments.out.with_extension(format!("{suffix}.png"));
            write_png(&with_suffix("reference"), &reference).map_err(|error| error.to_string())?;
            write_png(&with_suffix("difference"), &difference(&frame, &reference))
                .map_err(|error| error.to_string())?;
        }
        Ok(())
    };
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("deferred: {message}");
            ExitCode::from(1)
        }
    }
}
