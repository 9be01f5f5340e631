//! Bevy's deferred renderer shading what its own G-buffer drops: a specular tint, anisotropy
//! and a clearcoat with its own normal map, through a 128-bit layout that holds them.
//!
//! `cargo run --example deferred_features` opens a window where there is a display
//! (`DISPLAY` or `WAYLAND_DISPLAY` set), and otherwise renders one frame headless and writes it
//! to `deferred_features.png`. Copy it to start from: the layout, the plugin and the camera's
//! prepasses are all a deferred app needs.

use std::path::PathBuf;

use bevy::asset::RenderAssetUsages;
use bevy::camera::RenderTarget;
use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::light::{DirectionalLight, GlobalAmbientLight};
use bevy::mesh::VertexAttributeValues;
use bevy::pbr::DefaultOpaqueRendererMethod;
use bevy::prelude::*;
use bevy::render::pipelined_rendering::PipelinedRenderingPlugin;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::view::screenshot::{save_to_disk, Screenshot};
use bevy::render::RenderPlugin;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;
use gbuffer_bevy::GBufferPlugin;

/// The G-buffer, in a module of its own because its `Vec3`s are gbuffer's glam, not Bevy's.
mod layout {
    use gbuffer::glam::Vec3;
    use gbuffer::GBufferLayout;

    /// The G-buffer: Bevy's quantities, fewer bits each, and what Bevy's own drops (coloured
    /// reflectance, anisotropy, the clearcoat normal). `gbuffer_bevy::solve` finds such a layout
    /// from the precision each quantity needs.
    #[rustfmt::skip]
    #[allow(dead_code)] // the fields are read on the GPU
    #[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
    #[gbuffer(budget = 128)]
    pub struct Features {
        #[bits(27, unsigned_float)] emissive: Vec3,
        #[bits(5, unorm)]           perceptual_roughness: f32,
        #[bits(18, unorm)]          base_color: Vec3,
        #[bits(12, octahedral)]     anisotropy_tangent: Vec3,
        #[bits(2, unorm)]           anisotropy_strength: f32,
        #[bits(18, octahedral)]     normal: Vec3,
        #[bits(12, octahedral)]     clearcoat_normal: Vec3,
        #[bits(1, unorm)]           clearcoat: f32,
        #[bits(18, unorm)]          reflectance_color: Vec3,
        #[bits(4, unorm)]           clearcoat_perceptual_roughness: f32,
        #[bits(3, uint)]            flags: u32,
    }
}
use layout::Features;

/// The headless frame's size and file.
const SIZE: (u32, u32) = (640, 360);
const OUTPUT: &str = "deferred_features.png";

fn main() {
    let display = ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|name| std::env::var_os(name).is_some_and(|value| !value.is_empty()));
    let mut app = App::new();
    app.insert_resource(DefaultOpaqueRendererMethod::deferred())
        .insert_resource(GlobalAmbientLight {
            brightness: 400.0,
            ..default()
        });
    if display {
        app.add_plugins((DefaultPlugins, GBufferPlugin::<Features>::new()))
            .add_systems(Startup, (scene, window_camera));
        app.run();
        return;
    }
    app.add_plugins((
        DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            // One frame, so every pipeline compiles before it is drawn.
            .set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            })
            // The render app stays in the app, where `settle` reads its pipelines.
            .disable::<PipelinedRenderingPlugin>()
            .disable::<WinitPlugin>(),
        GBufferPlugin::<Features>::new(),
    ))
    .add_systems(Startup, (scene, image_camera));
    app.finish();
    app.cleanup();
    // Until every pipeline is compiled, the layout's module in Bevy's place and nothing new
    // asked for over five updates: the frame the app will keep drawing.
    if let Err(reason) = gbuffer_bevy::settle(&mut app, 5, 200) {
        eprintln!("{reason}");
        std::process::exit(1);
    }
    let target = app.world().resource::<Target>().0.clone();
    let path = PathBuf::from(OUTPUT);
    app.world_mut()
        .spawn(Screenshot::image(target))
        .observe(save_to_disk(path.clone()));
    // The screenshot is read back a frame or two later and written on Bevy's IO threads.
    for _ in 0..200 {
        app.update();
        if path.exists() {
            println!("wrote {}", path.display());
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    eprintln!("no frame written after 200 updates");
    std::process::exit(1);
}

/// The image the headless camera renders into.
#[derive(Resource)]
struct Target(Handle<Image>);

fn window_camera(mut commands: Commands) {
    commands.spawn(camera());
}

fn image_camera(mut commands: Commands, mut images: ResMut<Assets<Image>>) {
    let mut image = Image::new_uninit(
        Extent3d {
            width: SIZE.0,
            height: SIZE.1,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    image.texture_descriptor.usage |= TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
    let image = images.add(image);
    commands.insert_resource(Target(image.clone()));
    commands.spawn((camera(), RenderTarget::from(image)));
}

/// A deferred camera: no MSAA, with the depth and deferred prepasses.
fn camera() -> impl Bundle {
    (
        Camera3d::default(),
        Transform::from_xyz(0.0, 1.2, 3.6).looking_at(Vec3::new(0.0, 0.4, 0.0), Vec3::Y),
        Msaa::Off,
        DepthPrepass,
        DeferredPrepass,
    )
}

/// Three spheres, each with one feature Bevy's own G-buffer drops, on a plane, in the sun.
fn scene(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
) {
    commands.spawn((
        DirectionalLight {
            illuminance: 5_000.0,
            ..default()
        },
        Transform::from_xyz(1.5, 2.0, 2.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(8.0, 8.0))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.5, 0.5, 0.5),
            perceptual_roughness: 0.9,
            ..default()
        })),
    ));
    let sphere = meshes.add(sphere_with_tangents(0.45));
    let looks = [
        // An orange specular highlight on a dark dielectric.
        StandardMaterial {
            base_color: Color::srgb(0.12, 0.12, 0.15),
            perceptual_roughness: 0.3,
            reflectance: 1.0,
            specular_tint: Color::srgb(1.0, 0.45, 0.1),
            ..default()
        },
        // Brushed along the sphere's parallels.
        StandardMaterial {
            base_color: Color::srgb(0.55, 0.55, 0.6),
            perceptual_roughness: 0.35,
            anisotropy_strength: 1.0,
            ..default()
        },
        // A bumpy clearcoat over a rough blue base.
        StandardMaterial {
            base_color: Color::srgb(0.1, 0.35, 0.8),
            perceptual_roughness: 0.7,
            clearcoat: 1.0,
            clearcoat_perceptual_roughness: 0.2,
            clearcoat_normal_texture: Some(images.add(bumps(256))),
            ..default()
        },
    ];
    for (index, look) in looks.into_iter().enumerate() {
        commands.spawn((
            Mesh3d(sphere.clone()),
            MeshMaterial3d(materials.add(look)),
            Transform::from_xyz(index as f32 - 1.0, 0.45, 0.0),
        ));
    }
}

/// A UV sphere with tangents along its parallels: anisotropy and normal maps need tangents.
fn sphere_with_tangents(radius: f32) -> Mesh {
    let mut mesh = Sphere::new(radius).mesh().uv(64, 32);
    let Some(VertexAttributeValues::Float32x3(positions)) =
        mesh.attribute(Mesh::ATTRIBUTE_POSITION)
    else {
        unreachable!("a sphere has positions");
    };
    let tangents: Vec<[f32; 4]> = positions
        .iter()
        .map(|&[x, _, z]| {
            let along = Vec3::new(-z, 0.0, x).try_normalize().unwrap_or(Vec3::X);
            [along.x, along.y, along.z, 1.0]
        })
        .collect();
    mesh.insert_attribute(Mesh::ATTRIBUTE_TANGENT, tangents);
    mesh
}

/// A tangent-space normal map of bumps, `size` x `size`, RGBA8 linear.
fn bumps(size: u32) -> Image {
    let wave = |at: u32| (at as f32 / size as f32 * 6.0 * std::f32::consts::TAU).sin();
    let data = (0..size * size)
        .flat_map(|index| {
            let normal = Vec3::new(0.35 * wave(index % size), 0.35 * wave(index / size), 1.0);
            let encoded = normal.normalize() * 0.5 + Vec3::splat(0.5);
            [encoded.x, encoded.y, encoded.z, 1.0].map(|c| (c * 255.0).round() as u8)
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
