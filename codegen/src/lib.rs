//! Everything generated from a G-buffer layout: the WGSL, GLSL and Rust emitters, over the
//! layout model of [`gbuffer_core`].
//!
//! One implementation serves every front end: the `#[derive(GBufferLayout)]` macro's attribute
//! parser (`gbuffer-macros`) and the layout-file reader (`gbuffer-layout-file`) both make a
//! [`Layout`](gbuffer_core::Layout) and [`check`](gbuffer_core::Layout::check) it, and the
//! emitters take it from there:
//!
//! - [`LoweredLayout`] (`lowered.rs`): the layout lowered once, its words, each field's place
//!   and the generated names, which every emitter reads instead of asking the model again;
//! - [`wgsl`]: the layout's WGSL, written from the lowered layout: the text every other output
//!   derives from (and, in `targets.rs`, what a lighting pass declares to read the packed
//!   targets); each codec's WGSL is a file of [`wgsl::codecs`], its helpers named through the
//!   layout's `Symbols` (the shading library takes its codecs' WGSL from there too);
//! - [`emit`]: the back ends: the Rust mirror as tokens (`emit/rust.rs`), and with `tools` the
//!   GLSL includes (`emit/glsl/`: which include writes what in `mod.rs`; EXT pixel
//!   local storage, framebuffer fetch and subpass attachments, WebGL's pixel local storage and
//!   its JavaScript host module, and what a Vulkan host sets to read an include under dynamic
//!   rendering local read, a file each);
//! - with the `tools` feature (on by default), the compile step, `CompiledLayout`
//!   (`compiled/`): the lowered layout, its WGSL, naga's module of it, its GLSL declarations
//!   with the names and items they declare and its words' GLSL names, made once and handed to
//!   every back end; it calls the WGSL emitter and gbuffer-translate, never a back end that
//!   reads it. WGSL comes in and GLSL goes out through `gbuffer-translate`, which every package
//!   that translates a shader shares.
//!
//! Writing the files (`gbuffer codegen`'s, a build script's) is `gbuffer-build`'s, over these
//! emitters: a library that compiles layouts builds none of it.
//!
//! The model is named by one path, `gbuffer_core` (users of the facade: `gbuffer::layout`);
//! this crate re-exports none of it.
//!
//! # Feature flags
//!
//! - `tools` (on by default): the compile step and the GLSL and Rust-source emitters (naga
//!   and prettyplease come with it). The derive builds without it.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

// On docs.rs (`--cfg docsrs`, Cargo.toml's [package.metadata.docs.rs]), each feature-gated item
// says which feature it needs.
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(feature = "tools")]
mod compiled;
pub mod emit;
mod lowered;
pub mod wgsl;

#[cfg(feature = "tools")]
pub use compiled::{CompiledLayout, GlslNames, Translation, TranslationError};
pub use lowered::LoweredLayout;
