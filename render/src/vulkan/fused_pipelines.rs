//! The fused paths' pipelines as compiled shaders and the state they are created with: what the
//! renderer creates them from, and what a compiler outside it takes to build the same pipelines
//! (the tile compilers of `gbuffer-cost`, `integration-tests/tests/tile_compilers_vulkan.rs`).
//! The subpass and the local-read paths share them: what differs is the pass they are created
//! for.

use ash::vk;
use gbuffer_gpu::tools::glslang;

use super::objects::{combined_image_bindings, vertex_input, vertex_spirv};
use super::{OUTPUT_FORMAT, PACKED_FORMAT};
use crate::fused_programs::{fused_programs, FusedDialect, FusedPrograms};
use crate::on_tile::{Stage, TRANSLATION_ENTRY};
use crate::options::Options;
use crate::shaders::used_bindings;

/// The push constants every fused stage's layout holds: the volume index (a `u32`).
pub const PUSH_CONSTANT_BYTES: u32 = 4;

/// One fused stage's pipeline.
#[derive(Clone, Debug)]
pub struct FusedPipeline {
    /// The stage it draws.
    pub stage: Stage,
    /// The vertex stage: naga's SPIR-V of [`Stage::vertex_entry`] (that entry point).
    pub vertex: Vec<u8>,
    /// The fragment stage: the GLSL 450 of [`crate::fused_programs`] (its entry point `main`),
    /// compiled by glslang.
    pub fragment: Vec<u8>,
    /// Descriptor set 0: the combined image samplers the stages sample, by binding.
    pub sampled: Vec<u32>,
    /// Descriptor set 1: the G-buffer's input attachments at bindings `0..`, input attachment
    /// index the binding (each reads the colour attachment at the same index).
    pub input_attachments: u32,
    /// The colour attachments' formats by location: the G-buffer's, then the output.
    pub colour_formats: Vec<vk::Format>,
    /// The vertex attributes' formats by location.
    pub vertex_attributes: Vec<vk::Format>,
}

/// The fused paths' pipelines for `options`, one a stage, in drawing order ([`Stage`]).
pub fn fused_pipelines(options: &Options) -> Result<Vec<FusedPipeline>, String> {
    of_programs(&fused_programs(options, FusedDialect::VulkanSubpass)?)
}

/// The pipelines of the Vulkan fused programs `programs`.
pub(super) fn of_programs(programs: &FusedPrograms) -> Result<Vec<FusedPipeline>, String> {
    let targets = programs.interface.attachments.len();
    let sampled = combined_image_bindings(&used_bindings(&programs.wgsl, TRANSLATION_ENTRY));
    let colour_formats: Vec<vk::Format> = std::iter::repeat_n(PACKED_FORMAT, targets)
        .chain([OUTPUT_FORMAT])
        .collect();
    programs
        .programs
        .iter()
        .map(|program| {
            let entry = program.stage.vertex_entry();
            let (_, attributes) = vertex_input(entry);
            Ok(FusedPipeline {
                stage: program.stage,
                vertex: vertex_spirv(&programs.wgsl, entry)?,
                fragment: glslang(&program.fragment, "frag", true)?,
                sampled: sampled.clone(),
                input_attachments: targets as u32,
                colour_formats: colour_formats.clone(),
                vertex_attributes: attributes
                    .iter()
                    .map(|attribute| attribute.format)
                    .collect(),
            })
        })
        .collect()
}
