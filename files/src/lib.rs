//! The plain-text files the tools read and write, one module each: how every input file is
//! read ([`input`]: regular files only, within a size limit), the shape checks of every TOML
//! file the project reads, with each problem at its span ([`toml_table`], over `toml`'s parser
//! without serde), and JSON string literals ([`json`], for generated JavaScript and the tools'
//! JSON). The layout files (`gbuffer-layout-file`), the scene files (`gbuffer-solver`), the
//! validator's includes and the command line share them.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod input;
pub mod json;
pub mod toml_table;
