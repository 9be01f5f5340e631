//! What a derived G-buffer layout runs on: the [`GBufferLayout`] trait that
//! `#[derive(GBufferLayout)]` implements, the slices' vector loops behind its `pack_slice` and
//! `unpack_slice`, the layouts of the seed texts ([`seed_layouts`]) and of two engines
//! ([`engine_layouts`]), and with the `wgpu` feature each layout's render targets, bindings and
//! limits ([`targets`]).
//!
//! Users take all of it through the facade, `gbuffer`, which adds the derive and the build
//! script helpers; the packages below the facade (the renderer, the trade-off study) take it
//! from here, and derive their own layouts with `#[gbuffer(crate = "gbuffer_runtime")]`.
//!
//! # Feature flags
//!
//! - `wgpu`: [`targets`] (`GBufferTargets` for every layout, and the helpers for a layout known
//!   at run time), and `gbuffer_runtime::wgpu`, the wgpu they are written against.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

// On docs.rs (`--cfg docsrs`, Cargo.toml's [package.metadata.docs.rs]), each feature-gated item
// says which feature it needs.
#![cfg_attr(docsrs, feature(doc_cfg))]

// The derive's expansion names `::gbuffer` by default; this lets the seed and engine layouts
// below use it as they are.
extern crate self as gbuffer;

pub mod engine_layouts;
pub mod seed_layouts;

// The derive, for the seed and engine layouts (the facade gives it to users).
use gbuffer_macros::GBufferLayout;

pub use glam;
#[cfg(feature = "wgpu")]
pub use targets::{GBufferTargets, GBufferTextures, LimitError};
/// The wgpu the helpers of [`targets`] are written against (feature `wgpu`): use it, and
/// versions never clash.
#[cfg(feature = "wgpu")]
pub use wgpu;

#[cfg(feature = "wgpu")]
pub mod targets;

/// The layout model: fields, their formats or bit fields, the words they fill and the budget,
/// as every front end (the derive, layout files, the solver) describes a G-buffer; and the bit
/// report. Derived code calls its formats' conversions.
///
/// ```
/// # use gbuffer_runtime as gbuffer; // as the facade re-exports it
/// use gbuffer::{engine_layouts::BevyDeferred, layout::Storage, GBufferLayout};
///
/// let layout = BevyDeferred::layout();
/// assert_eq!((layout.words(), layout.bits()), (4, 128));
/// let normal = layout.fields.iter().find(|field| field.name == "normal").unwrap();
/// assert!(matches!(normal.storage, Storage::Bits(bits) if bits.bits == 24));
/// ```
pub mod layout {
    pub use gbuffer_core::report::Report;
    pub use gbuffer_core::{
        BitField, Conversions, Direction, Encoding, Field, FieldType, Format, Layout, Named,
        PackedTarget, RgbmRange, ScalarKind, Storage, Symbols,
    };
    // The format table's rows, a word's members, a scalar's conversion and the report's
    // parts: what the tools and the derive read, reachable by these paths but kept out of the
    // documented surface (`gbuffer_core` documents them).
    #[doc(hidden)]
    pub use gbuffer_core::convert::Scalar;
    #[doc(hidden)]
    pub use gbuffer_core::report::FieldTable;
    #[doc(hidden)]
    pub use gbuffer_core::{
        Channel, Codec, FormatRow, GlFormat, Member, TargetFormat, VulkanFormat, WebGpuTarget, Word,
    };
}

/// The codecs (how a value becomes bits, one module each with its contract, its exact Rust
/// conversions and its error bounds): what the derive, the emitters and the
/// solvers (the Bevy plugin's among them) read. Reachable by this path, kept out of the
/// documented surface (`gbuffer_core::codecs` documents them).
#[doc(hidden)]
pub use gbuffer_core::codecs;

/// A pixel local storage G-buffer layout. Derive it with `#[derive(GBufferLayout)]`.
///
/// A `#[pls(format)]` field takes the next word of [`Self::Packed`]; consecutive
/// `#[bits(N, encoding)]` fields share `r32ui` words from the least significant bit up, a
/// field that does not fit starting the next word. Inside a word the channels r, g, b, a sit
/// from the least significant bit up, so the words load unchanged into `Rgba32Uint` render
/// targets.
pub trait GBufferLayout: Sized {
    /// Bits the layout occupies: 32 per word.
    const BITS: u32;
    /// Bits of the channels and bit fields the fields use (the rest is zero padding).
    const USED_BITS: u32;
    /// The tile memory budget the layout was checked against.
    const BUDGET: u32;
    /// Number of 32-bit words.
    const WORDS: usize;
    /// `[u32; WORDS]`.
    type Packed: Copy + AsRef<[u32]> + AsMut<[u32]> + for<'a> TryFrom<&'a [u32]>;
    /// The WGSL: the struct, `pack_<snake>`, `unpack_<snake>`, `load_<snake>_<field>` and the
    /// `Rgba32Uint` target helpers. Valid on its own and beside other layouts' WGSL.
    const WGSL: &'static str;

    /// Packs the texel, bit for bit as the WGSL `pack_<snake>` does with exact conversions
    /// (the default). Under `conversions = fast` the mirror stays exact and the WGSL's
    /// channels are within one code of it on finite values within f16's range.
    fn pack(&self) -> Self::Packed;
    /// Unpacks a texel: floats and integers exactly, unorm as the correctly rounded quotient.
    fn unpack(words: &Self::Packed) -> Self;
    /// The layout's description: fields, formats, types and budget.
    fn layout() -> layout::Layout;

    /// Packs `texels` into `packed`, texel i into `packed[i]`, each as [`Self::pack`] packs
    /// it, bit for bit: a whole G-buffer at once, for uploads and readbacks
    /// (`bytemuck::cast_slice` turns the packed texels into the bytes of `Rgba32Uint` targets).
    /// The derive converts many texels at a time, each channel over them in vector
    /// instructions: on x86-64 CPUs with AVX-512 (checked at run time) sixteen at a time in a
    /// copy compiled for it, with AVX2 eight in a copy compiled for AVX2, elsewhere eight in
    /// plain loops. Single-threaded and allocation-free: split an image over threads to use more
    /// cores (the guide shows how).
    ///
    /// # Panics
    ///
    /// When the slices' lengths differ.
    fn pack_slice(texels: &[Self], packed: &mut [Self::Packed]) {
        __private::check_slice_lengths("pack_slice", texels.len(), packed.len());
        slices::convert_lanes::<slices::Pack<Self>, _, _>(texels, packed);
    }

    /// Unpacks `packed` into `texels`, texel i from `packed[i]`, each as [`Self::unpack`]
    /// unpacks it; with AVX-512 or AVX2 where the CPU has them, as [`Self::pack_slice`].
    ///
    /// # Panics
    ///
    /// When the slices' lengths differ.
    fn unpack_slice(packed: &[Self::Packed], texels: &mut [Self]) {
        __private::check_slice_lengths("unpack_slice", texels.len(), packed.len());
        slices::convert_lanes::<slices::Unpack<Self>, _, _>(packed, texels);
    }

    /// The bit report: per field the format, bits and used bits; the total against the
    /// budget; and the WebGPU cost of the same fields as separate render targets.
    fn report() -> layout::Report {
        layout::Report::new(&Self::layout())
    }

    /// [`Self::WGSL`] as a naga_oil composable module, importable as `gbuffer::<snake>`
    /// (`#import gbuffer::mobile_metallic::{MobileMetallic, unpack_mobile_metallic}`), as
    /// Bevy up to 0.19 composes its shaders. [`Self::wesl_module`] is its WESL twin.
    fn composable_wgsl() -> String {
        format!(
            "#define_import_path {}\n\n{}",
            Self::layout().symbols().module_path(),
            Self::WGSL
        )
    }

    /// [`Self::WGSL`] as a WESL module of the package `gbuffer`, for Bevy 0.20's shaders and
    /// other WESL users (`import gbuffer::mobile_metallic::{MobileMetallic,
    /// unpack_mobile_metallic};`): WESL names a module by where it is found, not by a
    /// directive, so the text is the WGSL under a comment, and [`WeslModule::path`] says where
    /// to register it (with the `wesl` crate, a `VirtualResolver` module at that path).
    fn wesl_module() -> WeslModule {
        let symbols = Self::layout().symbols();
        let path = symbols.module_path();
        WeslModule {
            source: format!(
                "// WESL module {path}, generated by gbuffer: import what you need,\n\
                 // for example `import {path}::{};`.\n\n{}",
                symbols.unpack(),
                Self::WGSL
            ),
            path,
        }
    }
}

/// A layout's WGSL as a WESL module ([`GBufferLayout::wesl_module`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WeslModule {
    /// Its module path, as an importing shader names it: `gbuffer::<snake>`.
    pub path: String,
    /// Its text.
    pub source: String,
}

/// What the derive's `pack_slice` and `unpack_slice` call: not an API, and not covered by
/// semantic versioning.
#[doc(hidden)]
pub mod __private {
    pub use crate::slices::{convert_lanes, force_simd, Isa, Lanes, Row, Simd, Words};

    /// Each field's first column in the derived slices' rows of a texel's `u32` bits, given
    /// the fields' offsets in the texel and their components: the fields in the order the
    /// texel's memory holds them (by offset, declared order among equals), each one's
    /// components one after another. A row's runs of columns are then runs of the texel's
    /// bytes (the whole texel, where it is exactly its components' `u32`s), which the loops
    /// load and store whole.
    pub const fn row_columns<const F: usize>(
        offsets: [usize; F],
        components: [usize; F],
    ) -> [usize; F] {
        let mut columns = [0; F];
        let mut field = 0;
        while field < F {
            // The components of the fields before it in memory.
            let mut column = 0;
            let mut other = 0;
            while other < F {
                if offsets[other] < offsets[field]
                    || (offsets[other] == offsets[field] && other < field)
                {
                    column += components[other];
                }
                other += 1;
            }
            columns[field] = column;
            field += 1;
        }
        columns
    }

    /// Panics, naming the call and the lengths, unless they agree.
    pub fn check_slice_lengths(call: &str, texels: usize, packed: usize) {
        assert_eq!(
            texels, packed,
            "{call}: {texels} texels and {packed} packed texels; the lengths must agree"
        );
    }
}

mod slices;
