//! The GLSL ES the project ships for tile-based GPUs, compiled by those GPUs' own compilers as
//! Mesa ships them: Mali-G52 (Bifrost) and Mali-G610 (Valhall) through panfrost, Adreno 630
//! and 740 through freedreno, run with Mesa's drm-shim (`gbuffer-cost`, set up by
//! `scripts/cost-setup.sh`). Both drivers offer GL_EXT_shader_framebuffer_fetch, so:
//!
//! - every framebuffer-fetch include the codegen writes (packed and native, exact and fast) of
//!   the seed and engine layouts and of layouts of every format and encoding, pasted unedited
//!   into a user's two passes, on Mali-G52, Mali-G610 and Adreno 740, under two preambles its
//!   header allows: the oldest version with no precision statement, and the newest the driver
//!   offers (panfrost: GLSL ES 3.10) with `mediump` defaults. The preambles matter to the
//!   front end, which is Mesa's alike on every driver and which `gles_includes` runs with every
//!   preamble on llvmpipe; a compile under qemu costs about a tenth of a second, so the back
//!   ends get the two that differ most;
//! - the fused renderer's five GLES programs for every layout it renders, on both fetch paths,
//!   exactly as the GLES backend links them, on all four.
//!
//! Each must compile and link, and the compiler must report its statistics. The fused Vulkan
//! paths' pipelines go through turnip, RADV and panvk in `tile_compilers_vulkan`. No Mesa driver
//! offers GL_EXT_shader_pixel_local_storage: the PLS includes are checked by glslang only
//! (`codegen_outputs`). Outside CI a missing setup skips with the reason; under `CI=true` it
//! fails.

use gbuffer_codegen::emit::glsl::{self, Include};
use gbuffer_codegen::CompiledLayout;
use gbuffer_core::Conversions;
use gbuffer_core::Named;
use gbuffer_cost::{measure, CostError, Shader, Stage, Target};
use gbuffer_render::fused_programs::{fused_programs, FusedDialect};
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::on_tile::Path;
use gbuffer_render::options::{IblForm, Options, SunForm};
use gbuffer_testkit::layouts::seeds_and_every_format;
use gbuffer_testkit::skip_without_driver;
use gbuffer_testkit::user_shaders::{fetch_user_shaders, preambles};

/// The targets, and the newest GLSL ES each offers.
const TARGETS: [(&str, &str); 4] = [
    ("mali-g52", "310 es"),
    ("mali-g610", "310 es"),
    ("adreno-740", "320 es"),
    ("adreno-630", "320 es"),
];

/// The includes are compiled on the first three: Adreno 630's ir3 is 740's, one generation back.
const INCLUDE_TARGETS: usize = 3;

/// More attachments than GLES guarantees draw buffers (8, as both drivers offer).
const MAX_DRAW_BUFFERS: usize = 8;

/// Compiles `shaders` (named for messages) on `target`; returns the failures, or `None` when
/// the target is not set up (skipped outside CI, a failure under it).
fn compile_all(target: &Target, shaders: &[(String, Shader)]) -> Option<Vec<String>> {
    let list: Vec<Shader> = shaders.iter().map(|(_, shader)| shader.clone()).collect();
    let results = match measure(&list, target, false) {
        Ok(results) => results,
        Err(error @ CostError::NotSetUp(_)) => {
            skip_without_driver(target.name, &error.to_string());
            return None;
        }
        Err(error) => panic!("{}: {error}", target.name),
    };
    let mut failures = Vec::new();
    for ((name, _), result) in shaders.iter().zip(results) {
        match result {
            Ok(measurement) if measurement.statistics.instructions > 0 => {}
            Ok(_) => failures.push(format!("{}: {name}: no instructions", target.name)),
            Err(error) => failures.push(format!("{}: {name}: {error}", target.name)),
        }
    }
    Some(failures)
}

#[test]
fn fetch_includes_compile_on_mali_and_adreno() {
    let mut failures = Vec::new();
    for (name, newest) in &TARGETS[..INCLUDE_TARGETS] {
        let target = Target::named(name).unwrap();
        let mut shaders = Vec::new();
        for layout in seeds_and_every_format() {
            for conversions in [Conversions::Exact, Conversions::Fast] {
                let compiled = CompiledLayout::new(&layout, conversions).unwrap();
                for include in [Include::FetchPacked, Include::FetchNative] {
                    let (_, interface) = glsl::include(&compiled, include, 0).unwrap();
                    if interface.attachments.len() > MAX_DRAW_BUFFERS {
                        continue;
                    }
                    let all = preambles(include);
                    let newest_line = format!("#version {newest}\n");
                    let oldest = all.first().cloned();
                    let newest_mediump = all
                        .iter()
                        .filter(|preamble| preamble.starts_with(&newest_line))
                        .find(|preamble| preamble.contains("mediump"))
                        .cloned();
                    for preamble in oldest.into_iter().chain(newest_mediump) {
                        let (store, reload) =
                            fetch_user_shaders(&layout, conversions, include, &preamble, 64);
                        let what = format!(
                            "{} {include:?} {conversions:?} under {:?}",
                            layout.name,
                            preamble.replace('\n', " ")
                        );
                        shaders.push((
                            format!("{what}, store pass"),
                            Shader::glsl(Stage::Fragment, &store),
                        ));
                        shaders.push((
                            format!("{what}, reload pass"),
                            Shader::glsl(Stage::Fragment, &reload),
                        ));
                    }
                }
            }
        }
        let Some(target_failures) = compile_all(&target, &shaders) else {
            return;
        };
        eprintln!(
            "{name}: {} shaders, {} failed",
            shaders.len(),
            target_failures.len()
        );
        failures.extend(target_failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn fused_renderer_compiles_on_mali_and_adreno() {
    let mut shaders = Vec::new();
    for &layout in PackedLayout::ALL {
        let options = Options {
            gbuffer: GBuffer::Packed(layout),
            sun: SunForm::Ggx,
            ibl: IblForm::Lut,
            width: 320,
            height: 180,
        };
        for path in [Path::FetchPacked, Path::FetchNative] {
            // A layout the fused paths do not render (it has no on-tile WGSL) is skipped.
            if layout.on_tile_wgsl().is_err() {
                continue;
            }
            let dialect = FusedDialect::of(path).expect("a fused path");
            let fused = fused_programs(&options, dialect)
                .unwrap_or_else(|error| panic!("{}: {error}", layout.name()));
            if fused.interface.attachments.len() + 1 > MAX_DRAW_BUFFERS {
                continue;
            }
            for program in fused.programs {
                let vertex = program
                    .glsl_vertex()
                    .unwrap_or_else(|error| panic!("{}: {error}", layout.name()));
                let shader = Shader::glsl(Stage::Fragment, &program.fragment).with_vertex(vertex);
                shaders.push((
                    format!("{} {} {}", layout.name(), path.name(), program.stage.name()),
                    shader,
                ));
            }
        }
    }
    assert!(
        shaders.len() >= 12,
        "the fused programs of at least one layout"
    );
    let mut failures = Vec::new();
    for (name, _) in TARGETS {
        let target = Target::named(name).unwrap();
        let Some(target_failures) = compile_all(&target, &shaders) else {
            return;
        };
        failures.extend(target_failures);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
