//! Textures up and down: the baked inputs uploaded, and render targets read back.

use wgpu::util::DeviceExt;

use super::Renderer;
use crate::inputs::Texels;

impl Renderer {
    /// The texels of `texture` (`bytes_per_pixel` each), row by row, tightly packed.
    pub(super) fn read_texture(
        &self,
        texture: &wgpu::Texture,
        width: u32,
        height: u32,
        bytes_per_pixel: u32,
    ) -> Result<Vec<u8>, String> {
        let row_bytes =
            (width * bytes_per_pixel).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: u64::from(row_bytes * height),
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        let mut encoder = self.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            texture.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row_bytes),
                    rows_per_image: None,
                },
            },
            wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        let slice = buffer.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| error.to_string())?;
        let view = slice
            .get_mapped_range()
            .map_err(|error| error.to_string())?;
        Ok((0..height)
            .flat_map(|row| {
                view[(row * row_bytes) as usize..][..(width * bytes_per_pixel) as usize].to_vec()
            })
            .collect())
    }
}

/// A sampled texture of `mips` (largest first), uploaded.
pub fn texture_with_data(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    format: wgpu::TextureFormat,
    mips: &[Texels],
) -> wgpu::TextureView {
    let bytes: Vec<u8> = mips
        .iter()
        .flat_map(|mip| mip.bytes.iter().copied())
        .collect();
    device
        .create_texture_with_data(
            queue,
            &wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: mips[0].width,
                    height: mips[0].height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: mips.len() as u32,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            },
            wgpu::util::TextureDataOrder::LayerMajor,
            &bytes,
        )
        .create_view(&Default::default())
}
