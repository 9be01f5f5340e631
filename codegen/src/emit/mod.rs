//! Emitters: each turns a checked [`gbuffer_core::Layout`] into source text or tokens: WGSL (the
//! source of truth), the Rust mirror, and (with the `tools` feature) GLSL ES includes.

#[cfg(feature = "tools")]
pub mod glsl;
pub mod rust;
pub mod wgsl;
