//! Chrome's WGSL compiler: every WGSL the project generates or ships (layouts seed, engine,
//! solved and random, exact and fast; the shading library's modules alone and composed; the
//! renderer's passes) goes through Tint (in Dawn, npm `webgpu`), which must say nothing about
//! it. A wgpu application on the web has
//! its WGSL compiled by the browser, not by naga.
//!
//! Dawn's Node bindings are looked for in `$GBUFFER_DAWN_MODULES` (a `node_modules` folder),
//! else `/opt/gbuffer-dawn/node_modules`, where `.ci/run` installs them; `dawn/run.mjs` drives
//! them. Without them the tests skip, except under `CI=true`.

use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

use gbuffer::packing::{Conversions, Layout};
use gbuffer::GBufferLayout;
use gbuffer_codegen::emit::wgsl::emit_with;
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::options::{IblForm, Options, SunForm};
use gbuffer_render::shaders::{self, Positions};
use gbuffer_testkit::{AllFormats, EveryEncoding, FastBitFields, FastFormats, MixedConversions};
use proptest::strategy::{Strategy, ValueTree};
use serde_json::{json, Value};

/// Where `.ci/run` installs `webgpu`.
const DEFAULT_MODULES: &str = "/opt/gbuffer-dawn/node_modules";

/// Jobs per Node process: Dawn's OpenGL ES backend on llvmpipe (Mesa 22.3) aborts or hangs
/// now and then with a second shader module in one process (a mutex assertion in the driver),
/// and its Vulkan backend on lavapipe after a few dozen pipelines; one shader a process runs
/// cleanly.
const JOBS_PER_PROCESS: usize = 1;

/// Dawn's Node bindings, found.
struct Dawn {
    modules: PathBuf,
}

/// What Dawn made of the jobs: the adapter, whether it has shader-f16, one result a job.
struct Outcome {
    adapter: String,
    has_f16: bool,
    results: Vec<Value>,
}

impl Dawn {
    fn find() -> Result<Dawn, String> {
        let modules = std::env::var_os("GBUFFER_DAWN_MODULES")
            .map_or_else(|| PathBuf::from(DEFAULT_MODULES), PathBuf::from);
        if !modules.join("webgpu").join("package.json").exists() {
            return Err(format!(
                "Dawn's Node bindings are not in {} (npm install --prefix {} webgpu@0.6.2, as \
                 .ci/run does, or set GBUFFER_DAWN_MODULES)",
                modules.display(),
                modules
                    .parent()
                    .map_or(modules.clone(), PathBuf::from)
                    .display()
            ));
        }
        Command::new("node")
            .arg("--version")
            .output()
            .map_err(|error| format!("node: {error}"))?;
        Ok(Dawn { modules })
    }

    /// Compiles the jobs (`{name, wgsl}`, see `dawn/run.mjs`), one to a process.
    fn run(&self, jobs: &[Value]) -> Outcome {
        static RUNS: AtomicUsize = AtomicUsize::new(0);
        let mut outcome = Outcome {
            adapter: String::new(),
            has_f16: false,
            results: Vec::new(),
        };
        for batch in jobs.chunks(JOBS_PER_PROCESS) {
            let run = RUNS.fetch_add(1, Ordering::Relaxed);
            let stem =
                std::env::temp_dir().join(format!("gbuffer-dawn-{}-{run}", std::process::id()));
            let (jobs_path, results_path) = (
                stem.with_extension("jobs.json"),
                stem.with_extension("results.json"),
            );
            std::fs::write(&jobs_path, serde_json::to_string(batch).unwrap()).unwrap();
            let node = || {
                Command::new("node")
                    .arg(gbuffer_testkit::workspace().join("integration-tests/dawn/run.mjs"))
                    .arg(&jobs_path)
                    .arg(&results_path)
                    .env("GBUFFER_DAWN_MODULES", &self.modules)
                    .env("EGL_PLATFORM", "surfaceless")
                    // Cargo points the loader at its own folders, whose libraries Node must
                    // not load.
                    .env_remove("LD_LIBRARY_PATH")
                    .output()
                    .expect("node runs")
            };
            // The driver's abort (see JOBS_PER_PROCESS) is a crash, not a verdict on the
            // shader: a crashed run is tried again, twice.
            let mut output = node();
            for _ in 0..2 {
                if output.status.success() {
                    break;
                }
                output = node();
            }
            assert!(
                output.status.success(),
                "dawn/run.mjs failed ({}): {}",
                output.status,
                String::from_utf8_lossy(&output.stderr)
            );
            let results: Value =
                serde_json::from_str(&std::fs::read_to_string(&results_path).unwrap()).unwrap();
            let _ = std::fs::remove_file(&jobs_path);
            let _ = std::fs::remove_file(&results_path);
            outcome.adapter = results["adapter"].as_str().unwrap_or_default().to_string();
            outcome.has_f16 = results["f16"].as_bool().unwrap_or(false);
            outcome
                .results
                .extend(results["results"].as_array().cloned().unwrap_or_default());
        }
        outcome
    }
}

fn dawn() -> Option<Dawn> {
    gbuffer_testkit::or_skip("Dawn's Node bindings (npm webgpu)", Dawn::find())
}

/// A job that only compiles `wgsl`.
fn compile(name: impl Into<String>, wgsl: impl Into<String>) -> Value {
    json!({ "name": name.into(), "wgsl": wgsl.into() })
}

/// Every WGSL the project generates or ships, named.
fn every_wgsl() -> Vec<Value> {
    let mut jobs = Vec::new();
    let mut layouts: Vec<(Layout, String)> = Vec::new();
    for (layout, wgsl) in gbuffer::seed_layouts::all()
        .into_iter()
        .chain(gbuffer::engine_layouts::all())
    {
        layouts.push((layout, wgsl.to_string()));
    }
    for (layout, wgsl) in [
        (AllFormats::layout(), AllFormats::WGSL),
        (EveryEncoding::layout(), EveryEncoding::WGSL),
        (FastFormats::layout(), FastFormats::WGSL),
        (FastBitFields::layout(), FastBitFields::WGSL),
        (MixedConversions::layout(), MixedConversions::WGSL),
    ] {
        layouts.push((layout, wgsl.to_string()));
    }
    for preset in gbuffer_testkit::scene_presets() {
        let solution = gbuffer_solver::file::read_and_solve(&preset).unwrap();
        let name = format!("solved {}", preset.display());
        jobs.push(compile(name, gbuffer_solver::texel::texel_wgsl(&solution)));
    }
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = gbuffer_testkit::layouts::random_layout();
    for _ in 0..24 {
        let layout = strategy.new_tree(&mut runner).unwrap().current();
        for conversions in [Conversions::Exact, Conversions::Fast] {
            let wgsl = emit_with(&layout, conversions);
            layouts.push((layout.clone(), wgsl));
        }
    }
    for (layout, wgsl) in layouts {
        jobs.push(compile(format!("layout {}", layout.name), wgsl));
    }
    let modules = gbuffer::modules::modules();
    for module in modules {
        jobs.push(compile(
            format!("shading module {}", module.name),
            gbuffer::modules::compose(&[module.name]).unwrap(),
        ));
    }
    for &layout in PackedLayout::all() {
        let options = Options {
            gbuffer: GBuffer::Packed(layout),
            sun: SunForm::Ggx,
            ibl: IblForm::Lut,
            width: 64,
            height: 64,
        };
        let name = layout.flag();
        let lighting = shaders::lighting_pass_wgsl(&options, Positions::DepthBuffer).unwrap();
        jobs.push(compile(
            format!("{name}: G-buffer pass"),
            shaders::gbuffer_wgsl(&options, 1.0),
        ));
        jobs.push(compile(format!("{name}: lighting pass"), lighting));
    }
    let names: Vec<&str> = modules.iter().map(|module| module.name).collect();
    jobs.push(compile(
        "the shading library composed",
        gbuffer::modules::compose(&names).unwrap(),
    ));
    // What an adapter without shader-f16 composes: every module but the one that enables it.
    let without_f16: Vec<&str> = modules
        .iter()
        .filter(|module| module.directives().is_empty())
        .map(|module| module.name)
        .collect();
    jobs.push(compile(
        "the shading library composed without f16",
        gbuffer::modules::compose(&without_f16).unwrap(),
    ));
    jobs
}

/// Tint compiles every WGSL the project generates or ships without an error or a warning (a
/// module that enables f16 is left out where the adapter has no shader-f16).
#[test]
fn every_wgsl_compiles_in_tint_without_a_message() {
    let Some(dawn) = dawn() else {
        return;
    };
    let jobs = every_wgsl();
    let outcome = dawn.run(&jobs);
    eprintln!("Dawn: {}; {} shaders", outcome.adapter, jobs.len());
    let mut failures = Vec::new();
    for (job, result) in jobs.iter().zip(&outcome.results) {
        let wgsl = job["wgsl"].as_str().unwrap();
        if wgsl.contains("enable f16;") && !outcome.has_f16 {
            eprintln!("{}: enables f16, which this adapter lacks", job["name"]);
            continue;
        }
        let messages = result["messages"].as_array().cloned().unwrap_or_default();
        if !messages.is_empty() || !result["error"].is_null() {
            let first: Vec<String> = messages
                .iter()
                .take(3)
                .map(|message| format!("line {}: {}", message["line"], message["text"]))
                .collect();
            failures.push(format!("{}: {}", job["name"], first.join("; ")));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
