//! The renderer's cost: per G-buffer on wgpu, and per path of the on-tile backends (GLES and
//! Vulkan), the bytes each frame loads and stores, computed from the load and store operations
//! and formats the frame's passes really used (`gbuffer_render::recording`), in the bandwidth units of
//! Arm's tile-memory article (1 BU = width x height x 4 bytes), and the median frame time at
//! 1280x720 and 1920x1080 (wgpu: timestamp queries where the adapter has them; GLES and Vulkan:
//! wall clock around a synchronised frame). Then every wgpu configuration's PSNR against the
//! CPU reference. Run with `cargo bench -p gbuffer-render --bench deferred`. Between them,
//! where the Vulkan paths' time goes: each fused stage and each two-pass pass left out in turn.
//!
//! On a CPU rasteriser (llvmpipe, lavapipe) there is no tile memory: its times are a CPU's,
//! and the traffic the fused paths save is counted, not felt.

use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::gles::GlesRenderer;
use gbuffer_render::image::compare;
use gbuffer_render::named::Named;
use gbuffer_render::on_tile::{Path, Stage, TileOptions};
use gbuffer_render::options::{Frame, IblForm, Options, SunForm};
use gbuffer_render::recording::Recording;
use gbuffer_render::reference;
use gbuffer_render::vulkan::VulkanRenderer;
use gbuffer_render::wgpu::Renderer;

const FRAMES: usize = 10;
const SIZES: [(u32, u32); 2] = [(1280, 720), (1920, 1080)];

fn options(gbuffer: GBuffer, (width, height): (u32, u32)) -> Options {
    Options {
        gbuffer,
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width,
        height,
    }
}

/// The median of some frame times, in milliseconds, or why there is none.
fn median_ms(times: Result<Vec<f64>, String>) -> String {
    match times {
        Ok(mut times) if !times.is_empty() => {
            times.sort_by(f64::total_cmp);
            format!("{:.1}", times[times.len() / 2] * 1e3)
        }
        Ok(_) => "n/a".into(),
        Err(error) => {
            eprintln!("{error}");
            "n/a".into()
        }
    }
}

/// One row: the traffic of a recorded frame and the times at both sizes.
fn row(name: &str, recording: &Recording, times: [String; 2]) {
    let (width, height) = SIZES[1];
    let traffic = recording.traffic(width, height);
    println!(
        "{:<28} {:>6} {:>11.1} {:>11.1} {:>6.1} {:>12} {:>12}",
        name,
        recording.passes(),
        traffic.loaded as f64 / 1e6,
        traffic.stored as f64 / 1e6,
        traffic.bandwidth_units(width, height),
        times[0],
        times[1]
    );
}

/// Where the Vulkan paths' time goes, at 1280x720: each stage of the fused frame (and each
/// pass of the two-pass frame) timed by leaving it out, its share the whole frame's median less
/// the median without it.
fn stages(progress: &dyn Fn(&str)) {
    let vulkan = match VulkanRenderer::new(progress) {
        Ok(vulkan) => vulkan,
        Err(error) => return eprintln!("Vulkan: {error}"),
    };
    let median = |times: Result<Vec<f64>, String>| -> Option<f64> {
        let mut times = times.map_err(|error| eprintln!("{error}")).ok()?;
        times.sort_by(f64::total_cmp);
        times.get(times.len() / 2).map(|time| time * 1e3)
    };
    println!(
        "\nVulkan at {}x{}, each stage left out (median of {FRAMES} frames, ms):",
        SIZES[0].0, SIZES[0].1
    );
    println!(
        "{:<36} {:>10} {:>13} {:>10}",
        "path / stage", "frame ms", "without ms", "stage ms"
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
            let Some(whole) = median(vulkan.time_frames(&tile, FRAMES)) else {
                continue;
            };
            println!(
                "{:<36} {whole:>10.1}",
                format!("{} {}", path.name(), layout.name())
            );
            for name in names {
                if let Some(without) =
                    median(vulkan.time_frames_leaving_out(&tile, FRAMES, &[name]))
                {
                    println!(
                        "{:<36} {:>10} {without:>13.1} {:>10.1}",
                        format!("  {name}"),
                        "",
                        whole - without
                    );
                }
            }
        }
    }
}

fn main() {
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
        "wgpu adapter: {} ({:?}); frame times from {clock}, median of {FRAMES}",
        renderer.adapter.name, renderer.adapter.backend
    );
    println!("traffic per frame at 1920x1080 from the passes' load and store operations:");
    println!(
        "{:<28} {:>6} {:>11} {:>11} {:>6} {:>12} {:>12}",
        "G-buffer / path", "passes", "MB loaded", "MB stored", "BU", "1280x720 ms", "1920x1080 ms"
    );
    for gbuffer in GBuffer::named() {
        let recorded = renderer.render_recorded(&options(gbuffer.clone(), SIZES[1]));
        let times = SIZES
            .map(|size| median_ms(renderer.time_frames(&options(gbuffer.clone(), size), FRAMES)));
        match recorded {
            Ok((_, recording)) => row(&format!("wgpu {}", gbuffer.name()), &recording, times),
            Err(error) => eprintln!("{}: {error}", gbuffer.name()),
        }
    }

    // The on-tile backends, for the layouts they keep on tile.
    for layout in [PackedLayout::MobileMetallic, PackedLayout::FutureMetallic] {
        let tile = |path, size| TileOptions {
            options: options(GBuffer::Packed(layout), size),
            path,
        };
        match GlesRenderer::new(&progress) {
            Ok(gles) => {
                for path in [Path::TwoPass, Path::FetchPacked, Path::FetchNative] {
                    let name = format!("gles {} {}", path.name(), layout.name());
                    match gles.render(&tile(path, SIZES[1])) {
                        Ok((_, recording)) => {
                            let times = SIZES
                                .map(|size| median_ms(gles.time_frames(&tile(path, size), FRAMES)));
                            row(&name, &recording, times);
                        }
                        Err(error) => eprintln!("{name}: {error}"),
                    }
                }
            }
            Err(error) => eprintln!("GLES: {error}"),
        }
        match VulkanRenderer::new(&progress) {
            Ok(vulkan) => {
                for path in [Path::TwoPass, Path::Subpass] {
                    let name = format!("vulkan {} {}", path.name(), layout.name());
                    match vulkan.render(&tile(path, SIZES[1])) {
                        Ok((_, recording)) => {
                            let times = SIZES.map(|size| {
                                median_ms(vulkan.time_frames(&tile(path, size), FRAMES))
                            });
                            row(&name, &recording, times);
                        }
                        Err(error) => eprintln!("{name}: {error}"),
                    }
                }
            }
            Err(error) => eprintln!("Vulkan: {error}"),
        }
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
