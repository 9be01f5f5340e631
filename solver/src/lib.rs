//! Generate only what a scene requires.
//!
//! A [`SceneDescription`] names a scene's material model, the features it uses, the precision
//! each stored quantity needs and its bit budget. From it:
//!
//! - [`quantity`]: what the G-buffer must store, and for which features;
//! - [`representation`]: the ways to store each quantity, their storage and predicted error;
//! - [`solver`]: the smallest layout that meets the precision within the budget, an ordinary
//!   [`gbuffer_core::Layout`] (the same WGSL, Rust mirror and report as a hand-written one), or
//!   the requirement that cannot be met;
//! - [`texel`]: the WGSL that stores the scene's values in that layout and reads them back;
//! - [`lighting`]: a lighting shader with only the terms the scene uses;
//! - [`file`](mod@file): scene descriptions in TOML, with file:line:column errors.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod description;
pub mod file;
pub mod lighting;
pub mod presets;
pub mod quantity;
pub mod representation;
pub mod solver;
mod summary;
pub mod texel;

pub use description::{Feature, Features, MaterialModel, Precision, SceneDescription, Setting};
pub use solver::{solve, Placement, Solution, SolveError};
