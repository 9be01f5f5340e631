//! The renderer's cost: per G-buffer on wgpu, and per path of the on-tile backends (GLES and
//! Vulkan), the bytes each frame loads and stores, computed from the load and store operations
//! and formats the frame's passes really used (`gbuffer_render::recording`), in the bandwidth units of
//! Arm's tile-memory article (1 BU = width x height x 4 bytes), and the frame time at 1280x720
//! and 1920x1080 (wgpu: timestamp queries where the adapter has them; GLES and Vulkan: wall
//! clock around a synchronised frame), by the protocol the trade-off study's frame table uses
//! (`gbuffer_gpu::timing::time_items`: warm-up rounds, then every frame of a table once a
//! round; the median, and the rounds' spread). Then every wgpu configuration's PSNR against the
//! CPU reference. Run with `cargo bench -p gbuffer-render --bench deferred`. Between them,
//! where the Vulkan paths' time goes: the frame built up stage by stage, each fused stage and
//! each two-pass pass timed by what it adds.
//!
//! On a CPU rasteriser (llvmpipe, lavapipe) there is no tile memory: its times are a CPU's,
//! and the traffic the fused paths save is counted, not felt.

use std::sync::LazyLock;

use gbuffer_core::Named;
use gbuffer_gpu::stages::stage_times;
use gbuffer_gpu::timing::{time_items, Protocol, Spread};
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::gles::GlesRenderer;
use gbuffer_render::image::compare;
use gbuffer_render::on_tile::{Path, Stage, TileOptions};
use gbuffer_render::options::{Frame, IblForm, Options, SunForm};
use gbuffer_render::recording::Recording;
use gbuffer_render::reference;
use gbuffer_render::vulkan::VulkanRenderer;
use gbuffer_render::wgpu::Renderer;

const SIZES: [(u32, u32); 2] = [(1280, 720), (1920, 1080)];
/// The report's protocol: its frame table and this bench time frames alike (the full one, or
/// the short one where `GBUFFER_TIMING=short` asks for it). A bad value ends the bench at its
/// start, naming the variable.
static PROTOCOL: LazyLock<Protocol> = LazyLock::new(|| {
    Protocol::chosen().unwrap_or_else(|error| {
        eprintln!("{error}");
        std::process::exit(1)
    })
});

fn options(gbuffer: GBuffer, (width, height): (u32, u32)) -> Options {
    Options {
        gbuffer,
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width,
        height,
    }
}

/// Times `frames` (each a closure timing one frame, in seconds) by the protocol; per frame,
/// its median and spread in milliseconds as `12.3 (12.1-12.9)`, or `n/a` where a frame could
/// not be timed (the reason on stderr).
fn time_all(frames: &[Result<FrameClock<'_>, String>]) -> Vec<String> {
    let timed: Vec<&dyn Fn() -> Result<f64, String>> = frames
        .iter()
        .filter_map(|frame| {
            frame
                .as_ref()
                .map_err(|error| eprintln!("{error}"))
                .ok()
                .map(|frame| frame.as_ref())
        })
        .collect();
    // Where the protocol fails (the reason on stderr), every frame reads n/a.
    let spreads = time_items(&PROTOCOL, timed.len(), &mut |index| timed[index]())
        .map_err(|error| eprintln!("{error}"))
        .map(|(_, spreads)| spreads)
        .unwrap_or_default();
    let mut spreads = spreads.into_iter();
    frames
        .iter()
        .map(|frame| match frame {
            Ok(_) => spreads.next().map_or_else(|| "n/a".into(), ms),
            Err(_) => "n/a".into(),
        })
        .collect()
}

/// A frame that times itself (a renderer's `TimedFrame::seconds`): one frame's seconds each
/// call.
type FrameClock<'a> = Box<dyn Fn() -> Result<f64, String> + 'a>;

/// Each of `items`' frames (`frame(item, size)`) timed at both sizes, one table per size: per
/// size, the times in `items`' order ([`time_all`]).
fn time_sizes<'a, T>(
    items: &[T],
    frame: impl Fn(&T, (u32, u32)) -> Result<FrameClock<'a>, String>,
) -> [std::vec::IntoIter<String>; 2] {
    SIZES.map(|size| {
        let frames: Vec<_> = items.iter().map(|item| frame(item, size)).collect();
        time_all(&frames).into_iter()
    })
}

/// A spread of seconds as milliseconds: the median, then the least and greatest.
fn ms(spread: Spread) -> String {
    let spread = spread.map(|seconds| seconds * 1e3);
    format!("{:.1} ({:.1}-{:.1})", spread.median, spread.min, spread.max)
}

/// One row: the traffic of a recorded frame and the times at both sizes.
fn row(name: &str, recording: &Recording, times: [String; 2]) {
    let (width, height) = SIZES[1];
    let traffic = recording.traffic(width, height);
    println!(
        "{:<42} {:>6} {:>11.1} {:>11.1} {:>6.1} {:>18} {:>18}",
        name,
        recording.passes(),
        traffic.loaded as f64 / 1e6,
        traffic.stored as f64 / 1e6,
        traffic.bandwidth_units(width, height),
        times[0],
        times[1]
    );
}

/// Where the Vulkan paths' time goes, at 1280x720: the frame built up stage by stage (each
/// fused stage, each two-pass pass) in the frame's order, from the render passes with nothing
/// drawn to the whole frame, every one of those frames timed together; a stage's time is what it
/// adds to the frame before it (`gbuffer_gpu::stages`): frames the rounds cannot tell apart are
/// pooled, the pool's first stage carries what the pool adds and the others are printed `with
/// the stage before`, so no stage's time is negative or taken by another, and the stages' times
/// sum to the whole frame's less the empty passes', within the spread.
fn stages(progress: &dyn Fn(&str)) {
    let vulkan = match VulkanRenderer::new(progress) {
        Ok(vulkan) => vulkan,
        Err(error) => return eprintln!("Vulkan: {error}"),
    };
    println!(
        "\nVulkan at {}x{}, the frame built up stage by stage (median of {} rounds, ms; a \
         stage's time is what it adds to the frame before it):",
        SIZES[0].0, SIZES[0].1, PROTOCOL.rounds
    );
    println!(
        "{:<36} {:>14} {:>14} {:>8}",
        "path / stage", "frame so far", "stage adds", "share"
    );
    for layout in [PackedLayout::MobileMetallic, PackedLayout::FutureMetallic] {
        for (path, names) in [
            (
                Path::Subpass,
                Stage::ALL
                    .iter()
                    .map(|stage| stage.name())
                    .collect::<Vec<_>>(),
            ),
            (Path::TwoPass, vec!["gbuffer", "lighting and resolve"]),
        ] {
            let tile = TileOptions {
                options: options(GBuffer::Packed(layout), SIZES[0]),
                path,
            };
            // Frame k draws the first k stages: frame 0 none, the last every one.
            let frames = match (0..=names.len())
                .map(|drawn| vulkan.timed_frame(&tile, &names[drawn..]))
                .collect::<Result<Vec<_>, String>>()
            {
                Ok(frames) => frames,
                Err(error) => {
                    eprintln!("{error}");
                    continue;
                }
            };
            let spreads = match time_items(&PROTOCOL, frames.len(), &mut |index| {
                frames[index].seconds()
            }) {
                Ok((_, spreads)) => spreads,
                Err(error) => {
                    eprintln!("{error}");
                    continue;
                }
            };
            let spreads: Vec<Spread> = spreads
                .iter()
                .map(|spread| spread.map(|s| s * 1e3))
                .collect();
            println!(
                "{:<36} {:>14.2}",
                format!("{} {}", path.name(), layout.name()),
                spreads[names.len()].median
            );
            println!(
                "{:<36} {:>14.2}",
                "  render passes, nothing drawn", spreads[0].median
            );
            let times = stage_times(&spreads);
            // The stages' times sum to what the frame adds to the empty passes, pooled frames'
            // means where the rounds could not separate them: the shares sum to 100%.
            let drawn: f64 = times.iter().filter_map(|time| time.adds()).sum();
            for (index, (name, time)) in names.iter().zip(&times).enumerate() {
                let cell = match time.adds() {
                    Some(ms) => format!("{ms:>14.2} {:>7.0}%", 100.0 * ms / drawn),
                    None => format!("{:>23}", "with the stage before"),
                };
                let so_far = spreads[index + 1].median;
                println!("{:<36} {so_far:>14.2} {cell}", format!("  {name}"));
            }
        }
    }
}

/// One on-tile backend's rows: each layout it keeps on tile on each of `paths`, all of them
/// timed together at each size (`frame`), with the traffic of the 1920x1080 frame (`render`).
fn tile_rows<'a>(
    backend: &str,
    paths: &[Path],
    frame: impl Fn(&TileOptions) -> Result<FrameClock<'a>, String>,
    render: impl Fn(&TileOptions) -> Result<Recording, String>,
) {
    let tile = |layout, path, size| TileOptions {
        options: options(GBuffer::Packed(layout), size),
        path,
    };
    let configurations: Vec<(PackedLayout, Path)> =
        [PackedLayout::MobileMetallic, PackedLayout::FutureMetallic]
            .into_iter()
            .flat_map(|layout| paths.iter().map(move |&path| (layout, path)))
            .collect();
    let mut times = time_sizes(&configurations, |&(layout, path), size| {
        frame(&tile(layout, path, size))
    });
    for &(layout, path) in &configurations {
        let name = format!("{backend} {} {}", path.name(), layout.name());
        let row_times = [0, 1].map(|size| times[size].next().unwrap_or_default());
        match render(&tile(layout, path, SIZES[1])) {
            Ok(recording) => row(&name, &recording, row_times),
            Err(error) => eprintln!("{name}: {error}"),
        }
    }
}

fn main() {
    LazyLock::force(&PROTOCOL);
    let progress = |message: &str| eprintln!("{message}");
    let renderer = match Renderer::new(&progress) {
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
        "wgpu adapter: {} ({:?}); frame times from {clock}, median (min-max) of {} rounds",
        renderer.adapter.name, renderer.adapter.backend, PROTOCOL.rounds
    );
    println!("traffic per frame at 1920x1080 from the passes' load and store operations:");
    println!(
        "{:<42} {:>6} {:>11} {:>11} {:>6} {:>18} {:>18}",
        "G-buffer / path", "passes", "MB loaded", "MB stored", "BU", "1280x720 ms", "1920x1080 ms"
    );
    // Every G-buffer's frame at one size timed together, so no clock change falls on one.
    let gbuffers: Vec<GBuffer> = GBuffer::named().collect();
    let mut times = time_sizes(&gbuffers, |gbuffer, size| {
        let frame = renderer.timed_frame(&options(gbuffer.clone(), size))?;
        Ok(Box::new(move || frame.seconds()))
    });
    for gbuffer in &gbuffers {
        let recorded = renderer.render_recorded(&options(gbuffer.clone(), SIZES[1]));
        let row_times = [0, 1].map(|size| times[size].next().unwrap_or_default());
        match recorded {
            Ok((_, recording)) => row(&format!("wgpu {}", gbuffer.name()), &recording, row_times),
            Err(error) => eprintln!("{}: {error}", gbuffer.name()),
        }
    }

    // The on-tile backends, for the layouts they keep on tile.
    match GlesRenderer::new(&progress) {
        Ok(gles) => tile_rows(
            "gles",
            &[Path::TwoPass, Path::FetchPacked, Path::FetchNative],
            |tile| {
                let frame = gles.timed_frame(tile)?;
                Ok(Box::new(move || frame.seconds()))
            },
            |tile| gles.render(tile).map(|(_, recording)| recording),
        ),
        Err(error) => eprintln!("GLES: {error}"),
    }
    match VulkanRenderer::new(&progress) {
        Ok(vulkan) => tile_rows(
            "vulkan",
            &[
                Path::TwoPass,
                Path::Subpass,
                Path::LocalRead,
                Path::LocalReadOrdered,
            ],
            |tile| {
                let frame = vulkan.timed_frame(tile, &[])?;
                Ok(Box::new(move || frame.seconds()))
            },
            |tile| vulkan.render(tile).map(|(_, recording)| recording),
        ),
        Err(error) => eprintln!("Vulkan: {error}"),
    }

    stages(&progress);

    // Every wgpu configuration against the CPU reference, at a size it renders quickly.
    let (width, height) = (320, 180);
    let reference: Frame = reference::render(
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
    for gbuffer in GBuffer::named() {
        for (sun, ibl) in [
            (SunForm::Ggx, IblForm::Lut),
            (SunForm::Ggx, IblForm::Approx),
            (SunForm::Approx, IblForm::Lut),
            (SunForm::Approx, IblForm::Approx),
        ] {
            let options = Options {
                sun,
                ibl,
                ..options(gbuffer.clone(), (width, height))
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
