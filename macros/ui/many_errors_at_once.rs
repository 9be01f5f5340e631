// Every problem of a layout is reported in one compilation.
use gbuffer::glam::{Vec3, Vec4};
use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
#[gbuffer(budget = 96)]
struct Broken {
    #[pls(rgba9)]
    colour: Vec4,
    #[pls(r32f)]
    normal: Vec3,
    roughness: f32,
    #[pls(r32f)]
    depth: f32,
    #[pls(rgba8)]
    albedo: Vec4,
    #[pls(rgba8)]
    emissive: Vec4,
}

fn main() {}
