//! Bevy scenes rendered headless into an image: [`render`] runs an app with a scene's setup
//! and returns the last frame's pixels. The scenes: [`spheres`] (Bevy's own G-buffer's
//! quantities) and [`features`] (what Bevy's G-buffer drops).

pub mod features;
pub mod spheres;

pub use features::{bumps, Deferred};

use std::sync::{Arc, Mutex};

use bevy::camera::RenderTarget;
use bevy::core_pipeline::prepass::{DeferredPrepass, DepthPrepass};
use bevy::image::Image;
use bevy::pbr::DefaultOpaqueRendererMethod;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};

/// The frame's size.
pub const SIZE: (u32, u32) = (320, 180);

/// A frame: `SIZE`, RGBA8 sRGB, row by row.
pub type Pixels = Vec<[u8; 4]>;

/// What a test adds to the app after Bevy's plugins.
pub type AddPlugins = Box<dyn FnOnce(&mut App)>;

/// A scene's regions: each one's name and whether each pixel, row by row, is in it.
pub type Regions = Vec<(&'static str, Vec<bool>)>;

/// A frame and where the scene's regions lie in it.
pub struct Frame {
    /// Its pixels.
    pub pixels: Pixels,
    /// The scene's regions.
    pub regions: Regions,
}

/// Renders a scene (`scene` adds its setup, and its material plugins) deferred or forward,
/// with `plugin` added after Bevy's own (none: Bevy's G-buffer), and returns its frame once
/// the frame is final: every pipeline compiled and the same for [`STEADY`] updates, the
/// layout's module in Bevy's place, and two captures [`STEADY`] updates apart identical.
/// `regions` finds the scene's regions from the app, once it has rendered.
pub fn render(
    deferred: bool,
    scene: AddPlugins,
    plugin: Option<AddPlugins>,
    regions: fn(&mut App) -> Regions,
) -> Frame {
    let mut app = App::new();
    let method = if deferred {
        DefaultOpaqueRendererMethod::deferred()
    } else {
        DefaultOpaqueRendererMethod::forward()
    };
    app.insert_resource(method)
        .insert_resource(Deferred(deferred))
        .add_plugins(features::headless_plugins().disable::<bevy::log::LogPlugin>());
    let replacing = plugin.is_some();
    if let Some(plugin) = plugin {
        plugin(&mut app);
    }
    scene(&mut app);
    app.finish();
    app.cleanup();
    let updates =
        gbuffer_bevy::settle(&mut app, STEADY, 200).unwrap_or_else(|reason| panic!("{reason}"));
    eprintln!("settled after {updates} updates");
    // The frame is the layout's only if its module took Bevy's place before it.
    assert_eq!(gbuffer_bevy::is_replaced(&app), replacing);
    // Bevy 0.20.1's readers of its G-buffer texture read the layout, through its decode: its
    // deferred lighting pass and its screen-space reflections (the plugin stops the app at a
    // reader that does not).
    if replacing {
        let readers = gbuffer_bevy::layout_readers(&app);
        for reader in [
            "embedded://bevy_pbr/deferred/deferred_lighting.wesl",
            "embedded://bevy_pbr/ssr.wesl",
        ] {
            assert!(
                readers.iter().any(|read| read == reader),
                "{reader} is not among the layout's readers, {readers:?}"
            );
        }
    }
    let pixels = capture(&mut app);
    for _ in 0..STEADY {
        app.update();
    }
    let again = capture(&mut app);
    let changed = pixels.iter().zip(&again).filter(|(a, b)| a != b).count();
    assert_eq!(
        changed, 0,
        "{changed} pixels changed after the frame settled"
    );
    Frame {
        pixels,
        regions: regions(&mut app),
    }
}

/// Updates the rendering must hold still for before its frame counts as final.
pub const STEADY: usize = 5;

/// The target's pixels, read back by a screenshot a frame or two after this update.
fn capture(app: &mut App) -> Pixels {
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
            assert_eq!(
                pixels.len(),
                (SIZE.0 * SIZE.1) as usize,
                "a frame of another size"
            );
            return pixels;
        }
    }
    panic!("no screenshot after 20 frames");
}

/// The scene's camera, at `transform`, rendering into the target; deferred, with the
/// prepasses Bevy's deferred renderer needs.
pub fn camera(
    commands: &mut Commands,
    images: &mut Assets<Image>,
    deferred: Deferred,
    transform: Transform,
) {
    let target = target(commands, images);
    let mut camera = commands.spawn((
        Camera3d::default(),
        RenderTarget::from(target),
        transform,
        Msaa::Off,
    ));
    if deferred.0 {
        camera.insert((DepthPrepass, DeferredPrepass));
    }
}

/// The image the camera renders into.
#[derive(Resource)]
pub struct Target(pub Handle<Image>);

/// The image a scene's camera renders into, `SIZE`, read back after the frame; its handle is
/// kept as the [`Target`] resource.
pub fn target(commands: &mut Commands, images: &mut Assets<Image>) -> Handle<Image> {
    let target = images.add(features::headless_target(SIZE.0, SIZE.1));
    commands.insert_resource(Target(target.clone()));
    target
}

/// The scene's camera and where it is, once the app has run.
pub fn view(app: &mut App) -> (Camera, GlobalTransform) {
    let mut cameras = app.world_mut().query::<(&Camera, &GlobalTransform)>();
    let (camera, transform) = cameras.single(app.world()).expect("one camera");
    (camera.clone(), *transform)
}

/// Whether each pixel, row by row, is in a region, from its centre in viewport coordinates.
pub fn region(inside: impl Fn(Vec2) -> bool) -> Vec<bool> {
    (0..SIZE.1)
        .flat_map(|y| (0..SIZE.0).map(move |x| Vec2::new(x as f32 + 0.5, y as f32 + 0.5)))
        .map(inside)
        .collect()
}

/// Pixels within a disc: the screen-space projection of a sphere at `center` of `radius`,
/// shrunk by `inset` pixels to leave its silhouette out.
pub fn disc(app: &mut App, center: Vec3, radius: f32, inset: f32) -> Vec<bool> {
    let (camera, transform) = view(app);
    let centre = camera.world_to_viewport(&transform, center).unwrap();
    let edge = camera
        .world_to_viewport(&transform, center + transform.right() * radius)
        .unwrap();
    let reach = centre.distance(edge) - inset;
    region(|pixel| pixel.distance(centre) < reach)
}
