//! The reference deferred renderer: a packed G-buffer pass, full PBS lighting and tone mapping
//! on wgpu, beside a CPU reference renderer of the same analytic scene.

#![warn(missing_docs)]

pub mod gbuffers;
pub mod image;
pub mod inputs;
pub mod mesh;
pub mod on_tile;
pub mod presets;
pub mod reference;
pub mod renderer;
pub mod scene;
pub mod shaders;
