// Listing 2.1 (specular workflow) is 160 bits: it does not fit a 128-bit tile.
use gbuffer::glam::{Vec3, Vec4};
use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
#[gbuffer(budget = 128)]
struct SpecularWorkflow {
    #[pls(rgb10a2)]
    light_accumulation: Vec3,
    #[pls(r32f)]
    depth: f32,
    #[pls(rgba8)]
    normals_roughness: Vec4,
    #[pls(rgba8)]
    base_colour: Vec3,
    #[pls(rgba8)]
    specular_colour: Vec3,
}

// Without a budget attribute the default, 128 bits, applies.
#[derive(GBufferLayout)]
struct DefaultBudget {
    #[pls(r32f)] a: f32,
    #[pls(r32f)] b: f32,
    #[pls(r32f)] c: f32,
    #[pls(r32f)] d: f32,
    #[pls(r32f)] e: f32,
}

fn main() {}
