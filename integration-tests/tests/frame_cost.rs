//! What a layout costs the picture: each layout's frame against the lossless G-buffer's (every
//! quantity an f32), in the order the trade-off study's whole-layout rows predict, and a scene
//! solved for a tighter precision no worse in the frame than the same scene solved looser.

use std::path::Path;
use std::sync::Arc;

use gbuffer_core::Named;
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::image::compare;
use gbuffer_render::options::{Frame, IblForm, Options, SunForm};
use gbuffer_render::wgpu::Renderer;

/// A frame, small: 160x90.
fn options(gbuffer: GBuffer) -> Options {
    Options {
        gbuffer,
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: 160,
        height: 90,
    }
}

fn renderer() -> Option<Renderer> {
    gbuffer_testkit::or_skip(
        "the wgpu renderer",
        Renderer::new(&|message| eprintln!("{message}")),
    )
}

fn render(renderer: &Renderer, gbuffer: GBuffer) -> Frame {
    renderer
        .render(&options(gbuffer))
        .unwrap_or_else(|error| panic!("{error}"))
}

/// Coarser storage, lower PSNR against the lossless frame: the layouts the study rates worse
/// (a larger largest error over its surfaces) come out further from the lossless frame. The
/// coarse layout (2 x 8-bit octahedral normals), Listing 2.2, the Arm block, Listing 2.7 and
/// Listing 2.8: five PSNRs, all different, in the predicted order.
#[test]
fn frames_order_the_layouts_as_the_trade_off_study_predicts() {
    let Some(renderer) = renderer() else {
        return;
    };
    let predictions = gbuffer_tradeoff::layout_errors();
    let predicted = |layout: PackedLayout| {
        let name = format!("({})", layout.layout().name);
        predictions
            .iter()
            .find(|(row, _)| row.ends_with(&name))
            .unwrap_or_else(|| panic!("no trade-off row for {name}"))
            .1
    };
    let lossless = render(&renderer, GBuffer::Packed(PackedLayout::Lossless));
    let mut measured: Vec<(f64, f64, PackedLayout)> = [
        PackedLayout::CoarseNormals,
        PackedLayout::MobileMetallic,
        PackedLayout::ArmTileBlock,
        PackedLayout::FutureMetallic,
        PackedLayout::FutureSpecular,
    ]
    .into_iter()
    .map(|layout| {
        let psnr = compare(&render(&renderer, GBuffer::Packed(layout)), &lossless).psnr;
        eprintln!(
            "{}: predicted {:.3} steps; PSNR {psnr:.2} dB against the lossless frame",
            layout.name(),
            predicted(layout),
        );
        (predicted(layout), psnr, layout)
    })
    .collect();
    // From the largest predicted error down: the PSNR must rise.
    measured.sort_by(|a, b| b.0.total_cmp(&a.0));
    for pair in measured.windows(2) {
        assert!(
            pair[0].1 < pair[1].1,
            "{} (predicted {:.3}) has PSNR {:.2} dB, not below {} (predicted {:.3}) at {:.2} dB",
            pair[0].2.name(),
            pair[0].0,
            pair[0].1,
            pair[1].2.name(),
            pair[1].0,
            pair[1].1
        );
    }
}

/// The mobile-metallic preset's scene, with its precision replaced by `precision`.
fn scene(precision: &str, budget: u32) -> gbuffer_solver::Solution {
    let source = format!(
        "name = \"PrecisionScene\"\nmodel = \"metallic\"\nbudget = {budget}\n\n\
         [features]\nmetals = true\nnormal_maps = true\nimage_based_lighting = true\n\
         light_maps = true\nsun = true\n\n[precision]\n{precision}"
    );
    gbuffer_solver::file::parse_and_solve(&source, Path::new("precision.toml"))
        .unwrap_or_else(|diagnostics| panic!("{diagnostics:?}"))
}

/// A scene solved for a tighter precision (finer normals, colours, materials and light) takes
/// more bits and comes out no worse against the lossless frame of the same scene than the
/// scene solved for the preset's precision; and the coarse precision, no better.
#[test]
fn a_tighter_precision_is_no_worse_in_the_frame() {
    let Some(renderer) = renderer() else {
        return;
    };
    let coarse = scene(
        "normal_degrees = 2.0\ncolour_steps = 64\nmaterial_steps = 64\nhdr_max = 8.0\n\
         hdr_min = 0.015625\nhdr_relative = 0.05\n",
        128,
    );
    let preset = scene(
        "normal_degrees = 0.5\ncolour_steps = 256\nmaterial_steps = 256\nhdr_max = 8.0\n\
         hdr_min = 0.015625\nhdr_relative = 0.02\n",
        128,
    );
    let tight = scene(
        "normal_degrees = 0.05\ncolour_steps = 1024\nmaterial_steps = 1024\nhdr_max = 8.0\n\
         hdr_min = 0.015625\nhdr_relative = 0.002\n",
        256,
    );
    // The three scenes differ in precision only: one lossless frame serves them all.
    let lossless = render(&renderer, GBuffer::LosslessScene(preset.scene.features));
    let mut measured = Vec::new();
    for solution in [coarse, preset, tight] {
        let bits = solution.layout.used_bits();
        let solved = render(&renderer, GBuffer::Solved(Arc::new(solution)));
        let psnr = compare(&solved, &lossless).psnr;
        eprintln!("{bits} used bits: PSNR {psnr:.2} dB against the lossless frame");
        measured.push((bits, psnr));
    }
    for pair in measured.windows(2) {
        let ((looser_bits, looser), (tighter_bits, tighter)) = (pair[0], pair[1]);
        assert!(tighter_bits > looser_bits, "{measured:?}");
        assert!(
            tighter >= looser,
            "tighter precision, worse frame: {measured:?}"
        );
    }
}
