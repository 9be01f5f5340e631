//! The features scene, which the example shows and the tests render: what Bevy's own G-buffer
//! drops and its forward renderer shades. Five spheres in a row, each with one feature
//! (specular tint; anisotropy along a swirl of directions from a tangent-space direction map; a
//! clearcoat with its own normal map; coloured diffuse occlusion; diffuse transmission,
//! deferred where the frame is), on a lightmapped plane under an ambient light that must leave
//! the plane alone (`affects_lightmapped_meshes: false`), lit by the sun; and `BevyFeatures`,
//! the layout that keeps it all in 128 bits.
//!
//! `examples/deferred_features/main.rs` adds it to its app as `mod scene`; `tests/deferred.rs`
//! includes this file (`tests/scene/features.rs`) and renders it forward, deferred with Bevy's
//! G-buffer and deferred through the layout.

use bevy::app::PluginGroupBuilder;
use bevy::asset::{uuid_handle, RenderAssetUsages};
use bevy::light::{DirectionalLight, GlobalAmbientLight};
use bevy::material::OpaqueRendererMethod;
use bevy::math::Rect;
use bevy::mesh::{Mesh, Mesh3d, VertexAttributeValues};
use bevy::pbr::{
    ExtendedMaterial, Lightmap, MaterialExtension, MaterialPlugin, MeshMaterial3d, StandardMaterial,
};
use bevy::prelude::*;
use bevy::render::pipelined_rendering::PipelinedRenderingPlugin;
use bevy::render::render_resource::{
    AsBindGroup, Extent3d, TextureDimension, TextureFormat, TextureUsages,
};
use bevy::render::RenderPlugin;
use bevy::shader::{Shader, ShaderRef};
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;

/// The layout, in a module of its own because its `Vec3`s are gbuffer's glam, not Bevy's.
pub mod layout {
    // Bevy's `Vec3`: the library is on Bevy's glam, so the derive takes it as its own.
    use bevy::math::Vec3;
    use gbuffer::GBufferLayout;

    /// The G-buffer: Bevy's quantities the scene uses, fewer bits each, and what Bevy's own
    /// drops (coloured reflectance and occlusion, anisotropy, the clearcoat normal, diffuse
    /// transmission, whether a mesh is lightmapped): what `gbuffer_bevy::solve` answers for the
    /// precision the scene needs (`tests/scene/features.rs` states it, and a test holds the
    /// two together).
    #[rustfmt::skip]
    #[allow(dead_code)] // the fields are read on the GPU
    #[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
    #[gbuffer(budget = 128)]
    pub struct BevyFeatures {
        #[bits(27, unsigned_float)] pub emissive: Vec3,
        #[bits(5, unorm)]           pub perceptual_roughness: f32,
        #[bits(18, unorm)]          pub base_color: Vec3,
        #[bits(12, octahedral)]     pub anisotropy_tangent: Vec3,
        #[bits(2, unorm)]           pub anisotropy_strength: f32,
        #[bits(18, octahedral)]     pub normal: Vec3,
        #[bits(12, octahedral)]     pub clearcoat_normal: Vec3,
        #[bits(1, unorm)]           pub clearcoat: f32,
        #[bits(1, uint)]            pub lightmapped: u32,
        #[bits(15, unorm)]          pub reflectance_color: Vec3,
        #[bits(9, unorm)]           pub diffuse_occlusion_color: Vec3,
        #[bits(4, unorm)]           pub clearcoat_perceptual_roughness: f32,
        #[bits(4, unorm)]           pub diffuse_transmission: f32,
    }
}

/// Bevy's default plugins for frames rendered into an image, without a window: every pipeline
/// compiled before the frame that uses it is drawn, the render app kept in the app (where
/// `gbuffer_bevy::settle` reads its pipelines), no winit.
pub fn headless_plugins() -> PluginGroupBuilder {
    DefaultPlugins
        .set(WindowPlugin {
            primary_window: None,
            exit_condition: ExitCondition::DontExit,
            ..default()
        })
        .set(RenderPlugin {
            synchronous_pipeline_compilation: true,
            ..default()
        })
        .disable::<PipelinedRenderingPlugin>()
        .disable::<WinitPlugin>()
}

/// An sRGB image of `width` x `height` a camera renders into and a screenshot reads back.
pub fn headless_target(width: u32, height: u32) -> Image {
    let mut image = Image::new_uninit(
        Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.usage |= TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
    image
}

/// The spheres' radius.
pub const RADIUS: f32 = 0.45;

/// Each sphere's feature and centre, left to right.
pub const SPHERES: [(&str, Vec3); 5] = [
    ("specular tint", Vec3::new(-2.0, RADIUS, 0.0)),
    ("anisotropy", Vec3::new(-1.0, RADIUS, 0.0)),
    ("clearcoat normal map", Vec3::new(0.0, RADIUS, 0.0)),
    ("coloured occlusion", Vec3::new(1.0, RADIUS, 0.0)),
    ("diffuse transmission", Vec3::new(2.0, RADIUS, 0.0)),
];

/// Where the camera looks from, at the spheres.
pub fn camera_transform() -> Transform {
    Transform::from_xyz(0.0, 1.5, 5.2).looking_at(Vec3::new(0.0, 0.4, 0.0), Vec3::Y)
}

/// Whether the frame renders deferred: the diffuse transmission's material asks for it, as Bevy
/// renders such a material forward unless told otherwise.
#[derive(Resource, Clone, Copy)]
pub struct Deferred(pub bool);

/// The scene: its lights, meshes and materials, the coloured-occlusion material's plugin and
/// shader. The app brings the camera and the [`Deferred`] resource.
pub struct FeaturesScene;

impl Plugin for FeaturesScene {
    fn build(&self, app: &mut App) {
        app.world_mut()
            .resource_mut::<Assets<Shader>>()
            .insert(
                &COLORED_OCCLUSION_SHADER,
                Shader::from_wesl(COLORED_OCCLUSION_WESL, "features/colored_occlusion.wesl"),
            )
            .expect("the shader's handle is free");
        app.add_plugins(MaterialPlugin::<
            ExtendedMaterial<StandardMaterial, ColoredOcclusion>,
        >::default())
            .insert_resource(GlobalAmbientLight {
                color: Color::WHITE,
                brightness: 600.0,
                affects_lightmapped_meshes: false,
            })
            .add_systems(Startup, setup);
    }
}

/// The shader of the coloured-occlusion material: Bevy's standard material with its diffuse
/// occlusion coloured, forward and deferred, as Bevy's `extended_material` example writes one
/// (in WESL, as Bevy 0.20's own shaders are).
const COLORED_OCCLUSION_SHADER: Handle<Shader> =
    uuid_handle!("6b0f7e52-3c4a-4f31-9a57-2d6c1e0b8a41");

const COLORED_OCCLUSION_WESL: &str = r#"
import bevy_pbr::render::pbr_fragment::pbr_input_from_standard_material;
@if(PREPASS_PIPELINE)
import bevy_pbr::{prepass::io::{VertexOutput, FragmentOutput}, deferred::functions::deferred_output};
@else
import bevy_pbr::render::{forward_io::{VertexOutput, FragmentOutput}, pbr_functions::{apply_pbr_lighting, main_pass_post_lighting_processing}};

@group(constants::MATERIAL_BIND_GROUP) @binding(100) var<uniform> occlusion_color: vec4<f32>;

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);
    // Bands of the colour and white around the sphere.
    let band = 0.5 + 0.5 * sin(in.uv.x * 6.2831853 * 4.0);
    pbr_input.diffuse_occlusion = mix(occlusion_color.rgb, vec3(1.0), band * 0.6);
    @if(PREPASS_PIPELINE)
    let out = deferred_output(in, pbr_input);
    @if(!PREPASS_PIPELINE)
    var out: FragmentOutput;
    @if(!PREPASS_PIPELINE) {
        out.color = apply_pbr_lighting(pbr_input);
        out.color = main_pass_post_lighting_processing(pbr_input, out.color);
    }
    return out;
}
"#;

/// Coloured diffuse occlusion over Bevy's standard material.
#[derive(Asset, AsBindGroup, Reflect, Debug, Clone)]
pub struct ColoredOcclusion {
    /// The occlusion's colour.
    #[uniform(100)]
    pub color: LinearRgba,
}

impl MaterialExtension for ColoredOcclusion {
    fn fragment_shader() -> ShaderRef {
        ShaderRef::Handle(COLORED_OCCLUSION_SHADER)
    }

    fn deferred_fragment_shader() -> ShaderRef {
        ShaderRef::Handle(COLORED_OCCLUSION_SHADER)
    }
}

/// The texel centre (u, v) of column `x` and row `y` of a `size` x `size` image.
fn centre(size: u32, x: u32, y: u32) -> (f32, f32) {
    (
        (x as f32 + 0.5) / size as f32,
        (y as f32 + 0.5) / size as f32,
    )
}

/// A UV sphere with tangents along its parallels (the direction of increasing u), which the
/// anisotropy and the clearcoat normal map are read along.
fn sphere() -> Mesh {
    let mut mesh = Sphere::new(RADIUS).mesh().uv(64, 32);
    let Some(VertexAttributeValues::Float32x3(positions)) =
        mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        panic!("a sphere has positions");
    };
    let tangents: Vec<[f32; 4]> = positions
        .iter()
        .map(|&[x, _, z]| {
            let along = Vec3::new(-z, 0.0, x);
            let tangent = if along.length() > 1e-6 {
                along.normalize()
            } else {
                Vec3::X
            };
            [tangent.x, tangent.y, tangent.z, 1.0]
        })
        .collect();
    mesh.insert_attribute(Mesh::ATTRIBUTE_TANGENT, tangents);
    mesh
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut occluded: ResMut<Assets<ExtendedMaterial<StandardMaterial, ColoredOcclusion>>>,
    mut images: ResMut<Assets<Image>>,
    deferred: Res<Deferred>,
) {
    commands.spawn((
        DirectionalLight {
            illuminance: 5_000.0,
            ..default()
        },
        Transform::from_xyz(1.5, 2.0, 2.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));

    // The plane, lightmapped: a baked gradient of warm and cool light, through its second UVs.
    let mut plane = Mesh::from(Plane3d::default().mesh().size(8.0, 8.0));
    let Some(uvs) = plane.attribute(Mesh::ATTRIBUTE_UV_0).cloned() else {
        panic!("a plane has UVs");
    };
    plane.insert_attribute(Mesh::ATTRIBUTE_UV_1, uvs);
    let light_map = images.add(image(64, |x, y| {
        let (u, v) = centre(64, x, y);
        [0.3 + 0.7 * u, 0.35 + 0.4 * v, 0.9 - 0.6 * u, 1.0]
    }));
    commands.spawn((
        Mesh3d(meshes.add(plane)),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.5, 0.5, 0.5),
            perceptual_roughness: 0.9,
            lightmap_exposure: 1_000.0,
            ..default()
        })),
        Lightmap {
            image: light_map,
            uv_rect: Rect::new(0.0, 0.0, 1.0, 1.0),
            bicubic_sampling: false,
        },
    ));

    let sphere = meshes.add(sphere());
    let at = |index: usize| Transform::from_translation(SPHERES[index].1);
    // Anisotropy's directions swirl around the map's centre, at full strength.
    let swirl = images.add(image(128, |x, y| {
        let (u, v) = centre(128, x, y);
        let angle = (v - 0.5).atan2(u - 0.5) + std::f32::consts::FRAC_PI_2;
        [0.5 + 0.5 * angle.cos(), 0.5 + 0.5 * angle.sin(), 1.0, 1.0]
    }));
    // The standard materials, each at its sphere's index in SPHERES.
    let standard = [
        // Specular tint: an orange highlight on a dark dielectric.
        (
            0,
            StandardMaterial {
                base_color: Color::srgb(0.12, 0.12, 0.15),
                perceptual_roughness: 0.3,
                reflectance: 1.0,
                specular_tint: Color::srgb(1.0, 0.45, 0.1),
                ..default()
            },
        ),
        // Anisotropy along the swirl.
        (
            1,
            StandardMaterial {
                base_color: Color::srgb(0.55, 0.55, 0.6),
                perceptual_roughness: 0.35,
                anisotropy_strength: 1.0,
                anisotropy_texture: Some(swirl),
                ..default()
            },
        ),
        // A bumpy clearcoat over a smooth rough base.
        (
            2,
            StandardMaterial {
                base_color: Color::srgb(0.1, 0.35, 0.8),
                perceptual_roughness: 0.7,
                clearcoat: 1.0,
                clearcoat_perceptual_roughness: 0.2,
                clearcoat_normal_texture: Some(images.add(bumps(256, 6.0))),
                ..default()
            },
        ),
        // Diffuse transmission: the sun shows through on the side away from it. Bevy renders
        // such a material forward unless told to render it deferred, as the deferred frames do.
        (
            4,
            StandardMaterial {
                base_color: Color::srgb(0.9, 0.6, 0.3),
                perceptual_roughness: 0.6,
                diffuse_transmission: 0.8,
                opaque_render_method: if deferred.0 {
                    OpaqueRendererMethod::Deferred
                } else {
                    OpaqueRendererMethod::Auto
                },
                ..default()
            },
        ),
    ];
    for (index, material) in standard {
        commands.spawn((
            Mesh3d(sphere.clone()),
            MeshMaterial3d(materials.add(material)),
            at(index),
        ));
    }
    // Coloured occlusion: bands of orange occlusion, seen in the ambient light.
    commands.spawn((
        Mesh3d(sphere),
        MeshMaterial3d(occluded.add(ExtendedMaterial {
            base: StandardMaterial {
                base_color: Color::srgb(0.8, 0.8, 0.8),
                perceptual_roughness: 0.6,
                ..default()
            },
            extension: ColoredOcclusion {
                color: LinearRgba::rgb(1.0, 0.35, 0.1),
            },
        })),
        at(3),
    ));
}

/// A `size` x `size` RGBA8 linear image, each texel's channels (in [0, 1]) from its column
/// and row.
pub fn image(size: u32, texel: impl Fn(u32, u32) -> [f32; 4]) -> Image {
    let data = (0..size * size)
        .flat_map(|index| {
            texel(index % size, index / size)
                .map(|channel| (channel.clamp(0.0, 1.0) * 255.0).round() as u8)
        })
        .collect();
    Image::new(
        Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        data,
        TextureFormat::Rgba8Unorm,
        RenderAssetUsages::RENDER_WORLD,
    )
}

/// A tangent-space normal map of bumps, `size` x `size`, RGBA8 linear, `periods` bumps across.
pub fn bumps(size: u32, periods: f32) -> Image {
    let wave = |at: u32| (at as f32 / size as f32 * periods * std::f32::consts::TAU).sin();
    image(size, |x, y| {
        let normal = Vec3::new(0.35 * wave(x), 0.35 * wave(y), 1.0).normalize();
        let encoded = normal * 0.5 + Vec3::splat(0.5);
        [encoded.x, encoded.y, encoded.z, 1.0]
    })
}
