//! When a headless app's frame is the one it will keep drawing: every render pipeline it asked
//! for compiled, the layout's module in Bevy's place, and nothing new asked for since. A frame
//! read back earlier may come from a pipeline compiled with Bevy's own module, or lack a
//! material whose textures are still on their way to the GPU: tests and screenshots wait for
//! [`Readiness::Settled`].

use bevy::app::App;
use bevy::render::render_resource::{CachedPipelineState, PipelineCache, PipelineDescriptor};
use bevy::render::RenderApp;
use bevy::shader::ShaderCacheError;

/// Where a headless app's rendering stands ([`readiness`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Readiness {
    /// Pipelines are queued or compiling, or the plugin's module is not in place yet.
    Waiting,
    /// Every pipeline the render world has asked for is compiled: this many.
    Settled {
        /// How many pipelines the render world holds.
        pipelines: usize,
    },
}

/// Where `app`'s rendering stands, or why it cannot be told: the render app must be inside
/// `app` (add `DefaultPlugins` without `PipelinedRenderingPlugin`, which moves it to a thread
/// of its own), and a pipeline that failed to compile is an error naming its shader's message
/// (one whose shader is still loading is waiting: Bevy tries it again).
///
/// A count that stays the same over several updates says that nothing new was asked for:
/// materials are specialised once their assets are on the GPU, so one settled update alone
/// does not prove the frame final.
pub fn readiness(app: &App) -> Result<Readiness, String> {
    if !crate::is_replaced(app) && app.world().contains_resource::<crate::Replacement>() {
        return Ok(Readiness::Waiting);
    }
    let render = app.get_sub_app(RenderApp).ok_or(
        "the render app is not in the app: disable PipelinedRenderingPlugin to read its pipelines",
    )?;
    let cache = render
        .world()
        .get_resource::<PipelineCache>()
        .ok_or("the render app has no pipeline cache yet")?;
    let mut pipelines = 0;
    for pipeline in cache.pipelines() {
        match &pipeline.state {
            CachedPipelineState::Ok(_) => pipelines += 1,
            // Bevy queues these again on its next update (`PipelineCache::process_queue`,
            // bevy_render 0.20.1): a shader, or one it imports, is still on its way from the
            // asset server. Not a failure: how early it is seen depends on the loader's timing.
            CachedPipelineState::Err(
                ShaderCacheError::ShaderNotLoaded(_)
                | ShaderCacheError::ShaderImportNotYetAvailable,
            ) => return Ok(Readiness::Waiting),
            CachedPipelineState::Err(error) => {
                let label = match &pipeline.descriptor {
                    PipelineDescriptor::RenderPipelineDescriptor(render) => &render.label,
                    PipelineDescriptor::ComputePipelineDescriptor(compute) => &compute.label,
                    PipelineDescriptor::MeshPipelineDescriptor(mesh) => &mesh.label,
                };
                return Err(format!("pipeline {label:?} failed to compile: {error}"));
            }
            CachedPipelineState::Queued | CachedPipelineState::Creating(_) => {
                return Ok(Readiness::Waiting)
            }
        }
    }
    Ok(Readiness::Settled { pipelines })
}

/// Updates `app` until its rendering has been [`Readiness::Settled`] with the same pipelines
/// for `steady` updates in a row, at most `limit` updates; returns how many it took, or why
/// it did not settle.
pub fn settle(app: &mut App, steady: usize, limit: usize) -> Result<usize, String> {
    let (mut last, mut same) = (None, 0);
    for update in 1..=limit {
        app.update();
        match readiness(app)? {
            Readiness::Waiting => (last, same) = (None, 0),
            settled => {
                same = if last.as_ref() == Some(&settled) {
                    same + 1
                } else {
                    1
                };
                last = Some(settled);
                if same >= steady {
                    return Ok(update);
                }
            }
        }
    }
    Err(format!(
        "rendering did not settle in {limit} updates (last: {last:?}, {same} steady)"
    ))
}
