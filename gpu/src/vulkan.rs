//! A Vulkan device on a real driver, without a window: `ash` with the loader opened at run time
//! (Mesa's lavapipe here). Tests build render passes of several subpasses over transient
//! attachments, draw fullscreen triangles in each, and read what the shaders wrote to storage
//! buffers; the attachments themselves never leave the render pass, as on a tiler.
//!
//! Every object a test creates is recorded and destroyed by [`Vulkan::release`] (or when the
//! device is dropped), so a test creates what it needs without bookkeeping of its own.

use std::cell::RefCell;
use std::ffi::CStr;

use ash::vk;
use ash::Device;

/// Records a global memory barrier: what `from` (access, stage) wrote is visible to `to`.
///
/// # Safety
///
/// `commands` is a command buffer of `device` being recorded.
unsafe fn memory_barrier(
    device: &ash::Device,
    commands: vk::CommandBuffer,
    (src_access, src_stage): Access,
    (dst_access, dst_stage): Access,
    dependency: vk::DependencyFlags,
) {
    let barrier = vk::MemoryBarrier::default()
        .src_access_mask(src_access)
        .dst_access_mask(dst_access);
    // SAFETY: as the caller promises.
    unsafe {
        device.cmd_pipeline_barrier(
            commands,
            src_stage,
            dst_stage,
            dependency,
            &[barrier],
            &[],
            &[],
        );
    }
}

/// Makes what `written` (an access and its stage) wrote visible to the host once the commands
/// are done, before a read back.
///
/// # Safety
///
/// `commands` is a command buffer of `device` being recorded.
pub unsafe fn host_read_barrier(
    device: &ash::Device,
    commands: vk::CommandBuffer,
    written: Access,
) {
    let host = (vk::AccessFlags::HOST_READ, vk::PipelineStageFlags::HOST);
    // SAFETY: as the caller promises.
    unsafe {
        memory_barrier(
            device,
            commands,
            written,
            host,
            vk::DependencyFlags::empty(),
        )
    }
}

/// Makes a draw's colour attachment writes visible to the next draw's input attachment reads
/// in the same subpass, pixel by pixel (a subpass self-dependency).
///
/// # Safety
///
/// `commands` is a command buffer of `device` recording a subpass that declares the
/// self-dependency.
pub unsafe fn feedback_barrier(device: &ash::Device, commands: vk::CommandBuffer) {
    let (written, read) = FEEDBACK;
    // SAFETY: as the caller promises.
    unsafe {
        memory_barrier(
            device,
            commands,
            written,
            read,
            vk::DependencyFlags::BY_REGION,
        )
    }
}

/// A subpass's colour writes, then the next one's input attachment reads.
const FEEDBACK: (Access, Access) = (
    (
        vk::AccessFlags::COLOR_ATTACHMENT_WRITE,
        vk::PipelineStageFlags::COLOR_ATTACHMENT_OUTPUT,
    ),
    (
        vk::AccessFlags::INPUT_ATTACHMENT_READ,
        vk::PipelineStageFlags::FRAGMENT_SHADER,
    ),
);

/// An image's layout change, as one barrier: from (layout, what wrote it, where) to (layout,
/// what reads it, where).
pub struct ImageTransition {
    /// The image.
    pub image: vk::Image,
    /// The part of it that changes layout.
    pub range: vk::ImageSubresourceRange,
}

/// One side of a barrier: what accesses memory, and in which stage.
pub type Access = (vk::AccessFlags, vk::PipelineStageFlags);

impl ImageTransition {
    /// Records the barrier.
    ///
    /// # Safety
    ///
    /// `commands` is recording and the image is alive.
    pub unsafe fn record(
        &self,
        device: &ash::Device,
        commands: vk::CommandBuffer,
        (old_layout, (src_access, src_stage)): (vk::ImageLayout, Access),
        (new_layout, (dst_access, dst_stage)): (vk::ImageLayout, Access),
    ) {
        let barrier = vk::ImageMemoryBarrier::default()
            .src_access_mask(src_access)
            .dst_access_mask(dst_access)
            .old_layout(old_layout)
            .new_layout(new_layout)
            .image(self.image)
            .subresource_range(self.range);
        // SAFETY: as the caller promises.
        unsafe {
            device.cmd_pipeline_barrier(
                commands,
                src_stage,
                dst_stage,
                vk::DependencyFlags::empty(),
                &[],
                &[],
                &[barrier],
            );
        }
    }
}

/// What a graphics pipeline is made of, for [`Vulkan::graphics_pipeline`].
pub struct GraphicsPipeline<'a> {
    /// The render pass it draws in.
    pub render_pass: vk::RenderPass,
    /// Its subpass there.
    pub subpass: u32,
    /// Its layout.
    pub layout: vk::PipelineLayout,
    /// The vertex and fragment modules (entry points `main`).
    pub shaders: (vk::ShaderModule, vk::ShaderModule),
    /// The vertex buffers' bindings and attributes (none for a fullscreen triangle).
    pub vertex_input: (
        &'a [vk::VertexInputBindingDescription],
        &'a [vk::VertexInputAttributeDescription],
    ),
    /// The depth test, if the render pass has a depth attachment: whether it writes, and its
    /// comparison.
    pub depth: Option<(bool, vk::CompareOp)>,
    /// Per colour attachment, whether the pipeline writes it.
    pub colour_writes: &'a [bool],
    /// The viewport's width and height.
    pub size: (u32, u32),
}

/// Where a transient attachment's memory came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AttachmentMemory {
    /// A `LAZILY_ALLOCATED` memory type: on a tiler, memory that is never backed at all when
    /// the attachment lives only in tile memory.
    LazilyAllocated,
    /// The device offers no lazily allocated type for the image: ordinary device memory.
    DeviceLocal,
}

/// How an object of type `T` is destroyed: `ash::Device`'s `destroy_*` (or `free_memory`).
type Destroy<T> = unsafe fn(&ash::Device, T, Option<&vk::AllocationCallbacks<'_>>);

/// An object's destruction, kept until [`Vulkan::release`].
type Created = Box<dyn FnOnce(&ash::Device)>;

/// A logical device with one graphics queue.
pub struct Vulkan {
    /// The logical device.
    pub device: ash::Device,
    /// The physical device's limits.
    pub limits: vk::PhysicalDeviceLimits,
    instance: ash::Instance,
    physical_device: vk::PhysicalDevice,
    queue: vk::Queue,
    command_pool: vk::CommandPool,
    memory_types: Vec<vk::MemoryType>,
    name: String,
    created: RefCell<Vec<Created>>,
    // Dropped last: it holds the loader the other handles' functions come from.
    _entry: ash::Entry,
}

/// A host-visible, coherent buffer of `u32` words (a storage buffer, or any usage).
pub struct StorageBuffer {
    /// The buffer, to bind.
    pub buffer: vk::Buffer,
    memory: vk::DeviceMemory,
    words: usize,
}

/// One subpass of a render pass: the attachments it reads as input attachments and those it
/// writes as colour attachments, as indices into the render pass's attachments.
pub struct Subpass {
    /// Attachments read as input attachments, in input attachment index order.
    pub inputs: Vec<u32>,
    /// Attachments written as colour attachments, in location order.
    pub colours: Vec<u32>,
}

impl Vulkan {
    /// Opens the first device with a graphics queue and fragment-shader stores. The error says
    /// what was missing (the loader, a device, a feature).
    pub fn new() -> Result<Vulkan, String> {
        // SAFETY: loading libvulkan runs its initialisers; it is the system's loader.
        let entry = unsafe { ash::Entry::load() }.map_err(|error| {
            format!("cannot load the Vulkan loader ({error}): install Debian's libvulkan1 and mesa-vulkan-drivers")
        })?;
        let application = vk::ApplicationInfo::default().api_version(vk::API_VERSION_1_1);
        // SAFETY: a valid create info without layers or extensions.
        let instance = unsafe {
            entry.create_instance(
                &vk::InstanceCreateInfo::default().application_info(&application),
                None,
            )
        }
        .map_err(|error| format!("vkCreateInstance: {error}"))?;
        match Self::open_device(&instance) {
            Ok((physical_device, device, queue_family, name)) => {
                // SAFETY: the physical device and device are alive; the create infos are valid.
                unsafe {
                    let properties = instance.get_physical_device_properties(physical_device);
                    let memory = instance.get_physical_device_memory_properties(physical_device);
                    let command_pool = device
                        .create_command_pool(
                            &vk::CommandPoolCreateInfo::default().queue_family_index(queue_family),
                            None,
                        )
                        .map_err(|error| format!("vkCreateCommandPool: {error}"))?;
                    Ok(Vulkan {
                        queue: device.get_device_queue(queue_family, 0),
                        device,
                        limits: properties.limits,
                        instance,
                        physical_device,
                        command_pool,
                        memory_types: memory.memory_types_as_slice().to_vec(),
                        name,
                        created: RefCell::new(Vec::new()),
                        _entry: entry,
                    })
                }
            }
            Err(error) => {
                // SAFETY: nothing was created from the instance.
                unsafe { instance.destroy_instance(None) };
                Err(error)
            }
        }
    }

    /// The first device with a graphics queue that can store from fragment shaders: the
    /// physical device, the logical device, its queue family and a description.
    fn open_device(
        instance: &ash::Instance,
    ) -> Result<(vk::PhysicalDevice, ash::Device, u32, String), String> {
        // SAFETY: the instance is alive.
        let physical_devices = unsafe { instance.enumerate_physical_devices() }
            .map_err(|error| format!("vkEnumeratePhysicalDevices: {error}"))?;
        if physical_devices.is_empty() {
            return Err(
                "no Vulkan device: install Debian's mesa-vulkan-drivers (lavapipe)".to_string(),
            );
        }
        let mut seen = Vec::new();
        for physical_device in physical_devices {
            // SAFETY: the physical device comes from the instance.
            let (properties, features, families) = unsafe {
                (
                    instance.get_physical_device_properties(physical_device),
                    instance.get_physical_device_features(physical_device),
                    instance.get_physical_device_queue_family_properties(physical_device),
                )
            };
            let name = properties
                .device_name_as_c_str()
                .map_or_else(|_| "?".into(), CStr::to_string_lossy)
                .into_owned();
            let graphics = families
                .iter()
                .position(|family| family.queue_flags.contains(vk::QueueFlags::GRAPHICS));
            let (Some(family), vk::TRUE) = (graphics, features.fragment_stores_and_atomics) else {
                seen.push(name);
                continue;
            };
            let description = format!(
                "{name} (Vulkan {}.{}.{}, driver {:#x})",
                vk::api_version_major(properties.api_version),
                vk::api_version_minor(properties.api_version),
                vk::api_version_patch(properties.api_version),
                properties.driver_version
            );
            let priorities = [1.0];
            let queues = [vk::DeviceQueueCreateInfo::default()
                .queue_family_index(family as u32)
                .queue_priorities(&priorities)];
            let enabled = vk::PhysicalDeviceFeatures::default().fragment_stores_and_atomics(true);
            // SAFETY: the queue family exists and the feature is supported.
            let device = unsafe {
                instance.create_device(
                    physical_device,
                    &vk::DeviceCreateInfo::default()
                        .queue_create_infos(&queues)
                        .enabled_features(&enabled),
                    None,
                )
            }
            .map_err(|error| format!("vkCreateDevice on {name}: {error}"))?;
            return Ok((physical_device, device, family as u32, description));
        }
        Err(format!(
            "no Vulkan device has a graphics queue and fragmentStoresAndAtomics (seen: {})",
            seen.join(", ")
        ))
    }

    /// The device's name, API version and driver version.
    pub fn describe(&self) -> &str {
        &self.name
    }

    /// A sampler, destroyed with the device.
    pub fn sampler(&self, info: &vk::SamplerCreateInfo) -> Result<vk::Sampler, String> {
        // SAFETY: a valid sampler of the device.
        let sampler = unsafe { self.device.create_sampler(info, None) };
        self.created("vkCreateSampler", sampler, Device::destroy_sampler)
    }

    /// The object a `vkCreate*` call (`call`) made, kept to be destroyed by `destroy` at
    /// [`Vulkan::release`], or the call's error.
    fn created<T: Copy + 'static>(
        &self,
        call: &str,
        result: ash::prelude::VkResult<T>,
        destroy: Destroy<T>,
    ) -> Result<T, String> {
        let made = result.map_err(|error| format!("{call}: {error}"))?;
        // SAFETY: release runs each destruction once, after the device is idle.
        let destruction: Created = Box::new(move |device| unsafe { destroy(device, made, None) });
        self.created.borrow_mut().push(destruction);
        Ok(made)
    }

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
    fn allocate(
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

    /// A shader module from SPIR-V bytes.
    pub fn shader_module(&self, spirv: &[u8]) -> Result<vk::ShaderModule, String> {
        let code = ash::util::read_spv(&mut std::io::Cursor::new(spirv))
            .map_err(|error| format!("not SPIR-V: {error}"))?;
        // SAFETY: the code is whole SPIR-V words.
        let module = unsafe {
            self.device
                .create_shader_module(&vk::ShaderModuleCreateInfo::default().code(&code), None)
        };
        self.created(
            "vkCreateShaderModule",
            module,
            Device::destroy_shader_module,
        )
    }

    /// A render pass over `formats` whose subpasses run in order, each reading its inputs
    /// after the previous ones wrote them (by region, as a tiler keeps them). No attachment is
    /// loaded or stored: they live and die inside the pass.
    pub fn render_pass(
        &self,
        formats: &[vk::Format],
        subpasses: &[Subpass],
    ) -> Result<vk::RenderPass, String> {
        let attachments: Vec<vk::AttachmentDescription> = formats
            .iter()
            .map(|&format| {
                vk::AttachmentDescription::default()
                    .format(format)
                    .samples(vk::SampleCountFlags::TYPE_1)
                    .load_op(vk::AttachmentLoadOp::DONT_CARE)
                    .store_op(vk::AttachmentStoreOp::DONT_CARE)
                    .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
                    .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
                    .initial_layout(vk::ImageLayout::UNDEFINED)
                    .final_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)
            })
            .collect();
        let references = |indices: &[u32], layout| -> Vec<vk::AttachmentReference> {
            indices
                .iter()
                .map(|&attachment| vk::AttachmentReference { attachment, layout })
                .collect()
        };
        let inputs: Vec<_> = subpasses
            .iter()
            .map(|subpass| references(&subpass.inputs, vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL))
            .collect();
        let colours: Vec<_> = subpasses
            .iter()
            .map(|subpass| references(&subpass.colours, vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL))
            .collect();
        let descriptions: Vec<vk::SubpassDescription> = inputs
            .iter()
            .zip(&colours)
            .map(|(inputs, colours)| {
                vk::SubpassDescription::default()
                    .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
                    .input_attachments(inputs)
                    .color_attachments(colours)
            })
            .collect();
        let dependencies: Vec<vk::SubpassDependency> = (1..subpasses.len() as u32)
            .map(|next| {
                vk::SubpassDependency::default()
                    .src_subpass(next - 1)
                    .dst_subpass(next)
                    .src_stage_mask(FEEDBACK.0 .1)
                    .dst_stage_mask(FEEDBACK.1 .1)
                    .src_access_mask(FEEDBACK.0 .0)
                    .dst_access_mask(FEEDBACK.1 .0)
                    .dependency_flags(vk::DependencyFlags::BY_REGION)
            })
            .collect();
        self.render_pass_of(&attachments, &descriptions, &dependencies)
    }

    /// A render pass of these attachments, subpasses and dependencies, as they are written.
    pub fn render_pass_of(
        &self,
        attachments: &[vk::AttachmentDescription],
        subpasses: &[vk::SubpassDescription],
        dependencies: &[vk::SubpassDependency],
    ) -> Result<vk::RenderPass, String> {
        let info = vk::RenderPassCreateInfo::default()
            .attachments(attachments)
            .subpasses(subpasses)
            .dependencies(dependencies);
        // SAFETY: the caller's descriptions reference only `attachments`.
        let made = unsafe { self.device.create_render_pass(&info, None) };
        self.created("vkCreateRenderPass", made, Device::destroy_render_pass)
    }

    /// A framebuffer of `views` for `render_pass`.
    pub fn framebuffer(
        &self,
        render_pass: vk::RenderPass,
        views: &[vk::ImageView],
        width: u32,
        height: u32,
    ) -> Result<vk::Framebuffer, String> {
        let info = vk::FramebufferCreateInfo::default()
            .render_pass(render_pass)
            .attachments(views)
            .width(width)
            .height(height)
            .layers(1);
        // SAFETY: the views match the render pass's attachments.
        let made = unsafe { self.device.create_framebuffer(&info, None) };
        self.created("vkCreateFramebuffer", made, Device::destroy_framebuffer)
    }

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

    /// A pipeline layout of `set_layouts` (set i is `set_layouts[i]`) and, where given, a
    /// push-constant range of that many bytes for the fragment stage.
    pub fn pipeline_layout(
        &self,
        set_layouts: &[vk::DescriptorSetLayout],
        fragment_push_constant_bytes: Option<u32>,
    ) -> Result<vk::PipelineLayout, String> {
        let ranges: Vec<vk::PushConstantRange> = fragment_push_constant_bytes
            .into_iter()
            .map(|size| vk::PushConstantRange {
                stage_flags: vk::ShaderStageFlags::FRAGMENT,
                offset: 0,
                size,
            })
            .collect();
        let info = vk::PipelineLayoutCreateInfo::default()
            .set_layouts(set_layouts)
            .push_constant_ranges(&ranges);
        // SAFETY: valid set layouts.
        let layout = unsafe { self.device.create_pipeline_layout(&info, None) };
        self.created(
            "vkCreatePipelineLayout",
            layout,
            Device::destroy_pipeline_layout,
        )
    }

    /// A pipeline for `subpass` of `render_pass` that draws a fullscreen triangle (`vertex`
    /// makes it from the vertex index) and runs `fragment` on a `width` x `height` viewport,
    /// writing `colour_attachments` attachments without blending.
    #[allow(clippy::too_many_arguments)]
    pub fn fullscreen_pipeline(
        &self,
        render_pass: vk::RenderPass,
        subpass: u32,
        layout: vk::PipelineLayout,
        vertex: vk::ShaderModule,
        fragment: vk::ShaderModule,
        colour_attachments: usize,
        size: (u32, u32),
    ) -> Result<vk::Pipeline, String> {
        self.graphics_pipeline(&GraphicsPipeline {
            render_pass,
            subpass,
            layout,
            shaders: (vertex, fragment),
            vertex_input: (&[], &[]),
            depth: None,
            colour_writes: &vec![true; colour_attachments],
            size,
        })
    }

    /// A graphics pipeline as `description` says: triangle lists, no culling, no blending, one
    /// sample, a viewport and scissor of its size.
    pub fn graphics_pipeline(
        &self,
        description: &GraphicsPipeline,
    ) -> Result<vk::Pipeline, String> {
        let (vertex, fragment) = description.shaders;
        let stages = [
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::VERTEX)
                .module(vertex)
                .name(c"main"),
            vk::PipelineShaderStageCreateInfo::default()
                .stage(vk::ShaderStageFlags::FRAGMENT)
                .module(fragment)
                .name(c"main"),
        ];
        let (bindings, attributes) = description.vertex_input;
        let vertex_input = vk::PipelineVertexInputStateCreateInfo::default()
            .vertex_binding_descriptions(bindings)
            .vertex_attribute_descriptions(attributes);
        let input_assembly = vk::PipelineInputAssemblyStateCreateInfo::default()
            .topology(vk::PrimitiveTopology::TRIANGLE_LIST);
        let (width, height) = description.size;
        let viewports = [vk::Viewport {
            x: 0.0,
            y: 0.0,
            width: width as f32,
            height: height as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        }];
        let scissors = [vk::Rect2D {
            offset: vk::Offset2D { x: 0, y: 0 },
            extent: vk::Extent2D { width, height },
        }];
        let viewport = vk::PipelineViewportStateCreateInfo::default()
            .viewports(&viewports)
            .scissors(&scissors);
        let rasterization = vk::PipelineRasterizationStateCreateInfo::default()
            .polygon_mode(vk::PolygonMode::FILL)
            .cull_mode(vk::CullModeFlags::NONE)
            .front_face(vk::FrontFace::COUNTER_CLOCKWISE)
            .line_width(1.0);
        let multisample = vk::PipelineMultisampleStateCreateInfo::default()
            .rasterization_samples(vk::SampleCountFlags::TYPE_1);
        let blend_attachments: Vec<vk::PipelineColorBlendAttachmentState> = description
            .colour_writes
            .iter()
            .map(|&writes| {
                vk::PipelineColorBlendAttachmentState::default().color_write_mask(if writes {
                    vk::ColorComponentFlags::RGBA
                } else {
                    vk::ColorComponentFlags::empty()
                })
            })
            .collect();
        let blend =
            vk::PipelineColorBlendStateCreateInfo::default().attachments(&blend_attachments);
        let depth_state = description.depth.map(|(write, compare)| {
            vk::PipelineDepthStencilStateCreateInfo::default()
                .depth_test_enable(true)
                .depth_write_enable(write)
                .depth_compare_op(compare)
        });
        let mut info = vk::GraphicsPipelineCreateInfo::default()
            .stages(&stages)
            .vertex_input_state(&vertex_input)
            .input_assembly_state(&input_assembly)
            .viewport_state(&viewport)
            .rasterization_state(&rasterization)
            .multisample_state(&multisample)
            .color_blend_state(&blend)
            .layout(description.layout)
            .render_pass(description.render_pass)
            .subpass(description.subpass);
        if let Some(depth_state) = &depth_state {
            info = info.depth_stencil_state(depth_state);
        }
        // SAFETY: the stages, layout and render pass are alive and agree with each other.
        let pipelines = unsafe {
            self.device
                .create_graphics_pipelines(vk::PipelineCache::null(), &[info], None)
        }
        .map_err(|(_, error)| error)
        .map(|pipelines| pipelines[0]);
        self.created(
            "vkCreateGraphicsPipelines",
            pipelines,
            Device::destroy_pipeline,
        )
    }

    /// Records commands with `record`, submits them, and waits until the device is idle, with
    /// everything fragment shaders stored made visible to the host.
    pub fn submit_and_wait(
        &self,
        record: impl FnOnce(&ash::Device, vk::CommandBuffer),
    ) -> Result<(), String> {
        // SAFETY: one primary command buffer, recorded, submitted and waited for here.
        unsafe {
            let command_buffer = self
                .device
                .allocate_command_buffers(
                    &vk::CommandBufferAllocateInfo::default()
                        .command_pool(self.command_pool)
                        .level(vk::CommandBufferLevel::PRIMARY)
                        .command_buffer_count(1),
                )
                .map_err(|error| format!("vkAllocateCommandBuffers: {error}"))?[0];
            self.device
                .begin_command_buffer(
                    command_buffer,
                    &vk::CommandBufferBeginInfo::default()
                        .flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT),
                )
                .map_err(|error| format!("vkBeginCommandBuffer: {error}"))?;
            record(&self.device, command_buffer);
            let shader_writes = (
                vk::AccessFlags::SHADER_WRITE,
                vk::PipelineStageFlags::FRAGMENT_SHADER,
            );
            host_read_barrier(&self.device, command_buffer, shader_writes);
            self.device
                .end_command_buffer(command_buffer)
                .map_err(|error| format!("vkEndCommandBuffer: {error}"))?;
            let command_buffers = [command_buffer];
            let submitted = self.device.queue_submit(
                self.queue,
                &[vk::SubmitInfo::default().command_buffers(&command_buffers)],
                vk::Fence::null(),
            );
            let waited = self.device.queue_wait_idle(self.queue);
            self.device
                .free_command_buffers(self.command_pool, &command_buffers);
            submitted.map_err(|error| format!("vkQueueSubmit: {error}"))?;
            waited.map_err(|error| format!("vkQueueWaitIdle: {error}"))
        }
    }

    /// Destroys every object created so far, newest first.
    pub fn release(&self) {
        // SAFETY: after the wait no submitted work uses the objects; each is destroyed once.
        unsafe {
            let _ = self.device.device_wait_idle();
            for destruction in self.created.borrow_mut().drain(..).rev() {
                destruction(&self.device);
            }
        }
    }
}

impl Drop for Vulkan {
    fn drop(&mut self) {
        self.release();
        // SAFETY: the device is idle and everything created from it is destroyed.
        unsafe {
            self.device.destroy_command_pool(self.command_pool, None);
            self.device.destroy_device(None);
            self.instance.destroy_instance(None);
        }
    }
}

/// What a descriptor set binding holds.
#[derive(Clone, Copy, Debug)]
pub enum Resource {
    /// An image view read as an input attachment, in `SHADER_READ_ONLY_OPTIMAL`.
    InputAttachment(vk::ImageView),
    /// An image view read as an input attachment by the subpass that also writes it (a
    /// feedback loop), in `GENERAL`.
    FeedbackAttachment(vk::ImageView),
    /// An image view sampled with a sampler, in `SHADER_READ_ONLY_OPTIMAL`.
    SampledImage(vk::ImageView, vk::Sampler),
    /// A storage buffer.
    StorageBuffer(vk::Buffer),
}

impl Resource {
    /// Its descriptor type.
    pub fn descriptor_type(&self) -> vk::DescriptorType {
        match self {
            Resource::InputAttachment(_) | Resource::FeedbackAttachment(_) => {
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
            Resource::FeedbackAttachment(view) => {
                (view, vk::Sampler::null(), vk::ImageLayout::GENERAL)
            }
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
