//! The `codegen` outputs for the seed layout files: they agree with the derive, they are
//! snapshot-tested, the GLSL compiles with glslang, and naga's SPIR-V passes spirv-val.
//!
//! glslangValidator and spirv-val come from Debian's `glslang-tools` and `spirv-tools`
//! (`.ci/run` installs them). glslang does not know EXT_shader_pixel_local_storage nor
//! EXT_shader_framebuffer_fetch: their declarations are checked against the extensions' rules
//! here, and the rest of each shader is compiled with glslang.

use std::path::{Path, PathBuf};
use std::process::Command;

use codegen::emit::glsl::PlsBlock;
use codegen::emit::wgsl::Conversions;
use codegen::layout_file::read_layout_file;
use codegen::output::{generate, Output};
use shaderlib::packing::{Format, Layout};
use tests::harness::fragment_harness;

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
fn layout_files_describe_the_derived_seed_layouts_and_give_the_same_wgsl() {
    let derived = shaderlib::seed_layouts::all();
    assert_eq!(layout_files().len(), derived.len());
    for (path, layout) in layout_files() {
        let (seed, wgsl) = derived
            .iter()
            .find(|(seed, _)| seed.name == layout.name)
            .unwrap_or_else(|| panic!("{} is no seed", path.display()));
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

/// Runs an external tool; a missing tool fails the test with how to install it.
fn run(tool: &str, arguments: &[&str], package: &str) -> (bool, String) {
    let output = Command::new(tool)
        .args(arguments)
        .output()
        .unwrap_or_else(|error| panic!("cannot run `{tool}` ({error}): install Debian's `{package}` (apt-get install -y {package})"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    (output.status.success(), text)
}

fn glslang(source: &str, stage: &str, vulkan: bool) -> Result<Vec<u8>, String> {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join(format!("shader.{stage}"));
    let spirv = folder.path().join("shader.spv");
    std::fs::write(&path, source).unwrap();
    let mut arguments = vec![path.to_str().unwrap()];
    if vulkan {
        arguments.extend(["-V", "-o", spirv.to_str().unwrap()]);
    }
    let (ok, text) = run("glslangValidator", &arguments, "glslang-tools");
    if !ok {
        return Err(format!("{text}\n{source}"));
    }
    Ok(if vulkan {
        std::fs::read(spirv).unwrap()
    } else {
        Vec::new()
    })
}

fn spirv_val(words: &[u8]) -> Result<(), String> {
    let folder = tempfile::tempdir().unwrap();
    let path = folder.path().join("module.spv");
    std::fs::write(&path, words).unwrap();
    let (ok, text) = run(
        "spirv-val",
        &["--target-env", "vulkan1.1", path.to_str().unwrap()],
        "spirv-tools",
    );
    if ok {
        Ok(())
    } else {
        Err(text)
    }
}

fn output(layout: &Layout, which: Output, suffix: &str) -> String {
    generate(layout, Conversions::Exact, &[which])
        .unwrap()
        .into_iter()
        .find(|file| file.name.ends_with(suffix))
        .unwrap()
        .contents
}

/// A fragment shader body that loads, changes and stores a texel.
fn exercise(layout: &Layout, store: bool) -> String {
    let prefix = layout.snake_name();
    let first = &layout.fields[0].name;
    let rounds = if store {
        format!("    store_{prefix}(texel);\n")
    } else {
        String::new()
    };
    format!("void main() {{\n    {name} texel = load_{prefix}();\n    texel.{first} = texel.{first};\n{rounds}}}\n", name = layout.name)
}

#[test]
fn framebuffer_fetch_include_follows_the_extension_and_compiles() {
    for (_, layout) in layout_files() {
        let include = output(&layout, Output::GlslFramebufferFetch, ".fetch.glsl");
        // The extension's form: the extension required, each attachment an `inout` colour
        // output at its location.
        assert!(include.contains("#extension GL_EXT_shader_framebuffer_fetch : require"));
        for target in 0..layout.targets() {
            let declaration = format!(
                "layout(location = {target}) inout highp uvec4 {}_target{target}_;",
                layout.snake_name()
            );
            assert!(include.contains(&declaration), "{declaration}");
        }
        // The rest compiles once `inout` is spelled `out` (what the extension adds to GLSL).
        let body = include
            .replace("#extension GL_EXT_shader_framebuffer_fetch : require", "")
            .replace(") inout highp uvec4", ") out highp uvec4");
        let shader = format!(
            "#version 310 es\nprecision highp float;\nprecision highp int;\n{body}\n{}",
            exercise(&layout, true)
        );
        glslang(&shader, "frag", false).unwrap_or_else(|error| panic!("{}: {error}", layout.name));
    }
}

#[test]
fn vulkan_include_compiles_to_valid_spirv() {
    for (_, layout) in layout_files() {
        let include = output(&layout, Output::GlslVulkan, ".vulkan.glsl");
        let shader = format!("#version 450\n{include}\n{}", exercise(&layout, false));
        let spirv = glslang(&shader, "frag", true)
            .unwrap_or_else(|error| panic!("{}: {error}", layout.name));
        spirv_val(&spirv).unwrap_or_else(|error| panic!("{}: {error}", layout.name));
    }
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
    if !text.contains("#extension GL_EXT_shader_pixel_local_storage : require") {
        return Err("the extension is not required".into());
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
    // Every format is 32 bits: the block's size is 4 bytes a member.
    if 32 * members.len() as u32 > budget_bits {
        return Err(format!(
            "{} members exceed the {budget_bits}-bit budget",
            members.len()
        ));
    }
    Ok(members)
}

#[test]
fn pixel_local_storage_blocks_follow_the_extension_and_their_shaders_compile() {
    for (_, layout) in layout_files() {
        for block in PlsBlock::ALL {
            let text = output(
                &layout,
                Output::GlslPixelLocalStorage,
                &format!(".pls_{}.glsl", block.suffix()),
            );
            let members = check_pls_block(&text, block, layout.budget)
                .unwrap_or_else(|error| panic!("{} {block:?}: {error}\n{text}", layout.name));
            assert_eq!(members.len(), layout.fields.len());
            for ((_, ty, name), field) in members.iter().zip(&layout.fields) {
                assert_eq!(name, &field.name);
                assert_eq!(Some(ty.as_str()), extension_type(field.format.name()));
            }
            // The shader around the block compiles with the members as plain globals.
            let globals: String = members
                .iter()
                .map(|(precision, ty, name)| format!("{precision} {ty} {name};\n"))
                .collect();
            let uses: String = members
                .iter()
                .map(|(_, _, name)| format!("    {name} = {name};\n"))
                .collect();
            let shader = format!(
                "#version 310 es\nprecision highp float;\n{globals}void main() {{\n{uses}}}\n"
            );
            glslang(&shader, "frag", false)
                .unwrap_or_else(|error| panic!("{}: {error}", layout.name));
        }
    }
}

#[test]
fn every_format_has_the_extension_type() {
    for format in Format::ALL {
        assert_eq!(
            Some(codegen::emit::glsl::pls_member_type(format)),
            extension_type(format.name()),
            "{format}"
        );
    }
}

#[test]
fn naga_spirv_of_every_layout_passes_spirv_val() {
    for (_, layout) in layout_files() {
        let wgsl = codegen::emit::wgsl::emit(&layout);
        let validated = validator::validate_wgsl(&fragment_harness(&layout, &wgsl)).unwrap();
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
