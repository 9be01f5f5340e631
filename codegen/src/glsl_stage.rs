//! A whole stage of a validated module as GLSL, by naga's GLSL writer: the validator's
//! portability check, the renderer's vertex and two-pass stages and the cost model's GLSL ES
//! all write stages here, with the same options, so they translate alike. What a hand-written
//! `main` or an include declares is printed from the module instead (`emit::glsl::printer`).

use naga::back::glsl;
use naga::valid::ModuleInfo;

/// Options for naga's GLSL writer: `version`, clip space left as the WGSL writes it (no
/// coordinate adjustment), and every resource keeping its WGSL binding number (GLSL ES 3.10
/// and GLSL 450 declare bindings in the shader; a host binds by those numbers).
pub fn options_keeping_bindings(module: &naga::Module, version: glsl::Version) -> glsl::Options {
    let mut binding_map = glsl::BindingMap::default();
    for (_, global) in module.global_variables.iter() {
        if let Some(binding) = &global.binding {
            binding_map.insert(*binding, binding.binding as u8);
        }
    }
    glsl::Options {
        version,
        writer_flags: glsl::WriterFlags::empty(),
        binding_map,
        ..glsl::Options::default()
    }
}

/// naga's GLSL of entry point `entry` (of `stage`) of a validated module, and the reflection
/// that says which uniform samples which texture. `options` says the version, the writer's
/// flags (naga's default adjusts clip space to GL's) and the bindings.
pub fn write(
    (module, info): (&naga::Module, &ModuleInfo),
    stage: naga::ShaderStage,
    entry: &str,
    options: &glsl::Options,
) -> Result<(String, glsl::ReflectionInfo), String> {
    let pipeline = glsl::PipelineOptions {
        shader_stage: stage,
        entry_point: entry.to_string(),
        multiview: None,
    };
    let mut text = String::new();
    let reflection = glsl::Writer::new(
        &mut text,
        module,
        info,
        options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .and_then(|mut writer| writer.write())
    .map_err(|error| format!("naga cannot translate `{entry}` to GLSL: {error}"))?;
    Ok((text, reflection))
}
