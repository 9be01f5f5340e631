//! The renderer's WGSL as GLSL for the on-tile backends: whole stages translated by naga's
//! GLSL writer, and the declarations a fragment entry point reaches (types, constants,
//! textures, functions) printed from naga's IR, which a hand-written `main` wraps with what
//! WGSL cannot say: framebuffer fetch on GLES, subpass inputs on Vulkan.
//!
//! The G-buffer layout's own declarations come from its generated include, pasted verbatim; the
//! renderer's WGSL declares the layout too (its functions take the texel struct), and its
//! printed declarations leave out the items the include declares (its interface lists them),
//! by their WGSL names, so each is declared once.

use gbuffer_translate::printer::{self, Choice};
use gbuffer_translate::{glsl_stage, wgsl};

/// Which GLSL a translation is for: the stage writer's dialects.
pub use gbuffer_translate::glsl_stage::Dialect;

/// GLSL written from the renderer's WGSL (a stage, or the declarations an entry point
/// reaches), and the sampler uniforms it declares with the binding of the texture each samples
/// (GLES binds them to texture units by name).
#[derive(Clone, Debug)]
pub struct GlslSource {
    /// The GLSL.
    pub text: String,
    /// (uniform name, binding of its texture in group 0).
    pub samplers: Vec<(String, u32)>,
}

/// Parses and validates WGSL, naming the problem with the source when it does not.
pub fn module(wgsl: &str) -> Result<(naga::Module, naga::valid::ModuleInfo), String> {
    wgsl::validate(wgsl, wgsl::GENERATED_CODE_CAPABILITIES)
        .map_err(|error| format!("the renderer's WGSL: {error}"))
}

/// naga's GLSL of entry point `entry` (of `stage`) in `wgsl`. Clip space is left as the WGSL
/// writes it (no coordinate adjustment: the scene flips y itself, `CLIP_Y_SIGN`), and every
/// resource of group 0 keeps its binding number. Vulkan's vertex stages are not GLSL here:
/// naga writes GL's names of the vertex and instance indices, which Vulkan's GLSL renames, so
/// the Vulkan backend takes them as naga's SPIR-V.
pub fn write_stage(
    wgsl: &str,
    stage: naga::ShaderStage,
    entry: &str,
    dialect: Dialect,
) -> Result<GlslSource, String> {
    if (dialect, stage) == (Dialect::Vulkan, naga::ShaderStage::Vertex) {
        return Err(format!(
            "`{entry}`: Vulkan's vertex stages are naga's SPIR-V, not GLSL (naga's GLSL names GL's vertex index)"
        ));
    }
    let (module, info) = module(wgsl)?;
    let (text, reflection) = glsl_stage::write((&module, &info), stage, entry, dialect)?;
    let mut samplers: Vec<(String, u32)> = reflection
        .texture_mapping
        .iter()
        .filter_map(|(name, mapping)| {
            let binding = module.global_variables[mapping.texture].binding.as_ref()?;
            Some((name.clone(), binding.binding))
        })
        .collect();
    samplers.sort();
    Ok(GlslSource { text, samplers })
}

/// The declarations fragment entry point `entry` of `wgsl` reaches, for a hand-written `main`
/// in `dialect`: its structs, constants, the textures it samples and the functions it calls,
/// printed from naga's IR, less what the layout's include declares (`include`, its interface).
pub fn fragment_declarations(
    wgsl: &str,
    entry: &str,
    dialect: Dialect,
    include: &gbuffer_codegen::emit::glsl::Interface,
) -> Result<GlslSource, String> {
    let (module, info) = module(wgsl)?;
    let leave_out: Vec<&str> = include
        .declares
        .iter()
        .filter_map(|item| item.wgsl.as_deref())
        .collect();
    let choice = Choice {
        entry_point: Some((naga::ShaderStage::Fragment, entry)),
        leave_out: &leave_out,
        from_310: &[],
        binding_qualifiers: dialect != Dialect::WebGl,
    };
    let printed = printer::print(&module, &info, &choice)
        .map_err(|error| format!("the declarations `{entry}` reaches: {error}"))?;
    let mut samplers: Vec<(String, u32)> = printed
        .texture_bindings
        .into_iter()
        .map(|(name, binding)| (name, binding.binding))
        .collect();
    samplers.sort();
    Ok(GlslSource {
        text: printed.text,
        samplers,
    })
}
