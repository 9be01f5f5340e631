//! Deferred shading on tile memory: declare a G-buffer once, get everything that must agree
//! with it.
//!
//! ```
//! use gbuffer::{GBufferLayout, glam::{Vec3, Vec4}};
//!
//! #[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
//! #[gbuffer(budget = 128)] // bits of tile memory; default 128; a positive multiple of 32
//! struct MobileMetallic {
//!     #[pls(rgb10_a2)] light_accumulation: Vec3, // alpha unused: 30 of 32 bits used
//!     #[pls(r32f)]     depth: f32,
//!     #[pls(rgba8)]    normals_roughness: Vec4,
//!     #[pls(rgba8)]    albedo_metallic: Vec4,
//! }
//!
//! assert_eq!((MobileMetallic::BITS, MobileMetallic::USED_BITS), (128, 126));
//! let texel = MobileMetallic {
//!     light_accumulation: Vec3::new(0.25, 0.5, 1.0),
//!     depth: 0.75,
//!     normals_roughness: Vec4::new(0.5, 0.5, 1.0, 0.3),
//!     albedo_metallic: Vec4::new(1.0, 0.8, 0.2, 1.0),
//! };
//! let words: [u32; 4] = texel.pack(); // the same bits as the WGSL `pack_mobile_metallic`
//! assert_eq!(MobileMetallic::unpack(&words).depth, 0.75);
//! assert!(MobileMetallic::WGSL.contains("fn unpack_mobile_metallic(w: array<u32, 4>) -> MobileMetallic"));
//! ```
//!
//! A `#[pls(...)]` field is one 32-bit word of a format of EXT_shader_pixel_local_storage:
//! `r11f_g11f_b10f`, `r32f`, `rg16f`, `rgb10_a2` (or `rgb10a2`), `rgba8`, `rg16`, `rgba8i`,
//! `rg16i`, `rgb10_a2ui`, `rgba8ui`, `rg16ui`, `r32ui`. It holds `f32` or `Vec2`..`Vec4` in
//! float and unorm formats, `u32` or `UVec2`..`UVec4` in `ui` formats, `i32` or
//! `IVec2`..`IVec4` in `i` formats; channels it does not fill are zero padding.
//!
//! A `#[bits(N, encoding)]` field is N bits of a shared `r32ui` word: consecutive bit fields
//! fill a word from its least significant bit up, and one that does not fit starts the next.
//! The encodings are `unorm`, `snorm`, `uint`, `sint`, `bool`, `half`, `float32`,
//! `unsigned_float`, `rgb9e5`, `octahedral`, `rgbm(range)` and `log_luminance`
//! ([`layout::Encoding`]); [`engine_layouts`] declares Bevy's and HDRP's G-buffers with them:
//!
//! ```
//! use gbuffer::{GBufferLayout, glam::{Vec3, Vec4}};
//!
//! #[derive(GBufferLayout)]
//! #[gbuffer(budget = 64)]
//! struct Small {
//!     #[bits(24, octahedral)] normal: Vec3,   // word 0, bits 0-23
//!     #[bits(8, unorm)]       roughness: f32, // word 0, bits 24-31
//!     #[pls(rgba8)]           albedo: Vec4,   // word 1
//! }
//!
//! let words = Small { normal: Vec3::Z, roughness: 1.0, albedo: Vec4::ONE }.pack();
//! assert_eq!(words, [0xff80_0800, 0xffff_ffff]);
//! ```
//!
//! `#[gbuffer(conversions = fast)]` makes the WGSL use what engines write (the pack builtins
//! for rgba8, rg16 and rg16f, f32 rounding for rgb10_a2, cut halves for r11f_g11f_b10f): fewer
//! instructions, the adapter's rounding (one code at most from the Rust mirror). One field can
//! choose for itself: `#[pls(rgba8, conversions = fast)]`. The default, `exact`, is
//! bit-identical everywhere.
//!
//! A layout over its budget does not compile, and the error lists every field's bits.
//!
//! # Feature flags
//!
//! - `wgpu`: every layout's wgpu helpers (`GBufferTargets`: target formats, textures,
//!   bindings, the limits it needs and `LimitError`, the lighting pass's WGSL, which
//!   `gbuffer-codegen`'s WGSL back end writes), and `gbuffer::wgpu`, the wgpu they are written
//!   against.
//! - `build`: `gbuffer::build`, layout files to includes and Rust mirrors from a build script.
//!
//! # The guide
//!
//! The guide is the repository's `book/` (an mdBook: `mdbook` from crates.io, then
//! `mdbook build book`), for users first: layouts and their formats and encodings, the wgpu
//! and Bevy walkthroughs, the GLES, Vulkan and WebGL 2 includes, the shading library, the
//! command line and the speed/accuracy trade, measured. Each package's own documentation links
//! here.

// On docs.rs (`--cfg docsrs`, Cargo.toml's [package.metadata.docs.rs]), each feature-gated item
// says which feature it needs.
#![cfg_attr(docsrs, feature(doc_cfg))]

// The facade: the derive beside what derived layouts run on (gbuffer-runtime, every item
// re-exported at the path users name), and the build script helpers. The derive's expansion
// names `::gbuffer`, whose paths (`GBufferLayout`, `layout`, `glam`, `__private`) are these.

pub use gbuffer_macros::GBufferLayout;
#[doc(inline)]
pub use gbuffer_runtime::{engine_layouts, glam, layout, seed_layouts, GBufferLayout, WeslModule};
#[cfg(feature = "wgpu")]
#[doc(inline)]
pub use gbuffer_runtime::{targets, wgpu, GBufferTargets, GBufferTextures, LimitError};

#[doc(hidden)]
pub use gbuffer_runtime::{__private, codecs};

#[cfg(feature = "build")]
pub mod build;
