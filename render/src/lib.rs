//! The reference deferred renderer: a packed G-buffer pass, full PBS lighting and tone mapping
//! on wgpu (`renderer`) and kept on tile on GLES and Vulkan (`on_tile`), beside a CPU reference
//! renderer of the same triangles (`reference`).

pub mod gbuffers;
pub mod image;
pub mod inputs;
pub mod mesh;
pub mod on_tile;
pub mod parallel;
pub mod presets;
pub mod reference;
pub mod renderer;
pub mod scene;
pub mod shaders;

/// The command-line name of a value of the renderer's options, as clap's `ValueEnum` derives
/// it (kebab case: `mobile-metallic`, `two-pass`): the one spelling of every flag.
pub fn flag(value: &impl clap::ValueEnum) -> String {
    value
        .to_possible_value()
        .map(|possible| possible.get_name().to_string())
        .unwrap_or_default()
}
