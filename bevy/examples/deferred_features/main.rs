//! Bevy's deferred renderer shading what its own G-buffer drops (a specular tint, anisotropy,
//! a clearcoat with its own normal map, coloured occlusion, diffuse transmission, an ambient
//! light that leaves lightmapped meshes alone) through `BevyFeatures`, a 128-bit layout that
//! holds them: the scene and the layout the plugin's tests render (`scene.rs`).
//!
//! `cargo run --example deferred_features` opens a window where there is a display
//! (`DISPLAY` or `WAYLAND_DISPLAY` set), and otherwise renders one frame headless and writes it
//! to `deferred_features.png`. Copy it to start from: the layout, the plugin and the camera's
//! prepasses are all a deferred app needs.

use std::path::PathBuf;

use bevy::camera::RenderTarget;
use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::pbr::DefaultOpaqueRendererMethod;
use bevy::prelude::*;
use bevy::render::view::screenshot::{save_to_disk, Screenshot};
use gbuffer_bevy::GBufferPlugin;

mod scene;

use scene::layout::BevyFeatures;
use scene::{camera_transform, headless_plugins, headless_target, Deferred, FeaturesScene};

/// The headless frame's size and file.
const SIZE: (u32, u32) = (640, 360);
const OUTPUT: &str = "deferred_features.png";

fn main() {
    let display = ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|name| std::env::var_os(name).is_some_and(|value| !value.is_empty()));
    let mut app = App::new();
    app.insert_resource(DefaultOpaqueRendererMethod::deferred())
        .insert_resource(Deferred(true));
    if display {
        app.add_plugins((
            DefaultPlugins,
            GBufferPlugin::<BevyFeatures>::new(),
            FeaturesScene,
        ))
        .add_systems(Startup, window_camera);
        app.run();
        return;
    }
    app.add_plugins((
        headless_plugins(),
        GBufferPlugin::<BevyFeatures>::new(),
        FeaturesScene,
    ))
    .add_systems(Startup, image_camera);
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
    // A frame of an earlier run would read as this one's below.
    if let Err(error) = std::fs::remove_file(&path) {
        if error.kind() != std::io::ErrorKind::NotFound {
            eprintln!("cannot replace {}: {error}", path.display());
            std::process::exit(1);
        }
    }
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
    let image = images.add(headless_target(SIZE.0, SIZE.1));
    commands.insert_resource(Target(image.clone()));
    commands.spawn((camera(), RenderTarget::from(image)));
}

/// A deferred camera: no MSAA, with the depth and deferred prepasses.
fn camera() -> impl Bundle {
    (
        Camera3d::default(),
        camera_transform(),
        Msaa::Off,
        DepthPrepass,
        DeferredPrepass,
    )
}
