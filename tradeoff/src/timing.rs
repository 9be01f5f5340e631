//! Time per evaluation: on the adapter, in both stages, a shader that feeds each result into
//! the next evaluation (so nothing is optimised away), its chain grown until a run lasts 10 ms,
//! timed by timestamp queries at the pass's start and end where the device has them (wall
//! clock around a synchronised submit otherwise, and the report says which): a compute
//! dispatch of 2^14 invocations, and a fullscreen draw into a 1920x1080 target whose fragment
//! shader runs the chain (G-buffer packing and lighting are fragment work, and some GPUs run
//! fragments on few of their units). On the CPU, the f32 mirror over the same kind of inputs.
//! All are medians of several runs.

use std::time::Instant;

use gbuffer::glam::Vec4;
use gbuffer_gpu::fullscreen::FULLSCREEN_WGSL;
use gbuffer_gpu::timestamps::Timestamps;
use gbuffer_gpu::Gpu;

/// Invocations per dispatch, and the evaluations per invocation a calibration starts from.
const INVOCATIONS: u32 = 1 << 14;
const CHAIN: u32 = 64;
/// The fragment stage's target: one invocation per pixel.
const FRAGMENT_WIDTH: u32 = 1920;
const FRAGMENT_HEIGHT: u32 = 1080;
/// The chain grows until one run lasts this long (seconds), or reaches `MAX_CHAIN`.
const TARGET_RUN: f64 = 0.010;
const MAX_CHAIN: u32 = 1 << 16;
/// Timed runs per row, after the calibration's.
pub const GPU_RUNS: usize = 7;
const CPU_RUNS: usize = 5;

/// Where a row's chain runs on the adapter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// A compute dispatch.
    Compute,
    /// A fullscreen draw's fragment shader.
    Fragment,
}

impl Stage {
    /// Both stages, in report order.
    pub const ALL: [Stage; 2] = [Stage::Compute, Stage::Fragment];

    /// The stage's name in the report: `compute` or `fragment`.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Compute => "compute",
            Stage::Fragment => "fragment",
        }
    }
}

/// How a run was timed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Clock {
    /// Timestamp queries written at the start and end of the pass.
    Timestamps,
    /// Wall clock around a synchronised submit.
    Wall,
}

impl Clock {
    /// The clock's name in the report: `timestamps` or `wall`.
    pub fn name(self) -> &'static str {
        match self {
            Clock::Timestamps => "timestamps",
            Clock::Wall => "wall",
        }
    }
}

/// A row's time on the adapter, per evaluation and invocation, over `GPU_RUNS` runs of
/// `chain` evaluations in each of `invocations`.
#[derive(Clone, Copy, Debug)]
pub struct GpuTime {
    /// The stage timed.
    pub stage: Stage,
    /// How it was timed.
    pub clock: Clock,
    /// The median run's time divided by the evaluations of a run (`chain` x `invocations`),
    /// in nanoseconds: device nanoseconds per evaluation, the whole device's throughput (not
    /// one invocation's latency).
    pub median_ns: f64,
    /// The fastest run's, likewise.
    pub min_ns: f64,
    /// The slowest run's, likewise.
    pub max_ns: f64,
    /// Evaluations per invocation, as calibrated.
    pub chain: u32,
    /// Invocations per run.
    pub invocations: u32,
    /// The median run's milliseconds.
    pub run_ms: f64,
    /// False once the consistency check found the adapter's times out of the order the
    /// instruction counts predict: no time of the run is then printed.
    pub trusted: bool,
}

impl GpuTime {
    /// The time less `harness`'s (the baseline row's), each statistic less the harness's
    /// median.
    pub fn less(self, harness: Option<GpuTime>) -> GpuTime {
        let base = harness.map_or(0.0, |harness| harness.median_ns);
        GpuTime {
            median_ns: self.median_ns - base,
            min_ns: self.min_ns - base,
            max_ns: self.max_ns - base,
            ..self
        }
    }

    /// Whether the median stands clear of the runs' spread: a time within the spread (or
    /// under zero, once the harness is taken off) is not a measurement to print.
    pub fn resolved(&self) -> bool {
        self.trusted && self.median_ns > 0.0 && self.median_ns > self.max_ns - self.min_ns
    }

    /// Where the time does not resolve but was trusted: an upper bound on it, in nanoseconds
    /// per evaluation. The row's own time (the run's less the harness's) is then smaller than
    /// the runs' spread, so it is at most the median (taken as zero when the harness's time
    /// exceeded it) plus that spread. Never negative.
    pub fn upper_bound_ns(&self) -> Option<f64> {
        (self.trusted && !self.resolved())
            .then(|| self.median_ns.max(0.0) + (self.max_ns - self.min_ns).max(0.0))
    }

    /// Evaluations per run, over the whole device.
    pub fn evaluations_per_run(&self) -> u64 {
        u64::from(self.chain) * u64::from(self.invocations)
    }

    /// Evaluations per second over the whole device at the median run: a run's evaluations over
    /// its time, the harness's own time taken off (once [`GpuTime::less`] has), which is
    /// 1e9 / [`GpuTime::median_ns`].
    pub fn evaluations_per_second(&self) -> f64 {
        let evaluations = self.evaluations_per_run() as f64;
        let run_seconds = self.median_ns * evaluations / 1e9;
        evaluations / run_seconds
    }

    /// The time of runs of `chain` evaluations in each of `invocations`, from their durations
    /// in seconds (any order).
    pub fn of_runs(
        stage: Stage,
        clock: Clock,
        mut run_seconds: Vec<f64>,
        chain: u32,
        invocations: u32,
    ) -> GpuTime {
        let ns_per_evaluation = 1e9 / (f64::from(invocations) * f64::from(chain));
        let median = median(&mut run_seconds);
        GpuTime {
            stage,
            clock,
            median_ns: median * ns_per_evaluation,
            min_ns: run_seconds[0] * ns_per_evaluation,
            max_ns: run_seconds[run_seconds.len() - 1] * ns_per_evaluation,
            chain,
            invocations,
            run_ms: median * 1e3,
            trusted: true,
        }
    }
}

/// A row's times in both stages, each less the harness's own (the baseline row's) in that
/// stage; `None` where the stage could not be timed.
#[derive(Clone, Copy, Debug, Default)]
pub struct StageTimes {
    /// The compute dispatch's.
    pub compute: Option<GpuTime>,
    /// The fullscreen draw's.
    pub fragment: Option<GpuTime>,
}

impl StageTimes {
    /// Times `row_wgsl` in both stages (see [`gpu_time`]), less `baseline`'s; a stage that
    /// fails is reported on stderr and left out.
    pub fn measure(
        gpu: &Gpu,
        row_wgsl: &str,
        lut: &[[f32; 2]],
        lut_size: usize,
        baseline: &StageTimes,
    ) -> StageTimes {
        let mut times = StageTimes::default();
        for stage in Stage::ALL {
            *times.get_mut(stage) = gpu_time(gpu, stage, row_wgsl, lut, lut_size)
                .map_err(|error| eprintln!("  {} timing failed: {error}", stage.name()))
                .ok()
                .map(|time| time.less(baseline.get(stage)));
        }
        times
    }

    /// The time in `stage`.
    pub fn get(&self, stage: Stage) -> Option<GpuTime> {
        match stage {
            Stage::Compute => self.compute,
            Stage::Fragment => self.fragment,
        }
    }

    fn get_mut(&mut self, stage: Stage) -> &mut Option<GpuTime> {
        match stage {
            Stage::Compute => &mut self.compute,
            Stage::Fragment => &mut self.fragment,
        }
    }

    /// Marks both stages' times untrusted.
    pub fn distrust(&mut self) {
        for time in [&mut self.compute, &mut self.fragment]
            .into_iter()
            .flatten()
        {
            time.trusted = false;
        }
    }
}

/// The compute shader around a row's `row_eval`, as the static costs count it.
pub fn harness(row_wgsl: &str) -> String {
    harness_with_chain(row_wgsl, CHAIN)
}

/// The fragment shader around a row's `row_eval` with one evaluation, entry point
/// `bench_fragment`, as the GPU compilers cost it.
pub fn fragment_harness(row_wgsl: &str) -> String {
    fragment_harness_with_chain(row_wgsl, 1)
}

/// The fragment stage's shaders around a row's `row_eval`, with `chain` evaluations per
/// pixel: a fullscreen triangle, and a fragment shader whose inputs come from its position.
fn fragment_harness_with_chain(row_wgsl: &str, chain: u32) -> String {
    format!(
        "{row_wgsl}\n\
         @group(0) @binding(2) var lut_texture: texture_2d<f32>;\n\
         @group(0) @binding(3) var lut_sampler: sampler;\n\n\
         {FULLSCREEN_WGSL}\n\
         @fragment\n\
         fn bench_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {{\n\
         \x20   var x = fract(vec4<f32>(position.x * 0.000521, position.y * 0.000927, (position.x + position.y) * 0.00037, 0.5));\n\
         \x20   for (var step = 0u; step < {chain}u; step++) {{\n\
         \x20       x = fract(row_eval(x) * 0.25 + x * 0.75 + vec4<f32>(0.1));\n\
         \x20   }}\n\
         \x20   return x;\n\
         }}\n"
    )
}

/// The compute shader around a row's `row_eval`, with `chain` evaluations per invocation.
fn harness_with_chain(row_wgsl: &str, chain: u32) -> String {
    format!(
        "{row_wgsl}\n\
         @group(0) @binding(0) var<storage, read> bench_inputs: array<vec4<f32>>;\n\
         @group(0) @binding(1) var<storage, read_write> bench_outputs: array<vec4<f32>>;\n\
         @group(0) @binding(2) var lut_texture: texture_2d<f32>;\n\
         @group(0) @binding(3) var lut_sampler: sampler;\n\n\
         @compute @workgroup_size(64)\n\
         fn bench(@builtin(global_invocation_id) id: vec3<u32>) {{\n\
         \x20   var x = bench_inputs[id.x];\n\
         \x20   for (var step = 0u; step < {chain}u; step++) {{\n\
         \x20       x = fract(row_eval(x) * 0.25 + x * 0.75 + vec4<f32>(0.1));\n\
         \x20   }}\n\
         \x20   bench_outputs[id.x] = x;\n\
         }}\n"
    )
}

/// A row whose evaluation is free: its time is the harness's own, subtracted from each row's.
pub const BASELINE_ROW: &str = "fn row_eval(x: vec4<f32>) -> vec4<f32> {\n    return x;\n}\n";

/// Times a row's `row_eval` on the adapter in `stage`, with the environment BRDF LUT texture
/// bound (a `lut_size` square of (scale, bias), or 1x1): the chain of evaluations grows until
/// one run lasts `TARGET_RUN`, then `GPU_RUNS` runs are timed.
pub fn gpu_time(
    gpu: &Gpu,
    stage: Stage,
    row_wgsl: &str,
    lut: &[[f32; 2]],
    lut_size: usize,
) -> Result<GpuTime, String> {
    let device = &gpu.device;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let visibility = match stage {
        Stage::Compute => wgpu::ShaderStages::COMPUTE,
        Stage::Fragment => wgpu::ShaderStages::FRAGMENT,
    };
    let storage = |read_only| wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only },
        has_dynamic_offset: false,
        min_binding_size: None,
    };
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty,
        count: None,
    };
    let mut entries = vec![
        entry(
            2,
            wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: true },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
        ),
        entry(
            3,
            wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
        ),
    ];
    if stage == Stage::Compute {
        entries.extend([entry(0, storage(true)), entry(1, storage(false))]);
    }
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: None,
        entries: &entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let target_format = wgpu::TextureFormat::Rgba32Float;
    let pipeline_for = |chain: u32| match stage {
        Stage::Compute => {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("bench"),
                source: wgpu::ShaderSource::Wgsl(harness_with_chain(row_wgsl, chain).into()),
            });
            Pipeline::Compute(
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("bench"),
                    layout: Some(&pipeline_layout),
                    module: &module,
                    entry_point: Some("bench"),
                    compilation_options: Default::default(),
                    cache: None,
                }),
            )
        }
        Stage::Fragment => {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("bench"),
                source: wgpu::ShaderSource::Wgsl(
                    fragment_harness_with_chain(row_wgsl, chain).into(),
                ),
            });
            Pipeline::Render(gbuffer_gpu::fullscreen::render_pipeline(
                device,
                &module,
                "bench_fragment",
                Some(&pipeline_layout),
                &[Some(target_format.into())],
            ))
        }
    };
    use wgpu::util::DeviceExt;
    let inputs: Vec<[f32; 4]> = (0..INVOCATIONS)
        .map(|index| {
            let t = index as f32 / INVOCATIONS as f32;
            [
                t,
                (t * 7.31).fract(),
                (t * 3.17).fract(),
                (t * 5.53).fract(),
            ]
        })
        .collect();
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: None,
        contents: bytemuck::cast_slice(&inputs),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: 16 * u64::from(INVOCATIONS),
        usage: wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    let target = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("bench target"),
        size: wgpu::Extent3d {
            width: FRAGMENT_WIDTH,
            height: FRAGMENT_HEIGHT,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: target_format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let target_view = target.create_view(&Default::default());
    let lut = gbuffer_render::inputs::lut_texels(lut_size.max(1) as u32, lut);
    let view = gbuffer_render::wgpu::texture_with_data(
        device,
        &gpu.queue,
        "lut",
        wgpu::TextureFormat::Rgba16Float,
        &[lut],
    );
    let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    });
    let mut bind_entries = vec![
        wgpu::BindGroupEntry {
            binding: 2,
            resource: wgpu::BindingResource::TextureView(&view),
        },
        wgpu::BindGroupEntry {
            binding: 3,
            resource: wgpu::BindingResource::Sampler(&sampler),
        },
    ];
    if stage == Stage::Compute {
        bind_entries.extend([
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ]);
    }
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &layout,
        entries: &bind_entries,
    });
    // Timestamps at the pass's start and end, where the device has them.
    let timestamps = device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY)
        .then(|| Timestamps::new(device, "bench timestamps"));
    let compute_timestamps =
        timestamps
            .as_ref()
            .map(|timestamps| wgpu::ComputePassTimestampWrites {
                query_set: &timestamps.query_set,
                beginning_of_pass_write_index: Some(0),
                end_of_pass_write_index: Some(1),
            });
    let render_timestamps = timestamps
        .as_ref()
        .map(|timestamps| wgpu::RenderPassTimestampWrites {
            query_set: &timestamps.query_set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        });
    // A run's seconds: (wall clock, the timestamps' where the device has them).
    let run = |pipeline: &Pipeline| -> Result<(f64, Option<f64>), String> {
        let mut encoder = device.create_command_encoder(&Default::default());
        match pipeline {
            Pipeline::Compute(pipeline) => {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("bench"),
                    timestamp_writes: compute_timestamps.clone(),
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(INVOCATIONS / 64, 1, 1);
            }
            Pipeline::Render(pipeline) => {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("bench"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &target_view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: render_timestamps.clone(),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        if let Some(timestamps) = &timestamps {
            timestamps.resolve(&mut encoder);
        }
        let start = Instant::now();
        gpu.queue.submit([encoder.finish()]);
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| error.to_string())?;
        let wall = start.elapsed().as_secs_f64();
        let stamped = timestamps
            .as_ref()
            .map(|timestamps| timestamps.seconds(&gpu.device, &gpu.queue))
            .transpose()?;
        Ok((wall, stamped))
    };
    // Calibration: each run also warms the pipeline up; the chain grows by twice the factor
    // the run fell short (timed runs vary), at least doubling. A fullscreen draw has a
    // hundred times a dispatch's invocations: its chain starts at one.
    let mut chain = match stage {
        Stage::Compute => CHAIN,
        Stage::Fragment => 1,
    };
    let mut pipeline = pipeline_for(chain);
    if let Some(error) = pollster::block_on(scope.pop()) {
        return Err(error.to_string());
    }
    // The chain is calibrated on the wall clock, which a run cannot undercut.
    loop {
        let (time, _) = run(&pipeline)?;
        if time >= TARGET_RUN || chain >= MAX_CHAIN {
            break;
        }
        let factor = (2.0 * TARGET_RUN / time.max(1e-7)).max(2.0);
        chain = ((f64::from(chain) * factor).ceil() as u32).min(MAX_CHAIN);
        pipeline = pipeline_for(chain);
    }
    // The timed runs, by timestamps where they bracket the work: a device whose timestamps
    // come to less than half the wall clock's time (lavapipe's around a compute dispatch)
    // times something else, and the wall clock is used. Should the median fall short of the
    // target by the clock used (a first run can be the slowest), the chain grows again and
    // they are run again.
    let (clock, times) = loop {
        let runs: Vec<(f64, Option<f64>)> = (0..GPU_RUNS)
            .map(|_| run(&pipeline))
            .collect::<Result<_, _>>()?;
        let mut walls: Vec<f64> = runs.iter().map(|run| run.0).collect();
        let stamped: Option<Vec<f64>> = runs.iter().map(|run| run.1).collect();
        let wall_median = median(&mut walls);
        let (clock, mut times) = match stamped {
            Some(stamped) if 2.0 * median(&mut stamped.clone()) >= wall_median => {
                (Clock::Timestamps, stamped)
            }
            _ => (Clock::Wall, walls),
        };
        let median = median(&mut times);
        if median >= TARGET_RUN || chain >= MAX_CHAIN {
            break (clock, times);
        }
        let factor = (1.5 * TARGET_RUN / median.max(1e-7)).max(1.5);
        chain = ((f64::from(chain) * factor).ceil() as u32).min(MAX_CHAIN);
        pipeline = pipeline_for(chain);
        run(&pipeline)?;
    };
    let invocations = match stage {
        Stage::Compute => INVOCATIONS,
        Stage::Fragment => FRAGMENT_WIDTH * FRAGMENT_HEIGHT,
    };
    Ok(GpuTime::of_runs(stage, clock, times, chain, invocations))
}

/// A timing harness's pipeline, of either stage.
enum Pipeline {
    Compute(wgpu::ComputePipeline),
    Render(wgpu::RenderPipeline),
}

/// A measured item for the consistency check: its name, SPIR-V instructions and time.
pub struct Timed<'a> {
    /// Names the item in a message.
    pub name: String,
    /// Its SPIR-V instructions.
    pub instructions: usize,
    /// Its time, where measured.
    pub time: Option<&'a GpuTime>,
}

/// Pairs of one group whose order the instruction counts predict (one has at least twice the
/// other's instructions) but whose resolved times say the opposite: a line each. Empty when
/// the adapter's times can be trusted.
pub fn inconsistencies(group: &[Timed]) -> Vec<String> {
    let mut found = Vec::new();
    for cheap in group {
        for dear in group {
            let (Some(cheap_time), Some(dear_time)) = (cheap.time, dear.time) else {
                continue;
            };
            let predicted = 2 * cheap.instructions <= dear.instructions;
            if predicted
                && cheap_time.resolved()
                && dear_time.resolved()
                && cheap_time.min_ns > dear_time.max_ns
            {
                found.push(format!(
                    "{} ({} instructions) took {:.3} ns, more than {} ({} instructions) at {:.3} ns",
                    cheap.name,
                    cheap.instructions,
                    cheap_time.median_ns,
                    dear.name,
                    dear.instructions,
                    dear_time.median_ns
                ));
            }
        }
    }
    found
}

/// Nanoseconds per evaluation of a row's CPU mirror, chained as on the GPU (median of runs).
pub fn cpu_ns_per_eval(evaluate: &dyn Fn(Vec4) -> Vec4) -> f64 {
    const EVALUATIONS: u32 = 1 << 16;
    let mut times = Vec::new();
    for _ in 0..CPU_RUNS {
        let mut x = Vec4::new(0.3, 0.6, 0.2, 0.7);
        let start = Instant::now();
        for _ in 0..EVALUATIONS {
            let y = evaluate(std::hint::black_box(x));
            x = (y * 0.25 + x * 0.75 + Vec4::splat(0.1)).fract();
        }
        std::hint::black_box(x);
        times.push(start.elapsed().as_secs_f64());
    }
    median(&mut times) * 1e9 / f64::from(EVALUATIONS)
}

/// The median of `values` (sorted in place); they must not be empty.
pub(crate) fn median(values: &mut [f64]) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs whose evaluations and times are known: 7 runs of 100 evaluations in each of 1000
    /// invocations (1e5 a run), the median lasting 10 ms, give 100 ns per evaluation and 1e7
    /// evaluations a second; with a harness whose median run lasts 2 ms taken off, 80 ns and
    /// 1e5 evaluations in 8 ms.
    #[test]
    fn the_units_are_what_their_names_say() {
        let runs = vec![0.011, 0.0095, 0.010, 0.0102, 0.0099, 0.0105, 0.0098];
        let time = GpuTime::of_runs(Stage::Compute, Clock::Wall, runs, 100, 1000);
        assert_eq!(time.evaluations_per_run(), 100_000);
        assert!((time.median_ns - 100.0).abs() < 1e-9, "{}", time.median_ns);
        assert!((time.run_ms - 10.0).abs() < 1e-9);
        assert!((time.min_ns - 95.0).abs() < 1e-9 && (time.max_ns - 110.0).abs() < 1e-9);
        assert!((time.evaluations_per_second() - 1e7).abs() < 1e-3);
        let harness = GpuTime::of_runs(Stage::Compute, Clock::Wall, vec![0.002; 7], 100, 1000);
        let less = time.less(Some(harness));
        assert!((less.median_ns - 80.0).abs() < 1e-9);
        assert!((less.evaluations_per_second() - 1e5 / 0.008).abs() < 1e-3);
    }

    /// A row faster than the harness can tell (its median, less the harness's, below zero: the
    /// "fully rough" row read -0.11 ns on llvmpipe) reports an upper bound, never a negative
    /// time; a resolved row reports none.
    #[test]
    fn a_time_below_the_resolution_is_an_upper_bound() {
        let runs = vec![0.0100, 0.0104, 0.0098, 0.0101, 0.0099, 0.0102, 0.0097];
        let row = GpuTime::of_runs(Stage::Compute, Clock::Wall, runs, 100, 1000);
        let harness = GpuTime::of_runs(Stage::Compute, Clock::Wall, vec![0.0101; 7], 100, 1000);
        let less = row.less(Some(harness));
        assert!(less.median_ns < 0.0 && !less.resolved());
        let bound = less.upper_bound_ns().unwrap();
        // Spread 7 ns (97 to 104 ns a run), the median taken as zero.
        assert!((bound - 7.0).abs() < 1e-6, "{bound}");
        assert_eq!(time(100.0).upper_bound_ns(), None);
        let mut untrusted = less;
        untrusted.trusted = false;
        assert_eq!(untrusted.upper_bound_ns(), None);
    }

    fn time(median_ns: f64) -> GpuTime {
        GpuTime {
            stage: Stage::Compute,
            clock: Clock::Wall,
            median_ns,
            min_ns: median_ns * 0.95,
            max_ns: median_ns * 1.05,
            chain: 64,
            invocations: INVOCATIONS,
            run_ms: 10.0,
            trusted: true,
        }
    }

    /// A builtin of 16 instructions and an exact conversion of 44, timed as given.
    fn pair<'a>(builtin: &'a GpuTime, exact: &'a GpuTime) -> Vec<Timed<'a>> {
        vec![
            Timed {
                name: "builtin".into(),
                instructions: 16,
                time: Some(builtin),
            },
            Timed {
                name: "exact".into(),
                instructions: 44,
                time: Some(exact),
            },
        ]
    }

    #[test]
    fn both_stages_calibrate_their_runs_to_ten_milliseconds_on_the_adapter() {
        let row =
            "fn row_eval(x: vec4<f32>) -> vec4<f32> {\n    return sqrt(x + vec4<f32>(0.5));\n}\n";
        // With the timestamp feature where the adapter has it, and without: the wall clock.
        let with_timestamps = gbuffer_testkit::gpu_with(None, wgpu::Features::TIMESTAMP_QUERY);
        let Some(with_timestamps) = with_timestamps else {
            return;
        };
        for gpu in [with_timestamps, gbuffer_testkit::gpu().unwrap()] {
            let timestamps = gpu
                .device
                .features()
                .contains(wgpu::Features::TIMESTAMP_QUERY);
            for stage in Stage::ALL {
                let time = gpu_time(&gpu, stage, row, &[], 1).unwrap();
                assert_eq!(time.stage, stage);
                // Timestamps only where the device has them (and they bracket the work).
                if !timestamps {
                    assert_eq!(time.clock, Clock::Wall);
                }
                eprintln!("{stage:?}: {} clock, {time:?}", time.clock.name());
                assert!(
                    time.run_ms >= 1e3 * TARGET_RUN || time.chain == MAX_CHAIN,
                    "{stage:?}: {time:?}"
                );
                assert!(time.min_ns <= time.median_ns && time.median_ns <= time.max_ns);
                let invocations = match stage {
                    Stage::Compute => INVOCATIONS,
                    Stage::Fragment => FRAGMENT_WIDTH * FRAGMENT_HEIGHT,
                };
                assert_eq!(time.invocations, invocations);
            }
        }
    }

    #[test]
    fn times_out_of_the_predicted_order_are_found_and_others_are_not() {
        let (fast, slow) = (time(2.0), time(5.0));
        assert!(inconsistencies(&pair(&fast, &slow)).is_empty());
        let found = inconsistencies(&pair(&slow, &fast));
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].starts_with("builtin (16 instructions) took 5.000 ns"));
        // Untrusted or unresolved times are not compared.
        let untrusted = GpuTime {
            trusted: false,
            ..slow
        };
        assert!(inconsistencies(&pair(&untrusted, &fast)).is_empty());
    }
}
