//! A wgpu device on a real adapter, opened without a window: whatever wgpu finds among the
//! backends `WGPU_BACKEND` allows (on a machine without a GPU, Mesa's lavapipe through Vulkan or
//! llvmpipe through GL). Not finding one is an error that names what was tried.

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

/// What a device is opened with.
#[derive(Clone, Debug, Default)]
pub struct Request {
    /// The device's label, for wgpu's messages.
    pub label: &'static str,
    /// Limits to hold the device to (lowered from the adapter's own, so that, say, WebGPU's
    /// defaults can be enforced on a more capable adapter); `None` takes the adapter's.
    pub limits: Option<wgpu::Limits>,
    /// Features wanted: those of them the adapter has are enabled (timestamp queries, say).
    pub features: wgpu::Features,
    /// The backends to look on (`wgpu::Backends::GL` for WebGL2's), where the caller chooses;
    /// `None` takes `WGPU_BACKEND`, else the primary backends first and then any.
    pub backends: Option<wgpu::Backends>,
}

impl Gpu {
    /// Opens the adapter wgpu prefers, with its full limits and no optional features.
    pub fn new() -> Result<Gpu, String> {
        Gpu::open(&Request {
            label: "gbuffer",
            ..Request::default()
        })
    }

    /// Opens the adapter wgpu prefers among the backends `WGPU_BACKEND` allows: the primary
    /// backends (Vulkan, Metal, DX12) first, GL only where none offers an adapter. wgpu's GL
    /// backend opens the process's EGL display and terminates it when dropped, which would end
    /// any other GLES context of the process (the on-tile renderer's, a test's) on that display.
    /// The error names the backends tried, the adapters seen and how to get one.
    pub fn open(request: &Request) -> Result<Gpu, String> {
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            apply_limit_buckets: false,
        };
        let instance = |backends| {
            let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
            descriptor.backends = backends;
            wgpu::Instance::new(descriptor)
        };
        let request_adapter =
            |backends| pollster::block_on(instance(backends).request_adapter(&options));
        let chosen = request.backends.or_else(wgpu::Backends::from_env);
        let adapter = match chosen {
            Some(backends) => request_adapter(backends),
            None => request_adapter(wgpu::Backends::PRIMARY)
                .or_else(|_| request_adapter(wgpu::Backends::all())),
        };
        let adapter = adapter.map_err(|error| {
            let backends = chosen.unwrap_or(wgpu::Backends::all());
            let seen: Vec<String> =
                pollster::block_on(instance(backends).enumerate_adapters(backends))
                    .iter()
                    .map(|adapter| adapter.get_info().name)
                    .collect();
            format!(
                "no GPU adapter: wgpu tried the backends {backends:?} and found {seen:?} ({error}); \
                 without a GPU install Mesa's software drivers (apt-get install -y \
                 mesa-vulkan-drivers libegl1), or choose a backend with WGPU_BACKEND=vulkan|gl"
            )
        })?;
        let info = adapter.get_info();
        let descriptor = wgpu::DeviceDescriptor {
            label: Some(request.label),
            required_features: request.features & adapter.features(),
            required_limits: match &request.limits {
                Some(limits) => limits.clone().or_worse_values_from(&adapter.limits()),
                None => adapter.limits(),
            },
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor))
            .map_err(|error| format!("could not open a device on {}: {error}", info.name))?;
        Ok(Gpu {
            device,
            queue,
            info,
        })
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
    /// binding a uniform `vec4<u32>(count, 0, 0, 0)`. Returns the outputs, or wgpu's message
    /// where it rejected the shader or the device was lost.
    pub fn run_compute(
        &self,
        wgsl: &str,
        entry_point: &str,
        inputs: &[u32],
        output_lengths: &[usize],
        count: u32,
    ) -> Result<Vec<Vec<u32>>, String> {
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
        let storage = |contents: &[u32], usage| self.buffer_of(contents, usage);
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
            return Err(format!(
                "wgpu rejected the compute shader `{entry_point}`: {error}"
            ));
        }
        staging.iter().map(|buffer| self.read(buffer)).collect()
    }

    /// A buffer holding `words`, for `usage`.
    pub fn buffer_of(&self, words: &[u32], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        self.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(words),
                usage,
            })
    }

    /// The words of a mapped-readable buffer.
    fn read(&self, buffer: &wgpu::Buffer) -> Result<Vec<u32>, String> {
        let slice = buffer.slice(..);
        let (sender, receiver) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| format!("waiting for the GPU: {error}"))?;
        receiver
            .recv()
            .map_err(|_| "the GPU never answered a buffer mapping".to_string())?
            .map_err(|error| format!("mapping a staging buffer: {error}"))?;
        let view = slice
            .get_mapped_range()
            .map_err(|error| format!("reading a mapped staging buffer: {error}"))?;
        let words = bytemuck::cast_slice(&view).to_vec();
        drop(view);
        buffer.unmap();
        Ok(words)
    }
}
