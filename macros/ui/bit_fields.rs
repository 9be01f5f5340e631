use gbuffer::glam::{UVec2, Vec2, Vec3};
use gbuffer::GBufferLayout;

// Each field's storage suits neither its type nor its width: every error at its attribute.
#[derive(GBufferLayout)]
#[gbuffer(budget = 256)]
struct BadBitFields {
    #[bits(16, octahedral)]
    octahedral_on_a_scalar: f32,
    #[bits(33, unorm)]
    too_wide: f32,
    #[bits(16, rgb9e5)]
    narrow_rgb9e5: Vec3,
    #[bits(8, sint)]
    signed_on_unsigned: u32,
    #[bits(15, octahedral)]
    odd_octahedral: Vec3,
    #[bits(24, unorm)]
    unorm_past_23_bits: f32,
    #[bits(9, uint)]
    uneven_vector: UVec2,
    #[bits(2, bool)]
    wide_bool: bool,
    #[bits(32, half)]
    halves_of_a_scalar: f32,
}

// The attribute itself is wrong.
#[derive(GBufferLayout)]
#[gbuffer(budget = 256)]
struct BadBitAttributes {
    #[bits(8, gamma)]
    unknown_encoding: f32,
    #[bits(32, rgbm)]
    rgbm_without_range: Vec3,
    #[bits(32, rgbm(-1.0))]
    negative_range: Vec3,
    #[bits(8, unorm(2.0))]
    range_on_unorm: f32,
    #[bits(unorm)]
    missing_width: f32,
    #[pls(rgba8)]
    #[bits(8, unorm)]
    word_and_bits: Vec2,
    #[bits(8, unorm, rounding = fast)]
    unknown_option: f32,
}

fn main() {}
