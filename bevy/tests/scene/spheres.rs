//! Bevy's own G-buffer's quantities: spheres across roughness and metallic, an emissive
//! sphere, a clearcoat sphere, a normal-mapped plane, a directional and a point light.

use bevy::light::{DirectionalLight, PointLight};
use bevy::mesh::{Mesh, Mesh3d, VertexAttributeValues};
use bevy::pbr::{MeshMaterial3d, StandardMaterial};
use bevy::prelude::*;

use super::{bumps, camera, AddPlugins, Deferred, Regions};

/// The scene's setup.
pub fn scene() -> AddPlugins {
    Box::new(|app| {
        app.add_systems(Startup, setup);
    })
}

/// It has no regions: its frames are compared whole.
pub fn regions(_: &mut App) -> Regions {
    Vec::new()
}

fn setup(
    mut commands: Commands,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
    deferred: Res<Deferred>,
) {
    camera(
        &mut commands,
        &mut images,
        *deferred,
        Transform::from_xyz(0.0, 2.2, 6.5).looking_at(Vec3::new(0.0, 0.6, 0.0), Vec3::Y),
    );
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
            normal_map_texture: Some(images.add(bumps(256, 8.0))),
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
