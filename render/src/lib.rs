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
