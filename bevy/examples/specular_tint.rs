//! A deferred Bevy app through a layout of your own: one sphere, one light, and a material with
//! an orange specular tint on a dark blue base. Bevy's own G-buffer keeps only the tint's luma
//! (a white highlight); `TintedSurface` keeps its colour, and the highlight stays orange.
//!
//! In a window. With `--frame FILE`, the window's 30th frame is saved to FILE (PNG) and the app
//! exits.

use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::pbr::DefaultOpaqueRendererMethod;
use bevy::prelude::*;
use bevy::render::view::screenshot::{save_to_disk, Screenshot, ScreenshotCaptured};
use bevy::render::RenderPlugin;
use gbuffer::GBufferLayout;
use gbuffer_bevy::GBufferPlugin;

/// 96 of Bevy's 128 bits: the fields name the quantities the plugin reads from them.
#[rustfmt::skip]
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 128)]
pub struct TintedSurface {
    #[pls(rgba8)]           pub base_color: Vec3,
    #[bits(24, octahedral)] pub normal: Vec3,
    #[bits(8, unorm)]       pub perceptual_roughness: f32,
    #[bits(24, unorm)]      pub reflectance_color: Vec3, // reflectance x specular tint
    #[bits(8, unorm)]       pub metallic: f32,
}

/// The file `--frame` names.
#[derive(Resource)]
struct FrameFile(Option<String>);

fn main() {
    let frame = std::env::args().skip_while(|arg| arg != "--frame").nth(1);
    App::new()
        .insert_resource(DefaultOpaqueRendererMethod::deferred())
        .insert_resource(FrameFile(frame))
        .add_plugins((
            // Pipelines compiled as they are asked for, so that the 30th frame is the final one.
            DefaultPlugins.set(RenderPlugin {
                synchronous_pipeline_compilation: true,
                ..default()
            }),
            GBufferPlugin::<TintedSurface>::new(),
        ))
        .add_systems(Startup, scene)
        .add_systems(Update, save_frame)
        .run();
}

fn scene(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    commands.spawn((
        Mesh3d(meshes.add(Sphere::new(1.0).mesh().uv(64, 32))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.02, 0.05, 0.2),
            perceptual_roughness: 0.3,
            reflectance: 1.0,
            specular_tint: Color::srgb(1.0, 0.45, 0.0),
            ..default()
        })),
    ));
    commands.spawn((
        PointLight {
            intensity: 2_000_000.0,
            ..default()
        },
        Transform::from_xyz(3.0, 4.0, 5.0),
    ));
    // Bevy's deferred path wants these on the camera, with or without the plugin.
    commands.spawn((
        Camera3d::default(),
        Msaa::Off,
        DepthPrepass,
        DeferredPrepass,
        Transform::from_xyz(0.0, 0.0, 3.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
}

/// With `--frame FILE`: a screenshot of the 30th frame, saved, then the app's exit.
fn save_frame(mut commands: Commands, file: Res<FrameFile>, mut frames: Local<u32>) {
    let Some(path) = &file.0 else { return };
    *frames += 1;
    if *frames == 30 {
        let mut save = save_to_disk(path.clone());
        commands.spawn(Screenshot::primary_window()).observe(
            move |captured: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
                save(captured);
                exit.write(AppExit::Success);
            },
        );
    }
}
