// Solved by gbuffer for scene `DesktopSpecularScene`.
use gbuffer::glam::{Vec2, Vec3};
use gbuffer::GBufferLayout;

#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 256)]
pub struct DesktopSpecularScene {
    #[bits(32, half)]
    pub light_rg: Vec2,
    #[bits(16, half)]
    pub light_b: f32,
    #[bits(16, half)]
    pub roughness: f32,
    #[pls(r32f)]
    pub depth: f32,
    #[bits(28, octahedral)]
    pub normal: Vec3,
    #[pls(rgb10_a2)]
    pub albedo: Vec3,
    #[pls(rgb10_a2)]
    pub specular_colour: Vec3,
}
