//! Exports the fused frame for the browser: the programs, mesh and baked inputs
//! (`scene.mjs`) and the layout's host module (`layout.webgl_pls.js`) that `web/index.html`
//! loads beside `web/fused.mjs`.
//!
//! `cargo run --release -p gbuffer-render --example webgl -- --out web/generated`, then serve
//! `web/` (`python3 -m http.server -d web`) and open it in Chromium started with
//! `--enable-webgl-draft-extensions`.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::Parser;
use gbuffer_core::Named;
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::inputs::Inputs;
use gbuffer_render::options::{parse_size, IblForm, Options, SunForm};
use gbuffer_render::webgl;

/// Writes what the browser's fused frame loads into a folder (created if missing).
#[derive(Parser, Debug)]
#[command(name = "webgl", about, long_about)]
struct Arguments {
    /// The G-buffer: a seed layout the fused paths keep on tile (mobile-metallic or
    /// future-metallic).
    #[arg(long, value_parser = named::<PackedLayout>(), default_value = "mobile-metallic")]
    layout: PackedLayout,
    /// Frame size, WIDTHxHEIGHT (at most 8192 each).
    #[arg(long, default_value = "1280x720", value_parser = parse_size)]
    size: (u32, u32),
    /// The folder to write into.
    #[arg(long, default_value = "web/generated")]
    out: PathBuf,
}

/// The parser of an option whose values the renderer names.
fn named<T: Named + Send + Sync>() -> impl TypedValueParser<Value = T> {
    PossibleValuesParser::new(T::names()).map(|name| T::from_name(&name).expect("a listed name"))
}

fn main() -> ExitCode {
    let arguments = Arguments::parse();
    let (width, height) = arguments.size;
    let options = Options {
        gbuffer: GBuffer::Packed(arguments.layout),
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width,
        height,
    };
    eprintln!("baking the split-sum LUT, the light map and the prefiltered sky...");
    let files = match webgl::export(&options, &Inputs::bake()) {
        Ok(files) => files,
        Err(error) => {
            eprintln!("webgl: {error}");
            return ExitCode::FAILURE;
        }
    };
    let written = std::fs::create_dir_all(&arguments.out).and_then(|()| {
        files
            .iter()
            .try_for_each(|(name, bytes)| std::fs::write(arguments.out.join(name), bytes))
    });
    match written {
        Ok(()) => {
            eprintln!("wrote {}", arguments.out.display());
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("webgl: cannot write {}: {error}", arguments.out.display());
            ExitCode::FAILURE
        }
    }
}
