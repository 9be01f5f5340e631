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
//! # Where things are
//!
//! - the scene, meshes, baked inputs and the CPU reference; how the surface goes into each seed
//!   and engine layout (`conventions/`); the layouts others are measured against
//!   (`lossless.rs`, `coarse.rs`);
//! - the backends side by side (`wgpu/`, `gles/`, `vulkan/`), which reach only into the shared
//!   modules, never into each other; the fused paths' shared parts (`on_tile.rs`); what the
//!   browser's fused frame loads, exported for the page in `web/` (`webgl.rs`);
//! - the WGSL: the two-pass frame's passes assembled in `shaders.rs` from the sources in
//!   `wgsl/` and the library's modules; the fused paths' in `on_tile.rs` (`fused_wgsl`);
//! - the fused programs of every dialect assembled in one place (`fused_programs.rs`: GLES
//!   framebuffer fetch, WebGL pixel local storage, Vulkan subpass inputs), with the layout's
//!   include, its local-read host data and its WebGL host module from one compiled layout;
//! - the WGSL as GLSL (`glsl.rs`, through gbuffer-translate); Vulkan's vertex stages as naga's
//!   SPIR-V (`vulkan/objects.rs`); the fused Vulkan stages' compiled shaders and pipeline
//!   state, which the tile compilers' test builds in Mesa's drivers
//!   (`vulkan/fused_pipelines.rs`);
//! - a frame's recording and its memory traffic (`recording.rs`), PNG files and the error
//!   colour ramp (`image.rs`).
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
