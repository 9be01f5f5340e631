//! The scene presets on the adapter at hand: each renders through its solved layout and
//! specialised lighting pass, close to the full model, and the specialisations cost less.

use gbuffer_render::presets::measure_preset;
use gbuffer_render::wgpu::Renderer;
use gbuffer_solver::lighting::Forms;
use gbuffer_solver::presets::PRESETS;

#[test]
fn every_preset_renders_close_to_the_full_model_and_fits_its_budget() {
    let renderer = gbuffer_testkit::or_skip(
        "the wgpu renderer",
        Renderer::new(&|message| eprintln!("{message}")),
    );
    let Some(renderer) = renderer else {
        return;
    };
    let mut instructions = Vec::new();
    for (preset, _) in PRESETS {
        let row = measure_preset(&renderer, preset, Forms::ACCURATE, 160, 90)
            .unwrap_or_else(|error| panic!("{preset}: {error}"));
        let layout = &row.solution.layout;
        assert!(layout.bits() <= layout.budget, "{preset}: {}", row.solution);
        assert!(
            row.psnr >= 35.0,
            "{preset}: PSNR {:.2} dB against the full model",
            row.psnr
        );
        instructions.push(row.lighting.spirv_instructions);
    }
    // Dropping metals, then the environment map, shrinks the lighting pass.
    let [mobile, dielectric, rough, _] = instructions[..] else {
        unreachable!()
    };
    assert!(
        rough < dielectric && dielectric < mobile,
        "{instructions:?}"
    );
}
