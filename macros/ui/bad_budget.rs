use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
#[gbuffer(budget = 0)]
struct Zero {
    #[pls(r32f)]
    depth: f32,
}

#[derive(GBufferLayout)]
#[gbuffer(budget = 100)]
struct NotAMultipleOf32 {
    #[pls(r32f)]
    depth: f32,
}

#[derive(GBufferLayout)]
#[gbuffer(budget = -32)]
struct Negative {
    #[pls(r32f)]
    depth: f32,
}

fn main() {}
