//! The reference deferred renderer: a packed G-buffer pass, full PBS lighting and tone mapping,
//! on three backends side by side: [`wgpu`] (the G-buffer through memory), [`gles`] and
//! [`vulkan`] (the G-buffer kept on tile by their fused paths, [`on_tile`]), beside a CPU
//! reference renderer of the same triangles ([`reference`](mod@reference)).
//!
//! What the backends share: the [`options`] of a frame, the [`scene`] and its [`mesh`], the
//! [`inputs`] baked once, the G-buffers ([`gbuffers`]), the WGSL of every pass ([`shaders`],
//! translated to GLSL by [`glsl`] for GLES and Vulkan), and the [`recording`] of a frame's
//! passes, from which its memory traffic is counted.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod coarse;
pub mod conventions;
pub mod fused_programs;
pub mod gbuffers;
pub mod gles;
pub mod glsl;
pub mod image;
pub mod inputs;
pub mod lossless;
pub mod mesh;
pub mod on_tile;
pub mod options;
pub mod parallel;
pub mod presets;
pub mod recording;
pub mod reference;
pub mod scene;
pub mod shaders;
pub mod vulkan;
pub mod webgl;
pub mod wgpu;
