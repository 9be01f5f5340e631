//! The renderer's cost per G-buffer configuration: bytes per pixel, external bandwidth per
//! frame in the bandwidth units of Arm's tile-memory article (1 BU = width x height x 4 bytes
//! read or written), and the measured GPU frame time (timestamp queries where the adapter has
//! them, else wall clock around a synchronised submit; median of 20 frames) at 1280x720 and
//! 1920x1080, packed against classic, on the adapter at hand; then the PSNR and largest error
//! of every configuration (G-buffer, sun and IBL forms) against the CPU reference. Run with `cargo bench -p examples --bench deferred`.

use gbuffer_render::gbuffers::{GBuffer, SeedLayout};
use gbuffer_render::image::compare;
use gbuffer_render::reference;
use gbuffer_render::renderer::{IblForm, Options, Renderer, SunForm};

const FRAMES: usize = 20;

/// External traffic of one frame in BU, as this renderer runs on wgpu: the G-buffer written
/// and read back (g BU each), the HDR light written and read (2 BU each, Rgba16Float), the
/// 8-bit output written (1 BU). Fused on tile (pixel local storage, framebuffer fetch or
/// subpasses) only the output leaves the chip: 1 BU.
fn bandwidth_units(gbuffer: &GBuffer) -> f64 {
    let gbuffer_units = f64::from(gbuffer.bytes_per_pixel()) / 4.0;
    2.0 * gbuffer_units + 2.0 * 2.0 + 1.0
}

fn main() {
    let renderer = match Renderer::new(&|message| eprintln!("{message}")) {
        Ok(renderer) => renderer,
        Err(error) => {
            eprintln!("deferred bench: {error}");
            std::process::exit(1);
        }
    };
    let clock = if renderer.has_timestamps() {
        "timestamp queries"
    } else {
        "wall clock around a synchronised submit"
    };
    println!(
        "adapter: {} ({:?}); frame times from {clock}, median of {FRAMES}",
        renderer.adapter.name, renderer.adapter.backend
    );
    println!(
        "{:<18} {:>9} {:>11} {:>12} {:>10} {:>14} {:>14}",
        "G-buffer",
        "bytes/px",
        "fits 128b",
        "BU (wgpu)",
        "BU (tile)",
        "1280x720 ms",
        "1920x1080 ms"
    );
    let gbuffers = SeedLayout::ALL
        .into_iter()
        .map(GBuffer::Packed)
        .chain([GBuffer::Classic]);
    for gbuffer in gbuffers {
        let mut times = Vec::new();
        for (width, height) in [(1280, 720), (1920, 1080)] {
            let options = Options {
                gbuffer: gbuffer.clone(),
                sun: SunForm::Ggx,
                ibl: IblForm::Lut,
                width,
                height,
            };
            match renderer.time_frames(&options, FRAMES) {
                Ok(mut frames) => {
                    frames.sort_by(f64::total_cmp);
                    times.push(format!("{:.2}", frames[frames.len() / 2] * 1e3));
                }
                Err(error) => {
                    eprintln!("{}: {error}", gbuffer.name());
                    times.push("n/a".into());
                }
            }
        }
        let bytes = gbuffer.bytes_per_pixel();
        println!(
            "{:<18} {:>9} {:>11} {:>12.1} {:>10.1} {:>14} {:>14}",
            gbuffer.name(),
            bytes,
            if bytes <= 16 { "yes" } else { "no" },
            bandwidth_units(&gbuffer),
            1.0,
            times[0],
            times[1]
        );
    }

    // Every configuration against the CPU reference, at a size the reference renders quickly.
    let (width, height) = (320, 180);
    let reference = reference::render(
        width,
        height,
        gbuffer_render::scene::reference_features(),
        &|_| {},
    );
    println!("\nagainst the CPU reference at {width}x{height}:");
    println!(
        "{:<18} {:<7} {:<7} {:>9} {:>13}",
        "G-buffer", "sun", "IBL", "PSNR dB", "largest error"
    );
    for gbuffer in SeedLayout::ALL
        .into_iter()
        .map(GBuffer::Packed)
        .chain([GBuffer::Classic])
    {
        for (sun, ibl) in [
            (SunForm::Ggx, IblForm::Lut),
            (SunForm::Ggx, IblForm::Approx),
            (SunForm::Approx, IblForm::Lut),
            (SunForm::Approx, IblForm::Approx),
        ] {
            let options = Options {
                gbuffer: gbuffer.clone(),
                sun,
                ibl,
                width,
                height,
            };
            match renderer.render(&options) {
                Ok(frame) => {
                    let comparison = compare(&frame, &reference);
                    println!(
                        "{:<18} {:<7} {:<7} {:>9.2} {:>13}",
                        gbuffer.name(),
                        format!("{sun:?}"),
                        format!("{ibl:?}"),
                        comparison.psnr,
                        comparison.max_error
                    );
                }
                Err(error) => eprintln!("{}: {error}", gbuffer.name()),
            }
        }
    }
}
