use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
#[gbuffer(budget = 256)]
struct Unsupported {
    #[pls(rgba8)]
    text: String,
    #[pls(rgba8)]
    array: [f32; 4],
    #[pls(rgba8)]
    double: f64,
    #[pls(r32f)]
    filter: f32,
}

fn main() {}
