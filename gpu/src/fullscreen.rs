//! The fullscreen triangle every fullscreen pass draws (the renderer's lighting and tone-map
//! passes, its fused paths' surface and sky draws, the trade-off's fragment-stage timing, the
//! tests' harnesses): three vertices made from the vertex index, no vertex buffer. The corners
//! (-1, -1), (3, -1) and (-1, 3) cover clip space with one triangle, so no pixel is shaded twice
//! along a diagonal as with two.

/// `fullscreen_corner(vertex)`, the clip-space corner of vertex 0, 1 or 2, and the vertex
/// entry point `full_screen`, which puts it at depth 0.
pub const FULLSCREEN_WGSL: &str = "
// The fullscreen triangle (gbuffer_gpu::fullscreen): corners (-1, -1), (3, -1), (-1, 3).
fn fullscreen_corner(vertex: u32) -> vec2<f32> {
    return vec2<f32>(f32((vertex << 1u) & 2u), f32(vertex & 2u)) * 2.0 - vec2<f32>(1.0);
}

@vertex
fn full_screen(@builtin(vertex_index) vertex: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(fullscreen_corner(vertex), 0.0, 1.0);
}
";

/// The same triangle as a GLSL vertex shader under `version` (a `#version` line): GLSL ES names
/// the vertex index `gl_VertexID`, Vulkan GLSL `gl_VertexIndex`.
pub fn fullscreen_vertex_glsl(version: &str, vulkan: bool) -> String {
    let index = if vulkan {
        "gl_VertexIndex"
    } else {
        "gl_VertexID"
    };
    format!(
        "{version}\n\
         void main() {{\n    \
         vec2 corner = vec2(float(({index} << 1) & 2), float({index} & 2));\n    \
         gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);\n\
         }}\n"
    )
}

/// A pipeline that draws the fullscreen triangle of `module` (which holds [`FULLSCREEN_WGSL`])
/// with its `fragment` entry point into `targets`: no vertex buffer, no depth, `layout` or the
/// one wgpu derives from the shader.
pub fn render_pipeline(
    device: &wgpu::Device,
    module: &wgpu::ShaderModule,
    fragment: &str,
    layout: Option<&wgpu::PipelineLayout>,
    targets: &[Option<wgpu::ColorTargetState>],
) -> wgpu::RenderPipeline {
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(fragment),
        layout,
        vertex: wgpu::VertexState {
            module,
            entry_point: Some("full_screen"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: Default::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}
