use gbuffer::glam::{Vec2, Vec4};
use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
struct Typos {
    #[pls(rgba16f)]
    colour: Vec4,
    #[pls(rgb10_a2u)]
    flags: Vec4,
    #[pls(rg16_float)]
    motion: Vec2,
}

fn main() {}
