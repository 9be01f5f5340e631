//! A shader as each API's compiler sees it. WGSL is translated by naga, to GLSL ES 3.10 for GL
//! (panfrost's newest) and to SPIR-V for Vulkan; GLSL ES is given to GL drivers as written, and
//! a pipeline already in SPIR-V (a renderer's, [`Shader::spirv`]) to Vulkan drivers.
//! A fragment shader needs a vertex shader to link with: one is made that writes what the fragment
//! shader reads, as a renderer's would, from values no compiler can know: on GL each input from a
//! vertex attribute of its own, on Vulkan each from its own words of a storage buffer. For WGSL it
//! is built from naga's IR of the fragment shader (its inputs' locations, types and interpolation)
//! as WGSL, and translated as the fragment shader is; for GLSL ES input it is built from the
//! fragment shader's `in` declarations, read one a line (the form naga and most shaders write; a
//! declaration split over lines, or two on one line, is not seen: `gbuffer cost`'s help says so).
//! Neither a constant nor one value for every component: Mesa's linkers propagate a constant output
//! into the next stage (a pack of zeros costs two Adreno instructions where a pack of varyings
//! costs thirty), and merge outputs that hold the same value, so a `vec4(gl_VertexID)` input makes
//! the fragment shader compute one channel for four (an rgba8 pack costs 18 Mali-G610 instructions
//! from it, 30 from an attribute).

use std::sync::Arc;

use naga::back::spv;
use naga::valid::{Capabilities, ModuleInfo};
use naga::{AddressSpace, Binding, ImageClass, Interpolation, ScalarKind, ShaderStage, TypeInner};

use gbuffer_translate::{glsl_stage, wgsl};

use crate::Stage;

/// A shader to cost.
#[derive(Clone, Debug)]
pub struct Shader {
    stage: Stage,
    source: Source,
    colors: Option<Vec<String>>,
    vertex: Option<String>,
}

#[derive(Clone, Debug)]
enum Source {
    /// GLSL ES, with its `#version` line.
    Glsl(String),
    /// WGSL, validated once when the shader is made (shared by its clones), and the entry
    /// point to compile.
    Wgsl {
        module: Arc<(naga::Module, ModuleInfo)>,
        entry: String,
    },
    /// A pipeline in SPIR-V, as its renderer creates it.
    Spirv(Box<VulkanForm>),
}

/// The GL form: the stage's GLSL ES and, for a fragment shader, the vertex shader it links with.
#[derive(Clone, Debug, PartialEq)]
pub struct GlesForm {
    /// The shader.
    pub shader: String,
    /// The vertex shader (fragment shaders only).
    pub vertex: Option<String>,
}

/// What a Vulkan graphics pipeline is created for (the helper's `--rendering`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Rendering {
    /// A render pass object of one subpass, each input attachment an attachment of its own.
    #[default]
    RenderPass,
    /// A dynamic rendering read through `VK_KHR_dynamic_rendering_local_read`, input
    /// attachment index `i` reading colour attachment `i` (a fused G-buffer pass).
    LocalRead,
    /// [`Rendering::LocalRead`] with rasterization-order colour attachment access
    /// (`VK_EXT_rasterization_order_attachment_access`, or ARM's).
    LocalReadOrdered,
}

gbuffer_core::named!(
    /// The helper's name of the mode: `render-pass`, `local-read`, `local-read-ordered`.
    Rendering {
        RenderPass => "render-pass",
        LocalRead => "local-read",
        LocalReadOrdered => "local-read-ordered",
    }
);

/// The Vulkan form: SPIR-V, the vertex shader's, and the pipeline layout and attachments.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VulkanForm {
    /// The shader's SPIR-V.
    pub shader: Vec<u32>,
    /// Its entry point's name (the WGSL's).
    pub entry: String,
    /// The vertex shader's SPIR-V (fragment shaders only).
    pub vertex: Option<Vec<u32>>,
    /// Its entry point's name, where it is not `main` (the helper's `--vertex-entry`).
    pub vertex_entry: Option<String>,
    /// `SET,BINDING,KIND` for each resource (the helper's `--descriptor`).
    pub descriptors: Vec<String>,
    /// The colour attachments' formats by location (the helper's `--color`).
    pub colors: Vec<String>,
    /// The vertex attributes' formats by location (the helper's `--attribute`: `r32ui`,
    /// `rgb32f`...), each in a binding of its own; none for WGSL, whose companion vertex
    /// shader reads a storage buffer.
    pub attributes: Vec<String>,
    /// The push constants' size in bytes, visible to every stage (none for WGSL).
    pub push_constant_bytes: u32,
    /// What the pipeline is created for.
    pub rendering: Rendering,
}

/// Why a shader cannot be prepared: it does not parse, validate or translate.
pub type ShaderError = String;

impl Shader {
    /// GLSL ES as written, `#version` line included; it compiles only on GL targets.
    pub fn glsl(stage: Stage, text: &str) -> Shader {
        Shader {
            stage,
            source: Source::Glsl(text.to_string()),
            colors: None,
            vertex: None,
        }
    }

    /// A fragment shader's pipeline already in SPIR-V, with everything it is created with
    /// (`form.vertex` must be given); it compiles only on Vulkan targets.
    pub fn spirv(form: VulkanForm) -> Shader {
        Shader {
            stage: Stage::Fragment,
            source: Source::Spirv(Box::new(form)),
            colors: None,
            vertex: None,
        }
    }

    /// WGSL's entry point `entry`; the stage is the entry point's. The module must validate.
    pub fn wgsl(text: &str, entry: &str) -> Result<Shader, ShaderError> {
        let validated = wgsl::validate(text, wgsl::GENERATED_CODE_CAPABILITIES)?;
        Shader::of_entry_point(Arc::new(validated), entry)
    }

    /// WGSL's one fragment or compute entry point; an error names them where there are several.
    pub fn wgsl_only_entry_point(text: &str) -> Result<Shader, ShaderError> {
        let validated = wgsl::validate(text, wgsl::GENERATED_CODE_CAPABILITIES)?;
        let names: Vec<String> = validated
            .0
            .entry_points
            .iter()
            .filter(|point| matches!(point.stage, ShaderStage::Fragment | ShaderStage::Compute))
            .map(|point| point.name.clone())
            .collect();
        match names.as_slice() {
            [name] => Shader::of_entry_point(Arc::new(validated), name),
            [] => Err("no fragment or compute entry point to cost".into()),
            _ => Err(format!(
                "several entry points ({}): name one with --entry",
                names.join(", ")
            )),
        }
    }

    fn of_entry_point(
        validated: Arc<(naga::Module, ModuleInfo)>,
        entry: &str,
    ) -> Result<Shader, ShaderError> {
        let entry_point = validated
            .0
            .entry_points
            .iter()
            .find(|point| point.name == entry)
            .ok_or_else(|| format!("the WGSL has no entry point `{entry}`"))?;
        let stage = match entry_point.stage {
            ShaderStage::Fragment => Stage::Fragment,
            ShaderStage::Compute => Stage::Compute,
            other => {
                return Err(format!(
                    "`{entry}` is a {other:?} shader: only fragment and compute shaders are costed"
                ))
            }
        };
        Ok(Shader {
            stage,
            source: Source::Wgsl {
                module: validated,
                entry: entry.to_string(),
            },
            colors: None,
            vertex: None,
        })
    }

    /// The colour attachments' formats on Vulkan, by location, where the default (32-bit
    /// integers for integer outputs, `rgba16f` or `r32f` for floats) is not the one a renderer
    /// uses: `rgba8`, `rgb10a2`, `rg11b10f`, `r32ui`...
    pub fn with_colors(mut self, colors: &[&str]) -> Shader {
        self.colors = Some(colors.iter().map(|color| color.to_string()).collect());
        self
    }

    /// The GLSL ES vertex shader a fragment shader links with on GL, where the program has
    /// one of its own (a renderer's), instead of the one made from the fragment's inputs.
    pub fn with_vertex(mut self, vertex: &str) -> Shader {
        self.vertex = Some(vertex.to_string());
        self
    }

    /// The shader's stage.
    pub fn stage(&self) -> Stage {
        self.stage
    }

    /// The GLSL ES a GL driver compiles.
    pub fn gles(&self) -> Result<GlesForm, ShaderError> {
        match &self.source {
            Source::Spirv(_) => Err("SPIR-V is costed on Vulkan targets only".into()),
            Source::Glsl(text) => Ok(GlesForm {
                shader: text.clone(),
                vertex: self.vertex_or(|| Ok(companion_vertex_glsl(text)))?,
            }),
            Source::Wgsl { module, entry } => {
                let (module, info) = &**module;
                let shader = gles_310((module, info), naga_stage(self.stage), entry)?;
                let vertex = self.vertex_or(|| {
                    let function = &entry_point(module, entry).function;
                    let (module, info) = companion_vertex(module, function, Inputs::Attributes)?;
                    gles_310((&module, &info), ShaderStage::Vertex, "main")
                })?;
                Ok(GlesForm { shader, vertex })
            }
        }
    }

    /// The GL vertex shader a fragment shader links with: the one given
    /// ([`Shader::with_vertex`]), else `companion`'s; none for a compute shader.
    fn vertex_or(
        &self,
        companion: impl FnOnce() -> Result<String, ShaderError>,
    ) -> Result<Option<String>, ShaderError> {
        match (self.stage, &self.vertex) {
            (Stage::Compute, _) => Ok(None),
            (Stage::Fragment, Some(vertex)) => Ok(Some(vertex.clone())),
            (Stage::Fragment, None) => companion().map(Some),
        }
    }

    /// The SPIR-V a Vulkan driver compiles, with what its pipeline needs.
    pub fn vulkan(&self) -> Result<VulkanForm, ShaderError> {
        let (module, entry) = match &self.source {
            Source::Spirv(form) if form.vertex.is_none() => {
                return Err("a fragment shader's pipeline needs its vertex shader".into())
            }
            Source::Spirv(form) => return Ok((**form).clone()),
            Source::Glsl(_) => {
                return Err("GLSL ES is costed on GL targets only: give WGSL for Vulkan".into())
            }
            Source::Wgsl { module, entry } => (module, entry),
        };
        let (module, info) = &**module;
        let shader = spirv(module, info, naga_stage(self.stage), entry)?;
        let entry_point = entry_point(module, entry);
        let mut descriptors = descriptors(module);
        let (vertex, colors) = match self.stage {
            Stage::Compute => (None, Vec::new()),
            Stage::Fragment => {
                // The companion's buffer sits in the set after the fragment shader's last.
                let set = module
                    .global_variables
                    .iter()
                    .filter_map(|(_, global)| global.binding.as_ref())
                    .map(|binding| binding.group + 1)
                    .max()
                    .unwrap_or(0);
                descriptors.push(format!("{set},0,storage"));
                let (vertex_module, vertex_info) =
                    companion_vertex(module, &entry_point.function, Inputs::Buffer(set))?;
                let vertex = spirv(&vertex_module, &vertex_info, ShaderStage::Vertex, "main")?;
                let colors = match &self.colors {
                    Some(colors) => colors.clone(),
                    None => default_colors(module, &entry_point.function),
                };
                (Some(vertex), colors)
            }
        };
        Ok(VulkanForm {
            shader,
            entry: entry.clone(),
            vertex,
            descriptors,
            colors,
            ..VulkanForm::default()
        })
    }
}

/// The entry point `entry` of a module (found when the shader was made).
fn entry_point<'a>(module: &'a naga::Module, entry: &str) -> &'a naga::EntryPoint {
    module
        .entry_points
        .iter()
        .find(|point| point.name == entry)
        .expect("the entry point was found when the shader was made")
}

/// Entry point `entry` of `module` in GLSL ES 3.10 (panfrost's newest), its bindings kept.
fn gles_310(
    (module, info): (&naga::Module, &ModuleInfo),
    stage: ShaderStage,
    entry: &str,
) -> Result<String, ShaderError> {
    Ok(glsl_stage::write((module, info), stage, entry, glsl_stage::Dialect::Gles)?.0)
}

fn naga_stage(stage: Stage) -> ShaderStage {
    match stage {
        Stage::Fragment => ShaderStage::Fragment,
        Stage::Compute => ShaderStage::Compute,
    }
}

fn spirv(
    module: &naga::Module,
    info: &ModuleInfo,
    stage: ShaderStage,
    entry: &str,
) -> Result<Vec<u32>, ShaderError> {
    let pipeline = spv::PipelineOptions {
        shader_stage: stage,
        entry_point: entry.to_string(),
    };
    spv::write_vec(module, info, &spv::Options::default(), Some(&pipeline))
        .map_err(|error| format!("naga cannot translate `{entry}` to SPIR-V: {error}"))
}

/// `SET,BINDING,KIND` for every resource the module declares.
fn descriptors(module: &naga::Module) -> Vec<String> {
    let mut descriptors = Vec::new();
    for (_, global) in module.global_variables.iter() {
        let Some(binding) = &global.binding else {
            continue;
        };
        let kind = match (global.space, &module.types[global.ty].inner) {
            (AddressSpace::Uniform, _) => "uniform",
            (AddressSpace::Storage { .. }, _) => "storage",
            (_, TypeInner::Sampler { .. }) => "sampler",
            (
                _,
                TypeInner::Image {
                    class: ImageClass::Storage { .. },
                    ..
                },
            ) => "storage-image",
            (_, TypeInner::Image { .. }) => "sampled",
            _ => continue,
        };
        descriptors.push(format!("{},{},{kind}", binding.group, binding.binding));
    }
    descriptors
}

/// The `(location, type)` of each of a function's arguments or results bound to a location,
/// struct members included.
fn located(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
    binding: Option<&Binding>,
) -> Vec<(u32, Option<Interpolation>, naga::Handle<naga::Type>)> {
    match (binding, &module.types[ty].inner) {
        (
            Some(Binding::Location {
                location,
                interpolation,
                ..
            }),
            _,
        ) => {
            vec![(*location, *interpolation, ty)]
        }
        (None, TypeInner::Struct { members, .. }) => members
            .iter()
            .flat_map(|member| located(module, member.ty, member.binding.as_ref()))
            .collect(),
        _ => Vec::new(),
    }
}

/// Where the companion vertex shader reads the values it writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Inputs {
    /// Each output from a vertex attribute of its own, at the output's location (GL: a vertex
    /// shader's storage buffers are optional in GLES 3.1, and Mali's older drivers offer none).
    Attributes,
    /// Each component from its own word of a storage buffer at `@group(set) @binding(0)`, per
    /// vertex (Vulkan: the helper binds a buffer, not vertex attributes).
    Buffer(u32),
}

/// The WGSL type of an input: its scalar's name and its number of components.
fn wgsl_scalar_and_components(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
) -> (&'static str, u32) {
    let (components, scalar) = match module.types[ty].inner {
        TypeInner::Vector { size, scalar } => (size as u32, Some(scalar)),
        TypeInner::Scalar(scalar) => (1, Some(scalar)),
        _ => (1, None),
    };
    let scalar = match scalar.map(|scalar| scalar.kind) {
        Some(ScalarKind::Sint) => "i32",
        Some(ScalarKind::Uint) => "u32",
        _ => "f32",
    };
    (scalar, components)
}

/// The WGSL type of `components` of `scalar`.
fn wgsl_type((scalar, components): (&str, u32)) -> String {
    match components {
        1 => scalar.to_string(),
        _ => format!("vec{components}<{scalar}>"),
    }
}

/// A value of `components` of `scalar` read from the companion's buffer at `word` (the
/// input's first word for this vertex): one word a component.
fn buffer_value((scalar, components): (&str, u32), word: &str) -> String {
    let words: Vec<String> = (0..components)
        .map(|index| format!("bitcast<{scalar}>(inputs[{word} + {index}u])"))
        .collect();
    match components {
        1 => words.join(""),
        _ => format!("{}({})", wgsl_type((scalar, components)), words.join(", ")),
    }
}

/// The companion vertex shader of `function` (a fragment entry point of `module`), reading
/// `inputs`, validated: naga's module of [`companion_vertex_wgsl`].
fn companion_vertex(
    module: &naga::Module,
    function: &naga::Function,
    inputs: Inputs,
) -> Result<(naga::Module, ModuleInfo), ShaderError> {
    let source = companion_vertex_wgsl(module, function, inputs);
    wgsl::validate(&source, Capabilities::empty())
        .map_err(|error| format!("the companion vertex shader: {error}"))
}

/// A WGSL vertex shader, built from the fragment shader's IR, whose outputs are the fragment
/// shader's inputs (the same locations, types and interpolation), each read from `inputs`,
/// over a fullscreen triangle.
fn companion_vertex_wgsl(
    module: &naga::Module,
    function: &naga::Function,
    inputs: Inputs,
) -> String {
    let located: Vec<_> = function
        .arguments
        .iter()
        .flat_map(|argument| located(module, argument.ty, argument.binding.as_ref()))
        .collect();
    let mut members = String::from("    @builtin(position) position: vec4<f32>,\n");
    let mut attributes = String::new();
    let mut writes = String::new();
    let mut words = 0;
    for (location, interpolation, ty) in located {
        let flat = match interpolation {
            Some(Interpolation::Flat) => " @interpolate(flat)",
            Some(Interpolation::Linear) => " @interpolate(linear)",
            _ => "",
        };
        let scalar_and_components = wgsl_scalar_and_components(module, ty);
        let ty = wgsl_type(scalar_and_components);
        let value = match inputs {
            Inputs::Attributes => {
                attributes.push_str(&format!(
                    ", @location({location}) attribute{location}: {ty}"
                ));
                format!("attribute{location}")
            }
            Inputs::Buffer(_) => {
                let value = buffer_value(scalar_and_components, &format!("first + {words}u"));
                words += scalar_and_components.1;
                value
            }
        };
        members.push_str(&format!(
            "    @location({location}){flat} input{location}: {ty},\n"
        ));
        writes.push_str(&format!("    out.input{location} = {value};\n"));
    }
    let (source, buffer, first) = match inputs {
        Inputs::Attributes => (
            "a vertex attribute of its own",
            String::new(),
            String::new(),
        ),
        Inputs::Buffer(set) => (
            "its own word of a\n// buffer",
            format!("@group({set}) @binding(0) var<storage, read> inputs: array<u32>;\n\n"),
            format!("    let first = index * {words}u;\n"),
        ),
    };
    format!(
        "// Writes what the costed fragment shader reads, each component from {source}: values\n\
         // no compiler can fold or merge.\n\
         {buffer}struct Varyings {{\n{members}}}\n\n\
         @vertex\nfn main(@builtin(vertex_index) index: u32{attributes}) -> Varyings {{\n    \
         var out: Varyings;\n{first}{writes}    \
         let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));\n    \
         out.position = vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);\n    \
         return out;\n}}\n"
    )
}

/// Each colour output's attachment format: 32-bit integers for integer outputs (`r32ui`,
/// `rg32ui`, `rgba32ui`, `r32i`, `rgba32i`), `r32f` or `rgba16f` for floats.
fn default_colors(module: &naga::Module, function: &naga::Function) -> Vec<String> {
    let Some(result) = &function.result else {
        return Vec::new();
    };
    let mut outputs = located(module, result.ty, result.binding.as_ref());
    outputs.sort_by_key(|(location, _, _)| *location);
    outputs
        .iter()
        .map(|(_, _, ty)| {
            let (kind, components) = match module.types[*ty].inner {
                TypeInner::Scalar(scalar) => (scalar.kind, 1),
                TypeInner::Vector { size, scalar } => (scalar.kind, size as u8),
                _ => (ScalarKind::Float, 4),
            };
            match (kind, components) {
                (ScalarKind::Uint, 1) => "r32ui",
                (ScalarKind::Uint, 2) => "rg32ui",
                (ScalarKind::Uint, _) => "rgba32ui",
                (ScalarKind::Sint, 1) => "r32i",
                (ScalarKind::Sint, _) => "rgba32i",
                (_, 1) => "r32f",
                _ => "rgba16f",
            }
            .to_string()
        })
        .collect()
}

/// For GLSL ES input (WGSL's companion is built from the IR, [`companion_vertex_wgsl`]): a
/// GLSL ES vertex shader, under the fragment shader's `#version`, that writes each of the
/// fragment shader's `in` variables (as declared at the start of a line, naga's
/// `smooth in highp vec4 _vs2fs_location0;` as a user's `layout(location = 1) flat in uint id;`)
/// from a vertex attribute of its own, over a fullscreen triangle.
fn companion_vertex_glsl(fragment: &str) -> String {
    let version = fragment
        .lines()
        .find(|line| line.trim_start().starts_with("#version"))
        .unwrap_or("#version 310 es")
        .trim();
    let mut declarations = String::new();
    let mut writes = String::new();
    for (attribute, (qualifiers, declaration)) in
        fragment.lines().filter_map(input_declaration).enumerate()
    {
        let mut words = declaration.split_whitespace().collect::<Vec<_>>();
        let name = words.pop().unwrap_or_default().trim_end_matches(';');
        let ty = words.last().copied().unwrap_or("float");
        declarations.push_str(&format!(
            "layout(location = {attribute}) in highp {ty} attribute{attribute};\n\
             {qualifiers}out {declaration}\n"
        ));
        writes.push_str(&format!("    {name} = attribute{attribute};\n"));
    }
    format!(
        "{version}\n// Writes what the costed fragment shader reads, each from a vertex attribute of its\n\
         // own: values no compiler can fold or merge.\n\
         precision highp float;\nprecision highp int;\n{declarations}\
         void main() {{\n{writes}    \
         vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n    \
         gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);\n}}\n"
    )
}

/// `(qualifiers before `in`, the declaration after it)` of a line that declares a fragment
/// shader input: `[layout(...)] [flat|smooth|noperspective|centroid]... in [precision] TYPE NAME;`.
fn input_declaration(line: &str) -> Option<(String, String)> {
    let declaration = line.trim().strip_suffix(';')?;
    let (layout, rest) = if declaration.starts_with("layout") {
        let close = declaration.find(')')?;
        (&declaration[..=close], &declaration[close + 1..])
    } else {
        ("", declaration)
    };
    let words: Vec<&str> = rest.split_whitespace().collect();
    let position = words.iter().position(|word| *word == "in")?;
    let interpolation = &words[..position];
    let is_qualifier =
        |word: &&str| matches!(*word, "flat" | "smooth" | "noperspective" | "centroid");
    if !interpolation.iter().all(is_qualifier) || words.len() < position + 3 {
        return None;
    }
    let qualifiers: String = std::iter::once(layout)
        .chain(interpolation.iter().copied())
        .filter(|word| !word.is_empty())
        .map(|word| format!("{word} "))
        .collect();
    Some((qualifiers, format!("{};", words[position + 1..].join(" "))))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn companion_writes_every_input() {
        let fragment = "#version 310 es\nprecision highp float;\nsmooth in highp vec4 _vs2fs_location0;\nlayout(location = 1) flat in highp uint id;\nlayout(location = 0) out highp uint word;\nvoid main() { word = id; }\n";
        let vertex = companion_vertex_glsl(fragment);
        assert!(vertex.starts_with("#version 310 es\n"));
        assert!(vertex.contains("smooth out highp vec4 _vs2fs_location0;"));
        assert!(vertex.contains("layout(location = 1) flat out highp uint id;"));
        assert!(vertex.contains("layout(location = 1) in highp uint attribute1;"));
        assert!(vertex.contains("    id = attribute1;"));
        assert!(vertex.contains("    _vs2fs_location0 = attribute0;"));
        assert!(!vertex.contains("word"));
    }

    #[test]
    fn wgsl_is_prepared_for_both_apis() {
        let wgsl = "@group(0) @binding(0) var<uniform> scale: vec4<f32>;\n\
                    @fragment fn shade(@location(0) colour: vec4<f32>, @location(1) @interpolate(flat) id: u32) -> @location(0) u32 {\n\
                    return pack4x8unorm(colour * scale) ^ id;\n}\n";
        let shader = Shader::wgsl(wgsl, "shade").unwrap();
        assert_eq!(shader.stage(), Stage::Fragment);
        let gles = shader.gles().unwrap();
        assert!(gles.shader.starts_with("#version 310 es"));
        let vertex = gles.vertex.unwrap();
        // Built from the IR: naga's names for the fragment shader's inputs, each from an
        // attribute of its own at the same location.
        assert!(vertex.contains("layout(location = 1) flat out uint _vs2fs_location1;"));
        assert!(vertex.contains("layout(location = 0) smooth out vec4 _vs2fs_location0;"));
        assert!(vertex.contains("layout(location = 1) in uint _p2vs_location1;"));
        let vulkan = shader.vulkan().unwrap();
        // The companion's buffer, in the set after the fragment shader's.
        assert_eq!(vulkan.descriptors, ["0,0,uniform", "1,0,storage"]);
        assert_eq!(vulkan.colors, ["r32ui"]);
        assert_eq!(vulkan.shader[0], 0x0723_0203, "SPIR-V's magic number");
        assert!(Shader::wgsl(wgsl, "missing")
            .unwrap_err()
            .contains("`missing`"));
    }
}
