//! The reference renderer on the adapter at hand (in CI, Mesa's lavapipe or llvmpipe): a small
//! frame renders, is not blank, matches the CPU reference, and its PNG is written.

use gbuffer_gpu::adapter::Request;
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::image::{compare, is_blank, write_png};
use gbuffer_render::options::{IblForm, Options, SunForm};
use gbuffer_render::reference;
use gbuffer_render::wgpu::Renderer;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;

/// The renderer on the adapter at hand, or none (the test skips) without one, except under CI.
fn renderer() -> Option<Renderer> {
    gbuffer_testkit::or_skip(
        "the wgpu renderer",
        Renderer::new(&|message| eprintln!("{message}")),
    )
}

fn accurate(gbuffer: GBuffer) -> Options {
    Options {
        gbuffer,
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: WIDTH,
        height: HEIGHT,
    }
}

/// The renderer's floor: the lossless G-buffer's frame against the CPU reference at 320x180.
/// 49.75 dB on llvmpipe, nearly half of whose squared error is two silhouette pixels that the
/// rasteriser's subpixel snapping covers and the ray caster misses (the guide's reference renderer chapter); the bar
/// with that cause named is 47 dB. One sampler for the LUT and the sky, repeating, left 41.6.
#[test]
fn the_lossless_frame_reaches_the_floor_against_the_cpu_reference() {
    let Some(renderer) = renderer() else {
        return;
    };
    let (width, height) = (320, 180);
    let frame = renderer
        .render(&Options {
            width,
            height,
            ..accurate(GBuffer::Packed(PackedLayout::Lossless))
        })
        .unwrap_or_else(|error| panic!("{error}"));
    let features = gbuffer_render::scene::reference_features();
    let cpu = reference::render(width, height, features, &|_| {});
    let comparison = compare(&frame, &cpu);
    eprintln!(
        "lossless against the CPU reference: PSNR {:.2} dB, largest error {}",
        comparison.psnr, comparison.max_error
    );
    // What the guide says the floor is made of: the pixels the rasteriser covers where the ray
    // caster sees sky, their share of the squared error, and the PSNR without them.
    let mesh = gbuffer_render::mesh::Mesh::scene();
    let (mut covered, mut covered_squares, mut squares) = (0, 0.0, 0.0);
    for (index, (rendered, traced)) in frame.pixels.iter().zip(&cpu.pixels).enumerate() {
        let pixel_squares: f64 = (0..3)
            .map(|channel| f64::from(rendered[channel].abs_diff(traced[channel])).powi(2))
            .sum();
        squares += pixel_squares;
        let (x, y) = (index as u32 % width, index as u32 / width);
        let (origin, direction) = gbuffer_render::scene::camera_ray(
            f64::from(x),
            f64::from(y),
            f64::from(width),
            f64::from(height),
        );
        if mesh.intersect(origin, direction).is_none() && pixel_squares > 100.0 {
            covered += 1;
            covered_squares += pixel_squares;
        }
    }
    let psnr_without = comparison.psnr + 10.0 * (squares / (squares - covered_squares)).log10();
    eprintln!(
        "{covered} pixels the rasteriser covers where the ray caster sees sky: {:.0}% of the \
         squared error; without them {psnr_without:.2} dB",
        100.0 * covered_squares / squares
    );
    assert!(comparison.psnr >= 49.0, "{comparison:?}");
}

/// On wgpu's GL backend held to WebGL2's limits (`Limits::downlevel_webgl2_defaults()`), whose
/// GLSL cannot load from a depth texture: a layout that stores the distance to the surface
/// renders, close to the CPU reference, and one that stores neither distance nor position is
/// refused with a message that names the limit, not a panic.
#[test]
fn under_webgl2_limits_on_gl_a_layout_with_depth_renders_and_one_without_is_refused() {
    let request = Request {
        label: "webgl2",
        limits: Some(wgpu::Limits::downlevel_webgl2_defaults()),
        features: wgpu::Features::empty(),
        backends: Some(wgpu::Backends::GL),
    };
    let Some(renderer) = gbuffer_testkit::or_skip(
        "wgpu's GL backend",
        Renderer::with_request(&request, &|message| eprintln!("{message}")),
    ) else {
        return;
    };
    let frame = renderer
        .render(&accurate(GBuffer::Packed(PackedLayout::MobileMetallic)))
        .unwrap_or_else(|error| panic!("{error}"));
    let features = gbuffer_render::scene::reference_features();
    let comparison = compare(&frame, &reference::render(WIDTH, HEIGHT, features, &|_| {}));
    eprintln!(
        "mobile-metallic on GL under WebGL2 limits: PSNR {:.2} dB",
        comparison.psnr
    );
    assert!(comparison.psnr >= 45.0, "{comparison:?}");
    let refused = renderer
        .render(&accurate(GBuffer::Packed(PackedLayout::ArmTileBlock)))
        .expect_err("arm-tile-block stores no depth");
    assert!(
        refused.contains("cannot load from a depth texture"),
        "{refused}"
    );
}

#[test]
fn every_gbuffer_renders_a_frame_that_matches_the_cpu_reference() {
    let Some(renderer) = renderer() else {
        return;
    };
    let reference = reference::render(
        WIDTH,
        HEIGHT,
        gbuffer_render::scene::reference_features(),
        &|_| {},
    );
    assert!(!is_blank(&reference));
    for gbuffer in GBuffer::named() {
        let frame = renderer
            .render(&accurate(gbuffer.clone()))
            .unwrap_or_else(|error| panic!("{error}"));
        assert!(!is_blank(&frame), "{}: the frame is blank", gbuffer.name());
        let comparison = compare(&frame, &reference);
        eprintln!(
            "{}: PSNR {:.2} dB, largest error {}",
            gbuffer.name(),
            comparison.psnr,
            comparison.max_error
        );
        assert!(
            comparison.psnr >= 35.0,
            "{}: PSNR {:.2} dB against the CPU reference",
            gbuffer.name(),
            comparison.psnr
        );
    }
}

#[test]
fn the_mobile_forms_render_close_to_the_accurate_reference() {
    let Some(renderer) = renderer() else {
        return;
    };
    let options = Options {
        sun: SunForm::Approx,
        ibl: IblForm::Approx,
        ..accurate(GBuffer::Packed(PackedLayout::MobileMetallic))
    };
    let frame = renderer
        .render(&options)
        .unwrap_or_else(|error| panic!("{error}"));
    let comparison = compare(
        &frame,
        &reference::render(
            WIDTH,
            HEIGHT,
            gbuffer_render::scene::reference_features(),
            &|_| {},
        ),
    );
    eprintln!("mobile forms: PSNR {:.2} dB", comparison.psnr);
    // The approximations cost accuracy (D_Approx's lobe, EnvBRDFApprox at grazing angles).
    assert!(
        comparison.psnr >= 28.0 && comparison.psnr < 60.0,
        "PSNR {:.2} dB",
        comparison.psnr
    );
}

#[test]
fn the_png_is_written() {
    let Some(renderer) = renderer() else {
        return;
    };
    let frame = renderer
        .render(&accurate(GBuffer::Packed(PackedLayout::ArmTileBlock)))
        .unwrap_or_else(|error| panic!("{error}"));
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("frame.png");
    write_png(&path, &frame).unwrap();
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&path).unwrap()));
    let reader = decoder.read_info().unwrap();
    assert_eq!((reader.info().width, reader.info().height), (WIDTH, HEIGHT));
}
