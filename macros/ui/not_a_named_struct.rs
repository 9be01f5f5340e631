use gbuffer::GBufferLayout;

#[derive(GBufferLayout)]
struct Empty {}

#[derive(GBufferLayout)]
struct Unit;

#[derive(GBufferLayout)]
struct Tuple(#[pls(r32f)] f32);

#[derive(GBufferLayout)]
enum Choice {
    A,
    B,
}

#[derive(GBufferLayout)]
struct Generic<T> {
    #[pls(r32f)]
    depth: f32,
    marker: std::marker::PhantomData<T>,
}

fn main() {}
