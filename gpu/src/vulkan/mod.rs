//! A Vulkan device on a real driver, without a window: `ash` with the loader opened at run time
//! (Mesa's lavapipe here). Tests build render passes of several subpasses over transient
//! attachments, draw fullscreen triangles in each, and read what the shaders wrote to storage
//! buffers; the attachments themselves never leave the render pass, as on a tiler.
//!
//! Every object a test creates is recorded and destroyed by [`Vulkan::release`] (or when the
//! device is dropped), so a test creates what it needs without bookkeeping of its own.
//!
//! The device is split along its ideas: opening it and submitting work (here), memory and
//! images (`memory.rs`), host-visible buffers (`buffers.rs`), render passes and framebuffers
//! (`render_passes.rs`), drawing without them (`local_read.rs`: dynamic rendering with local
//! read), descriptors (`descriptors.rs`), pipelines (`pipelines.rs`) and barriers
//! (`barriers.rs`).

mod barriers;
mod buffers;
mod descriptors;
mod local_read;
mod memory;
mod pipelines;
mod render_passes;

pub use barriers::{feedback_barrier, host_read_barrier, Access, ImageTransition, FEEDBACK};
pub use buffers::StorageBuffer;
pub use descriptors::Resource;
pub use local_read::{LocalRead, OptionalExtensions};
pub use memory::AttachmentMemory;
pub use pipelines::{DrawsIn, GraphicsPipeline, RenderingAttachments};
pub use render_passes::Subpass;

use std::cell::RefCell;
use std::ffi::CStr;

use ash::vk;

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
    /// Dynamic rendering with local read, or why the device was opened without it.
    local_read: Result<LocalRead, String>,
    created: RefCell<Vec<Created>>,
    // Dropped last: it holds the loader the other handles' functions come from.
    _entry: ash::Entry,
}

impl Vulkan {
    /// Opens the first device with a graphics queue and fragment-shader stores, with every
    /// optional extension it offers enabled ([`OptionalExtensions::Offered`]). The error says
    /// what was missing (the loader, a device, a feature).
    pub fn new() -> Result<Vulkan, String> {
        Self::with(OptionalExtensions::Offered)
    }

    /// Opens the first device with a graphics queue and fragment-shader stores, with the
    /// optional extensions `optional` asks for where the device offers them.
    pub fn with(optional: OptionalExtensions) -> Result<Vulkan, String> {
        // SAFETY: loading libvulkan runs its initialisers; it is the system's loader.
        let entry = unsafe { ash::Entry::load() }.map_err(|error| {
            format!("cannot load the Vulkan loader ({error}): install Debian's libvulkan1 and mesa-vulkan-drivers")
        })?;
        // Vulkan 1.3 where the loader has it (dynamic rendering is core there), 1.1 otherwise.
        // SAFETY: a query of the loader.
        let loader_version = unsafe { entry.try_enumerate_instance_version() }
            .ok()
            .flatten()
            .unwrap_or(vk::API_VERSION_1_0);
        let api_version = if loader_version >= vk::API_VERSION_1_3 {
            vk::API_VERSION_1_3
        } else {
            vk::API_VERSION_1_1
        };
        let application = vk::ApplicationInfo::default().api_version(api_version);
        // SAFETY: a valid create info without layers or extensions.
        let instance = unsafe {
            entry.create_instance(
                &vk::InstanceCreateInfo::default().application_info(&application),
                None,
            )
        }
        .map_err(|error| format!("vkCreateInstance: {error}"))?;
        match Self::open_device(&instance, api_version, optional) {
            Ok((physical_device, device, queue_family, name, local_read)) => {
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
                        local_read,
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
    /// physical device, the logical device, its queue family, a description and dynamic
    /// rendering with local read (or why not).
    #[allow(clippy::type_complexity)]
    fn open_device(
        instance: &ash::Instance,
        api_version: u32,
        optional: OptionalExtensions,
    ) -> Result<
        (
            vk::PhysicalDevice,
            ash::Device,
            u32,
            String,
            Result<LocalRead, String>,
        ),
        String,
    > {
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
            // Storage writes from fragment shaders (the tests' readbacks), and independent
            // blend: a pass that writes some of its attachments and not others gives them
            // different write masks (VUID-VkPipelineColorBlendStateCreateInfo-pAttachments-00605).
            let needed = (
                features.fragment_stores_and_atomics,
                features.independent_blend,
            );
            let (Some(family), (vk::TRUE, vk::TRUE)) = (graphics, needed) else {
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
            let enabled = vk::PhysicalDeviceFeatures::default()
                .fragment_stores_and_atomics(true)
                .independent_blend(true);
            let offered = local_read::Offered::query(
                instance,
                physical_device,
                api_version.min(properties.api_version),
                optional,
            );
            let mut chain = offered.features();
            let extensions = offered.extension_names();
            // SAFETY: the queue family exists; the features and extensions are the device's own.
            let device = unsafe {
                instance.create_device(
                    physical_device,
                    &chain
                        .extend(
                            vk::DeviceCreateInfo::default()
                                .queue_create_infos(&queues)
                                .enabled_features(&enabled),
                        )
                        .enabled_extension_names(&extensions),
                    None,
                )
            }
            .map_err(|error| format!("vkCreateDevice on {name}: {error}"))?;
            let local_read = offered.enabled(instance, &device);
            return Ok((
                physical_device,
                device,
                family as u32,
                description,
                local_read,
            ));
        }
        Err(format!(
            "no Vulkan device has a graphics queue, fragmentStoresAndAtomics and independentBlend \
             (seen: {})",
            seen.join(", ")
        ))
    }

    /// The device's name, API version and driver version.
    pub fn describe(&self) -> &str {
        &self.name
    }

    /// Dynamic rendering with local read as the device was opened with it, or why it was not
    /// (the device's Vulkan version, a missing extension or feature, or not asked for).
    pub fn local_read(&self) -> Result<&LocalRead, &str> {
        self.local_read.as_ref().map_err(String::as_str)
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
