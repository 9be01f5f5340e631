//! The reference deferred renderer, headless: renders the scene with a chosen G-buffer layout,
//! lighting forms, backend and path to a PNG, and optionally compares it with the CPU reference.
//!
//! `cargo run --release -p gbuffer-render --example deferred -- --layout mobile-metallic --size 1280x720 --out frame.png`
//! `cargo run --release -p gbuffer-render --example deferred -- --backend gles --path fetch-native --reference`
//! `cargo run --release -p gbuffer-render --example deferred -- --backend vulkan --path subpass --reference`
//! `cargo run --release -p gbuffer-render --example deferred -- --backend vulkan --path local-read --reference`
//! `cargo run --release -p gbuffer-render --example deferred -- --scene solver/scenes/dielectric-only.toml --reference`

use std::path::PathBuf;
use std::process::ExitCode;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::Parser;
use gbuffer_core::Named;
use gbuffer_render::gbuffers::{GBuffer, LayoutArgument, PackedLayout};
use gbuffer_render::gles::GlesRenderer;
use gbuffer_render::image::{compare, difference, write_png};
use gbuffer_render::on_tile::{Backend, Path, TileOptions};
use gbuffer_render::options::{parse_size, Frame, IblForm, Options, SunForm};
use gbuffer_render::reference;
use gbuffer_render::vulkan::VulkanRenderer;
use gbuffer_render::wgpu::Renderer;

/// Renders the reference scene (spheres across roughness and metallic on a gold-and-stone
/// ground, a sun, image-based light and a light map) through a packed G-buffer layout and
/// full PBS lighting on wgpu, and writes it as a PNG.
#[derive(Parser, Debug)]
#[command(name = "deferred", about, long_about)]
struct Arguments {
    /// The G-buffer: a seed layout (mobile-metallic, specular-workflow, future-metallic,
    /// future-specular, arm-tile-block), packed into Rgba32Uint targets; `lossless` (every
    /// quantity an f32, twelve r32f words); or `classic` (separate Rgba16Float and Rgba8
    /// targets, as without this library).
    #[arg(
        long,
        value_parser = named::<LayoutArgument>(),
        default_value = "mobile-metallic",
        conflicts_with = "scene"
    )]
    layout: LayoutArgument,
    /// A scene description (TOML, see `gbuffer_solver::file`): renders the scene it describes through
    /// the layout solved for it and a lighting pass with only its terms.
    #[arg(long, value_name = "SCENE.toml")]
    scene: Option<PathBuf>,
    /// The API: `wgpu` (the G-buffer through memory), `gles` (GLES 3.2 through EGL
    /// surfaceless) or `vulkan`.
    #[arg(long, value_parser = named::<Backend>(), default_value = "wgpu")]
    backend: Backend,
    /// How the G-buffer travels: for gles `fetch-native` (default), `fetch-packed` or
    /// `two-pass`; for vulkan `subpass` (default), `local-read` (dynamic rendering local read),
    /// `local-read-ordered` (the same in rasterization order, without barriers) or `two-pass`.
    /// The fused paths keep it in the render pass and never store it.
    #[arg(long, value_parser = named::<Path>())]
    path: Option<Path>,
    /// Frame size, WIDTHxHEIGHT (at most 8192 each).
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    size: (u32, u32),
    /// Where to write the PNG.
    #[arg(long, default_value = "frame.png")]
    out: PathBuf,
    /// Sun: `ggx` (GGX, correlated Smith, Schlick) or `approx` (D_Approx with EnvBRDFApprox).
    #[arg(long, value_parser = named::<SunForm>(), default_value = "ggx")]
    sun: SunForm,
    /// Image-based light: `lut` (split-sum LUT) or `approx` (EnvBRDFApprox).
    #[arg(long, value_parser = named::<IblForm>(), default_value = "lut")]
    ibl: IblForm,
    /// Debug: also store the G-buffer as the geometry writes it (before the decals and the
    /// light) and write its packed words to this file (little-endian u32, the layout's words per
    /// pixel, row by row): the same for every backend and path, bit for bit.
    #[arg(long, value_name = "FILE")]
    store_gbuffer: Option<PathBuf>,
    /// Also render the scene through the lossless G-buffer (every quantity an f32, on wgpu)
    /// and the CPU reference, and print two lines: the frame's PSNR and largest error against
    /// the lossless frame (what the layout costs the picture), and the lossless frame's against
    /// the CPU reference (the renderer's own floor). Writes `<out>.lossless.png`,
    /// `<out>.reference.png` and their differences, `<out>.lossless-difference.png` and
    /// `<out>.reference-difference.png` (differences x8).
    #[arg(long)]
    reference: bool,
}

/// The parser of an option whose values the renderer names ([`Named`]): `--help` lists the
/// names, and a wrong one is a usage error that lists them too.
fn named<T: Named + Send + Sync>() -> impl TypedValueParser<Value = T> {
    PossibleValuesParser::new(T::names()).map(|name| T::from_name(&name).expect("a listed name"))
}

/// The path named on the command line, checked against the backend (its default if none).
fn backend_path(backend: Backend, path: Option<Path>) -> Result<Option<Path>, String> {
    match (path, backend.paths()) {
        (None, paths) => Ok(paths.first().copied()),
        (Some(path), []) => Err(format!(
            "--path {}: the wgpu backend has one path (the G-buffer through memory); \
             the on-tile paths are --backend gles or vulkan",
            path.name()
        )),
        (Some(path), paths) if paths.contains(&path) => Ok(Some(path)),
        (Some(path), paths) => {
            let names: Vec<&str> = paths.iter().map(|path| path.name()).collect();
            Err(format!(
                "--path {} is not a path of --backend {}: use {}",
                path.name(),
                backend.name(),
                names.join(", ")
            ))
        }
    }
}

fn parse(arguments: &Arguments) -> Result<Options, String> {
    let gbuffer = match &arguments.scene {
        Some(path) => {
            let solution =
                gbuffer_solver::file::read_and_solve(path).map_err(|error| error.to_string())?;
            eprintln!("{solution}");
            GBuffer::Solved(std::sync::Arc::new(solution))
        }
        None => arguments.layout.into(),
    };
    let (width, height) = arguments.size;
    Ok(Options {
        gbuffer,
        sun: arguments.sun,
        ibl: arguments.ibl,
        width,
        height,
    })
}

/// The frame, on the chosen backend and path, and with `store_gbuffer` the G-buffer's words
/// written there.
fn render(
    backend: Backend,
    path: Option<Path>,
    options: &Options,
    store_gbuffer: Option<&std::path::Path>,
    progress: &dyn Fn(&str),
) -> Result<Frame, String> {
    let tile = |path: Option<Path>| TileOptions {
        options: options.clone(),
        path: path.expect("the on-tile backends have a path"),
    };
    let store = |words: Vec<u32>| -> Result<(), String> {
        if let Some(file) = store_gbuffer {
            std::fs::write(file, bytemuck::cast_slice(&words))
                .map_err(|error| format!("{}: {error}", file.display()))?;
            eprintln!("wrote the G-buffer's words to {}", file.display());
        }
        Ok(())
    };
    let (frame, recording) = match backend {
        Backend::Wgpu => {
            let renderer = Renderer::new(progress)?;
            if store_gbuffer.is_some() {
                store(renderer.gbuffer_words(options)?)?;
            }
            renderer.render_recorded(options)?
        }
        Backend::Gles => {
            let renderer = GlesRenderer::new(progress)?;
            if store_gbuffer.is_some() {
                store(renderer.gbuffer_words(options)?)?;
            }
            renderer.render(&tile(path))?
        }
        Backend::Vulkan => {
            let renderer = VulkanRenderer::new(progress)?;
            if store_gbuffer.is_some() {
                store(renderer.gbuffer_words(options)?)?;
            }
            renderer.render(&tile(path))?
        }
    };
    let traffic = recording.traffic(options.width, options.height);
    eprintln!(
        "{} passes; stored: {}; {:.1} MB loaded, {:.1} MB stored ({:.1} BU)",
        recording.passes(),
        recording.stored().join(", "),
        traffic.loaded as f64 / 1e6,
        traffic.stored as f64 / 1e6,
        traffic.bandwidth_units(options.width, options.height)
    );
    Ok(frame)
}

fn main() -> ExitCode {
    let arguments = Arguments::parse();
    let backend = arguments.backend;
    let path = match backend_path(backend, arguments.path) {
        Ok(path) => path,
        Err(message) => {
            eprintln!("deferred: {message}");
            return ExitCode::from(2); // a usage error, as clap's own
        }
    };
    let options = match parse(&arguments) {
        Ok(options) => options,
        Err(message) => {
            eprintln!("deferred: {message}");
            return ExitCode::FAILURE; // a bad scene file
        }
    };
    let progress = |message: &str| eprintln!("{message}");
    let run = || -> Result<(), String> {
        eprintln!(
            "rendering {}x{} with {} ({} bytes per pixel) on {}{}...",
            options.width,
            options.height,
            options.gbuffer.name(),
            options.gbuffer.bytes_per_pixel(),
            backend.name(),
            path.map(|path| format!(", path {}", path.name()))
                .unwrap_or_default()
        );
        let frame = render(
            backend,
            path,
            &options,
            arguments.store_gbuffer.as_deref(),
            &progress,
        )?;
        write_png(&arguments.out, &frame)
            .map_err(|error| format!("{}: {error}", arguments.out.display()))?;
        eprintln!("wrote {}", arguments.out.display());
        if arguments.reference {
            // The same scene through the lossless G-buffer, on wgpu (the fused paths cannot
            // keep its twelve words on tile): what the layout alone costs the picture.
            let lossless_options = Options {
                gbuffer: GBuffer::Packed(PackedLayout::Lossless),
                ..options.clone()
            };
            eprintln!("rendering through the lossless G-buffer...");
            let lossless = render(Backend::Wgpu, None, &lossless_options, None, &progress)?;
            eprintln!("rendering the CPU reference...");
            let reference = reference::render(
                options.width,
                options.height,
                options.gbuffer.features(),
                &|done| eprintln!("  reference {:.0}%", done * 100.0),
            );
            let with_suffix = |suffix: &str| arguments.out.with_extension(format!("{suffix}.png"));
            let comparisons = [
                ("the lossless G-buffer", &frame, &lossless, "lossless"),
                ("the CPU reference", &lossless, &reference, "reference"),
            ];
            for (against, frame, yardstick, name) in comparisons {
                let comparison = compare(frame, yardstick);
                println!(
                    "PSNR {:.2} dB, largest error {} steps (against {against})",
                    comparison.psnr, comparison.max_error
                );
                write_png(&with_suffix(name), yardstick).map_err(|error| error.to_string())?;
                write_png(
                    &with_suffix(&format!("{name}-difference")),
                    &difference(frame, yardstick),
                )
                .map_err(|error| error.to_string())?;
            }
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
