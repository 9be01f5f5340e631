//! The GLSL user shaders the guide shows (its chapter on the includes) compile as written there, with the generated include
//! in place of their `#include` line: the fetch example on Mesa's GLES 3.2, the Vulkan ones with
//! glslangValidator.

use gbuffer::seed_layouts;
use gbuffer_codegen::emit::glsl::{self, Include};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::Conversions;
use gbuffer_gpu::gles::Gles;
use gbuffer_testkit::or_skip;

/// The chapter's ```glsl blocks, without the indentation of the list items they sit in.
fn guide_glsl_blocks() -> Vec<String> {
    let chapter =
        std::fs::read_to_string(gbuffer_testkit::workspace().join("book/src/on-tile-includes.md"))
            .unwrap();
    let mut blocks = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for line in chapter.lines() {
        let trimmed = line.trim_start();
        match &mut current {
            None if trimmed == "```glsl" => {
                current = Some((line.len() - trimmed.len(), String::new()))
            }
            Some((_, block)) if trimmed == "```" => {
                blocks.push(std::mem::take(block));
                current = None;
            }
            Some((indent, block)) => {
                block.push_str(line.get(*indent..).unwrap_or(""));
                block.push('\n');
            }
            None => {}
        }
    }
    blocks
}

/// The blocks that include `file`, with the generated text of `include` in its place.
fn with_include(include: Include, file: &str) -> Vec<String> {
    let layout = seed_layouts::all()
        .into_iter()
        .map(|(layout, _)| layout)
        .find(|layout| layout.name == "MobileMetallic")
        .unwrap();
    let compiled = CompiledLayout::new(&layout, Conversions::Exact).unwrap();
    let (text, _) = glsl::include(&compiled, include, 0).unwrap();
    let line = format!("#include \"{file}\"");
    let blocks: Vec<String> = guide_glsl_blocks()
        .into_iter()
        .filter(|block| block.contains(&line))
        .map(|block| block.replace(&line, &text))
        .collect();
    assert!(
        !blocks.is_empty(),
        "the includes chapter has no glsl block with `{line}`"
    );
    blocks
}

#[test]
fn the_guides_fetch_example_compiles_on_gles() {
    let shaders = with_include(Include::FetchPacked, "mobile_metallic.fetch.glsl");
    let Some(gles) = or_skip("GLES 3.2 through EGL", Gles::new()) else {
        return;
    };
    for shader in shaders {
        gles.program(&shader).unwrap_or_else(|log| panic!("{log}"));
    }
}

#[test]
fn the_guides_vulkan_examples_compile_to_spirv() {
    let shaders = with_include(Include::SubpassPacked, "mobile_metallic.vulkan.glsl");
    assert_eq!(
        shaders.len(),
        2,
        "the G-buffer subpass and the lighting subpass"
    );
    for shader in shaders {
        gbuffer_gpu::tools::glslang(&shader, "frag", true).unwrap_or_else(|log| panic!("{log}"));
    }
}
