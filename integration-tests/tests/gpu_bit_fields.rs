//! Bit fields on a real adapter against the Rust mirror, bit for bit: a layout of every
//! encoding at its hardest widths (`EveryEncoding`) fed each encoding's extremes (NaN,
//! infinities, subnormals, zeros of both signs, values beside rounding boundaries, the
//! octahedral map's poles, seams and diagonals, rgb9e5's largest value and its exponent
//! carry, RGBM's multiplier steps), then random layouts that mix whole words and bit fields.
//! The GLSL of the same layouts runs on Mesa's GLES and lavapipe in `gles_includes` and
//! `vulkan_includes`, whose random layouts hold bit fields too.

use gbuffer::codecs::octahedral;
use gbuffer::layout::{Encoding, Layout};
use gbuffer::GBufferLayout;
use gbuffer_gpu::harness::scalars_per_texel;
use gbuffer_gpu::values::{float_edges, Values};
use gbuffer_gpu::Gpu;
use gbuffer_testkit::texels::{check_on_adapter, inputs};
use gbuffer_testkit::EveryEncoding;
use proptest::prelude::*;

/// rgb9e5's hard cases: its largest value and past it, and around each power of two the
/// values whose mantissa rounds up to 512 (the exponent carry).
fn rgb9e5_edges() -> Vec<[f32; 3]> {
    let mut edges = vec![
        [65408.0; 3],
        [65409.0, 0.0, 1.0],
        [65407.99, 1e-9, f32::NAN],
    ];
    for exponent in -18..17 {
        let power = 2f32.powi(exponent);
        let carry = power * (1.0 - 2f32.powi(-10));
        edges.push([power, carry, f32::from_bits(carry.to_bits() - 1)]);
        edges.push([carry, f32::from_bits(power.to_bits() - 1), power * 0.5]);
    }
    edges
}

/// RGBM's hard cases for `range`: each multiplier step k range / 255 and its neighbours, the
/// range and past it, negatives, NaN, infinities, tiny values.
fn rgbm_edges(range: f32) -> Vec<[f32; 3]> {
    let mut edges = vec![
        [range, 0.0, -1.0],
        [range * 2.0, f32::NAN, f32::INFINITY],
        [f32::NEG_INFINITY, 1e-30, 1e-45],
    ];
    for k in 0..=255u32 {
        let step = (f64::from(k) * f64::from(range) / 255.0) as f32;
        let below = f32::from_bits(step.to_bits().saturating_sub(1));
        edges.push([step, below, f32::from_bits(step.to_bits() + 1)]);
    }
    edges
}

/// Inputs for `EveryEncoding`: texel t gives each octahedral field octahedral edge t, the
/// rgb9e5 field rgb9e5 edge t, each RGBM field its edge t (cycling), and every other
/// component the float, integer and bool edges and then random values, as `inputs` does.
fn every_encoding_inputs(layout: &Layout, texels: usize, values: &mut Values) -> Vec<u32> {
    let mut inputs = inputs(layout, 0, texels, values);
    let scalars = scalars_per_texel(layout);
    // Per field, the edge vectors its encoding takes (none for the others).
    let edges: Vec<Option<Vec<[f32; 3]>>> = layout
        .fields
        .iter()
        .map(|field| match field.bit_field()?.encoding {
            Encoding::Octahedral => Some(octahedral::edge_directions()),
            Encoding::Rgb9e5 => Some(rgb9e5_edges()),
            Encoding::Rgbm(range) => Some(rgbm_edges(range.get())),
            _ => None,
        })
        .collect();
    // The first texels take the edges; the rest keep their random values.
    for texel in 0..texels.min(4096) {
        let mut slot = texel * scalars;
        for (field, edges) in layout.fields.iter().zip(&edges) {
            if let Some(edges) = edges {
                for (index, component) in edges[texel % edges.len()].iter().enumerate() {
                    inputs[slot + index] = component.to_bits();
                }
            }
            slot += field.ty.components;
        }
    }
    inputs
}

/// Runs `texels` texels of `layout` through its WGSL on the adapter; returns a line per
/// mismatch with the mirror (words bit for bit, decodes within their tolerance).
fn check(gpu: &Gpu, layout: &Layout, wgsl: &str, inputs: Vec<u32>) -> Vec<String> {
    let scalars = scalars_per_texel(layout);
    let texels = inputs.len() / scalars;
    let batch = |first, count| inputs[first * scalars..(first + count) * scalars].to_vec();
    check_on_adapter(gpu, layout, wgsl, texels, batch, 16)
}

#[test]
fn every_encoding_matches_the_mirror_at_its_extremes_on_the_adapter() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    let layout = EveryEncoding::layout();
    let mut values = Values::new(31);
    // Enough texels for every edge set to pass each field, then random ones.
    let texels = float_edges().len().max(4096) + (1 << 16);
    let inputs = every_encoding_inputs(&layout, texels, &mut values);
    let failures = check(&gpu, &layout, EveryEncoding::WGSL, inputs);
    assert!(
        failures.is_empty(),
        "on {}:\n{}",
        gpu.describe(),
        failures.join("\n")
    );
    eprintln!(
        "{texels} texels of {} words: adapter and mirror agree on {}",
        layout.words(),
        gpu.describe()
    );
}

/// The solver's layouts of the scene presets, as `gbuffer solve` writes them: their WGSL on the
/// adapter is the solver's mirror.
#[test]
fn solved_layouts_match_the_mirror_on_the_adapter() {
    let Some(gpu) = gbuffer_testkit::gpu() else {
        return;
    };
    for path in gbuffer_testkit::scene_presets() {
        let solution = gbuffer_solver::file::read_and_solve(&path).unwrap();
        let layout = solution.layout;
        let wgsl = gbuffer_codegen::wgsl::emit(&layout);
        let mut values = Values::new(43);
        let inputs = every_encoding_inputs(&layout, 16384, &mut values);
        let failures = check(&gpu, &layout, &wgsl, inputs);
        assert!(
            failures.is_empty(),
            "{}:\n{}",
            path.display(),
            failures.join("\n")
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, failure_persistence: None, ..ProptestConfig::default() })]

    /// Layouts the repo has never seen, whole words beside bit fields of every encoding.
    #[test]
    fn random_layouts_with_bit_fields_match_the_mirror_on_the_adapter(mut layout in gbuffer_testkit::layouts::random_layout()) {
        // The harness declares `var<uniform>`: a layout named `uniform` would shadow it (the
        // includes' tests keep the awkward names).
        layout.name = "RandomBits".into();
        let Some(gpu) = gbuffer_testkit::gpu() else {
            return Ok(());
        };
        let wgsl = gbuffer_codegen::wgsl::emit(&layout);
        let mut values = Values::new(37);
        let inputs = every_encoding_inputs(&layout, 8192, &mut values);
        let failures = check(&gpu, &layout, &wgsl, inputs);
        prop_assert!(failures.is_empty(), "{}", failures.join("\n"));
    }
}
