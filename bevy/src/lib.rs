//! Any gbuffer layout of at most 128 bits in place of Bevy's own G-buffer, in Bevy 0.20's
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
//! `pbr_input_from_deferred_gbuffer`, both in the WESL module `bevy_pbr::deferred::functions`
//! (its screen-space reflections read the G-buffer through the same function). The plugin puts
//! a module generated from the layout in that module's place
//! ([`functions::deferred_functions_wesl`]): the same functions, storing Bevy's quantities in
//! the layout's fields through the layout's own `pack_`/`unpack_` (its WESL module, which the
//! generated one imports), so the words are the Rust mirror's. The module carries the shader
//! defs that what the layout holds needs ([`GBufferPlugin::shader_defs`]), which Bevy's shader
//! cache gives every shader that imports it; with anisotropy, two of Bevy's lighting functions
//! are patched so that pixels without it shade as Bevy's forward renderer shades them. A shader
//! that reads Bevy's G-buffer other than through the decode stops the app ([`readers`]).
//!
//! Which quantity a field holds is said by its name ([`Quantity::names`]: Bevy's own G-buffer's,
//! and what it drops: `reflectance_color`, `diffuse_occlusion_color`, `anisotropy_strength` and
//! `anisotropy_tangent`, `clearcoat_normal`, `diffuse_transmission`, `thickness`, `lightmapped`)
//! or by [`GBufferPlugin::with_field`]; what the layout does not store takes Bevy's default. A
//! field the plugin cannot map, of the wrong type or encoding, a quantity stored twice, half of
//! anisotropy, a layout over 128 bits or without a normal stops the app when the plugin is
//! added, with a message naming the layout and the field ([`MappingError`]).
//!
//! [`solve()`] picks a layout's bits for a scene in Bevy's terms ([`BevyScene`]), or lists what
//! must give when 128 bits cannot hold it.
//!
//! [The guide](https://docs.rs/gbuffer#the-guide) shows how the packages fit together.

// The README's Rust blocks, compiled (and run where they can) as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

pub mod functions;
mod patch;
pub mod quantity;
pub mod readers;
pub mod ready;
pub mod solve;

use std::marker::PhantomData;

use bevy::app::{App, Plugin, Update};
use bevy::asset::{AssetEvent, AssetServer, Assets, Handle};
use bevy::ecs::message::MessageReader;
use bevy::ecs::prelude::{Res, ResMut, Resource};
use bevy::shader::{Shader, ShaderDefVal, Source};
use gbuffer::GBufferLayout;
use patch::Patch;

pub use quantity::{MappingError, Quantity};
pub use readers::{RawRead, Reading};
pub use ready::{readiness, settle, Readiness};
pub use solve::{solve, BevyScene, Precision, Solution, SolveError};

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

    /// Each field of `L` with the quantity it holds, or why `L` cannot stand in for Bevy's
    /// G-buffer.
    pub fn mapping(&self) -> Result<Vec<(String, Quantity)>, MappingError> {
        quantity::map_fields(&L::layout(), &self.told)
    }

    /// The module that replaces Bevy's `bevy_pbr::deferred::functions`, or why `L` cannot.
    pub fn deferred_functions(&self) -> Result<String, MappingError> {
        let mapping = self.mapping()?;
        Ok(functions::deferred_functions_wesl(&L::layout(), &mapping))
    }

    /// The shader defs the module gives every shader that imports it (Bevy's deferred prepass
    /// and lighting pass) for what `L` holds (anisotropy, diffuse transmission), or why `L`
    /// cannot stand in for Bevy's G-buffer.
    pub fn shader_defs(&self) -> Result<Vec<&'static str>, MappingError> {
        Ok(functions::shader_defs(&self.mapping()?))
    }
}

impl<L: GBufferLayout> Default for GBufferPlugin<L> {
    fn default() -> Self {
        Self::new()
    }
}

/// What the plugin puts in Bevy's shader assets once Bevy's have loaded: the layout's module
/// in the place of Bevy's, and the patches of Bevy's lighting modules the layout needs. Each
/// entry is removed once done.
#[derive(Resource)]
struct Replacement {
    module: Option<(Handle<Shader>, Shader)>,
    patches: Vec<(Handle<Shader>, Patch)>,
}

impl<L: GBufferLayout + 'static> Plugin for GBufferPlugin<L> {
    fn build(&self, app: &mut App) {
        let mapping = self
            .mapping()
            .unwrap_or_else(|error| panic!("GBufferPlugin: {error}"));
        // The layout's own WESL module, which the functions' module imports; that module holds
        // it alive.
        let layout_module = L::wesl_module();
        let layout_module =
            app.world_mut()
                .resource_mut::<Assets<Shader>>()
                .add(Shader::from_wesl(
                    layout_module.source,
                    functions::asset_path(&layout_module.path),
                ));
        let source = functions::deferred_functions_wesl(&L::layout(), &mapping);
        // Bevy's own asset path, from which Bevy derives the module path its shaders import.
        let bevy_module = functions::asset_path(functions::MODULE_PATH);
        let mut module = Shader::from_wesl(source, bevy_module.clone());
        module.file_dependencies.push(layout_module);
        // Bevy's shader cache gives a module's defs to every shader that imports it.
        module.shader_defs = functions::shader_defs(&mapping)
            .into_iter()
            .map(|def| ShaderDefVal::Bool(def.into(), true))
            .collect();
        let assets = app.world().resource::<AssetServer>();
        let patches = if functions::holds(&mapping, Quantity::AnisotropyStrength) {
            patch::ISOTROPIC_WITHOUT_ANISOTROPY
                .iter()
                .map(|patch| (assets.load::<Shader>(patch.path), *patch))
                .collect()
        } else {
            Vec::new()
        };
        app.insert_resource(Replacement {
            module: Some((assets.load::<Shader>(bevy_module), module)),
            patches,
        })
        .init_resource::<LayoutReaders>()
        .add_systems(Update, (replace_bevy_shaders, check_g_buffer_readers));
    }
}

/// Once each of Bevy's shaders has loaded, puts the layout's module in its place or patches
/// it (once): the shader cache sees the asset change and rebuilds the pipelines that use it.
fn replace_bevy_shaders(mut replacement: ResMut<Replacement>, mut shaders: ResMut<Assets<Shader>>) {
    if let Some((handle, module)) = replacement.module.take() {
        if shaders.contains(&handle) {
            let _ = shaders.insert(&handle, module);
        } else {
            replacement.module = Some((handle, module));
        }
    }
    let mut waiting = Vec::new();
    for (handle, patch) in replacement.patches.drain(..) {
        match shaders.get(&handle).map(|shader| patch.apply(shader)) {
            Some(patched) => {
                let patched = patched.unwrap_or_else(|error| panic!("{error}"));
                let _ = shaders.insert(&handle, patched);
            }
            None => waiting.push((handle, patch)),
        }
    }
    replacement.patches = waiting;
}

/// The shaders that read Bevy's G-buffer texture, all through the layout's decode: their asset
/// paths, in the order they loaded.
#[derive(Resource, Default)]
struct LayoutReaders(Vec<String>);

/// Checks each shader as it loads or changes: one that reads Bevy's G-buffer other than through
/// `pbr_input_from_deferred_gbuffer` stops the app, naming the module and the line
/// ([`readers::reading`]); one that reads it through the decode is recorded.
fn check_g_buffer_readers(
    mut events: MessageReader<AssetEvent<Shader>>,
    shaders: Res<Assets<Shader>>,
    mut readers: ResMut<LayoutReaders>,
) {
    for event in events.read() {
        let (AssetEvent::Added { id } | AssetEvent::Modified { id }) = event else {
            continue;
        };
        let Some(shader) = shaders.get(*id) else {
            continue;
        };
        let (Source::Wgsl(source) | Source::Wesl(source)) = &shader.source else {
            continue;
        };
        match readers::reading(&shader.path, source) {
            Err(raw) => panic!("{raw}"),
            Ok(Reading::Decodes) if !readers.0.contains(&shader.path) => {
                readers.0.push(shader.path.clone())
            }
            Ok(_) => {}
        }
    }
}

/// The shaders loaded so far that read Bevy's G-buffer texture, each through the layout's decode
/// (the plugin stops the app at any other): their asset paths. In Bevy 0.20.1, its deferred
/// lighting pass and its screen-space reflections.
pub fn layout_readers(app: &App) -> Vec<String> {
    app.world()
        .get_resource::<LayoutReaders>()
        .map_or_else(Vec::new, |readers| readers.0.clone())
}

/// Whether the layout's module has taken Bevy's place and Bevy's lighting modules are patched
/// (frames rendered before may still use Bevy's G-buffer).
pub fn is_replaced(app: &App) -> bool {
    app.world()
        .get_resource::<Replacement>()
        .is_some_and(|replacement| replacement.module.is_none() && replacement.patches.is_empty())
}
