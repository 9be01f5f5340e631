//! Any gbuffer layout of at most 128 bits in place of Bevy's own G-buffer, in Bevy 0.19's
//! deferred renderer.
//!
//! ```ignore
//! use gbuffer_bevy::GBufferPlugin;
//!
//! #[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
//! #[gbuffer(budget = 128)]
//! struct FineNormals {
//!     #[pls(rgba8)]           base_color_roughness: Vec4,
//!     #[bits(32, rgb9e5)]     emissive: Vec3,
//!     #[bits(32, octahedral)] normal: Vec3,
//!     #[bits(8, unorm)]       metallic: f32,
//!     #[bits(8, unorm)]       reflectance: f32,
//!     #[bits(8, unorm)]       clearcoat: f32,
//!     #[bits(8, uint)]        flags: u32,
//! }
//!
//! app.insert_resource(DefaultOpaqueRendererMethod::deferred())
//!     .add_plugins((DefaultPlugins, GBufferPlugin::<FineNormals>::new()));
//! ```
//!
//! Bevy's deferred prepass writes its G-buffer, one `Rgba32Uint` texel, with
//! `deferred_gbuffer_from_pbr_input`, and its lighting pass reads it back with
//! `pbr_input_from_deferred_gbuffer`, both in the shader module `bevy_pbr::pbr_deferred_functions`.
//! The plugin replaces that module's text with one generated from the layout
//! ([`functions::deferred_functions_wgsl`]): the same functions, storing Bevy's quantities in the
//! layout's fields through the layout's own `pack_`/`unpack_` WGSL, so the words are the Rust
//! mirror's. Everything else of Bevy's lighting is unchanged.
//!
//! Which quantity a field holds is said by its name (`base_color`, `base_color_roughness`,
//! `perceptual_roughness`, `metallic`, `reflectance`, `diffuse_occlusion`, `emissive`, `normal`,
//! `flags`, `clearcoat`, `clearcoat_perceptual_roughness`, `depth`) or by
//! [`GBufferPlugin::with_field`]; what the layout does not store takes Bevy's default. A field
//! the plugin cannot map, a field of the wrong type, a layout over 128 bits or without a normal
//! stops the app when the plugin is added, with a message naming the layout and the field
//! ([`MappingError`]).

pub mod functions;
pub mod quantity;

use std::marker::PhantomData;

use bevy::app::{App, Plugin, Update};
use bevy::asset::{AssetServer, Assets, Handle};
use bevy::ecs::prelude::{ResMut, Resource};
use bevy::shader::Shader;
use gbuffer::GBufferLayout;

pub use quantity::{MappingError, Quantity};

/// Where Bevy 0.19 keeps the module the plugin replaces.
const BEVY_MODULE_PATH: &str = "embedded://bevy_pbr/deferred/pbr_deferred_functions.wgsl";

/// Makes Bevy's deferred renderer store and read the layout `L` instead of its own G-buffer.
/// Add it after `DefaultPlugins`, with `DefaultOpaqueRendererMethod::deferred()` (or deferred
/// materials) and a camera with `DepthPrepass` and `DeferredPrepass`.
pub struct GBufferPlugin<L> {
    told: Vec<(String, Quantity)>,
    layout: PhantomData<fn() -> L>,
}

impl<L: GBufferLayout> GBufferPlugin<L> {
    /// The plugin, each field holding the quantity its name says.
    pub fn new() -> Self {
        GBufferPlugin {
            told: Vec::new(),
            layout: PhantomData,
        }
    }

    /// Field `field` holds `quantity`, whatever its name says.
    pub fn with_field(mut self, field: &str, quantity: Quantity) -> Self {
        self.told.push((field.to_string(), quantity));
        self
    }

    /// The module that replaces Bevy's `bevy_pbr::pbr_deferred_functions`, or why `L` cannot.
    pub fn deferred_functions(&self) -> Result<String, MappingError> {
        let layout = L::layout();
        let mapping = quantity::map_fields(&layout, &self.told)?;
        Ok(functions::deferred_functions_wgsl(
            &layout,
            L::WGSL,
            &mapping,
        ))
    }
}

impl<L: GBufferLayout> Default for GBufferPlugin<L> {
    fn default() -> Self {
        Self::new()
    }
}

/// The replacement module and Bevy's handle of the module it replaces.
#[derive(Resource)]
struct Replacement {
    handle: Handle<Shader>,
    source: Option<String>,
}

impl<L: GBufferLayout + 'static> Plugin for GBufferPlugin<L> {
    fn build(&self, app: &mut App) {
        let source = self
            .deferred_functions()
            .unwrap_or_else(|error| panic!("GBufferPlugin: {error}"));
        let handle = app
            .world()
            .resource::<AssetServer>()
            .load::<Shader>(BEVY_MODULE_PATH);
        app.insert_resource(Replacement {
            handle,
            source: Some(source),
        })
        .add_systems(Update, replace_bevy_module);
    }
}

/// Once Bevy's module has loaded, puts the layout's in its place (once): the shader cache sees
/// the asset change and rebuilds the pipelines that import it.
fn replace_bevy_module(mut replacement: ResMut<Replacement>, mut shaders: ResMut<Assets<Shader>>) {
    if replacement.source.is_none() || !shaders.contains(&replacement.handle) {
        return;
    }
    if let Some(source) = replacement.source.take() {
        let shader = Shader::from_wgsl(source, "gbuffer-bevy/pbr_deferred_functions.wgsl");
        let _ = shaders.insert(&replacement.handle, shader);
    }
}

/// Whether the layout's module has taken Bevy's place (frames rendered before may still use
/// Bevy's G-buffer).
pub fn is_replaced(app: &App) -> bool {
    app.world()
        .get_resource::<Replacement>()
        .is_some_and(|replacement| replacement.source.is_none())
}
