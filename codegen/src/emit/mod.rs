//! The back ends: each reads a lowered or compiled layout and writes what a consumer takes:
//! the Rust mirror, and (with the `tools` feature) the GLSL ES includes, the Vulkan local-read
//! host data and the WebGL host module. None of them is called by the compile step.

#[cfg(feature = "tools")]
pub mod glsl;
pub mod rust;
