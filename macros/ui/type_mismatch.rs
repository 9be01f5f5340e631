use gbuffer::glam::{UVec2, Vec3, Vec4};
use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
struct Mismatched {
    #[pls(r32f)]
    too_wide: Vec4,
    #[pls(rgba8)]
    signed_in_unorm: i32,
    #[pls(rgba8ui)]
    float_in_uint: Vec3,
    #[pls(r11f_g11f_b10f)]
    four_in_three: Vec4,
    #[pls(rg16i)]
    unsigned_in_signed: UVec2,
}

fn main() {}
