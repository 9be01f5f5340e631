// Solved by gbuffer for scene `MobileMetallicScene`.
use gbuffer::glam::{Vec3};
use gbuffer::GBufferLayout;

#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128)]
pub struct MobileMetallicScene {
    #[pls(r11f_g11f_b10f)]
    pub light: Vec3,
    #[bits(18, octahedral)]
    pub normal: Vec3,
    #[bits(8, unorm)]
    pub roughness: f32,
    #[bits(24, unorm)]
    pub base_colour: Vec3,
    #[bits(8, unorm)]
    pub metallic: f32,
}
