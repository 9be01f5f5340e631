//! Device memory and the images in it: transient attachments in lazily allocated memory where
//! the device has it, sampled images, samplers.

use ash::vk;
use ash::Device;

use super::Vulkan;

/// Where a transient attachment's memory came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AttachmentMemory {
    /// A `LAZILY_ALLOCATED` memory type: on a tiler, memory that is never backed at all when
    /// the attachment lives only in tile memory.
    LazilyAllocated,
    /// The device offers no lazily allocated type for the image: ordinary device memory.
    DeviceLocal,
}

impl Vulkan {
    /// Whether the device offers a lazily allocated memory type (on a tiler, memory that an
    /// attachment living only in tile memory never touches).
    pub fn has_lazily_allocated_memory(&self) -> bool {
        self.memory_types.iter().any(|memory| {
            memory
                .property_flags
                .contains(vk::MemoryPropertyFlags::LAZILY_ALLOCATED)
        })
    }

    /// Whether the device can use `format` as a colour attachment (and so as an input
    /// attachment) in optimal tiling.
    pub fn renders_to(&self, format: vk::Format) -> bool {
        // SAFETY: the physical device is alive.
        let properties = unsafe {
            self.instance
                .get_physical_device_format_properties(self.physical_device, format)
        };
        properties
            .optimal_tiling_features
            .contains(vk::FormatFeatureFlags::COLOR_ATTACHMENT)
    }

    /// Memory for `requirements`, of the first of `preferences` (property flags, best first)
    /// that a memory type the requirements allow has, and the flags it was chosen for; `what`
    /// names the object in the error when none has.
    pub(super) fn allocate(
        &self,
        requirements: vk::MemoryRequirements,
        preferences: &[vk::MemoryPropertyFlags],
        what: &str,
    ) -> Result<(vk::DeviceMemory, vk::MemoryPropertyFlags), String> {
        // The first memory type the requirements allow that has all of `flags`.
        let offered = |flags: vk::MemoryPropertyFlags| {
            (0..self.memory_types.len()).find(|&index| {
                requirements.memory_type_bits & (1 << index) != 0
                    && self.memory_types[index].property_flags.contains(flags)
            })
        };
        let (type_index, flags) = preferences
            .iter()
            .find_map(|&flags| Some((offered(flags)?, flags)))
            .ok_or_else(|| format!("no memory type with {preferences:?} for {what}"))?;
        let info = vk::MemoryAllocateInfo::default()
            .allocation_size(requirements.size)
            .memory_type_index(type_index as u32);
        // SAFETY: the type index is one the requirements' type bits allow.
        let memory = unsafe { self.device.allocate_memory(&info, None) };
        let memory = self.created("vkAllocateMemory", memory, Device::free_memory)?;
        Ok((memory, flags))
    }

    /// A `width` x `height` colour attachment in `format` that is also read as an input
    /// attachment and never leaves the render pass: `TRANSIENT_ATTACHMENT`, in lazily allocated
    /// memory where the device offers it (which one it got is returned with the view).
    pub fn transient_attachment(
        &self,
        format: vk::Format,
        width: u32,
        height: u32,
    ) -> Result<(vk::ImageView, AttachmentMemory), String> {
        let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT
            | vk::ImageUsageFlags::INPUT_ATTACHMENT
            | vk::ImageUsageFlags::TRANSIENT_ATTACHMENT;
        let (_, view, memory) = self.image(format, (width, height, 1), usage)?;
        Ok((view, memory))
    }

    /// A `width` x `height` image of `mips` levels in `format` for `usage`, and a view of
    /// them all. A `TRANSIENT_ATTACHMENT` image takes lazily allocated memory where the device
    /// offers it (which memory it got is returned), any other device-local memory.
    pub fn image(
        &self,
        format: vk::Format,
        (width, height, mips): (u32, u32, u32),
        usage: vk::ImageUsageFlags,
    ) -> Result<(vk::Image, vk::ImageView, AttachmentMemory), String> {
        let info = vk::ImageCreateInfo::default()
            .image_type(vk::ImageType::TYPE_2D)
            .format(format)
            .extent(vk::Extent3D {
                width,
                height,
                depth: 1,
            })
            .mip_levels(mips)
            .array_layers(1)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        let aspect = if usage.contains(vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT) {
            vk::ImageAspectFlags::DEPTH
        } else {
            vk::ImageAspectFlags::COLOR
        };
        // SAFETY: a valid 2D image; the memory is bound once, at offset 0.
        unsafe {
            let image = self.device.create_image(&info, None);
            let image = self.created(
                &format!("vkCreateImage({format:?}, {usage:?})"),
                image,
                Device::destroy_image,
            )?;
            let requirements = self.device.get_image_memory_requirements(image);
            // A transient attachment prefers memory that a tiler never backs.
            let preferences: &[vk::MemoryPropertyFlags] =
                if usage.contains(vk::ImageUsageFlags::TRANSIENT_ATTACHMENT) {
                    &[
                        vk::MemoryPropertyFlags::LAZILY_ALLOCATED,
                        vk::MemoryPropertyFlags::DEVICE_LOCAL,
                    ]
                } else {
                    &[vk::MemoryPropertyFlags::DEVICE_LOCAL]
                };
            let (memory, flags) = self.allocate(requirements, preferences, "an image")?;
            let kind = if flags == vk::MemoryPropertyFlags::LAZILY_ALLOCATED {
                AttachmentMemory::LazilyAllocated
            } else {
                AttachmentMemory::DeviceLocal
            };
            self.device
                .bind_image_memory(image, memory, 0)
                .map_err(|error| format!("vkBindImageMemory: {error}"))?;
            let view = self.device.create_image_view(
                &vk::ImageViewCreateInfo::default()
                    .image(image)
                    .view_type(vk::ImageViewType::TYPE_2D)
                    .format(format)
                    .subresource_range(vk::ImageSubresourceRange {
                        aspect_mask: aspect,
                        base_mip_level: 0,
                        level_count: mips,
                        base_array_layer: 0,
                        layer_count: 1,
                    }),
                None,
            );
            let view = self.created("vkCreateImageView", view, Device::destroy_image_view)?;
            Ok((image, view, kind))
        }
    }

    /// A sampler, destroyed with the device.
    pub fn sampler(&self, info: &vk::SamplerCreateInfo) -> Result<vk::Sampler, String> {
        // SAFETY: a valid sampler of the device.
        let sampler = unsafe { self.device.create_sampler(info, None) };
        self.created("vkCreateSampler", sampler, Device::destroy_sampler)
    }
}
