//! The scene presets (`solver/scenes/*.toml`) side by side: the bits their solved layouts
//! take, what their specialised lighting pass costs, and their error against the full model
//! (the CPU reference of the same scene, every term, f64, no packing).

use std::sync::Arc;

use gbuffer_solver::lighting::Forms;
use gbuffer_solver::presets::solve_preset;
use gbuffer_solver::Solution;
use gbuffer_validator::cost::Cost;

use crate::gbuffers::{GBuffer, PackedLayout};
use crate::image::compare;
use crate::options::Options;
use crate::reference;
use crate::shaders::{lighting_pass_wgsl, Positions};
use crate::wgpu::Renderer;

/// One row of the report.
#[derive(Clone, Debug)]
pub struct PresetRow {
    /// The preset's name.
    pub preset: String,
    /// Its solved layout.
    pub solution: Arc<Solution>,
    /// The lighting pass's static cost (`lighting_main`).
    pub lighting: Cost,
    /// PSNR of the rendered frame against the full model, dB.
    pub psnr: f64,
    /// The largest error of a channel, in 8-bit steps.
    pub largest_error: u8,
}

/// The static cost of a configuration's lighting pass.
pub fn lighting_cost(options: &Options) -> Result<Cost, String> {
    gbuffer_validator::cost::measure(
        &lighting_pass_wgsl(options, Positions::DepthBuffer).expect("any layout"),
        "lighting_main",
    )
}

/// The lighting pass of the seed layout Listing 2.2 with every term of the reference scene:
/// what the presets are specialised from.
pub fn unspecialised_options(forms: Forms, width: u32, height: u32) -> Options {
    Options {
        gbuffer: GBuffer::Packed(PackedLayout::MobileMetallic),
        sun: forms.sun,
        ibl: forms.ibl,
        width,
        height,
    }
}

/// Solves, renders and measures one preset.
pub fn measure_preset(
    renderer: &Renderer,
    preset: &str,
    forms: Forms,
    width: u32,
    height: u32,
) -> Result<PresetRow, String> {
    let solution = Arc::new(solve_preset(preset)?);
    let options = Options {
        gbuffer: GBuffer::Solved(solution.clone()),
        sun: forms.sun,
        ibl: forms.ibl,
        width,
        height,
    };
    let frame = renderer.render(&options)?;
    let full_model = reference::render(width, height, solution.scene.features, &|_| {});
    let comparison = compare(&frame, &full_model);
    Ok(PresetRow {
        preset: preset.to_string(),
        lighting: lighting_cost(&options)?,
        solution,
        psnr: comparison.psnr,
        largest_error: comparison.max_error,
    })
}
