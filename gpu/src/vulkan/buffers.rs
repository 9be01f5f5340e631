//! Host-visible, coherent buffers of `u32` words, written and read back through a mapping.

use ash::vk;
use ash::Device;

use super::Vulkan;

/// A host-visible, coherent buffer of `u32` words (a storage buffer, or any usage).
pub struct StorageBuffer {
    /// The buffer, to bind.
    pub buffer: vk::Buffer,
    memory: vk::DeviceMemory,
    words: usize,
}

impl Vulkan {
    /// A storage buffer of `words` words that the host reads and writes directly.
    pub fn storage_buffer(&self, words: usize) -> Result<StorageBuffer, String> {
        self.host_buffer(words, vk::BufferUsageFlags::STORAGE_BUFFER)
    }

    /// A buffer of `words` words for `usage` that the host reads and writes directly.
    pub fn host_buffer(
        &self,
        words: usize,
        usage: vk::BufferUsageFlags,
    ) -> Result<StorageBuffer, String> {
        let info = vk::BufferCreateInfo::default()
            .size((words.max(1) * 4) as u64)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
        // SAFETY: a valid buffer; the memory is bound once, at offset 0.
        unsafe {
            let buffer = self.device.create_buffer(&info, None);
            let buffer = self.created("vkCreateBuffer", buffer, Device::destroy_buffer)?;
            let requirements = self.device.get_buffer_memory_requirements(buffer);
            let host_coherent =
                vk::MemoryPropertyFlags::HOST_VISIBLE | vk::MemoryPropertyFlags::HOST_COHERENT;
            let (memory, _) = self.allocate(requirements, &[host_coherent], "a buffer")?;
            self.device
                .bind_buffer_memory(buffer, memory, 0)
                .map_err(|error| format!("vkBindBufferMemory: {error}"))?;
            Ok(StorageBuffer {
                buffer,
                memory,
                words,
            })
        }
    }

    /// Maps a storage buffer and hands its words to `access`.
    fn with_mapped<T>(
        &self,
        buffer: &StorageBuffer,
        access: impl FnOnce(&mut [u32]) -> T,
    ) -> Result<T, String> {
        // SAFETY: the memory is host visible and coherent, at least `words` words long, not
        // mapped elsewhere, and the device is idle between submissions.
        unsafe {
            let pointer = self
                .device
                .map_memory(
                    buffer.memory,
                    0,
                    vk::WHOLE_SIZE,
                    vk::MemoryMapFlags::empty(),
                )
                .map_err(|error| format!("vkMapMemory: {error}"))?;
            let words = std::slice::from_raw_parts_mut(pointer.cast::<u32>(), buffer.words);
            let result = access(words);
            self.device.unmap_memory(buffer.memory);
            Ok(result)
        }
    }

    /// Writes `words` at the start of a storage buffer.
    pub fn write_buffer(&self, buffer: &StorageBuffer, words: &[u32]) -> Result<(), String> {
        self.with_mapped(buffer, |mapped| {
            mapped[..words.len()].copy_from_slice(words)
        })
    }

    /// The words of a storage buffer.
    pub fn read_buffer(&self, buffer: &StorageBuffer) -> Result<Vec<u32>, String> {
        self.with_mapped(buffer, |mapped| mapped.to_vec())
    }
}
