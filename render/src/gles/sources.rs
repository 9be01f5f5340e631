//! The GLSL ES of the fused paths' programs, made without a context: the GLES backend links
//! them, and the cost model (`gbuffer-cost`) and the tile compilers' test compile the same text
//! on Mali's and Adreno's compilers.

use gbuffer_codegen::emit::glsl::{self as includes, Include, Interface};
use gbuffer_core::Named;

use crate::glsl::{self, Dialect};
use crate::on_tile::{
    fused_wgsl, include_translation, store_through_include, tile_layout, Path, Stage,
    TRANSLATION_ENTRY,
};
use crate::options::Options;

/// One program's shaders.
#[derive(Clone, Debug)]
pub struct Program {
    /// What the program draws (`gbuffer`, `decals`, `lights`, ...).
    pub name: &'static str,
    /// The vertex shader.
    pub vertex: String,
    /// The fragment shader: the preamble, the layout's include as generated, the renderer's
    /// declarations and `main`.
    pub fragment: String,
}

/// A fused path's programs, one per stage, and the include's interface.
#[derive(Clone, Debug)]
pub struct FusedPrograms {
    /// The include the fragment shaders use.
    pub include: Include,
    /// Its attachments (the G-buffer's; the output follows them).
    pub interface: Interface,
    /// The programs, in [`Stage::ALL`]'s order.
    pub programs: Vec<Program>,
}

/// The programs of fused path `path` (`FetchPacked` or `FetchNative`) for `options`.
pub fn fused_programs(options: &Options, path: Path) -> Result<FusedPrograms, String> {
    let layout = tile_layout(options)?;
    let model = layout.layout();
    let include = if path == Path::FetchPacked {
        Include::FetchPacked
    } else {
        Include::FetchNative
    };
    let (include_text, interface) =
        includes::include(&model, include, 0).map_err(|error| error.to_string())?;
    let wgsl = fused_wgsl(options, layout, -1.0);
    let translation = include_translation(&model)?;
    let texel = &translation.names.layout;
    let stages =
        glsl::fragment_declarations(&wgsl, TRANSLATION_ENTRY, Dialect::Gles, &translation)?;
    let output = format!(
        "layout(location = {}) inout highp vec4 frame_colour;\n",
        interface.attachments.len()
    );
    // The volume drawn comes in a uniform; each draw writes only what it changes.
    let declarations = format!("{output}uniform highp uint volume_index;\n");
    let (load, store) = (model.symbols().load(), store_through_include(&model));
    let programs = Stage::ALL
        .iter()
        .copied()
        .map(|stage| {
            let main = format!(
                "{declarations}{}",
                stage.fragment_main(texel, &load, &store)
            );
            let (vertex, fragment) = program(
                &wgsl,
                (&include_text, &stages),
                &interface,
                stage.vertex_entry(),
                &main,
            )
            .map_err(|error| format!("the {} program: {error}", stage.name()))?;
            Ok(Program {
                name: stage.name(),
                vertex,
                fragment,
            })
        })
        .collect::<Result<_, String>>()?;
    Ok(FusedPrograms {
        include,
        interface,
        programs,
    })
}

/// A fused program's shaders: `vertex` of the WGSL translated, and a fragment shader of the
/// GLES preamble, the layout's include as generated, the stages' declarations
/// ([`glsl::fragment_declarations`], the same for every stage) and `main`.
pub fn program(
    wgsl: &str,
    (include, stages): (&str, &glsl::Translation),
    interface: &Interface,
    vertex: &str,
    main: &str,
) -> Result<(String, String), String> {
    let program = program_in(
        Dialect::Gles,
        wgsl,
        (include, interface.include, stages),
        vertex,
        main,
    )?;
    Ok((program.vertex, program.fragment))
}

/// A fused program in `dialect` (GLES's or WebGL's GLSL ES), with the sampler uniforms it
/// declares: `vertex` of the WGSL translated, and a fragment shader of the dialect's preamble
/// (its version, the `include`'s extensions, highp defaults), the layout's include as
/// generated, `stages` (the declarations the stages' functions need but the include does not
/// make, [`glsl::fragment_declarations`] in `dialect`) and `main`.
pub fn program_in(
    dialect: Dialect,
    wgsl: &str,
    (include_text, include, stages): (&str, Include, &glsl::Translation),
    vertex: &str,
    main: &str,
) -> Result<TranslatedProgram, String> {
    let vertex = glsl::translate(wgsl, naga::ShaderStage::Vertex, vertex, dialect)?;
    let extensions: String = include
        .shader_extensions()
        .iter()
        .map(|extension| format!("#extension {extension} : require\n"))
        .collect();
    let fragment = format!(
        "{}\n{extensions}{}precision highp float;\nprecision highp int;\n\n{include_text}\n{}\n{main}",
        dialect.version_line(),
        dialect.early_fragment_tests(),
        stages.text,
    );
    let mut samplers = stages.samplers.clone();
    samplers.extend(vertex.samplers);
    samplers.sort();
    samplers.dedup();
    Ok(TranslatedProgram {
        vertex: vertex.text,
        fragment,
        samplers,
    })
}

/// A program's shaders, and each sampler uniform with the binding (texture unit) of the texture
/// it samples, which a host without binding qualifiers (GLSL ES 3.00) sets by name.
#[derive(Clone, Debug)]
pub struct TranslatedProgram {
    /// The vertex shader.
    pub vertex: String,
    /// The fragment shader.
    pub fragment: String,
    /// (uniform name, texture unit).
    pub samplers: Vec<(String, u32)>,
}
