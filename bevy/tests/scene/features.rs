//! What Bevy's own G-buffer drops and its forward renderer shades: five spheres in a row, each
//! with one feature (specular tint; anisotropy along a swirl of directions from a tangent-space
//! direction map; a clearcoat with its own normal map; coloured diffuse occlusion; diffuse
//! transmission, deferred where the frame is), on a
//! lightmapped plane under an ambient light that must leave the plane alone
//! (`affects_lightmapped_meshes: false`), lit by the sun.

use bevy::asset::uuid_handle;
use bevy::light::{DirectionalLight, GlobalAmbientLight};
use bevy::material::OpaqueRendererMethod;
use bevy::math::Rect;
use bevy::mesh::{Mesh, Mesh3d, VertexAttributeValues};
use bevy::pbr::{
    ExtendedMaterial, Lightmap, MaterialExtension, MaterialPlugin, MeshMaterial3d, StandardMaterial,
};
use bevy::prelude::*;
use bevy::render::render_resource::AsBindGroup;
use bevy::shader::{Shader, ShaderRef};

use super::{bumps, camera, disc, image, region, view, AddPlugins, Deferred, Regions};

/// The spheres' radius.
const RADIUS: f32 = 0.45;

/// Each sphere's feature and centre, left to right.
pub const SPHERES: [(&str, Vec3); 5] = [
    ("specular tint", Vec3::new(-2.0, RADIUS, 0.0)),
    ("anisotropy", Vec3::new(-1.0, RADIUS, 0.0)),
    ("clearcoat normal map", Vec3::new(0.0, RADIUS, 0.0)),
    ("coloured occlusion", Vec3::new(1.0, RADIUS, 0.0)),
    ("diffuse transmission", Vec3::new(2.0, RADIUS, 0.0)),
];

/// The region of the lightmapped plane: the rows below this point's, in front of the spheres.
const PLANE_FRONT: Vec3 = Vec3::new(0.0, 0.0, 0.75);

/// The scene's setup and its coloured-occlusion material.
pub fn scene() -> AddPlugins {
    Box::new(|app| {
        app.world_mut()
            .resource_mut::<Assets<Shader>>()
            .insert(
                &COLORED_OCCLUSION_SHADER,
                Shader::from_wgsl(COLORED_OCCLUSION_WGSL, "features/colored_occlusion.wgsl"),
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
    })
}

/// Each sphere's disc (without its silhouette) and the plane's rows in front of the spheres.
pub fn regions(app: &mut App) -> Regions {
    let mut regions: Regions = SPHERES
        .iter()
        .map(|(name, centre)| (*name, disc(app, *centre, RADIUS, 2.0)))
        .collect();
    let (camera, transform) = view(app);
    let front = camera.world_to_viewport(&transform, PLANE_FRONT).unwrap();
    regions.push(("lightmapped plane", region(|pixel| pixel.y > front.y)));
    regions
}

/// The shader of the coloured-occlusion material: Bevy's standard material with its diffuse
/// occlusion coloured, forward and deferred, as Bevy's `extended_material` example writes one.
const COLORED_OCCLUSION_SHADER: Handle<Shader> =
    uuid_handle!("6b0f7e52-3c4a-4f31-9a57-2d6c1e0b8a41");

const COLORED_OCCLUSION_WGSL: &str = r#"
#import bevy_pbr::pbr_fragment::pbr_input_from_standard_material
#ifdef PREPASS_PIPELINE
#import bevy_pbr::{prepass_io::{VertexOutput, FragmentOutput}, pbr_deferred_functions::deferred_output}
#else
#import bevy_pbr::{forward_io::{VertexOutput, FragmentOutput}, pbr_functions::{apply_pbr_lighting, main_pass_post_lighting_processing}}
#endif

@group(#{MATERIAL_BIND_GROUP}) @binding(100) var<uniform> occlusion_color: vec4<f32>;

@fragment
fn fragment(in: VertexOutput, @builtin(front_facing) is_front: bool) -> FragmentOutput {
    var pbr_input = pbr_input_from_standard_material(in, is_front);
    // Bands of the colour and white around the sphere.
    let band = 0.5 + 0.5 * sin(in.uv.x * 6.2831853 * 4.0);
    pbr_input.diffuse_occlusion = mix(occlusion_color.rgb, vec3(1.0), band * 0.6);
#ifdef PREPASS_PIPELINE
    let out = deferred_output(in, pbr_input);
#else
    var out: FragmentOutput;
    out.color = apply_pbr_lighting(pbr_input);
    out.color = main_pass_post_lighting_processing(pbr_input, out.color);
#endif
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
    camera(
        &mut commands,
        &mut images,
        *deferred,
        Transform::from_xyz(0.0, 1.5, 5.2).looking_at(Vec3::new(0.0, 0.4, 0.0), Vec3::Y),
    );
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
