//! The GPUs the product runs on, opened without a window: a wgpu device, a GLES 3.2 context
//! through EGL surfaceless, a Vulkan device through `ash`, and the Khronos command-line tools.
//! Each is opened by a function returning a `Result` whose error names what was missing (a
//! driver, a library, a tool) and the package that brings it, so a command can exit with a
//! one-line reason where a test would fail. The harness shaders and their inputs, which run a
//! layout's generated code over buffers, serve the trade-off study and the tests alike.
//!
//! # Where things are
//!
//! - the wgpu adapter: `adapter.rs`; GLES 3.2 through EGL: `gles.rs`; the Khronos tools:
//!   `tools.rs`;
//! - Vulkan through `ash`, `vulkan/`: opening the device and submitting work in `mod.rs`;
//!   memory and images, buffers, render passes, descriptors, pipelines and barriers a file
//!   each; dynamic rendering local read and rasterization order, what the device offers and
//!   what is enabled, in `local_read.rs`;
//! - the fullscreen triangle (`fullscreen.rs`), timestamp queries (`timestamps.rs`), and the one
//!   timing protocol every printed time goes through (`timing.rs`: warm-up, rounds, the
//!   doubling check, spreads);
//! - the harness shaders that run a layout's code over buffers with their inputs
//!   (`harness.rs`, `values.rs`).
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod adapter;
pub mod fullscreen;
pub mod gles;
pub mod harness;
pub mod stages;
pub mod timestamps;
pub mod timing;
pub mod tools;
pub mod values;
pub mod vulkan;

pub use adapter::Gpu;
