//! The rounding step the octahedral and RGBM encodes share (the mirror's is
//! `gbuffer_core::codecs::scaled_quotient`): `floor(((2^bits - 1) numerator + bias) /
//! denominator)`, exactly, by binary long division in 32-bit integers.

/// The quotient, per lane (`PREFIX_LANES_scaled_quotient`).
pub const WGSL: &str = "\
// floor(((2^bits - 1) numerator + bias) / denominator), exactly, for numerator <= denominator
// < 2^31 and bias < denominator: bits steps of binary long division give floor(2^bits
// numerator / denominator) and its remainder in 32-bit integers, and taking numerator away
// and adding bias moves the quotient by at most one either way. The loop's count is the same
// for every fragment, so they never diverge.
fn PREFIX_LANES_scaled_quotient(numerator: UINTS, denominator: UINTS, bias: UINTS, bits: u32) -> UINTS {
    let whole = UINTS(numerator >= denominator);
    var quotient = whole;
    var remainder = numerator - whole * denominator;
    for (var step = 0u; step < bits; step++) {
        remainder = remainder << UINTS(1u);
        let bit = UINTS(remainder >= denominator);
        quotient = (quotient << UINTS(1u)) | bit;
        remainder = remainder - bit * denominator;
    }
    let up = UINTS(remainder + bias >= numerator + denominator);
    let down = UINTS(remainder + bias < numerator);
    return quotient + up - down;
}

";
