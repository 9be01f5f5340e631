//! The rows' times on the adapter, by the protocol of `gbuffer_gpu::timing`: every row's
//! pipeline built first, the clock warmed up on the harness alone, each row's chain calibrated
//! until a run lasts `TARGET_RUN` and doubling the chain doubles the time and adds at least
//! `TARGET_ADDED`, then every row timed once a round for the protocol's rounds, at its chain and
//! at twice it: its time is what the second chain adds.

use std::time::Instant;

use gbuffer_core::Named;
use gbuffer_gpu::timestamps::Timestamps;
use gbuffer_gpu::timing::{doubles, in_rounds, warm_up, Protocol, Spread};
use gbuffer_gpu::Gpu;

use super::harness::{compute_harness, fragment_harness_with, Chain, BASELINE_ROW};
use super::{
    Calibration, Clock, GpuTime, Stage, StageTimes, FRAGMENT_HEIGHT, FRAGMENT_WIDTH, INVOCATIONS,
    MAX_CHAIN, TARGET_ADDED, TARGET_RUN,
};

/// A row to time: its WGSL (`row_eval`) and the environment BRDF LUT it samples (a `lut_size`
/// square of (scale, bias), or 1x1 when empty).
struct TimedRow {
    name: String,
    wgsl: String,
    lut: Vec<[f32; 2]>,
    lut_size: usize,
}

/// Collects the rows of a report, then times them all together ([`Timer::run`]), the harness's
/// own time (an empty chain) among them.
pub struct Timer<'a> {
    gpu: &'a Gpu,
    protocol: Protocol,
    rows: Vec<TimedRow>,
}

impl<'a> Timer<'a> {
    /// A timer on `gpu` by `protocol`, holding the harness's baseline row.
    pub fn new(gpu: &'a Gpu, protocol: Protocol) -> Timer<'a> {
        Timer {
            gpu,
            protocol,
            rows: vec![TimedRow {
                name: "the harness".to_string(),
                wgsl: BASELINE_ROW.to_string(),
                lut: Vec::new(),
                lut_size: 1,
            }],
        }
    }

    /// Adds a row; its index in [`Timer::run`]'s times.
    pub fn add(&mut self, name: &str, row_wgsl: &str, lut: &[[f32; 2]], lut_size: usize) -> usize {
        self.rows.push(TimedRow {
            name: name.to_string(),
            wgsl: row_wgsl.to_string(),
            lut: lut.to_vec(),
            lut_size,
        });
        self.rows.len() - 2
    }

    /// Every added row's times in both stages, less the harness's in that stage, in the order
    /// added. A row or stage that fails is reported on stderr and left out.
    pub fn run(&self) -> Vec<StageTimes> {
        self.run_in(Stage::ALL)
    }

    /// As [`Timer::run`], in `stages` only (the others' times left `None`).
    pub fn run_in(&self, stages: &[Stage]) -> Vec<StageTimes> {
        let mut times = vec![StageTimes::default(); self.rows.len()];
        for &stage in stages {
            let stage_times = self
                .run_stage(stage)
                .map_err(|error| eprintln!("{} timing failed: {error}", stage.name()))
                .unwrap_or_default();
            let baseline = stage_times.first().copied().flatten();
            for (row, time) in times.iter_mut().zip(stage_times) {
                *row.get_mut(stage) = time.map(|time| time.less(baseline));
            }
        }
        times.remove(0);
        times
    }

    /// Every row's time in `stage` (the baseline's first), not yet less the baseline's.
    fn run_stage(&self, stage: Stage) -> Result<Vec<Option<GpuTime>>, String> {
        let bench = Bench::new(self.gpu, stage);
        let mut items: Vec<Option<Item>> = self
            .rows
            .iter()
            .map(|row| {
                bench
                    .item(row)
                    .map_err(|error| eprintln!("  {} ({}): {error}", row.name, stage.name()))
                    .ok()
            })
            .collect();
        let baseline = items[0]
            .as_mut()
            .ok_or("the harness's own pipeline failed")?;
        eprintln!("timing {} rows ({})...", self.rows.len(), stage.name());
        // The harness is sized first, for the warm-up's runs; every row, the harness again
        // among them, is sized once the clock has settled (on a cold clock every chain would
        // come out too short).
        bench.calibrate(baseline, &self.protocol)?;
        let warm = warm_up(&self.protocol, &mut || {
            bench
                .run(baseline, baseline.calibration.chain)
                .map(|run| run.0)
        })?;
        if !warm.settled {
            eprintln!(
                "  the clock did not settle in {} runs: the spreads show it",
                warm.runs
            );
        }
        for (row, item) in self.rows.iter().zip(&mut items) {
            if let Some(found) = item {
                if let Err(error) = bench.calibrate(found, &self.protocol) {
                    eprintln!("  {} ({}): {error}", row.name, stage.name());
                    *item = None;
                }
            }
        }
        // Each round times a row at its chain and at twice it: the difference is what the chain
        // costs, without the run's fixed part (the launch, each invocation's loads and
        // stores), which a short chain (2 to 16 steps on lavapipe) would otherwise carry. Each
        // is the faster of two runs: another process's load only adds to a run, and one slow
        // run would move the difference by all of its delay.
        let timed: Vec<&Item> = items.iter().flatten().collect();
        let mut runs = vec![Vec::new(); timed.len()];
        let added = in_rounds(&self.protocol, timed.len(), &mut |index| {
            let item = timed[index];
            let chain = item.calibration.chain;
            let (single, double) = (bench.seconds(item, chain)?, bench.seconds(item, 2 * chain)?);
            runs[index].push(single);
            Ok(double - single)
        })?;
        let mut timed = added.into_iter().zip(&runs);
        Ok(items
            .iter()
            .map(|item| {
                let item = item.as_ref()?;
                let (added, runs) = timed.next()?;
                Some(GpuTime::of_runs(
                    stage,
                    item.clock,
                    added,
                    Spread::of(runs)?.median,
                    Chain::Uniform.chains(),
                    bench.invocations(),
                    item.calibration,
                ))
            })
            .collect())
    }
}

/// A row's pipeline and bindings in one stage, and what calibration found.
struct Item {
    pipeline: Pipeline,
    bind_group: wgpu::BindGroup,
    clock: Clock,
    /// The chain, and a run of twice the chain over a run of the chain (best of two each).
    calibration: Calibration,
}

/// A timing harness's pipeline, of either stage.
enum Pipeline {
    Compute(wgpu::ComputePipeline),
    Render(wgpu::RenderPipeline),
}

/// What every row's runs in one stage share: the bind group layout, the compute stage's input
/// and output buffers, the fragment stage's 1920x1080 target, the chain's uniform and the
/// timestamp queries where the device has them.
struct Bench<'a> {
    gpu: &'a Gpu,
    stage: Stage,
    layout: wgpu::BindGroupLayout,
    pipeline_layout: wgpu::PipelineLayout,
    buffers: Option<(wgpu::Buffer, wgpu::Buffer)>,
    chain: wgpu::Buffer,
    sampler: wgpu::Sampler,
    target_view: wgpu::TextureView,
    timestamps: Option<Timestamps>,
}

/// The fragment stage's target format: four floats, so that no output is rounded away.
const TARGET_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

impl<'a> Bench<'a> {
    /// The layout, buffers and target of `stage`'s runs.
    fn new(gpu: &'a Gpu, stage: Stage) -> Bench<'a> {
        let device = &gpu.device;
        let visibility = match stage {
            Stage::Compute => wgpu::ShaderStages::COMPUTE,
            Stage::Fragment => wgpu::ShaderStages::FRAGMENT,
        };
        let buffer = |ty| wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        };
        let storage = |read_only| buffer(wgpu::BufferBindingType::Storage { read_only });
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
            entry(4, buffer(wgpu::BufferBindingType::Uniform)),
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
            format: TARGET_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
            view_formats: &[],
        });
        Bench {
            gpu,
            stage,
            buffers: (stage == Stage::Compute).then(|| compute_buffers(device)),
            chain: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("bench chain"),
                size: 16,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            sampler: device.create_sampler(&wgpu::SamplerDescriptor {
                mag_filter: wgpu::FilterMode::Linear,
                min_filter: wgpu::FilterMode::Linear,
                ..Default::default()
            }),
            layout,
            pipeline_layout,
            target_view: target.create_view(&Default::default()),
            // Timestamps at the pass's start and end, where the device has them.
            timestamps: device
                .features()
                .contains(wgpu::Features::TIMESTAMP_QUERY)
                .then(|| Timestamps::new(device, "bench timestamps")),
        }
    }

    /// Invocations per run: one per thread of the dispatch, or per pixel of the target.
    fn invocations(&self) -> u32 {
        match self.stage {
            Stage::Compute => INVOCATIONS,
            Stage::Fragment => FRAGMENT_WIDTH * FRAGMENT_HEIGHT,
        }
    }

    /// `row`'s pipeline and bind group in this stage, not yet calibrated. The error is wgpu's.
    fn item(&self, row: &TimedRow) -> Result<Item, String> {
        let device = &self.gpu.device;
        let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let source = match self.stage {
            Stage::Compute => compute_harness(&row.wgsl, Chain::Uniform),
            Stage::Fragment => fragment_harness_with(&row.wgsl, Chain::Uniform),
        };
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("bench"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline = match self.stage {
            Stage::Compute => Pipeline::Compute(device.create_compute_pipeline(
                &wgpu::ComputePipelineDescriptor {
                    label: Some("bench"),
                    layout: Some(&self.pipeline_layout),
                    module: &module,
                    entry_point: Some("bench"),
                    compilation_options: Default::default(),
                    cache: None,
                },
            )),
            Stage::Fragment => Pipeline::Render(gbuffer_gpu::fullscreen::render_pipeline(
                device,
                &module,
                "bench_fragment",
                Some(&self.pipeline_layout),
                &[Some(TARGET_FORMAT.into())],
            )),
        };
        let lut = gbuffer_render::inputs::lut_texels(row.lut_size.max(1) as u32, &row.lut);
        let view = gbuffer_render::wgpu::texture_with_data(
            device,
            &self.gpu.queue,
            "lut",
            wgpu::TextureFormat::Rgba16Float,
            &[lut],
        );
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&view),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Sampler(&self.sampler),
            },
            wgpu::BindGroupEntry {
                binding: 4,
                resource: self.chain.as_entire_binding(),
            },
        ];
        if let Some((input, output)) = &self.buffers {
            entries.extend([
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
            layout: &self.layout,
            entries: &entries,
        });
        if let Some(error) = pollster::block_on(scope.pop()) {
            return Err(error.to_string());
        }
        Ok(Item {
            pipeline,
            bind_group,
            clock: Clock::Wall,
            calibration: Calibration {
                chain: 1,
                doubling_ratio: 0.0,
                doubled: false,
            },
        })
    }

    /// One run of `item` with `chain` evaluations per invocation: its seconds (wall clock
    /// around a synchronised submit, the timestamps' where the device has them).
    fn run(&self, item: &Item, chain: u32) -> Result<(f64, Option<f64>), String> {
        let Gpu { device, queue, .. } = self.gpu;
        queue.write_buffer(&self.chain, 0, bytemuck::cast_slice(&[chain, 0, 0, 0]));
        let mut encoder = device.create_command_encoder(&Default::default());
        let query_set = self
            .timestamps
            .as_ref()
            .map(|timestamps| &timestamps.query_set);
        match &item.pipeline {
            Pipeline::Compute(pipeline) => {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("bench"),
                    timestamp_writes: query_set.map(|query_set| wgpu::ComputePassTimestampWrites {
                        query_set,
                        beginning_of_pass_write_index: Some(0),
                        end_of_pass_write_index: Some(1),
                    }),
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &item.bind_group, &[]);
                pass.dispatch_workgroups(INVOCATIONS / 64, 1, 1);
            }
            Pipeline::Render(pipeline) => {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("bench"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &self.target_view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    depth_stencil_attachment: None,
                    timestamp_writes: query_set.map(|query_set| wgpu::RenderPassTimestampWrites {
                        query_set,
                        beginning_of_pass_write_index: Some(0),
                        end_of_pass_write_index: Some(1),
                    }),
                    occlusion_query_set: None,
                    multiview_mask: None,
                });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &item.bind_group, &[]);
                pass.draw(0..3, 0..1);
            }
        }
        if let Some(timestamps) = &self.timestamps {
            timestamps.resolve(&mut encoder);
        }
        let start = Instant::now();
        queue.submit([encoder.finish()]);
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| error.to_string())?;
        let wall = start.elapsed().as_secs_f64();
        let stamped = self
            .timestamps
            .as_ref()
            .map(|timestamps| timestamps.seconds(device, queue))
            .transpose()?;
        Ok((wall, stamped))
    }

    /// The seconds of the faster of two runs of `item` with `chain` evaluations per
    /// invocation, by its clock.
    fn seconds(&self, item: &Item, chain: u32) -> Result<f64, String> {
        let (wall, stamped) = self.best_of_two(item, chain)?;
        Ok(match item.clock {
            Clock::Timestamps => stamped.unwrap_or(wall),
            Clock::Wall => wall,
        })
    }

    /// The faster of two runs of `chain`, by the wall clock and by the timestamps.
    fn best_of_two(&self, item: &Item, chain: u32) -> Result<(f64, Option<f64>), String> {
        let (first, second) = (self.run(item, chain)?, self.run(item, chain)?);
        let stamped = match (first.1, second.1) {
            (Some(a), Some(b)) => Some(a.min(b)),
            _ => None,
        };
        Ok((first.0.min(second.0), stamped))
    }

    /// Sizes `item`'s chain: it grows until a run lasts `TARGET_RUN` by the wall clock (which a
    /// run cannot undercut), then doubles until a run of twice the chain takes twice as long
    /// (the protocol's tolerance) and the second chain adds at least `TARGET_ADDED` to the
    /// run, or reaches `MAX_CHAIN`. The clock: the timestamps where
    /// they bracket the work (at least half the wall clock's time; lavapipe's around a compute
    /// dispatch come to a fraction of it), else the wall clock.
    fn calibrate(&self, item: &mut Item, protocol: &Protocol) -> Result<(), String> {
        let mut chain = item.calibration.chain.max(1);
        loop {
            let (wall, _) = self.run(item, chain)?;
            if wall >= TARGET_RUN || chain >= MAX_CHAIN {
                break;
            }
            // Twice the factor the run fell short by (runs vary), at least doubling.
            let factor = (2.0 * TARGET_RUN / wall.max(1e-7)).max(2.0);
            chain = ((f64::from(chain) * factor).ceil() as u32).min(MAX_CHAIN);
        }
        loop {
            let single = self.best_of_two(item, chain)?;
            let double = self.best_of_two(item, 2 * chain)?;
            let (clock, single, double) = match (single.1, double.1) {
                (Some(stamped), Some(stamped_double)) if 2.0 * stamped >= single.0 => {
                    (Clock::Timestamps, stamped, stamped_double)
                }
                _ => (Clock::Wall, single.0, double.0),
            };
            item.clock = clock;
            item.calibration = Calibration {
                chain,
                doubling_ratio: double / single,
                doubled: doubles(protocol, single, double),
            };
            // The time is what the chain adds to a run (`Timer::run_stage`): it must itself
            // last the target, or a short chain's few milliseconds drown in a run's noise.
            let resolves = item.calibration.doubled && double - single >= TARGET_ADDED;
            if resolves || 2 * chain > MAX_CHAIN {
                return Ok(());
            }
            chain *= 2;
        }
    }
}

/// The compute stage's input (a spread of values in [0, 1)) and output buffers, one vec4 per
/// invocation.
fn compute_buffers(device: &wgpu::Device) -> (wgpu::Buffer, wgpu::Buffer) {
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
    (input, output)
}
