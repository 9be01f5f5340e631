// Mirrors constants.wgsl.

/// π.
pub const PI: Float = core::f64::consts::PI as Float;
/// 1 / π.
pub const INV_PI: Float = core::f64::consts::FRAC_1_PI as Float;
/// The reflectance at normal incidence of a typical dielectric.
pub const DIELECTRIC_F0: Float = 0.04;
/// The smallest roughness the lighting functions are fed (see constants.wgsl).
pub const MIN_ROUGHNESS: Float = 0.045;
/// The smallest n.v the lighting functions are fed.
pub const MIN_N_DOT_V: Float = 1e-4;
/// The shortest view + light sum the half vector is normalized from.
pub const MIN_HALF_VECTOR_LENGTH: Float = 1e-6;
