use gbuffer::glam::Vec4;
use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
#[gbuffer(budget = 128, precision = 8)]
struct UnknownOption {
    #[pls(r32f)]
    depth: f32,
}

#[derive(GBufferLayout)]
#[gbuffer(conversions = "approximate")]
struct UnknownConversions {
    #[pls(r32f)]
    depth: f32,
}

#[derive(GBufferLayout)]
#[gbuffer(crate = "not a path")]
struct CrateNotAPath {
    #[pls(r32f)]
    depth: f32,
}

#[derive(GBufferLayout)]
#[gbuffer(budget = 128)]
#[gbuffer(budget = 256)]
struct TwoGbufferAttributes {
    #[pls(r32f)]
    depth: f32,
}

#[derive(GBufferLayout)]
#[gbuffer(budget = 256)]
struct PlsProblems {
    missing: f32,
    #[pls(rgba8)]
    #[pls(rgba8)]
    repeated: Vec4,
    #[pls("rgba8")]
    quoted: Vec4,
    #[pls]
    empty: Vec4,
    #[pls(rgba8, conversions = slow)]
    slow: Vec4,
    #[pls(rgba8, rounding = fast)]
    unknown_option: Vec4,
}

fn main() {}
