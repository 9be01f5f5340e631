//! Two timestamp queries around a pass, where the device has `TIMESTAMP_QUERY`, and their
//! reading back as seconds: how the renderer times a frame and the trade-off study a run.

/// The query set of a pass's start and end, and the buffers its values come back through.
pub struct Timestamps {
    /// The two queries: write them at the start (0) and end (1) of the pass timed.
    pub query_set: wgpu::QuerySet,
    resolved: wgpu::Buffer,
    readback: wgpu::Buffer,
}

impl Timestamps {
    /// The queries and buffers, on a device with `TIMESTAMP_QUERY`.
    pub fn new(device: &wgpu::Device, label: &str) -> Timestamps {
        let buffer = |usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: 16,
                usage,
                mapped_at_creation: false,
            })
        };
        Timestamps {
            query_set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some(label),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolved: buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
            readback: buffer(wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
        }
    }

    /// Records the copy of the two timestamps to where [`Timestamps::seconds`] reads them:
    /// after the pass timed, in the same or a later submission.
    pub fn resolve(&self, encoder: &mut wgpu::CommandEncoder) {
        encoder.resolve_query_set(&self.query_set, 0..2, &self.resolved, 0);
        encoder.copy_buffer_to_buffer(&self.resolved, 0, &self.readback, 0, 16);
    }

    /// The seconds between the two timestamps, once the submission that resolved them is done
    /// (this waits for it).
    pub fn seconds(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<f64, String> {
        let slice = self.readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| format!("waiting for the timestamps: {error}"))?;
        let ticks: [u64; 2] = {
            let bytes = slice
                .get_mapped_range()
                .map_err(|error| format!("reading the timestamps: {error:?}"))?;
            bytemuck::pod_read_unaligned(&bytes[..16])
        };
        self.readback.unmap();
        let nanoseconds =
            ticks[1].saturating_sub(ticks[0]) as f64 * f64::from(queue.get_timestamp_period());
        Ok(nanoseconds * 1e-9)
    }
}
