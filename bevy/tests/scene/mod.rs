//! A small Bevy scene rendered deferred, headless, into an image: spheres across roughness
//! and metallic, an emissive sphere, a clearcoat sphere, a normal-mapped plane, a directional
//! and a point light. [`render`] returns its pixels.

use std::sync::{Arc, Mutex};

use bevy::asset::RenderAssetUsages;
use bevy::camera::RenderTarget;
use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::image::Image;
use bevy::light::{DirectionalLight, PointLight};
use bevy::mesh::{Mesh, Mesh3d, VertexAttributeValues};
use bevy::pbr::{DefaultOpaqueRendererMethod, MeshMaterial3d, StandardMaterial};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat, TextureUsages};
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::render::RenderPlugin;
use bevy::window::ExitCondition;

/// The frame's size.
pub const SIZE: (u32, u32) = (320, 180);

/// A frame: `SIZE`, RGBA8 sRGB, row by row.
pub type Pixels = Vec<[u8; 4]>;

/// What a test adds to the app after Bevy's plugins.
pub type AddPlugins = Box<dyn FnOnce(&mut App)>;

/// Renders the scene with `plugin` added after Bevy's own (none: Bevy's G-buffer), frames
/// enough for every pipeline and the replaced module to be in place, and returns the last.
pub fn render(plugin: Option<AddPlugins>) -> Pixels {
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
                .disable::<bevy::log::LogPlugin>(),
        );
    let replacing = plugin.is_some();
    if let Some(plugin) = plugin {
        plugin(&mut app);
    }
    app.add_systems(Startup, setup);
    app.finish();
    app.cleanup();
    for _ in 0..20 {
        app.update();
    }
    let captured: Arc<Mutex<Option<Pixels>>> = Arc::default();
    let target = app.world().resource::<Target>().0.clone();
    let sink = captured.clone();
    app.world_mut().spawn(Screenshot::image(target)).observe(
        move |event: On<ScreenshotCaptured>| {
            let image = &event.image;
            let bytes = image.data.as_deref().unwrap_or_default();
            let pixels = bytes
                .chunks_exact(4)
                .map(|pixel| [pixel[0], pixel[1], pixel[2], pixel[3]])
                .collect();
            *sink.lock().unwrap() = Some(pixels);
        },
    );
    for _ in 0..20 {
        app.update();
        if let Some(pixels) = captured.lock().unwrap().take() {
            // The frame is the layout's only if its module took Bevy's place before it.
            assert_eq!(gbuffer_bevy::is_replaced(&app), replacing);
            return pixels;
        }
    }
    panic!("no screenshot after 20 frames");
}

/// The image the camera renders into.
#[derive(Resource)]
struct Target(Handle<Image>);

/// A tangent-space normal map of bumps, `size` x `size`, RGBA8 linear.
fn bumps(size: u32) -> Image {
    let mut data = Vec::with_capacity((size * size * 4) as usize);
    for y in 0..size {
        for x in 0..size {
            let (u, v) = (
                (x as f32 / size as f32 * 8.0 * std::f32::consts::TAU).sin(),
                (y as f32 / size as f32 * 8.0 * std::f32::consts::TAU).sin(),
            );
            let normal = Vec3::new(0.35 * u, 0.35 * v, 1.0).normalize();
            let encoded = normal * 0.5 + Vec3::splat(0.5);
            data.extend([encoded.x, encoded.y, encoded.z, 1.0].map(|c| (c * 255.0).round() as u8));
        }
    }
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

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
) {
    let mut target = Image::new_uninit(
        Extent3d {
            width: SIZE.0,
            height: SIZE.1,
            depth_or_array_layers: 1,
        },
        TextureDimension::D2,
        TextureFormat::Rgba8UnormSrgb,
        RenderAssetUsages::RENDER_WORLD,
    );
    target.texture_descriptor.usage |= TextureUsages::RENDER_ATTACHMENT | TextureUsages::COPY_SRC;
    let target = images.add(target);
    commands.insert_resource(Target(target.clone()));
    commands.spawn((
        Camera3d::default(),
        RenderTarget::from(target),
        Transform::from_xyz(0.0, 2.2, 6.5).looking_at(Vec3::new(0.0, 0.6, 0.0), Vec3::Y),
        Msaa::Off,
        DepthPrepass,
        DeferredPrepass,
    ));
    commands.spawn((
        DirectionalLight {
            illuminance: 8_000.0,
            ..default()
        },
        Transform::from_xyz(1.0, 2.0, 1.5).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.spawn((
        PointLight {
            intensity: 400_000.0,
            range: 8.0,
            color: Color::srgb(1.0, 0.8, 0.6),
            ..default()
        },
        Transform::from_xyz(-1.5, 1.8, 2.0),
    ));

    // The plane, normal-mapped: its tangents are +x everywhere.
    let mut plane = Mesh::from(Plane3d::default().mesh().size(8.0, 8.0));
    let count = plane.count_vertices();
    plane.insert_attribute(
        Mesh::ATTRIBUTE_TANGENT,
        VertexAttributeValues::Float32x4(vec![[1.0, 0.0, 0.0, 1.0]; count]),
    );
    commands.spawn((
        Mesh3d(meshes.add(plane)),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.45, 0.42, 0.38),
            perceptual_roughness: 0.6,
            normal_map_texture: Some(images.add(bumps(256))),
            ..default()
        })),
    ));

    // Spheres: roughness across, dielectric front row, metal back row.
    let sphere = meshes.add(Sphere::new(0.35).mesh().uv(48, 24));
    for column in 0..5 {
        for row in 0..2 {
            let material = StandardMaterial {
                base_color: if row == 0 {
                    Color::srgb(0.8, 0.1, 0.1)
                } else {
                    Color::srgb(0.95, 0.75, 0.35)
                },
                perceptual_roughness: 0.1 + 0.2 * column as f32,
                metallic: row as f32,
                ..default()
            };
            commands.spawn((
                Mesh3d(sphere.clone()),
                MeshMaterial3d(materials.add(material)),
                Transform::from_xyz(-2.0 + column as f32, 0.35, 0.8 - 1.2 * row as f32),
            ));
        }
    }
    // An emissive sphere and a clearcoat sphere, above the rows.
    commands.spawn((
        Mesh3d(sphere.clone()),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::BLACK,
            emissive: LinearRgba::rgb(4.0, 1.5, 0.4),
            ..default()
        })),
        Transform::from_xyz(-0.8, 1.4, -0.4),
    ));
    commands.spawn((
        Mesh3d(sphere),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.1, 0.3, 0.8),
            perceptual_roughness: 0.7,
            clearcoat: 1.0,
            clearcoat_perceptual_roughness: 0.1,
            ..default()
        })),
        Transform::from_xyz(0.8, 1.4, -0.4),
    ));
}
