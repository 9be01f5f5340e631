// `crate = "..."` is the path the expansion uses: a path to nothing fails there, not silently
// falling back to `::gbuffer`.
use gbuffer::GBufferLayout;

mod engine {}

#[derive(GBufferLayout)]
#[gbuffer(crate = "crate::engine::rendering")]
struct ThroughMissingReexport {
    #[pls(r32f)]
    depth: f32,
}

fn main() {}
