//! The Rust side of the WGSL shading library (`gbuffer/wgsl/`), twice over:
//!
//! - [`mirror`]: f32, the same formula in the same order of operations as the WGSL, for tests
//!   and CPU tools; on a conforming adapter the two agree within a few ulp;
//! - [`reference`](mod@reference): the same functions in f64, the ground truth the f32 forms (and the
//!   approximations among them) are measured against.
//!
//! - [`half_precision`]: the mobile forms of `mobile_half.wgsl`, rounded to f16 at every step.
//!
//! The first two are compiled from one source per module (`functions/<module>.rs`, included with the
//! float type set to f32 or f64), so the formulas cannot drift apart. Module and function names
//! are the WGSL's.

/// The f32 mirrors of the WGSL functions.
// The literals are the WGSL's, written as the shared source needs them for f64.
#[allow(clippy::excessive_precision)]
pub mod mirror {
    #[allow(unused_imports)]
    use glam::{BVec3, Vec2, Vec3, Vec4};
    type Float = f32;
    include!("functions/mod.rs");

    /// Shared-exponent rgb9e5: integer-exact, so the f32 form is its own reference.
    pub mod rgb9e5 {
        include!("rgb9e5.rs");
    }
}

/// The f64 references of the WGSL functions.
pub mod reference {
    #[allow(unused_imports)]
    use glam::{BVec3, DVec2 as Vec2, DVec3 as Vec3, DVec4 as Vec4};
    type Float = f64;
    include!("functions/mod.rs");
}

pub mod env_brdf_lut;
pub mod half_precision;
