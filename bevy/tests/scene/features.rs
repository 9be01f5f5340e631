//! The example's features scene (`examples/deferred_features/scene.rs`, included here as it
//! is), with the test's camera and the regions its frames are compared on.

#[path = "../../examples/deferred_features/scene.rs"]
mod shared;

use bevy::prelude::*;
use gbuffer_bevy::{BevyScene, Precision, Quantity};

pub use shared::layout::BevyFeatures;
pub use shared::{bumps, headless_plugins, headless_target, Deferred};
use shared::{camera_transform, FeaturesScene, RADIUS, SPHERES};

use super::{camera, disc, region, view, AddPlugins, Regions};

/// The region of the lightmapped plane: the rows below this point's, in front of the spheres.
const PLANE_FRONT: Vec3 = Vec3::new(0.0, 0.0, 0.75);

/// The features scene in Bevy's terms: what it uses, how precisely. Solved into
/// [`BevyFeatures`] (`tests/deferred.rs` holds the two together).
pub fn bevy_scene() -> BevyScene {
    use Precision::{Degrees, Exact, Relative, Steps};
    BevyScene::new("BevyFeatures")
        .needs(Quantity::BaseColor, Steps(64))
        .needs(Quantity::PerceptualRoughness, Steps(32))
        .needs(Quantity::Normal, Degrees(0.5))
        .needs(Quantity::Emissive, Relative(0.035))
        .needs(Quantity::ReflectanceColor, Steps(32))
        .needs(Quantity::DiffuseOcclusionColor, Steps(8))
        .needs(Quantity::AnisotropyStrength, Steps(4))
        .needs(Quantity::AnisotropyTangent, Degrees(4.0))
        .needs(Quantity::Clearcoat, Steps(2))
        .needs(Quantity::ClearcoatPerceptualRoughness, Steps(16))
        .needs(Quantity::ClearcoatNormal, Degrees(4.0))
        .needs(Quantity::Lightmapped, Exact)
        .needs(Quantity::DiffuseTransmission, Steps(16))
}

/// The scene, seen by the test's camera.
pub fn scene() -> AddPlugins {
    Box::new(|app| {
        app.add_plugins(FeaturesScene)
            .add_systems(Startup, test_camera);
    })
}

fn test_camera(mut commands: Commands, mut images: ResMut<Assets<Image>>, deferred: Res<Deferred>) {
    camera(&mut commands, &mut images, *deferred, camera_transform());
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
