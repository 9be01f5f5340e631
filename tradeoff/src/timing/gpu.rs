//! A row's time on the adapter: the bindings and target a stage's runs share ([`Bench`]), one
//! run timed by the wall clock and by timestamps, the chain calibrated on the wall clock, then
//! the timed runs.

use std::time::Instant;

use gbuffer_gpu::timestamps::Timestamps;
use gbuffer_gpu::Gpu;

use super::harness::{fragment_harness_with_chain, harness_with_chain};
use super::{
    median, Clock, GpuTime, Stage, CHAIN, FRAGMENT_HEIGHT, FRAGMENT_WIDTH, GPU_RUNS, INVOCATIONS,
    MAX_CHAIN, TARGET_RUN,
};

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
    let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
    let bench = Bench::new(gpu, stage, lut, lut_size);
    // A fullscreen draw has a hundred times a dispatch's invocations: its chain starts at one.
    let chain = match stage {
        Stage::Compute => CHAIN,
        Stage::Fragment => 1,
    };
    let pipeline = bench.pipeline(row_wgsl, chain);
    if let Some(error) = pollster::block_on(scope.pop()) {
        return Err(error.to_string());
    }
    let (chain, pipeline) = bench.calibrate(row_wgsl, chain, pipeline)?;
    let (chain, clock, times) = bench.timed_runs(row_wgsl, chain, pipeline)?;
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

/// What every run of one row in one stage shares: the bind group (the LUT and its sampler, and
/// for compute the input and output buffers), the fragment stage's 1920x1080 target, and the
/// timestamp queries where the device has them.
struct Bench<'a> {
    gpu: &'a Gpu,
    stage: Stage,
    pipeline_layout: wgpu::PipelineLayout,
    bind_group: wgpu::BindGroup,
    target_view: wgpu::TextureView,
    timestamps: Option<Timestamps>,
}

/// The fragment stage's target format: four floats, so that no output is rounded away.
const TARGET_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

impl<'a> Bench<'a> {
    /// The bindings and target of `stage`'s runs, with the LUT (`lut_size` square, or 1x1).
    fn new(gpu: &'a Gpu, stage: Stage, lut: &[[f32; 2]], lut_size: usize) -> Bench<'a> {
        let device = &gpu.device;
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
        let buffers = (stage == Stage::Compute).then(|| compute_buffers(device));
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
        if let Some((input, output)) = &buffers {
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
        Bench {
            gpu,
            stage,
            pipeline_layout,
            bind_group,
            target_view: target.create_view(&Default::default()),
            timestamps,
        }
    }

    /// The stage's pipeline around `row_wgsl` with `chain` evaluations per invocation.
    fn pipeline(&self, row_wgsl: &str, chain: u32) -> Pipeline {
        let device = &self.gpu.device;
        match self.stage {
            Stage::Compute => {
                let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some("bench"),
                    source: wgpu::ShaderSource::Wgsl(harness_with_chain(row_wgsl, chain).into()),
                });
                Pipeline::Compute(device.create_compute_pipeline(
                    &wgpu::ComputePipelineDescriptor {
                        label: Some("bench"),
                        layout: Some(&self.pipeline_layout),
                        module: &module,
                        entry_point: Some("bench"),
                        compilation_options: Default::default(),
                        cache: None,
                    },
                ))
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
                    Some(&self.pipeline_layout),
                    &[Some(TARGET_FORMAT.into())],
                ))
            }
        }
    }

    /// One run's seconds: (wall clock around a synchronised submit, the timestamps' where the
    /// device has them).
    fn run(&self, pipeline: &Pipeline) -> Result<(f64, Option<f64>), String> {
        let Gpu { device, queue, .. } = self.gpu;
        let mut encoder = device.create_command_encoder(&Default::default());
        let query_set = self
            .timestamps
            .as_ref()
            .map(|timestamps| &timestamps.query_set);
        match pipeline {
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
                pass.set_bind_group(0, &self.bind_group, &[]);
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
                pass.set_bind_group(0, &self.bind_group, &[]);
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

    /// Grows the chain until a run lasts `TARGET_RUN` by the wall clock, which a run cannot
    /// undercut: each run also warms the pipeline up, and the chain grows by twice the factor
    /// the run fell short (timed runs vary), at least doubling. The chain and its pipeline.
    fn calibrate(
        &self,
        row_wgsl: &str,
        mut chain: u32,
        mut pipeline: Pipeline,
    ) -> Result<(u32, Pipeline), String> {
        loop {
            let (time, _) = self.run(&pipeline)?;
            if time >= TARGET_RUN || chain >= MAX_CHAIN {
                return Ok((chain, pipeline));
            }
            let factor = (2.0 * TARGET_RUN / time.max(1e-7)).max(2.0);
            chain = ((f64::from(chain) * factor).ceil() as u32).min(MAX_CHAIN);
            pipeline = self.pipeline(row_wgsl, chain);
        }
    }

    /// `GPU_RUNS` timed runs, by timestamps where they bracket the work: a device whose
    /// timestamps come to less than half the wall clock's time (lavapipe's around a compute
    /// dispatch) times something else, and the wall clock is used. Should the median fall
    /// short of the target by the clock used (a first run can be the slowest), the chain grows
    /// again and they are run again. The final chain, the clock and the runs' seconds.
    fn timed_runs(
        &self,
        row_wgsl: &str,
        mut chain: u32,
        mut pipeline: Pipeline,
    ) -> Result<(u32, Clock, Vec<f64>), String> {
        loop {
            let runs: Vec<(f64, Option<f64>)> = (0..GPU_RUNS)
                .map(|_| self.run(&pipeline))
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
                return Ok((chain, clock, times));
            }
            let factor = (1.5 * TARGET_RUN / median.max(1e-7)).max(1.5);
            chain = ((f64::from(chain) * factor).ceil() as u32).min(MAX_CHAIN);
            pipeline = self.pipeline(row_wgsl, chain);
            self.run(&pipeline)?;
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
