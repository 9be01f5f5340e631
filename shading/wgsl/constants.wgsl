// constants: numbers the other modules share.
// requires:

const PI: f32 = 3.14159265358979;
const INV_PI: f32 = 0.318309886183791;

// The reflectance at normal incidence of a typical dielectric (about 4%, index 1.5).
const DIELECTRIC_F0: f32 = 0.04;

// The smallest roughness the lighting functions are fed: below it GGX's D peaks past what f32
// holds for mirror-like surfaces (D(1) = 1 / (pi * roughness^4)), and n.h = 1 gives 0 / 0 at
// roughness 0. 0.045 keeps 1 / roughness^4 under 2.4e5.
const MIN_ROUGHNESS: f32 = 0.045;

// The smallest n.v the lighting functions are fed: at n.v = 0 (a silhouette) the visibility
// terms divide by zero.
const MIN_N_DOT_V: f32 = 1e-4;

// The shortest view + light sum the half vector is normalized from (see half_vector_of).
const MIN_HALF_VECTOR_LENGTH: f32 = 1e-6;
