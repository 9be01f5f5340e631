//! WGSL in, GLSL out: the one package every gbuffer shader goes through on its way from WGSL
//! to GLSL, whoever wrote it (the codegen's layouts, the renderer's passes, the cost model's
//! probes, a user's WGSL in the validator).
//!
//! - [`wgsl`]: the front door, naga's parse and validation with every flag; generated code's
//!   capabilities ([`wgsl::GENERATED_CODE_CAPABILITIES`]) are named once;
//! - [`glsl_stage`]: a whole stage by naga's GLSL writer, in one [`glsl_stage::Dialect`] (GLSL
//!   ES 3.10, GLSL 450, GLSL ES 3.00) with one set of options: clip space as the WGSL writes
//!   it, bindings kept;
//! - [`printer`]: a module's declarations printed from naga's IR, each with an explicit
//!   `highp` and the name naga's writer gives it (GLSL's reserved words are listed once, in
//!   `printer/keywords.rs`), for an include or a hand-written `main` to paste;
//! - [`items`]: what a WGSL text or a printed GLSL text declares, by kind and name.
//!
//! It knows nothing of G-buffer layouts: gbuffer-codegen compiles layouts over it.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

pub mod glsl_stage;
pub mod items;
pub mod printer;
pub mod wgsl;
