//! The on-tile renderer on real drivers (Mesa's llvmpipe through EGL for GLES 3.2, lavapipe for
//! Vulkan): every path renders the scene with its decals and 32 light volumes close to the CPU
//! reference and to the wgpu frame; the fused paths' recorded calls show one pass that stores
//! only the output; the G-buffer's words agree across backends; bad configurations are named.

use gbuffer_core::Named;
use gbuffer_gpu::vulkan::OptionalExtensions;
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::gles::GlesRenderer;
use gbuffer_render::image::{compare, is_blank};
use gbuffer_render::on_tile::{Path, TileOptions};
use gbuffer_render::options::{Frame, IblForm, Options, SunForm};
use gbuffer_render::recording::{Call, Recording};
use gbuffer_render::reference;
use gbuffer_render::scene::{reference_features, DECALS};
use gbuffer_render::vulkan::VulkanRenderer;
use gbuffer_render::wgpu::Renderer;
use gbuffer_testkit::or_skip;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 180;

fn options(layout: PackedLayout) -> Options {
    Options {
        gbuffer: GBuffer::Packed(layout),
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: WIDTH,
        height: HEIGHT,
    }
}

fn tile(layout: PackedLayout, path: Path) -> TileOptions {
    TileOptions {
        options: options(layout),
        path,
    }
}

fn quiet(_: &str) {}

/// A GLES renderer, or none (the test skips) without a driver, except under CI.
fn gles() -> Option<GlesRenderer> {
    or_skip("the GLES on-tile renderer", GlesRenderer::new(&quiet))
}

/// A Vulkan renderer, or none (the test skips) without a driver, except under CI.
fn vulkan() -> Option<VulkanRenderer> {
    or_skip("the Vulkan on-tile renderer", VulkanRenderer::new(&quiet))
}

/// The wgpu renderer, or none (the test skips) without an adapter, except under CI.
fn wgpu() -> Option<Renderer> {
    or_skip("the wgpu renderer", Renderer::new(&quiet))
}

/// Every path of both backends, with the frame and the calls of one frame (none without the
/// drivers).
fn every_path(layout: PackedLayout) -> Vec<(String, Frame, Recording)> {
    let mut frames = Vec::new();
    let (Some(gles), Some(vulkan)) = (gles(), vulkan()) else {
        return frames;
    };
    for path in [Path::FetchNative, Path::FetchPacked, Path::TwoPass] {
        let (frame, recording) = gles
            .render(&tile(layout, path))
            .unwrap_or_else(|error| panic!("gles {}: {error}", path.name()));
        frames.push((format!("gles {}", path.name()), frame, recording));
    }
    for path in [
        Path::Subpass,
        Path::LocalRead,
        Path::LocalReadOrdered,
        Path::TwoPass,
    ] {
        let (frame, recording) = vulkan
            .render(&tile(layout, path))
            .unwrap_or_else(|error| panic!("vulkan {}: {error}", path.name()));
        frames.push((format!("vulkan {}", path.name()), frame, recording));
    }
    frames
}

#[test]
fn every_path_renders_the_scene_close_to_the_reference_and_to_wgpu() {
    let layout = PackedLayout::MobileMetallic;
    let reference = reference::render(WIDTH, HEIGHT, reference_features(), &|_| {});
    let Some(wgpu) = wgpu() else {
        return;
    };
    let wgpu = wgpu
        .render(&options(layout))
        .unwrap_or_else(|error| panic!("wgpu: {error}"));
    let mut failures = Vec::new();
    let mut figures = Vec::new();
    for (name, frame, _) in every_path(layout) {
        assert!(!is_blank(&frame), "{name}: the frame is blank");
        let against_reference = compare(&frame, &reference);
        let against_wgpu = compare(&frame, &wgpu);
        eprintln!(
            "{name}: {:.2} dB against the CPU reference, {:.2} dB against wgpu",
            against_reference.psnr, against_wgpu.psnr
        );
        let decibels = |psnr: f64| format!("{psnr:.1} dB");
        figures.push(vec![
            name.clone(),
            decibels(against_reference.psnr),
            decibels(against_wgpu.psnr),
        ]);
        if against_reference.psnr < 44.0 || against_wgpu.psnr < 45.0 {
            failures.push(format!(
                "{name}: {:.2} dB against the reference (44 needed), {:.2} dB against wgpu (45 needed)",
                against_reference.psnr, against_wgpu.psnr
            ));
        }
    }
    // The guide's table (the fused renderer's PSNRs).
    let header = [
        "path",
        "PSNR against the CPU reference",
        "PSNR against the wgpu frame",
    ];
    gbuffer_testkit::write_figures("on-tile-psnr", &header, &figures);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_fused_paths_keep_the_gbuffer_in_one_pass_and_store_only_the_output() {
    for (name, frame, recording) in every_path(PackedLayout::MobileMetallic) {
        let draws: Vec<&str> = recording
            .calls
            .iter()
            .filter_map(|call| match call {
                Call::Draw { program } => Some(program.as_str()),
                _ => None,
            })
            .collect();
        let read_back: Vec<&Call> = recording
            .calls
            .iter()
            .filter(|call| matches!(call, Call::ReadBack(_)))
            .collect();
        assert_eq!(read_back, [&Call::ReadBack("output".into())], "{name}");
        let traffic = recording.traffic(frame.width, frame.height);
        if name.ends_with("two-pass") {
            // The baseline: the G-buffer stored, then sampled by a second pass.
            assert_eq!(recording.passes(), 2, "{name}: {recording:#?}");
            assert_eq!(recording.stored(), ["gbuffer0", "output"], "{name}");
            assert_eq!(traffic.bandwidth_units(WIDTH, HEIGHT), 9.0, "{name}");
            continue;
        }
        assert_eq!(recording.passes(), 1, "{name}: {recording:#?}");
        assert_eq!(recording.stored(), ["output"], "{name}: {recording:#?}");
        if name.starts_with("gles") {
            // GLES says so explicitly: the G-buffer and depth are invalidated before the end.
            let invalidated = recording.invalidated();
            assert!(
                invalidated.contains(&"gbuffer0") && invalidated.contains(&"depth"),
                "{name}: invalidated {invalidated:?}"
            );
        }
        assert_eq!(
            (traffic.loaded, traffic.stored),
            (0, u64::from(WIDTH * HEIGHT * 4)),
            "{name}: only the output leaves the chip"
        );
        let count = |program| draws.iter().filter(|draw| **draw == program).count();
        assert_eq!(count("geometry"), 1, "{name}: {draws:?}");
        assert_eq!(count("decal"), DECALS.len(), "{name}: {draws:?}");
        // All the light in one draw: one read and one write of each texel for it.
        assert_eq!(count("lighting"), 1, "{name}: {draws:?}");
        assert_eq!(count("resolve"), 1, "{name}: {draws:?}");
    }
}

/// The draws after each barrier of a recording, in order: what each barrier guards.
fn draws_after_barriers(recording: &Recording) -> Vec<&str> {
    let mut guarded = Vec::new();
    let mut barrier = false;
    for call in &recording.calls {
        match call {
            Call::Barrier => barrier = true,
            Call::Draw { program } if barrier => {
                guarded.push(program.as_str());
                barrier = false;
            }
            _ => {}
        }
    }
    guarded
}

#[test]
fn the_local_read_paths_draw_the_subpass_frame_bit_for_bit() {
    let Some(vulkan) = vulkan() else {
        return;
    };
    for layout in [PackedLayout::MobileMetallic, PackedLayout::FutureMetallic] {
        let render = |path: Path| {
            vulkan
                .render(&tile(layout, path))
                .unwrap_or_else(|error| panic!("{} {}: {error}", layout.name(), path.name()))
        };
        let (subpass, subpass_calls) = render(Path::Subpass);
        let (local_read, local_read_calls) = render(Path::LocalRead);
        let (ordered, ordered_calls) = render(Path::LocalReadOrdered);
        for (name, frame) in [
            ("local-read", &local_read),
            ("local-read-ordered", &ordered),
        ] {
            let differing = frame
                .pixels
                .iter()
                .zip(&subpass.pixels)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(
                differing,
                0,
                "{} {name}: {differing} pixels differ from the subpass frame",
                layout.name()
            );
        }
        // A barrier before every draw that reads what earlier draws wrote (each decal, the
        // lighting, the resolve), as in the subpass; none at all in rasterization order.
        let mut guarded = vec!["decal"; DECALS.len()];
        guarded.extend(["lighting", "resolve"]);
        assert_eq!(draws_after_barriers(&subpass_calls), guarded);
        assert_eq!(draws_after_barriers(&local_read_calls), guarded);
        assert!(
            !ordered_calls.calls.contains(&Call::Barrier),
            "{}: {ordered_calls:#?}",
            layout.name()
        );
        for recording in [&local_read_calls, &ordered_calls] {
            assert_eq!(recording.passes(), 1);
            assert_eq!(recording.stored(), ["output"]);
            let traffic = recording.traffic(WIDTH, HEIGHT);
            assert_eq!(traffic.bandwidth_units(WIDTH, HEIGHT), 1.0);
        }
    }
}

#[test]
fn a_device_without_local_read_refuses_its_paths_naming_what_it_lacks() {
    let Some(device) = or_skip(
        "Vulkan",
        gbuffer_gpu::vulkan::Vulkan::with(OptionalExtensions::None),
    ) else {
        return;
    };
    let vulkan = VulkanRenderer::on(device, &quiet).unwrap_or_else(|error| panic!("{error}"));
    for path in [Path::LocalRead, Path::LocalReadOrdered] {
        let error = vulkan
            .render(&tile(PackedLayout::MobileMetallic, path))
            .expect_err("an error");
        assert!(
            error.contains(&format!("--path {}", path.name()))
                && error.contains("needs dynamic rendering with local read")
                && error.contains("opened without its optional extensions"),
            "{error}"
        );
    }
    // The other paths draw as before.
    vulkan
        .render(&tile(PackedLayout::MobileMetallic, Path::Subpass))
        .unwrap_or_else(|error| panic!("{error}"));
}

#[test]
fn a_256_bit_layout_renders_on_the_packed_paths() {
    let layout = PackedLayout::FutureMetallic;
    let (Some(gles), Some(vulkan)) = (gles(), vulkan()) else {
        return;
    };
    let reference = reference::render(WIDTH, HEIGHT, reference_features(), &|_| {});
    let (gles_frame, _) = gles
        .render(&tile(layout, Path::FetchPacked))
        .unwrap_or_else(|error| panic!("{error}"));
    let (vulkan_frame, recording) = vulkan
        .render(&tile(layout, Path::Subpass))
        .unwrap_or_else(|error| panic!("{error}"));
    assert_eq!(recording.stored(), ["output"]);
    for (name, frame) in [("gles", gles_frame), ("vulkan", vulkan_frame)] {
        let psnr = compare(&frame, &reference).psnr;
        eprintln!("future-metallic on {name}: {psnr:.2} dB");
        assert!(psnr >= 40.0, "future-metallic on {name}: {psnr:.2} dB");
    }
}

#[test]
fn the_gbuffer_words_agree_across_backends() {
    let options = options(PackedLayout::MobileMetallic);
    let (Some(gles), Some(vulkan)) = (gles(), vulkan()) else {
        return;
    };
    let Some(wgpu) = wgpu() else {
        return;
    };
    let wgpu = wgpu
        .gbuffer_words(&options)
        .unwrap_or_else(|error| panic!("wgpu: {error}"));
    let vulkan = vulkan
        .gbuffer_words(&options)
        .unwrap_or_else(|error| panic!("vulkan: {error}"));
    let gles = gles
        .gbuffer_words(&options)
        .unwrap_or_else(|error| panic!("gles: {error}"));
    assert_eq!(wgpu.len(), (WIDTH * HEIGHT * 4) as usize);
    // wgpu and Vulkan run the same SPIR-V path to the same rasteriser: bit for bit.
    let differing = wgpu.iter().zip(&vulkan).filter(|(a, b)| a != b).count();
    assert_eq!(differing, 0, "wgpu and Vulkan differ in {differing} words");
    // GL interpolates the varyings with other roundings, so the surface values reaching the
    // packing differ in their last bits: the depth word (an f32 eye distance) by a few ulps,
    // and at a handful of pixels on sphere tops, where the pixel centre lies on a triangle
    // edge, GL takes the neighbouring triangle: depth and normal differ a little more there.
    // The light and albedo words are the same everywhere.
    let pixels = (WIDTH * HEIGHT) as usize;
    let (mut close_depths, mut other_triangle, mut normal_codes) = (0, 0, 0);
    for (pixel, (a, b)) in wgpu.chunks(4).zip(gles.chunks(4)).enumerate() {
        assert_eq!(
            (a[0], a[3]),
            (b[0], b[3]),
            "pixel {pixel}: light or albedo words differ"
        );
        let ulps = a[1].abs_diff(b[1]);
        if ulps > 64 {
            other_triangle += 1;
        } else if ulps > 0 {
            close_depths += 1;
        }
        let codes = |word: u32| word.to_le_bytes();
        for (x, y) in codes(a[2]).iter().zip(codes(b[2])) {
            normal_codes = normal_codes.max(x.abs_diff(y));
        }
    }
    eprintln!(
        "GLES against wgpu: {close_depths} depths within 64 ulps, {other_triangle} pixels on \
         another triangle; normals within {normal_codes} codes"
    );
    assert!(
        other_triangle * 5000 < pixels,
        "{other_triangle} pixels differ by more"
    );
    assert!(
        normal_codes <= 8,
        "normals differ by up to {normal_codes} codes"
    );
}

#[test]
fn configurations_the_paths_cannot_draw_are_named() {
    let (Some(gles), Some(vulkan)) = (gles(), vulkan()) else {
        return;
    };
    let error = |result: Result<(Frame, Recording), String>| result.expect_err("an error");
    let specular = error(gles.render(&tile(PackedLayout::SpecularWorkflow, Path::FetchPacked)));
    assert!(
        specular.contains("diffuse and specular colour"),
        "{specular}"
    );
    let arm = error(gles.render(&tile(PackedLayout::ArmTileBlock, Path::FetchNative)));
    assert!(arm.contains("neither depth nor position"), "{arm}");
    // Eight native attachments and the output: more than llvmpipe's eight draw buffers.
    let native = error(gles.render(&tile(PackedLayout::FutureMetallic, Path::FetchNative)));
    assert!(
        native.contains("GL_MAX_DRAW_BUFFERS") && native.contains("9 colour attachments"),
        "{native}"
    );
    let wrong_api = error(gles.render(&tile(PackedLayout::MobileMetallic, Path::Subpass)));
    assert!(wrong_api.contains("Vulkan"), "{wrong_api}");
    let wrong_api = error(vulkan.render(&tile(PackedLayout::MobileMetallic, Path::FetchNative)));
    assert!(wrong_api.contains("GLES"), "{wrong_api}");
}
