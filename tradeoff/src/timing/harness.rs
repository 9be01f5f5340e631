//! The shaders a row is timed and costed in: its `row_eval` in a dependent chain, in a
//! compute dispatch and in a fullscreen draw's fragment shader. Each step's output, mixed with
//! its input, is the next step's input, so no compiler can drop or merge a step.

use gbuffer_gpu::fullscreen::FULLSCREEN_WGSL;

use super::CHAIN;

/// How many steps a harness chains.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Chain {
    /// A constant: what the static costs count (a compiler may unroll it).
    Fixed(u32),
    /// Read from the uniform at binding 4 (`bench_chain.x`): the timed form, whose length the
    /// protocol changes (calibration, the doubling check) without building another pipeline.
    Uniform,
}

impl Chain {
    /// The uniform's declaration, where the chain reads one.
    fn declaration(self) -> &'static str {
        match self {
            Chain::Fixed(_) => "",
            Chain::Uniform => "@group(0) @binding(4) var<uniform> bench_chain: vec4<u32>;\n",
        }
    }

    /// The loop's bound.
    fn bound(self) -> String {
        match self {
            Chain::Fixed(steps) => format!("{steps}u"),
            Chain::Uniform => "bench_chain.x".to_string(),
        }
    }
}

/// The compute shader around a row's `row_eval`, as the static costs count it.
pub fn harness(row_wgsl: &str) -> String {
    compute_harness(row_wgsl, Chain::Fixed(CHAIN))
}

/// The fragment shader around a row's `row_eval` with one evaluation, entry point
/// `bench_fragment`, as the GPU compilers cost it.
pub fn fragment_harness(row_wgsl: &str) -> String {
    fragment_harness_with(row_wgsl, Chain::Fixed(1))
}

/// The fragment stage's shaders around a row's `row_eval`: a fullscreen triangle, and a
/// fragment shader whose inputs come from its position.
pub(super) fn fragment_harness_with(row_wgsl: &str, chain: Chain) -> String {
    let (declaration, bound) = (chain.declaration(), chain.bound());
    format!(
        "{row_wgsl}\n\
         @group(0) @binding(2) var lut_texture: texture_2d<f32>;\n\
         @group(0) @binding(3) var lut_sampler: sampler;\n\
         {declaration}\n\
         {FULLSCREEN_WGSL}\n\
         @fragment\n\
         fn bench_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{\n\
         \x20   var x = fract(vec4<f32>(position.x * 0.000521, position.y * 0.000927, (position.x + position.y) * 0.00037, 0.5));\n\
         \x20   for (var step = 0u; step < {bound}; step++) {{\n\
         \x20       x = fract(row_eval(x) * 0.25 + x * 0.75 + vec4<f32>(0.1));\n\
         \x20   }}\n\
         \x20   return x;\n\
         }}\n"
    )
}

/// The compute shader around a row's `row_eval`.
pub(super) fn compute_harness(row_wgsl: &str, chain: Chain) -> String {
    let (declaration, bound) = (chain.declaration(), chain.bound());
    format!(
        "{row_wgsl}\n\
         @group(0) @binding(0) var<storage, read> bench_inputs: array<vec4<f32>>;\n\
         @group(0) @binding(1) var<storage, read_write> bench_outputs: array<vec4<f32>>;\n\
         @group(0) @binding(2) var lut_texture: texture_2d<f32>;\n\
         @group(0) @binding(3) var lut_sampler: sampler;\n\
         {declaration}\n\
         @compute @workgroup_size(64)\n\
         fn bench(@builtin(global_invocation_id) id: vec3<u32>) {{\n\
         \x20   var x = bench_inputs[id.x];\n\
         \x20   for (var step = 0u; step < {bound}; step++) {{\n\
         \x20       x = fract(row_eval(x) * 0.25 + x * 0.75 + vec4<f32>(0.1));\n\
         \x20   }}\n\
         \x20   bench_outputs[id.x] = x;\n\
         }}\n"
    )
}

/// A row whose evaluation is free: its time is the harness's own, subtracted from each row's.
pub const BASELINE_ROW: &str = "fn row_eval(x: vec4<f32>) -> vec4<f32> {\n    return x;\n}\n";
