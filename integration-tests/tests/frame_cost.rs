//! What a layout costs the picture: each seed layout's frame against the lossless G-buffer's
//! (every quantity an f32), in the order the trade-off study's whole-layout rows predict.

use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::image::compare;
use gbuffer_render::options::{IblForm, Options, SunForm};
use gbuffer_render::wgpu::Renderer;

/// The frame through a layout's G-buffer, small: 160x90.
fn options(layout: PackedLayout) -> Options {
    Options {
        gbuffer: GBuffer::Packed(layout),
        sun: SunForm::Ggx,
        ibl: IblForm::Lut,
        width: 160,
        height: 90,
    }
}

/// Coarser storage, lower PSNR against the lossless frame: the layouts the study rates worse
/// (a larger largest error over its surfaces) come out further from the lossless frame.
#[test]
fn frames_order_the_layouts_as_the_trade_off_study_predicts() {
    let Some(renderer) = gbuffer_testkit::or_skip(
        "the wgpu renderer",
        Renderer::new(&|message| eprintln!("{message}")),
    ) else {
        return;
    };
    let render = |layout| {
        renderer
            .render(&options(layout))
            .unwrap_or_else(|error| panic!("{error}"))
    };
    let lossless = render(PackedLayout::Lossless);
    let predictions = gbuffer_tradeoff::layout_errors();
    let predicted = |layout: PackedLayout| {
        let name = format!("({})", layout.layout().name);
        predictions
            .iter()
            .find(|(row, _)| row.ends_with(&name))
            .unwrap_or_else(|| panic!("no trade-off row for {name}"))
            .1
    };
    let mut measured: Vec<(f64, f64, PackedLayout)> = [
        PackedLayout::MobileMetallic,
        PackedLayout::ArmTileBlock,
        PackedLayout::FutureMetallic,
        PackedLayout::FutureSpecular,
    ]
    .into_iter()
    .map(|layout| {
        let comparison = compare(&render(layout), &lossless);
        eprintln!(
            "{}: predicted {:.3} steps; PSNR {:.2} dB, largest error {} against the lossless frame",
            layout.flag(),
            predicted(layout),
            comparison.psnr,
            comparison.max_error
        );
        (predicted(layout), comparison.psnr, layout)
    })
    .collect();
    // From the largest predicted error down: the PSNR must rise.
    measured.sort_by(|a, b| b.0.total_cmp(&a.0));
    for pair in measured.windows(2) {
        assert!(
            pair[0].1 < pair[1].1,
            "{} (predicted {:.3}) has PSNR {:.2} dB, not below {} (predicted {:.3}) at {:.2} dB",
            pair[0].2.flag(),
            pair[0].0,
            pair[0].1,
            pair[1].2.flag(),
            pair[1].0,
            pair[1].1
        );
    }
}
