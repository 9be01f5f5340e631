//! A real adapter for the tests: whatever wgpu finds (on CI, Mesa's lavapipe through Vulkan or
//! llvmpipe through GL). No adapter is a failure that names what was tried, never a skip.

use wgpu::util::DeviceExt;

/// A wgpu device on a real adapter, with helpers to run compute shaders.
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's name, backend and driver.
    pub info: wgpu::AdapterInfo,
}

impl Gpu {
    /// Opens the adapter wgpu prefers among the backends `WGPU_BACKEND` allows (all by
    /// default), with its full limits. Panics, naming the backends and adapters it saw, when
    /// none can be opened.
    // Not `Default`: opening an adapter can fail, and a default value should not panic.
    #[allow(clippy::new_without_default)]
    pub fn new() -> Gpu {
        Gpu::open(None, wgpu::Features::empty())
    }

    /// As [`Gpu::new`], with those of `features` the adapter has (e.g. timestamp queries).
    pub fn with_features(features: wgpu::Features) -> Gpu {
        Gpu::open(None, features)
    }

    /// As [`Gpu::new`], but with the adapter's limits lowered to the given ones (so WebGPU's
    /// default limits can be enforced on a more capable adapter) and with those of `features`
    /// the adapter has.
    pub fn with_limits_and_features(limits: wgpu::Limits, features: wgpu::Features) -> Gpu {
        Gpu::open(Some(limits), features)
    }

    fn open(limits: Option<wgpu::Limits>, features: wgpu::Features) -> Gpu {
        let descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
        let backends = descriptor.backends;
        let instance = wgpu::Instance::new(descriptor);
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        };
        let adapter = match pollster::block_on(instance.request_adapter(&options)) {
            Ok(adapter) => adapter,
            Err(error) => {
                let seen: Vec<String> = pollster::block_on(instance.enumerate_adapters(backends))
                    .iter()
                    .map(|adapter| format!("{:?}", adapter.get_info()))
                    .collect();
                panic!(
                    "no GPU adapter: wgpu tried the backends {backends:?} and found {seen:?} ({error}). \
                     The GPU tests need a real adapter; on a machine without a GPU install Mesa's \
                     software drivers (`apt-get install -y mesa-vulkan-drivers libegl1` gives \
                     lavapipe and llvmpipe), or choose a backend with WGPU_BACKEND=vulkan|gl."
                )
            }
        };
        let info = adapter.get_info();
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("tests"),
            required_features: features & adapter.features(),
            required_limits: match limits {
                Some(limits) => limits.or_worse_values_from(&adapter.limits()),
                None => adapter.limits(),
            },
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
            .unwrap_or_else(|error| panic!("could not open a device on {info:?}: {error}"));
        Gpu {
            device,
            queue,
            info,
        }
    }

    /// A short description of the adapter for test output.
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {})",
            self.info.name, self.info.backend, self.info.driver
        )
    }

    /// Runs `entry_point` of `wgsl` over `count` invocations (64 per workgroup) with binding 0
    /// the `inputs`, bindings 1.. the outputs of the given lengths in u32s, and the last
    /// binding a uniform `vec4<u32>(count, 0, 0, 0)`. Returns the outputs.
    pub fn run_compute(
        &self,
        wgsl: &str,
        entry_point: &str,
        inputs: &[u32],
        output_lengths: &[usize],
        count: u32,
    ) -> Vec<Vec<u32>> {
        let device = &self.device;
        let error_scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(entry_point),
            source: wgpu::ShaderSource::Wgsl(wgsl.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(entry_point),
            layout: None,
            module: &module,
            entry_point: Some(entry_point),
            compilation_options: Default::default(),
            cache: None,
        });
        let storage = |contents: &[u32], usage| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(contents),
                usage,
            })
        };
        let input = storage(inputs, wgpu::BufferUsages::STORAGE);
        let outputs: Vec<wgpu::Buffer> = output_lengths
            .iter()
            .map(|&length| {
                storage(
                    &vec![0u32; length],
                    wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                )
            })
            .collect();
        let parameters = storage(&[count, 0, 0, 0], wgpu::BufferUsages::UNIFORM);
        let mut entries = vec![wgpu::BindGroupEntry {
            binding: 0,
            resource: input.as_entire_binding(),
        }];
        for (index, output) in outputs.iter().enumerate() {
            entries.push(wgpu::BindGroupEntry {
                binding: index as u32 + 1,
                resource: output.as_entire_binding(),
            });
        }
        entries.push(wgpu::BindGroupEntry {
            binding: outputs.len() as u32 + 1,
            resource: parameters.as_entire_binding(),
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });

        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(count.div_ceil(64), 1, 1);
        }
        let staging: Vec<wgpu::Buffer> = output_lengths
            .iter()
            .zip(&outputs)
            .map(|(&length, output)| {
                let staging = device.create_buffer(&wgpu::BufferDescriptor {
                    label: None,
                    size: 4 * length as u64,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                encoder.copy_buffer_to_buffer(output, 0, &staging, 0, 4 * length as u64);
                staging
            })
            .collect();
        self.queue.submit([encoder.finish()]);
        if let Some(error) = pollster::block_on(error_scope.pop()) {
            panic!("wgpu rejected the compute shader `{entry_point}`: {error}");
        }
        staging.iter().map(|buffer| self.read(buffer)).collect()
    }

    fn read(&self, buffer: &wgpu::Buffer) -> Vec<u32> {
        let slice = buffer.slice(..);
        slice.map_async(wgpu::MapMode::Read, |result| {
            result.expect("mapping a staging buffer")
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("waiting for the GPU");
        let view = slice
            .get_mapped_range()
            .expect("reading a mapped staging buffer");
        let words = bytemuck::cast_slice(&view).to_vec();
        drop(view);
        buffer.unmap();
        words
    }
}
