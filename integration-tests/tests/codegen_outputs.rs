//! The `codegen` outputs for the seed layout files: they agree with the derive, they are
//! snapshot-tested, the GLSL compiles with glslang, and naga's SPIR-V passes spirv-val.
//!
//! glslangValidator and spirv-val come from Debian's `glslang-tools` and `spirv-tools`
//! (`.ci/run` installs them). glslang does not know EXT_shader_pixel_local_storage nor
//! EXT_shader_framebuffer_fetch: their declarations are checked against the extensions' rules
//! here, and the rest of each shader is compiled with glslang.

use std::path::{Path, PathBuf};

use gbuffer::layout::{Format, Layout};
use gbuffer_build::output::{generate, Output};
use gbuffer_codegen::emit::glsl::{self, Include, Interface, PlsBlock};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::Conversions;
use gbuffer_core::Named;
use gbuffer_gpu::harness::fragment_harness;
use gbuffer_gpu::tools::{glslang, spirv_val};
use gbuffer_layout_file::read_layout_file;
use gbuffer_testkit::user_shaders::{preambles, scalars_of_texel};
use proptest::prelude::*;

fn layout_files() -> Vec<(PathBuf, Layout)> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../codegen/layouts");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&folder)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            (
                path.clone(),
                read_layout_file(&path)
                    .unwrap_or_else(|error| panic!("{error}"))
                    .layout,
            )
        })
        .collect()
}

#[test]
fn layout_files_describe_the_derived_seed_and_engine_layouts_and_give_the_same_wgsl() {
    let mut derived = gbuffer::seed_layouts::all();
    derived.extend(gbuffer::engine_layouts::all());
    assert_eq!(layout_files().len(), derived.len());
    for (path, layout) in layout_files() {
        let (seed, wgsl) = derived
            .iter()
            .find(|(seed, _)| seed.name == layout.name)
            .unwrap_or_else(|| panic!("{} is no seed or engine layout", path.display()));
        assert_eq!(&layout, seed);
        let files = generate(&layout, Conversions::Exact, &[Output::Wgsl]).unwrap();
        assert_eq!(
            files[0].contents,
            format!("{wgsl}\n"),
            "the codegen WGSL is the derive's"
        );
    }
}

#[test]
fn every_output_matches_its_snapshot() {
    for (_, layout) in layout_files() {
        for file in generate(&layout, Conversions::Exact, &Output::ALL).unwrap() {
            insta::assert_snapshot!(file.name.clone(), file.contents);
        }
    }
}

/// Every include of a layout, with its interface.
fn includes(layout: &Layout) -> Vec<(Include, String, Interface)> {
    let compiled = CompiledLayout::new(layout, Conversions::Exact).unwrap();
    Include::ALL
        .into_iter()
        .map(|include| {
            let (text, interface) = glsl::include(&compiled, include, 0).unwrap();
            (include, text, interface)
        })
        .collect()
}

/// The lines of an include that are not comments.
fn code_lines(text: &str) -> impl Iterator<Item = &str> {
    text.lines()
        .filter(|line| !line.trim_start().starts_with("//"))
}

/// An include carries no `#version`, `#extension` or default precision (it is pasted after
/// the user's preamble), and its header lists the extensions that preamble must require.
fn check_include_shape(layout: &Layout) {
    for (include, text, interface) in includes(layout) {
        for line in code_lines(&text) {
            assert!(
                !line.starts_with("#version")
                    && !line.starts_with("#extension")
                    && !line.starts_with("precision "),
                "{} {include:?}: `{line}` belongs to the user's preamble",
                layout.name
            );
        }
        for extension in interface.include.shader_extensions() {
            let line = format!("//     #extension {extension} : require");
            assert!(
                text.contains(&line),
                "{} {include:?}: the header lacks `{line}`",
                layout.name
            );
        }
    }
}

#[test]
fn includes_leave_the_preamble_to_the_user_and_list_what_it_needs() {
    for (_, layout) in layout_files() {
        check_include_shape(&layout);
    }
}

/// Compiles the Vulkan includes unedited under every preamble they allow, inside a user
/// shader that loads the texel, and checks the SPIR-V.
fn check_vulkan_includes(layout: &Layout, conversions: Conversions) -> Result<(), String> {
    let compiled = CompiledLayout::new(layout, conversions).unwrap();
    let names = compiled.names();
    for include in [Include::SubpassPacked, Include::SubpassNative] {
        let (text, _) = glsl::include(&compiled, include, 0).unwrap();
        for preamble in preambles(include) {
            let user = format!(
                "layout(location = 0) out highp uvec4 user_output;
\
                 void main() {{\n    {} texel = {}();\n    user_output = uvec4({});\n}}\n",
                names.layout,
                layout.symbols().load(),
                scalars_of_texel(layout, names, "texel")[0]
            );
            let shader = format!("{preamble}{text}\n{user}");
            let spirv = glslang(&shader, "frag", true).map_err(|error| {
                format!("{} {include:?} under {preamble:?}: {error}", layout.name)
            })?;
            spirv_val(&spirv).map_err(|error| format!("{} {include:?}: {error}", layout.name))?;
        }
    }
    Ok(())
}

/// The `(input_attachment_index, set, binding, name)` of every subpass input a Vulkan include
/// declares, read from its text.
fn declared_subpass_inputs(text: &str) -> Vec<(u64, u64, u64, String)> {
    code_lines(text)
        .filter_map(|line| {
            let qualifiers = line.strip_prefix("layout(")?.split_once(')')?;
            let numbers: Vec<u64> = qualifiers
                .0
                .split(',')
                .map(|pair| pair.split_once('=').unwrap().1.trim().parse().unwrap())
                .collect();
            let name = qualifiers
                .1
                .trim()
                .trim_end_matches(';')
                .rsplit(' ')
                .next()?;
            Some((numbers[0], numbers[1], numbers[2], name.to_string()))
        })
        .collect()
}

#[test]
fn vulkan_includes_host_data_names_what_the_include_declares() {
    for (_, layout) in layout_files() {
        let files = generate(&layout, Conversions::Exact, &[Output::GlslVulkan]).unwrap();
        for include in [Include::SubpassPacked, Include::SubpassNative] {
            let glsl_name = include.file_name(&layout.symbols(), "glsl");
            let text = &files
                .iter()
                .find(|file| file.name == glsl_name)
                .unwrap()
                .contents;
            let json_name = glsl::local_read::LocalRead::file_name(&layout.symbols(), include);
            let json = &files
                .iter()
                .find(|file| file.name == json_name)
                .unwrap_or_else(|| panic!("{json_name} is not written"))
                .contents;
            let host: serde_json::Value = serde_json::from_str(json)
                .unwrap_or_else(|error| panic!("{json_name} is no JSON: {error}"));
            assert_eq!(host["include"], glsl_name.as_str());
            assert_eq!(
                host["image_layout"]["name"],
                "VK_IMAGE_LAYOUT_RENDERING_LOCAL_READ_KHR"
            );
            let declared = declared_subpass_inputs(text);
            let listed: Vec<(u64, u64, u64, String)> = host["colour_attachments"]
                .as_array()
                .unwrap()
                .iter()
                .map(|attachment| {
                    // The G-buffer draw writes attachment i at location i: the host's colour
                    // attachment order.
                    assert_eq!(attachment["location"], attachment["input_attachment_index"]);
                    (
                        attachment["input_attachment_index"].as_u64().unwrap(),
                        host["descriptor_set"].as_u64().unwrap(),
                        attachment["binding"].as_u64().unwrap(),
                        attachment["name"].as_str().unwrap().to_string(),
                    )
                })
                .collect();
            assert!(
                !declared.is_empty(),
                "{glsl_name} declares no subpass input"
            );
            assert_eq!(listed, declared, "{json_name} against {glsl_name}");
        }
    }
}

#[test]
fn vulkan_includes_compile_unedited_to_valid_spirv() {
    for (_, layout) in layout_files() {
        check_vulkan_includes(&layout, Conversions::Exact)
            .unwrap_or_else(|error| panic!("{error}"));
    }
    // Fast conversions: the builtins, and the `#if __VERSION__ >= 310` around rgba8's.
    use gbuffer::GBufferLayout;
    check_vulkan_includes(&gbuffer_testkit::FastFormats::layout(), Conversions::Fast)
        .unwrap_or_else(|error| panic!("{error}"));
    check_vulkan_includes(
        &gbuffer_testkit::MixedConversions::layout(),
        Conversions::Exact,
    )
    .unwrap_or_else(|error| panic!("{error}"));
}

/// The member type EXT_shader_pixel_local_storage gives each format (its format table).
fn extension_type(format: &str) -> Option<&'static str> {
    Some(match format {
        "r11f_g11f_b10f" => "vec3",
        "r32f" => "float",
        "rg16f" | "rg16" => "vec2",
        "rgb10_a2" | "rgba8" => "vec4",
        "rgba8i" => "ivec4",
        "rg16i" => "ivec2",
        "rgb10_a2ui" | "rgba8ui" => "uvec4",
        "rg16ui" => "uvec2",
        "r32ui" => "uint",
        _ => return None,
    })
}

/// Checks a pixel local storage include against the extension's rules; returns the members
/// as (precision, type, name) for the compile check.
fn check_pls_block(
    text: &str,
    block: PlsBlock,
    budget_bits: u32,
) -> Result<Vec<(String, String, String)>, String> {
    if !text.contains("//     #extension GL_EXT_shader_pixel_local_storage : require") {
        return Err("the header does not ask for the extension".into());
    }
    let mut lines = text
        .lines()
        .skip_while(|line| !line.starts_with("__pixel_local"));
    let opening = lines.next().ok_or("no block")?;
    let qualifier = opening.split_whitespace().next().unwrap_or_default();
    if qualifier != block.qualifier() || !opening.ends_with('{') {
        return Err(format!("bad block opening `{opening}`"));
    }
    let mut members = Vec::new();
    for line in lines.by_ref() {
        let line = line.split("//").next().unwrap().trim();
        if line == "};" {
            break;
        }
        let rest = line
            .strip_prefix("layout(")
            .ok_or(format!("member without layout qualifier: `{line}`"))?;
        let (format, declaration) = rest
            .split_once(')')
            .ok_or(format!("unclosed layout: `{line}`"))?;
        let words: Vec<&str> = declaration
            .trim()
            .trim_end_matches(';')
            .split_whitespace()
            .collect();
        let [precision, ty, name] = words[..] else {
            return Err(format!("bad member `{line}`"));
        };
        if !["highp", "mediump", "lowp"].contains(&precision) {
            return Err(format!("`{line}`: a member needs a precision qualifier"));
        }
        let expected =
            extension_type(format).ok_or(format!("`{format}` is not a format of the extension"))?;
        if ty != expected {
            return Err(format!(
                "`{line}`: format {format} takes {expected}, not {ty}"
            ));
        }
        members.push((precision.to_string(), ty.to_string(), name.to_string()));
    }
    // Every format is 32 bits: the block's size is 4 bytes a member. The extension guarantees
    // 16 bytes (GL_MAX_SHADER_PIXEL_LOCAL_STORAGE_SIZE_EXT is at least 16): a 128-bit budget
    // must fit in them.
    let bytes = 4 * members.len() as u32;
    if 8 * bytes > budget_bits {
        return Err(format!("{bytes} bytes exceed the {budget_bits}-bit budget"));
    }
    if budget_bits == 128 && bytes > 16 {
        return Err(format!(
            "{bytes} bytes exceed the 16 bytes the extension guarantees"
        ));
    }
    Ok(members)
}

/// `    name(0.0, vec3(0.0), ...);`: a call of the GLSL function defined on `line` with zero
/// arguments of its parameters' types.
fn call_with_zeros(name: &str, line: &str) -> String {
    let parameters = line
        .split_once('(')
        .and_then(|(_, rest)| rest.rsplit_once(')'))
        .map_or("", |(parameters, _)| parameters);
    let arguments: Vec<String> = parameters
        .split(',')
        .filter(|parameter| !parameter.trim().is_empty())
        .map(|parameter| {
            let ty = parameter.split_whitespace().rev().nth(1).unwrap_or("float");
            match ty {
                "bool" => "false".to_string(),
                "uint" => "0u".to_string(),
                "int" => "0".to_string(),
                "float" => "0.0".to_string(),
                vector => format!("{vector}(0)"),
            }
        })
        .collect();
    format!("    {name}({});\n", arguments.join(", "))
}

/// Checks every pixel local storage block of a layout against the extension's rules, and
/// compiles a shader that uses its members as plain globals (no driver here has the
/// extension, and glslang does not know it).
fn check_pls_blocks(layout: &Layout) -> Result<(), String> {
    let compiled = CompiledLayout::new(layout, Conversions::Exact).unwrap();
    for block in PlsBlock::ALL {
        let (text, _) = glsl::include(&compiled, Include::PixelLocalStorage(block), 0).unwrap();
        let members = check_pls_block(&text, block, layout.budget)
            .map_err(|error| format!("{} {block:?}: {error}\n{text}", layout.name))?;
        let words = layout.word_contents();
        assert_eq!(members.len(), words.len());
        let word_names = compiled.word_names();
        for (((_, ty, name), word), word_name) in members.iter().zip(&words).zip(word_names) {
            assert_eq!(
                name, word_name,
                "a member is named as its field is in the functions (bit words, as their fields)"
            );
            assert_eq!(Some(ty.as_str()), extension_type(word.format.name()));
        }
        let globals: String = members
            .iter()
            .map(|(precision, ty, name)| format!("{precision} {ty} {name};\n"))
            .collect();
        let uses: String = members
            .iter()
            .map(|(_, _, name)| format!("    {name} = {name};\n"))
            .collect();
        // A layout with bit fields adds functions after the block: compiled with the members
        // as globals too, and every accessor called.
        let after_block = text.split_once("\n};\n").map_or("", |(_, rest)| rest);
        let calls: String = after_block
            .lines()
            .filter_map(|line| {
                let name = line.split('(').next()?.rsplit(' ').next()?;
                let accessor = name.starts_with("load_pls_") || name.starts_with("store_pls_");
                (accessor && line.ends_with(") {")).then(|| call_with_zeros(name, line))
            })
            .collect();
        assert_eq!(
            calls.is_empty(),
            !layout.has_bit_fields(),
            "a layout with bit fields has PLS accessors: {}",
            layout.name
        );
        let shader =
            format!("#version 310 es\n{globals}{after_block}\nvoid main() {{\n{uses}{calls}}}\n");
        glslang(&shader, "frag", false).map_err(|error| format!("{}: {error}", layout.name))?;
    }
    Ok(())
}

#[test]
fn pixel_local_storage_blocks_follow_the_extension_and_their_shaders_compile() {
    for (_, layout) in layout_files() {
        check_pls_blocks(&layout).unwrap_or_else(|error| panic!("{error}"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, failure_persistence: None, ..ProptestConfig::default() })]

    /// Layouts the repo has never seen, with names GLSL reserves: the includes keep their
    /// shape, the PLS blocks follow the extension, the Vulkan includes compile.
    #[test]
    fn random_layouts_give_includes_that_follow_the_rules(layout in gbuffer_testkit::layouts::random_layout()) {
        check_include_shape(&layout);
        check_pls_blocks(&layout).map_err(TestCaseError::fail)?;
        check_vulkan_includes(&layout, Conversions::Exact).map_err(TestCaseError::fail)?;
    }
}

#[test]
fn every_format_has_the_extension_type() {
    for &format in Format::ALL {
        assert_eq!(
            Some(gbuffer_codegen::emit::glsl::pls_member_type(format)),
            extension_type(format.name()),
            "{format}"
        );
    }
}

#[test]
fn naga_spirv_of_every_layout_passes_spirv_val() {
    for (_, layout) in layout_files() {
        let wgsl = gbuffer_codegen::wgsl::emit(&layout);
        let validated =
            gbuffer_validator::validate_wgsl(&fragment_harness(&layout, &wgsl)).unwrap();
        let words = naga::back::spv::write_vec(
            &validated.module,
            &validated.info,
            &Default::default(),
            None,
        )
        .unwrap();
        spirv_val(bytemuck::cast_slice(&words))
            .unwrap_or_else(|error| panic!("{}: {error}", layout.name));
    }
}

/// README's sample of generated WGSL is what `gbuffer codegen` writes for the layout file it
/// names: its lines, in order, one stretch of the generated file.
#[test]
fn readme_shows_generated_wgsl_as_generated() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let sample = readme
        .split("```wgsl\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("README shows a ```wgsl block");
    let named = "codegen/layouts/mobile_metallic.toml";
    assert!(
        readme.contains(&format!("(`{named}`)")),
        "README names {named}"
    );
    let layout = read_layout_file(&root.join(named)).unwrap().layout;
    let generated = &generate(&layout, Conversions::Exact, &[Output::Wgsl]).unwrap()[0].contents;
    assert!(
        generated.contains(sample),
        "README's WGSL is not a stretch of {named}'s:\n{sample}"
    );
}
