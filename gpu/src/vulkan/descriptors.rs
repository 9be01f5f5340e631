//! Descriptor set layouts and sets: what a pipeline's bindings hold.

use ash::vk;
use ash::Device;

use super::Vulkan;

impl Vulkan {
    /// A descriptor set layout of one descriptor per type, at bindings 0, 1, ..., for the
    /// fragment stage.
    pub fn descriptor_set_layout(
        &self,
        types: &[vk::DescriptorType],
    ) -> Result<vk::DescriptorSetLayout, String> {
        self.descriptor_set_layout_at(&in_order(types))
    }

    /// A descriptor set layout of one descriptor per `(binding, type)`, for the fragment
    /// stage.
    pub fn descriptor_set_layout_at(
        &self,
        types: &[(u32, vk::DescriptorType)],
    ) -> Result<vk::DescriptorSetLayout, String> {
        let bindings: Vec<vk::DescriptorSetLayoutBinding> = types
            .iter()
            .map(|&(binding, descriptor_type)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(binding)
                    .descriptor_type(descriptor_type)
                    .descriptor_count(1)
                    .stage_flags(vk::ShaderStageFlags::FRAGMENT)
            })
            .collect();
        let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
        // SAFETY: valid bindings.
        let layout = unsafe { self.device.create_descriptor_set_layout(&info, None) };
        self.created(
            "vkCreateDescriptorSetLayout",
            layout,
            Device::destroy_descriptor_set_layout,
        )
    }

    /// A descriptor set of `layout` (made by [`Vulkan::descriptor_set_layout`] with the same
    /// kinds in the same order) whose binding i is `resources[i]`.
    pub fn descriptor_set(
        &self,
        layout: vk::DescriptorSetLayout,
        resources: &[Resource],
    ) -> Result<vk::DescriptorSet, String> {
        self.descriptor_set_at(layout, &in_order(resources))
    }

    /// A descriptor set of `layout` (made by [`Vulkan::descriptor_set_layout_at`] with the
    /// same bindings and kinds) holding each `(binding, resource)`.
    pub fn descriptor_set_at(
        &self,
        layout: vk::DescriptorSetLayout,
        resources: &[(u32, Resource)],
    ) -> Result<vk::DescriptorSet, String> {
        let sizes: Vec<vk::DescriptorPoolSize> = resources
            .iter()
            .map(|(_, resource)| vk::DescriptorPoolSize {
                ty: resource.descriptor_type(),
                descriptor_count: 1,
            })
            .collect();
        let mut pool_info = vk::DescriptorPoolCreateInfo::default().max_sets(1);
        if !sizes.is_empty() {
            pool_info = pool_info.pool_sizes(&sizes);
        }
        // SAFETY: the pool holds exactly the set's descriptors; the writes match the layout.
        unsafe {
            let pool = self.device.create_descriptor_pool(&pool_info, None);
            let pool = self.created(
                "vkCreateDescriptorPool",
                pool,
                Device::destroy_descriptor_pool,
            )?;
            let layouts = [layout];
            let set = self
                .device
                .allocate_descriptor_sets(
                    &vk::DescriptorSetAllocateInfo::default()
                        .descriptor_pool(pool)
                        .set_layouts(&layouts),
                )
                .map_err(|error| format!("vkAllocateDescriptorSets: {error}"))?[0];
            let images: Vec<[vk::DescriptorImageInfo; 1]> = resources
                .iter()
                .map(|(_, resource)| [resource.image_info()])
                .collect();
            let buffers: Vec<[vk::DescriptorBufferInfo; 1]> = resources
                .iter()
                .map(|(_, resource)| [resource.buffer_info()])
                .collect();
            let writes: Vec<vk::WriteDescriptorSet> = resources
                .iter()
                .enumerate()
                .map(|(index, (binding, resource))| {
                    let write = vk::WriteDescriptorSet::default()
                        .dst_set(set)
                        .dst_binding(*binding)
                        .descriptor_type(resource.descriptor_type());
                    match resource {
                        Resource::StorageBuffer(_) => write.buffer_info(&buffers[index]),
                        _ => write.image_info(&images[index]),
                    }
                })
                .collect();
            self.device.update_descriptor_sets(&writes, &[]);
            Ok(set)
        }
    }
}

/// What a descriptor set binding holds.
#[derive(Clone, Copy, Debug)]
pub enum Resource {
    /// An image view read as an input attachment, in `SHADER_READ_ONLY_OPTIMAL`.
    InputAttachment(vk::ImageView),
    /// An image view read as an input attachment by the draws that also write it (a feedback
    /// loop), in this layout: `GENERAL` in a subpass, `RENDERING_LOCAL_READ_KHR` in a dynamic
    /// rendering.
    FeedbackAttachment(vk::ImageView, vk::ImageLayout),
    /// An image view sampled with a sampler, in `SHADER_READ_ONLY_OPTIMAL`.
    SampledImage(vk::ImageView, vk::Sampler),
    /// A storage buffer.
    StorageBuffer(vk::Buffer),
}

impl Resource {
    /// Its descriptor type.
    pub fn descriptor_type(&self) -> vk::DescriptorType {
        match self {
            Resource::InputAttachment(_) | Resource::FeedbackAttachment(..) => {
                vk::DescriptorType::INPUT_ATTACHMENT
            }
            Resource::SampledImage(..) => vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            Resource::StorageBuffer(_) => vk::DescriptorType::STORAGE_BUFFER,
        }
    }

    /// Its image, for a write (empty for a buffer).
    fn image_info(&self) -> vk::DescriptorImageInfo {
        let (image_view, sampler, image_layout) = match *self {
            Resource::InputAttachment(view) => (
                view,
                vk::Sampler::null(),
                vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            ),
            Resource::FeedbackAttachment(view, layout) => (view, vk::Sampler::null(), layout),
            Resource::SampledImage(view, sampler) => {
                (view, sampler, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
            }
            Resource::StorageBuffer(_) => return vk::DescriptorImageInfo::default(),
        };
        vk::DescriptorImageInfo {
            sampler,
            image_view,
            image_layout,
        }
    }

    /// Its buffer, for a write (empty for an image).
    fn buffer_info(&self) -> vk::DescriptorBufferInfo {
        match *self {
            Resource::StorageBuffer(buffer) => vk::DescriptorBufferInfo {
                buffer,
                offset: 0,
                range: vk::WHOLE_SIZE,
            },
            _ => vk::DescriptorBufferInfo::default(),
        }
    }
}

/// Items at bindings 0, 1, ...
fn in_order<T: Copy>(items: &[T]) -> Vec<(u32, T)> {
    (0..).zip(items.iter().copied()).collect()
}
