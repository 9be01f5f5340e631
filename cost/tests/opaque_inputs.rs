//! A fragment shader is costed on inputs no compiler can fold or merge, as a renderer's shader
//! receives them. A four-channel pack (clamp, scale, round and shift each channel of an rgba8
//! word) costs, through `Shader`'s own vertex shader, what the same fragment shader costs beside
//! a hand-written vertex shader that feeds it from a vertex attribute; beside one that writes
//! `vec4(gl_VertexID)` to it (one value in every component, which Mesa's linker merges into
//! one channel of work), it costs less: the undercount the companion must not make. On GL,
//! panfrost (Mali-G610) and freedreno (Adreno 740); on Vulkan, the same WGSL costs more with
//! four channels of input than with one value spread over four.

use gbuffer_cost::{measure, Shader, Stage, Statistics, TARGETS};
use gbuffer_testkit::compilers_set_up;

const PACK: &str = "#version 310 es\nprecision highp float;\nin highp vec4 colour;\n\
    layout(location = 0) out highp uint word;\nvoid main() {\n    \
    uvec4 q = uvec4(round(clamp(colour, 0.0, 1.0) * 255.0));\n    \
    word = q.x | (q.y << 8) | (q.z << 16) | (q.w << 24);\n}\n";

/// A renderer's vertex shader: the colour from an attribute of its own.
const ATTRIBUTE_FED: &str = "#version 310 es\nlayout(location = 0) in highp vec4 position;\n\
    layout(location = 1) in highp vec4 source;\nout highp vec4 colour;\n\
    void main() {\n    colour = source;\n    gl_Position = position;\n}\n";

/// Every component one value: what the companion wrote before.
const MERGEABLE: &str = "#version 310 es\nout highp vec4 colour;\nvoid main() {\n    \
    colour = vec4(float(gl_VertexID));\n    gl_Position = vec4(float(gl_VertexID));\n}\n";

fn statistics(target: &str, shaders: &[Shader]) -> Vec<Statistics> {
    let target = TARGETS.iter().find(|t| t.name == target).unwrap();
    measure(shaders, target, false)
        .unwrap_or_else(|error| panic!("{}: {error}", target.name))
        .into_iter()
        .map(|result| {
            result
                .unwrap_or_else(|error| panic!("{}: {error}", target.name))
                .statistics
        })
        .collect()
}

/// What the cost model compares: instructions and, where the compiler estimates them, cycles.
fn cost(statistics: &Statistics) -> (u64, Option<f64>) {
    (
        statistics.instructions,
        statistics.cycles.as_ref().map(|cycles| cycles.total),
    )
}

#[test]
fn a_fragment_shader_costs_what_it_costs_beside_attributes() {
    if !compilers_set_up() {
        return;
    }
    for target in ["mali-g610", "adreno-740"] {
        let shaders = [
            Shader::glsl(Stage::Fragment, PACK),
            Shader::glsl(Stage::Fragment, PACK).with_vertex(ATTRIBUTE_FED),
            Shader::glsl(Stage::Fragment, PACK).with_vertex(MERGEABLE),
        ];
        let found = statistics(target, &shaders);
        let (companion, attributes, merged) = (cost(&found[0]), cost(&found[1]), cost(&found[2]));
        eprintln!(
            "{target} (instructions, cycles): companion {companion:?}, attribute-fed \
             {attributes:?}, merged {merged:?}"
        );
        assert_eq!(
            companion, attributes,
            "{target}: companion against attributes"
        );
        assert!(
            merged.0 < attributes.0,
            "{target}: the merged inputs ({merged:?}) cost no less than attributes ({attributes:?})"
        );
    }
}

#[test]
fn a_vulkan_fragment_shader_is_not_merged_to_one_channel() {
    if !compilers_set_up() {
        return;
    }
    let wgsl = "@fragment\nfn four(@location(0) colour: vec4<f32>) -> @location(0) u32 {\n    \
                let q = vec4<u32>(round(clamp(colour, vec4(0.0), vec4(1.0)) * 255.0));\n    \
                return q.x | (q.y << 8u) | (q.z << 16u) | (q.w << 24u);\n}\n\
                @fragment\nfn one(@location(0) value: f32) -> @location(0) u32 {\n    \
                let q = vec4<u32>(round(clamp(vec4(value), vec4(0.0), vec4(1.0)) * 255.0));\n    \
                return q.x | (q.y << 8u) | (q.z << 16u) | (q.w << 24u);\n}\n";
    let shaders = [
        Shader::wgsl(wgsl, "four").unwrap(),
        Shader::wgsl(wgsl, "one").unwrap(),
    ];
    for target in ["adreno-740-vulkan", "amd-navi21"] {
        let found = statistics(target, &shaders);
        assert!(
            found[0].instructions > found[1].instructions,
            "{target}: four channels ({}) cost no more than one value ({})",
            found[0].instructions,
            found[1].instructions
        );
    }
}
