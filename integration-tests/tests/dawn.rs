//! Chrome's WGSL compiler and engine: Tint (in Dawn, npm `webgpu`) compiles every WGSL the
//! project generates or ships (layouts seed, engine, solved and random, exact and fast; the
//! shading library's modules alone and composed; the renderer's passes) and must say nothing
//! about it, and Dawn runs the layouts' pack, unpack and per-field loads, whose words must be
//! the Rust mirror's. A wgpu application on the web has its WGSL compiled by the browser, not
//! by naga. Both run on each of Dawn's backends that this machine serves: Vulkan (core WebGPU,
//! SPIR-V from Tint) and OpenGL ES (compatibility mode, GLSL ES from Tint: a translation of its
//! own, the one Chrome uses for WebGL-class devices).
//!
//! Dawn's Node bindings are looked for in `$GBUFFER_DAWN_MODULES` (a `node_modules` folder),
//! else `/opt/gbuffer-dawn/node_modules`, where `.ci/run` installs them; `dawn/run.mjs` drives
//! them. Without them, or without a backend's adapter, the tests skip, except under `CI=true`.

use std::fmt;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

use gbuffer::layout::{Conversions, Layout};
use gbuffer::GBufferLayout;
use gbuffer_codegen::wgsl::emit_with;
use gbuffer_core::Named;
use gbuffer_gpu::harness::{compute_harness, scalars_per_texel};
use gbuffer_gpu::values::Values;
use gbuffer_render::gbuffers::{GBuffer, PackedLayout};
use gbuffer_render::options::{IblForm, Options, SunForm};
use gbuffer_render::shaders::{self, Positions};
use gbuffer_testkit::texels::{compare_harness, inputs};
use gbuffer_testkit::{AllFormats, EveryEncoding, FastBitFields, FastFormats, MixedConversions};
use gbuffer_tradeoff::packing_cost::{fast_domain_inputs, Deviation};
use proptest::strategy::{Strategy, ValueTree};
use serde_json::{json, Value};

/// Where `.ci/run` installs `webgpu`.
const DEFAULT_MODULES: &str = "/opt/gbuffer-dawn/node_modules";

/// Texels each layout runs through Dawn: the edge cases first, then random values.
const TEXELS: usize = 1 << 17;

/// Dawn's backends, each with the feature level it is asked for.
#[derive(Clone, Copy, Debug)]
enum Backend {
    /// Core WebGPU on Vulkan (lavapipe).
    Vulkan,
    /// Compatibility mode on OpenGL ES (llvmpipe through EGL surfaceless).
    OpenGles,
}

impl Backend {
    const ALL: [Backend; 2] = [Backend::Vulkan, Backend::OpenGles];

    /// The name `dawn/run.mjs` takes.
    fn flag(self) -> &'static str {
        match self {
            Backend::Vulkan => "vulkan",
            Backend::OpenGles => "opengles",
        }
    }
}

impl fmt::Display for Backend {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "Dawn's {} backend", self.flag())
    }
}

/// Dawn's Node bindings, found.
struct Dawn {
    modules: PathBuf,
}

/// What Dawn made of the jobs: the adapter, whether it has shader-f16, one result a job
/// (`{name, messages, error}`, see `dawn/run.mjs`).
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

    /// Runs the jobs (see `dawn/run.mjs`) in one Node process on `backend`. The error says
    /// that the backend has no adapter here; a crash or a failed run panics, with what Node
    /// printed.
    fn run(&self, backend: Backend, jobs: &[Value]) -> Result<Outcome, String> {
        let folder = scratch_folder();
        let (jobs_path, results_path) = (folder.join("jobs.json"), folder.join("results.json"));
        std::fs::write(&jobs_path, serde_json::to_string(jobs).unwrap()).unwrap();
        let output = Command::new("node")
            .arg(gbuffer_testkit::workspace().join("integration-tests/dawn/run.mjs"))
            .arg(backend.flag())
            .arg(&jobs_path)
            .arg(&results_path)
            .env("GBUFFER_DAWN_MODULES", &self.modules)
            .env("EGL_PLATFORM", "surfaceless")
            // Cargo points the loader at its own folders, whose libraries Node must not load.
            .env_remove("LD_LIBRARY_PATH")
            .output()
            .expect("node runs");
        assert!(
            output.status.success(),
            "dawn/run.mjs on {backend} failed ({}): {}",
            output.status,
            String::from_utf8_lossy(&output.stderr)
        );
        let results: Value =
            serde_json::from_str(&std::fs::read_to_string(&results_path).unwrap()).unwrap();
        let _ = std::fs::remove_dir_all(&folder);
        let Some(adapter) = results["adapter"].as_str() else {
            return Err("Dawn found no adapter there".to_string());
        };
        Ok(Outcome {
            adapter: adapter.to_string(),
            has_f16: results["f16"].as_bool().unwrap_or(false),
            results: results["results"].as_array().cloned().unwrap_or_default(),
        })
    }
}

/// A new empty folder under the system's temporary one, for one run's files.
fn scratch_folder() -> PathBuf {
    static RUNS: AtomicUsize = AtomicUsize::new(0);
    let run = RUNS.fetch_add(1, Ordering::Relaxed);
    let folder = std::env::temp_dir().join(format!("gbuffer-dawn-{}-{run}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    folder
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
    let modules = gbuffer_shading::wgsl::modules();
    for module in modules {
        jobs.push(compile(
            format!("shading module {}", module.name),
            gbuffer_shading::compose(&[module.name]).unwrap(),
        ));
    }
    for &layout in PackedLayout::ALL {
        let options = Options {
            gbuffer: GBuffer::Packed(layout),
            sun: SunForm::Ggx,
            ibl: IblForm::Lut,
            width: 64,
            height: 64,
        };
        let name = layout.name();
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
        gbuffer_shading::compose(&names).unwrap(),
    ));
    // What an adapter without shader-f16 composes: every module but the one that enables it.
    let without_f16: Vec<&str> = modules
        .iter()
        .filter(|module| module.directives().is_empty())
        .map(|module| module.name)
        .collect();
    jobs.push(compile(
        "the shading library composed without f16",
        gbuffer_shading::compose(&without_f16).unwrap(),
    ));
    jobs
}

/// Each of Dawn's backends this machine serves, with `run`'s outcome on it; a backend without
/// an adapter is reported by the GPU tests' rule (`or_skip`).
fn on_each_backend(dawn: &Dawn, jobs: &[Value]) -> Vec<(Backend, Outcome)> {
    Backend::ALL
        .iter()
        .copied()
        .filter_map(|backend| {
            let outcome = gbuffer_testkit::or_skip(&backend.to_string(), dawn.run(backend, jobs))?;
            eprintln!("{backend}: {}", outcome.adapter);
            Some((backend, outcome))
        })
        .collect()
}

/// What a job's result says went wrong: Tint's messages (the first three) and the error
/// Dawn raised, or `None`.
fn problems(result: &Value) -> Option<String> {
    let messages = result["messages"].as_array().cloned().unwrap_or_default();
    if messages.is_empty() && result["error"].is_null() {
        return None;
    }
    let mut lines: Vec<String> = messages
        .iter()
        .take(3)
        .map(|message| format!("line {}: {}", message["line"], message["text"]))
        .collect();
    if let Some(error) = result["error"].as_str() {
        lines.push(error.to_string());
    }
    Some(lines.join("; "))
}

/// Tint compiles every WGSL the project generates or ships without an error or a warning, on
/// each backend (a module that enables f16 is left out where the adapter has no shader-f16).
#[test]
fn every_wgsl_compiles_in_tint_without_a_message() {
    let Some(dawn) = dawn() else {
        return;
    };
    let jobs = every_wgsl();
    let mut failures = Vec::new();
    for (backend, outcome) in on_each_backend(&dawn, &jobs) {
        eprintln!("{backend}: {} shaders", jobs.len());
        for (job, result) in jobs.iter().zip(&outcome.results) {
            let wgsl = job["wgsl"].as_str().unwrap();
            if wgsl.contains("enable f16;") && !outcome.has_f16 {
                eprintln!(
                    "{backend}: {}: enables f16, which the adapter lacks",
                    job["name"]
                );
                continue;
            }
            if let Some(problems) = problems(result) {
                failures.push(format!("{backend}: {}: {problems}", job["name"]));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A layout's compute harness (`gbuffer_gpu::harness::compute_harness`: pack, unpack and each
/// field's load) over the texels `inputs` (scalar bits), as a Dawn job whose outputs land in
/// `folder`.
struct HarnessRun {
    job: Value,
    /// The files Dawn writes: packed words, unpacked scalars, loaded scalars.
    outputs: [PathBuf; 3],
    inputs: Vec<u32>,
}

impl HarnessRun {
    fn new(layout: &Layout, wgsl: &str, inputs: Vec<u32>, folder: &Path) -> HarnessRun {
        let texels = inputs.len() / scalars_per_texel(layout);
        let file = |what: &str| folder.join(format!("{}.{what}", layout.snake_name()));
        let outputs = [file("packed"), file("unpacked"), file("loaded")];
        std::fs::write(file("inputs"), bytemuck::cast_slice::<u32, u8>(&inputs)).unwrap();
        let job = json!({
            "name": layout.name,
            "wgsl": compute_harness(layout, wgsl),
            "entry": "harness_main",
            "inputs": file("inputs"),
            "outputs": [
                texels * layout.words(),
                texels * scalars_per_texel(layout),
                texels * scalars_per_texel(layout),
            ],
            "count": texels,
            "workgroups": texels.div_ceil(64),
            "results": outputs,
        });
        HarnessRun {
            job,
            outputs,
            inputs,
        }
    }

    /// What Dawn wrote: packed words, unpacked scalars, loaded scalars.
    fn read(&self) -> [Vec<u32>; 3] {
        self.outputs.clone().map(|path| {
            let bytes =
                std::fs::read(&path).unwrap_or_else(|error| panic!("{}: {error}", path.display()));
            bytemuck::pod_collect_to_vec(&bytes)
        })
    }
}

/// Runs the harnesses on each backend; `check(backend, index, [packed, unpacked, loaded])` is
/// called for each run (`runs[index]`), after Tint and Dawn are held to saying nothing about it.
fn run_harnesses(
    dawn: &Dawn,
    runs: &[HarnessRun],
    mut check: impl FnMut(Backend, usize, [Vec<u32>; 3]),
) {
    let jobs: Vec<Value> = runs.iter().map(|run| run.job.clone()).collect();
    for (backend, outcome) in on_each_backend(dawn, &jobs) {
        for (index, (run, result)) in runs.iter().zip(&outcome.results).enumerate() {
            if let Some(problems) = problems(result) {
                panic!("{backend}: {}: {problems}", run.job["name"]);
            }
            check(backend, index, run.read());
        }
    }
}

/// The exact layouts (every format, every encoding, the seeds and the engines') pack, unpack
/// and load each field on Dawn as the Rust mirror does: words bit for bit, decodes within the
/// tolerance each codec states (`gbuffer_testkit::texels`), over the edge cases (NaN,
/// infinities, subnormals, the ties of half and the small floats, which Tint's GLSL would leave
/// to the driver were they rounded with `round`) and random texels.
#[test]
fn exact_layouts_pack_unpack_and_load_as_the_mirror_on_dawn() {
    let Some(dawn) = dawn() else {
        return;
    };
    let folder = scratch_folder();
    let layouts: Vec<(Layout, &str)> = [
        (AllFormats::layout(), AllFormats::WGSL),
        (EveryEncoding::layout(), EveryEncoding::WGSL),
    ]
    .into_iter()
    .chain(gbuffer::seed_layouts::all())
    .chain(gbuffer::engine_layouts::all())
    .collect();
    let runs: Vec<HarnessRun> = layouts
        .iter()
        .enumerate()
        .map(|(index, (layout, wgsl))| {
            let mut values = Values::new(300 + index as u64);
            let texels = inputs(layout, 0, TEXELS, &mut values);
            HarnessRun::new(layout, wgsl, texels, &folder)
        })
        .collect();
    let mut failures = Vec::new();
    run_harnesses(
        &dawn,
        &runs,
        |backend, index, [packed, unpacked, loaded]| {
            let (layout, _) = &layouts[index];
            let outputs = [&packed[..], &unpacked, &loaded];
            compare_harness(
                &backend.to_string(),
                layout,
                &runs[index].inputs,
                outputs,
                &mut failures,
                20,
            );
            eprintln!("{backend}: {}: {TEXELS} texels as the mirror", layout.name);
        },
    );
    let _ = std::fs::remove_dir_all(&folder);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The fast layouts keep the layout contract's rule on Dawn (`packing_cost::allowed_code_error`: a fast
/// channel within one code of the exact mirror, octahedral and RGBM fields within two steps,
/// an exact field of a mixed layout bit for bit), over values in the fast domain (finite,
/// within f16's range), edge cases first.
#[test]
fn fast_layouts_keep_their_contract_on_dawn() {
    let Some(dawn) = dawn() else {
        return;
    };
    let folder = scratch_folder();
    // Each layout with its own conversions, which a field may override.
    let layouts = [
        (FastFormats::layout(), FastFormats::WGSL, Conversions::Fast),
        (
            FastBitFields::layout(),
            FastBitFields::WGSL,
            Conversions::Fast,
        ),
        (
            MixedConversions::layout(),
            MixedConversions::WGSL,
            Conversions::Exact,
        ),
    ];
    let runs: Vec<HarnessRun> = layouts
        .iter()
        .enumerate()
        .map(|(index, (layout, wgsl, _))| {
            let inputs = fast_domain_inputs(400 + index as u64, scalars_per_texel(layout))(TEXELS);
            HarnessRun::new(layout, wgsl, inputs, &folder)
        })
        .collect();
    let mut failures = Vec::new();
    run_harnesses(&dawn, &runs, |backend, index, [packed, _, _]| {
        let (layout, _, conversions) = &layouts[index];
        let mut found = Deviation::new(layout.fields.len());
        found.add(layout, &runs[index].inputs, &packed);
        eprintln!("{backend}: {}: {found}", layout.name);
        let beyond = found.beyond_contract(layout, *conversions);
        failures.extend(beyond.iter().map(|line| format!("{backend}: {line}")));
    });
    let _ = std::fs::remove_dir_all(&folder);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
