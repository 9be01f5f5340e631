//! The G-buffer layout model, and all that derived code calls at run time.
//!
//! Every front end (the `#[derive(GBufferLayout)]` macro, layout files, the solver) builds a
//! [`Layout`] and [`Layout::check`]s it; the emitters of `gbuffer-codegen` write its WGSL, GLSL
//! and Rust; the derived `pack`/`unpack` call the conversions here. The model, bottom up:
//!
//! - [`FieldType`] and [`ScalarKind`]: the types a field can have, the vocabulary below the
//!   rest (`field_type.rs`);
//! - [`format`](mod@format): the twelve pixel local storage formats and their channels;
//! - [`codecs`]: how values become bits, one file per codec (the contract, the mirror and
//!   its tests; the WGSL is the codegen's WGSL back end's), and [`Encoding`], the list that
//!   names them;
//! - [`bit_field`]: fields of a few bits sharing an `r32ui` word, each encoded by a codec;
//! - [`layout`]: fields, types, the words they fill, the bit budget and its checks;
//! - [`naming`]: the identifiers the emitters derive from the layout's names;
//! - [`convert`]: a whole word's channels through their codecs (the CPU side of the generated
//!   WGSL);
//! - [`report`]: the bit report and the WebGPU render-target cost;
//! - [`Named`]: the one trait by which every package's option enums (a format, a path, a
//!   backend) name their values;
//! - [`Symbols`]: the names of the items generated for a layout.
//!
//! It depends on nothing: a user's runtime links no proc-macro2, quote or syn.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod bit_field;
pub mod codecs;
pub mod convert;
mod field_type;
pub mod format;
pub mod layout;
mod named;
pub mod naming;
pub mod report;
mod symbols;

pub use bit_field::BitField;
pub use codecs::rgbm::RgbmRange;
pub use codecs::{Codec, Encoding, LightStorage};
pub use field_type::{FieldType, ScalarKind};
pub use format::{
    Channel, Format, FormatRow, GlFormat, PackedTarget, TargetFormat, VulkanFormat, WebGpuTarget,
};
pub use layout::{
    Conversions, Diagnostic, Field, Layout, Member, Storage, Subject, Word, DEFAULT_BUDGET,
};
pub use named::Named;
pub use report::Report;
pub use symbols::{Direction, Symbols};
