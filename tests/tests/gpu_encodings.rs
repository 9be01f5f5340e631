//! The conversions bit fields add (`emit::wgsl::bit_field_helpers`) on a real adapter against
//! the Rust mirror (`convert`), bit for bit: unorm and snorm at widths from 2 to 24 bits, the
//! snorm decode, and rgb9e5 both ways. Edge cases first (NaN, infinities, denormals, signed
//! zeros, values beside rounding boundaries, rgb9e5's largest value and its exponent carry),
//! then random values.

use gbuffer_codegen::convert::{
    f32_from_rgb9e5, f32_from_snorm, max_code, rgb9e5_from_f32, snorm_from_f32, unorm_from_f32,
};
use gbuffer_codegen::emit::wgsl::bit_field_helpers;
use gbuffer_testkit::gpu::Gpu;
use gbuffer_testkit::values::Values;

const UNORM_WIDTHS: [u32; 5] = [2, 4, 12, 20, 23];
const SNORM_WIDTHS: [u32; 5] = [2, 4, 8, 16, 24];
/// Per input value: a unorm code per width, a snorm code and its decode per width.
const OUTPUTS_PER_VALUE: usize = UNORM_WIDTHS.len() + 2 * SNORM_WIDTHS.len();

/// The compute shader: every conversion of `inputs[i]` into `scalar_outputs`, and for each
/// triple `inputs[3t..3t + 3]` its rgb9e5 word and that word's decode into `triple_outputs`.
fn harness() -> String {
    let mut body = String::new();
    let mut slot = 0;
    for bits in UNORM_WIDTHS {
        body.push_str(&format!(
            "    scalar_outputs[base + {slot}u] = enc_f32_to_unorm(value, {bits}u, {}u, {}u);\n",
            max_code(bits),
            150 - bits
        ));
        slot += 1;
    }
    for bits in SNORM_WIDTHS {
        let magnitude = bits - 1;
        body.push_str(&format!(
            "    let snorm{bits} = enc_f32_to_snorm(value, {magnitude}u, {}u, {}u, {}u);\n    \
             scalar_outputs[base + {slot}u] = snorm{bits};\n    \
             scalar_outputs[base + {}u] = bitcast<u32>(enc_f32_from_snorm(snorm{bits}, {}u, {:?}));\n",
            max_code(magnitude),
            150 - magnitude,
            max_code(bits),
            slot + 1,
            32 - bits,
            1.0f32 / max_code(magnitude) as f32,
        ));
        slot += 2;
    }
    format!(
        "{}\n\
         @group(0) @binding(0) var<storage, read> inputs: array<u32>;\n\
         @group(0) @binding(1) var<storage, read_write> scalar_outputs: array<u32>;\n\
         @group(0) @binding(2) var<storage, read_write> triple_outputs: array<u32>;\n\
         @group(0) @binding(3) var<uniform> count: vec4<u32>;\n\n\
         @compute @workgroup_size(64)\n\
         fn main(@builtin(global_invocation_id) id: vec3<u32>) {{\n    \
         if id.x >= count.x {{\n        return;\n    }}\n    \
         let value = bitcast<f32>(inputs[id.x]);\n    \
         let base = id.x * {OUTPUTS_PER_VALUE}u;\n{body}    \
         if id.x % 3u == 0u && id.x + 2u < count.x {{\n        \
         let triple = bitcast<vec3<f32>>(vec3<u32>(inputs[id.x], inputs[id.x + 1u], inputs[id.x + 2u]));\n        \
         let word = enc_f32x3_to_rgb9e5(triple);\n        \
         let decoded = bitcast<vec3<u32>>(enc_f32x3_from_rgb9e5(word));\n        \
         let at = id.x / 3u * 4u;\n        \
         triple_outputs[at] = word;\n        \
         triple_outputs[at + 1u] = decoded.x;\n        \
         triple_outputs[at + 2u] = decoded.y;\n        \
         triple_outputs[at + 3u] = decoded.z;\n    }}\n}}\n",
        bit_field_helpers("enc")
    )
}

/// Values for rgb9e5's hard cases, beside the formats' edge cases: powers of two and the
/// values whose mantissa rounds up to 512 (the exponent carry), and the largest value.
fn rgb9e5_edges() -> Vec<f32> {
    let mut values = vec![65408.0, 65409.0, 65407.99];
    for exponent in -18..17 {
        let power = 2f32.powi(exponent);
        let carry = power * (1.0 - 2f32.powi(-10));
        values.extend([
            power,
            carry,
            f32::from_bits(carry.to_bits() - 1),
            f32::from_bits(power.to_bits() - 1),
        ]);
    }
    values
}

#[test]
fn bit_field_conversions_match_the_rust_mirror_bit_for_bit_on_the_adapter() {
    let gpu = Gpu::new();
    let mut values = Values::new(15);
    let mut inputs: Vec<f32> = gbuffer_testkit::values::float_edges();
    inputs.extend(rgb9e5_edges());
    // Whole triples of edges, then random values.
    inputs.extend((0..(1 << 18)).map(|_| values.float()));
    inputs.truncate(inputs.len() / 3 * 3);
    let bits: Vec<u32> = inputs.iter().map(|value| value.to_bits()).collect();
    let count = inputs.len();
    let outputs = gpu.run_compute(
        &harness(),
        "main",
        &bits,
        &[count * OUTPUTS_PER_VALUE, count / 3 * 4],
        count as u32,
    );
    let mut failures = Vec::new();
    for (index, &value) in inputs.iter().enumerate() {
        let got = &outputs[0][index * OUTPUTS_PER_VALUE..][..OUTPUTS_PER_VALUE];
        let mut expected = Vec::new();
        for bits in UNORM_WIDTHS {
            expected.push((format!("unorm{bits}"), unorm_from_f32(value, bits)));
        }
        for bits in SNORM_WIDTHS {
            let code = snorm_from_f32(value, bits);
            expected.push((format!("snorm{bits}"), code));
            expected.push((
                format!("snorm{bits} decode"),
                f32_from_snorm(code, bits).to_bits(),
            ));
        }
        for ((what, want), have) in expected.iter().zip(got) {
            // The decode multiplies by a rounded reciprocal: within 2 ulp of the quotient.
            let tolerance = if what.ends_with("decode") { 2 } else { 0 };
            if want.abs_diff(*have) > tolerance {
                failures.push(format!(
                    "{what} of {value:e}: mirror {want:#x}, adapter {have:#x}"
                ));
            }
        }
    }
    for (triple, got) in inputs.chunks_exact(3).zip(outputs[1].chunks_exact(4)) {
        let rgb = [triple[0], triple[1], triple[2]];
        let word = rgb9e5_from_f32(rgb);
        let decoded = f32_from_rgb9e5(word).map(f32::to_bits);
        if got != [word, decoded[0], decoded[1], decoded[2]] {
            failures.push(format!(
                "rgb9e5 of {rgb:?}: mirror {word:#010x} {decoded:x?}, adapter {got:x?}"
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "on {}: {} mismatches, the first:\n{}",
        gpu.describe(),
        failures.len(),
        failures[..failures.len().min(20)].join("\n")
    );
    eprintln!(
        "{count} values, {} triples: adapter and mirror agree on {}",
        count / 3,
        gpu.describe()
    );
}
