//! The shaders a row is timed and costed in: its `row_eval` in a dependent chain, in a
//! compute dispatch and in a fullscreen draw's fragment shader. Each step's output, mixed with
//! its input, is the next step's input, so no compiler can drop or merge a step.
//!
//! The timed form runs [`CHAINS`] such chains side by side in every invocation, each from its
//! own start: one chain measures how long a step waits for the one before (its latency) where
//! the adapter runs an invocation's steps one after another, as a CPU rasteriser does. On
//! llvmpipe an rgba8 round trip read 2.9 ns in one chain and 2.1 ns a step in two, four or
//! eight (rgb10_a2's, the same code with other constants, 2.4 ns in one): a lone chain's figure
//! depends on how its steps' instructions happen to overlap, and the costs of two halves no
//! longer add up to the whole. Independent chains give the out-of-order core (and a GPU's
//! scheduler, which also has other warps) work to overlap, so a step's time is the adapter's
//! throughput, which adds.

use gbuffer_gpu::fullscreen::FULLSCREEN_WGSL;

use super::CHAIN;

/// Independent chains in each invocation of the timed harness.
pub const CHAINS: u32 = 4;

/// How many steps a harness chains.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Chain {
    /// A constant: what the static costs count (a compiler may unroll it), in one chain, so
    /// that they count one evaluation a step.
    Fixed(u32),
    /// Read from the uniform at binding 4 (`bench_chain.x`): the timed form, whose length the
    /// protocol changes (calibration, the doubling check) without building another pipeline,
    /// in [`CHAINS`] chains.
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

    /// Chains side by side in an invocation: the evaluations of one step.
    pub(super) fn chains(self) -> u32 {
        match self {
            Chain::Fixed(_) => 1,
            Chain::Uniform => CHAINS,
        }
    }

    /// The function body's chains from `start` (an expression of the stage's inputs, in
    /// [0, 1)): chain `j` starts `j / chains` further on (modulo 1), so no two chains hold the
    /// same values and no compiler can merge them; each step advances every chain; `result`
    /// receives their sum, which keeps every chain live.
    fn body(self, start: &str, result: &str) -> String {
        let chains = self.chains();
        let name = |chain: u32| format!("x{chain}");
        let mut body = format!("    let start = {start};\n");
        for chain in 0..chains {
            let value = match chain {
                0 => "start".to_string(),
                _ => format!(
                    "fract(start + vec4<f32>({:?}))",
                    chain as f32 / chains as f32
                ),
            };
            body.push_str(&format!("    var {} = {value};\n", name(chain)));
        }
        body.push_str(&format!(
            "    for (var step = 0u; step < {}; step++) {{\n",
            self.bound()
        ));
        for chain in 0..chains {
            let x = name(chain);
            body.push_str(&format!(
                "        {x} = fract(row_eval({x}) * 0.25 + {x} * 0.75 + vec4<f32>(0.1));\n"
            ));
        }
        let sum: Vec<String> = (0..chains).map(name).collect();
        body.push_str(&format!("    }}\n    {result}{};\n", sum.join(" + ")));
        body
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
    let body = chain.body(
        "fract(vec4<f32>(position.x * 0.000521, position.y * 0.000927, (position.x + position.y) * 0.00037, 0.5))",
        "return ",
    );
    format!(
        "{row_wgsl}\n\
         @group(0) @binding(2) var lut_texture: texture_2d<f32>;\n\
         @group(0) @binding(3) var lut_sampler: sampler;\n\
         {}\n\
         {FULLSCREEN_WGSL}\n\
         @fragment\n\
         fn bench_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{\n\
         {body}\
         }}\n",
        chain.declaration()
    )
}

/// The compute shader around a row's `row_eval`.
pub(super) fn compute_harness(row_wgsl: &str, chain: Chain) -> String {
    let body = chain.body("bench_inputs[id.x]", "bench_outputs[id.x] = ");
    format!(
        "{row_wgsl}\n\
         @group(0) @binding(0) var<storage, read> bench_inputs: array<vec4<f32>>;\n\
         @group(0) @binding(1) var<storage, read_write> bench_outputs: array<vec4<f32>>;\n\
         @group(0) @binding(2) var lut_texture: texture_2d<f32>;\n\
         @group(0) @binding(3) var lut_sampler: sampler;\n\
         {}\n\
         @compute @workgroup_size(64)\n\
         fn bench(@builtin(global_invocation_id) id: vec3<u32>) {{\n\
         {body}\
         }}\n",
        chain.declaration()
    )
}

/// A row whose evaluation is free: its time is the harness's own, subtracted from each row's.
pub const BASELINE_ROW: &str = "fn row_eval(x: vec4<f32>) -> vec4<f32> {\n    return x;\n}\n";

#[cfg(test)]
mod tests {
    use super::*;

    /// The timed harnesses, in both stages, run [`CHAINS`] chains from starts a fraction of 1
    /// apart and keep all of them; the static costs' harness runs one. All are valid WGSL.
    #[test]
    fn the_timed_harness_runs_its_chains_side_by_side() {
        let timed = [
            compute_harness(BASELINE_ROW, Chain::Uniform),
            fragment_harness_with(BASELINE_ROW, Chain::Uniform),
        ];
        for shader in &timed {
            gbuffer_validator::validate_wgsl(shader).unwrap_or_else(|problem| panic!("{problem}"));
            for needle in [
                "var x0 = start;",
                "var x1 = fract(start + vec4<f32>(0.25));",
                "var x3 = fract(start + vec4<f32>(0.75));",
                "x3 = fract(row_eval(x3) * 0.25 + x3 * 0.75 + vec4<f32>(0.1));",
                "x0 + x1 + x2 + x3;",
                "step < bench_chain.x;",
            ] {
                assert!(shader.contains(needle), "{needle}: {shader}");
            }
            assert!(!shader.contains("x4"), "{shader}");
        }
        for shader in [harness(BASELINE_ROW), fragment_harness(BASELINE_ROW)] {
            gbuffer_validator::validate_wgsl(&shader).unwrap_or_else(|problem| panic!("{problem}"));
            assert!(shader.contains("var x0 = start;"), "{shader}");
            assert!(!shader.contains("x1"), "{shader}");
        }
    }
}
