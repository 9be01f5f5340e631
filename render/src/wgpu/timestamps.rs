//! Timestamp queries around a frame, where the device has them.

use super::Renderer;

/// Two timestamp queries around a frame and the buffers that read them back.
pub(super) struct Timestamps {
    pub(super) query_set: wgpu::QuerySet,
    pub(super) resolve: wgpu::Buffer,
    pub(super) read_back: wgpu::Buffer,
}

impl Timestamps {
    pub(super) fn new(device: &wgpu::Device) -> Self {
        let buffer = |usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: 16,
                usage,
                mapped_at_creation: false,
            })
        };
        Timestamps {
            query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("frame"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            read_back: buffer(wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ),
        }
    }

    /// The seconds between the two timestamps of the last frame.
    pub(super) fn read(&self, renderer: &Renderer) -> Result<f64, String> {
        let mut encoder = renderer.device.create_command_encoder(&Default::default());
        encoder.resolve_query_set(&self.query_set, 0..2, &self.resolve, 0);
        encoder.copy_buffer_to_buffer(&self.resolve, 0, &self.read_back, 0, 16);
        renderer.queue.submit([encoder.finish()]);
        let slice = self.read_back.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        renderer
            .device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| error.to_string())?;
        let ticks: [u64; 2] = {
            let view = slice
                .get_mapped_range()
                .map_err(|error| error.to_string())?;
            bytemuck::pod_read_unaligned(&view[..16])
        };
        self.read_back.unmap();
        Ok(ticks[1].saturating_sub(ticks[0]) as f64
            * f64::from(renderer.queue.get_timestamp_period())
            * 1e-9)
    }
}
