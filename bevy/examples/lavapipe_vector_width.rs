//! Bevy alone, without gbuffer: its own deferred renderer drawing lit spheres headless, for a
//! fault that is lavapipe's. Run with `LP_NATIVE_VECTOR_WIDTH=128 cargo run --example
//! lavapipe_vector_width` on lavapipe (Mesa 25.0.7): the process aborts with a heap corruption
//! (`malloc(): invalid next size (unsorted)`, `corrupted double-linked list` or `corrupted size
//! vs. prev_size`) or a segmentation fault in one of lavapipe's own threads, while it compiles
//! pipelines, on Bevy 0.19.1 as on 0.20.1; with llvmpipe's default vector width it renders and
//! exits 0. Nothing here is gbuffer's, so the corruption is the driver's (the guide's testing
//! chapter, "Figures that depend on the machine").

use bevy::asset::RenderAssetUsages;
use bevy::camera::RenderTarget;
use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::light::{DirectionalLight, PointLight};
use bevy::pbr::DefaultOpaqueRendererMethod;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::RenderPlugin;
use bevy::window::ExitCondition;
use bevy::winit::WinitPlugin;

fn main() {
    let mut app = App::new();
    app.insert_resource(DefaultOpaqueRendererMethod::deferred())
        .add_plugins(
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
                .disable::<WinitPlugin>(),
        )
        .add_systems(Startup, scene);
    app.finish();
    app.cleanup();
    for _ in 0..30 {
        app.update();
    }
    println!("rendered 30 frames");
}

fn scene(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
) {
    let mut target = Image::new_uninit(
        Extent3d {
            width: 320,
            height: 180,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    target.texture_descriptor.usage |= TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
    commands.spawn((
        Camera3d::default(),
        RenderTarget::from(images.add(target)),
        Transform::from_xyz(0.0, 2.2, 6.5).looking_at(Vec3::new(0.0, 0.6, 0.0), Vec3::Y),
        Msaa::Off,
        DepthPrepass,
        DeferredPrepass,
    ));
    commands.spawn((
        DirectionalLight::default(),
        Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((PointLight::default(), Transform::from_xyz(-1.5, 1.8, 2.0)));
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(8.0, 8.0))),
        MeshMaterial3d(materials.add(StandardMaterial::default())),
    ));
    let sphere = meshes.add(Sphere::new(0.35).mesh().uv(48, 24));
    for column in 0..5 {
        commands.spawn((
            Mesh3d(sphere.clone()),
            MeshMaterial3d(materials.add(StandardMaterial {
                perceptual_roughness: 0.1 + 0.2 * column as f32,
                clearcoat: if column == 4 { 1.0 } else { 0.0 },
                ..default()
            })),
            Transform::from_xyz(-2.0 + column as f32, 0.35, 0.8),
        ));
    }
}
