//! Emitters: each turns a checked [`crate::Layout`] into source text or tokens.

pub mod rust;
pub mod wgsl;
