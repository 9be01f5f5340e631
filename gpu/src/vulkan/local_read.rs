//! Drawing without render pass objects: dynamic rendering (core in Vulkan 1.3) with
//! `VK_KHR_dynamic_rendering_local_read` (core in 1.4), under which a fragment shader reads the
//! attachments of the rendering it draws in as input attachments, as a subpass reads its own
//! (a by-region barrier between the draws, the attachments in `RENDERING_LOCAL_READ_KHR`). Where
//! the device also offers rasterization-order attachment access
//! (`VK_EXT_rasterization_order_attachment_access`, or ARM's extension it was promoted from),
//! a pipeline created with it reads what earlier fragments wrote in rasterization order, and
//! the draws need no barrier at all.
//!
//! Here: which of these a physical device offers, the features and extensions that enable
//! them when the device is opened, and the commands the host then calls.

use std::ffi::{c_char, CStr};

use ash::vk;

/// Which optional extensions [`super::Vulkan::with`] enables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OptionalExtensions {
    /// Every one the device offers: dynamic rendering with local read and rasterization-order
    /// attachment access.
    Offered,
    /// None: the device is opened as one without them, so that what refuses a path without
    /// them can be tested on a device that has them.
    None,
}

/// Dynamic rendering with local read, enabled on the device.
pub struct LocalRead {
    /// `vkCmdSetRenderingAttachmentLocationsKHR` and `vkCmdSetRenderingInputAttachmentIndicesKHR`.
    pub commands: ash::khr::dynamic_rendering_local_read::Device,
    /// The rasterization-order attachment access extension enabled with its
    /// `rasterizationOrderColorAttachmentAccess` feature, or why there is none.
    pub rasterization_order: Result<&'static CStr, String>,
}

/// What a physical device offers of these, found before it is opened.
pub(super) struct Offered {
    /// Dynamic rendering with local read, or why the device is opened without it.
    local_read: Result<(), String>,
    /// The rasterization-order extension to enable, or why none is.
    rasterization_order: Result<&'static CStr, String>,
}

/// The feature structures chained into `VkDeviceCreateInfo` for what is enabled.
pub(super) struct FeatureChain {
    local_read: bool,
    rasterization_order: bool,
    vulkan_13: vk::PhysicalDeviceVulkan13Features<'static>,
    dynamic_rendering_local_read: vk::PhysicalDeviceDynamicRenderingLocalReadFeaturesKHR<'static>,
    attachment_access: vk::PhysicalDeviceRasterizationOrderAttachmentAccessFeaturesEXT<'static>,
}

impl FeatureChain {
    /// `info` with the enabled features' structures chained to it.
    pub(super) fn extend<'a>(
        &'a mut self,
        info: vk::DeviceCreateInfo<'a>,
    ) -> vk::DeviceCreateInfo<'a> {
        let mut info = info;
        if self.local_read {
            info = info
                .push_next(&mut self.vulkan_13)
                .push_next(&mut self.dynamic_rendering_local_read);
            if self.rasterization_order {
                info = info.push_next(&mut self.attachment_access);
            }
        }
        info
    }
}

impl Offered {
    /// Neither, for this reason.
    fn without(why: String) -> Offered {
        Offered {
            local_read: Err(why.clone()),
            rasterization_order: Err(why),
        }
    }

    /// What `physical_device` offers at `api_version` (the instance's and the device's lower),
    /// of what `optional` asks for.
    pub(super) fn query(
        instance: &ash::Instance,
        physical_device: vk::PhysicalDevice,
        api_version: u32,
        optional: OptionalExtensions,
    ) -> Offered {
        if optional == OptionalExtensions::None {
            let why = "the device was opened without its optional extensions".to_string();
            return Offered::without(why);
        }
        // SAFETY: the physical device comes from the instance.
        let extensions = unsafe { instance.enumerate_device_extension_properties(physical_device) }
            .unwrap_or_default();
        let has = |name: &CStr| {
            extensions
                .iter()
                .any(|extension| extension.extension_name_as_c_str() == Ok(name))
        };
        let local_read_name = ash::khr::dynamic_rendering_local_read::NAME;
        if api_version < vk::API_VERSION_1_3 {
            let why = format!(
                "dynamic rendering needs Vulkan 1.3, and the device (or the loader) offers {}.{}",
                vk::api_version_major(api_version),
                vk::api_version_minor(api_version)
            );
            return Offered::without(why);
        }
        if !has(local_read_name) {
            let why = format!(
                "the device does not offer {}",
                local_read_name.to_string_lossy()
            );
            return Offered::without(why);
        }
        let mut vulkan_13 = vk::PhysicalDeviceVulkan13Features::default();
        let mut local_read = vk::PhysicalDeviceDynamicRenderingLocalReadFeaturesKHR::default();
        let mut attachment_access =
            vk::PhysicalDeviceRasterizationOrderAttachmentAccessFeaturesEXT::default();
        let order_names = [
            ash::ext::rasterization_order_attachment_access::NAME,
            ash::arm::rasterization_order_attachment_access::NAME,
        ];
        let order_name = order_names.into_iter().find(|name| has(name));
        {
            let mut features = vk::PhysicalDeviceFeatures2::default()
                .push_next(&mut vulkan_13)
                .push_next(&mut local_read);
            if order_name.is_some() {
                features = features.push_next(&mut attachment_access);
            }
            // SAFETY: every structure chained is the device's API version's or an extension it
            // lists.
            unsafe { instance.get_physical_device_features2(physical_device, &mut features) };
        }
        if vulkan_13.dynamic_rendering != vk::TRUE
            || local_read.dynamic_rendering_local_read != vk::TRUE
        {
            let why = "the device lists VK_KHR_dynamic_rendering_local_read but not the \
                       dynamicRendering and dynamicRenderingLocalRead features"
                .to_string();
            return Offered::without(why);
        }
        let rasterization_order = match order_name {
            None => Err(format!(
                "the device offers neither {} nor {}",
                order_names[0].to_string_lossy(),
                order_names[1].to_string_lossy()
            )),
            Some(name)
                if attachment_access.rasterization_order_color_attachment_access != vk::TRUE =>
            {
                Err(format!(
                    "the device lists {} without rasterizationOrderColorAttachmentAccess",
                    name.to_string_lossy()
                ))
            }
            Some(name) => Ok(name),
        };
        Offered {
            local_read: Ok(()),
            rasterization_order,
        }
    }

    /// The features to enable, to chain into the device's create info.
    pub(super) fn features(&self) -> FeatureChain {
        FeatureChain {
            local_read: self.local_read.is_ok(),
            rasterization_order: self.rasterization_order.is_ok(),
            vulkan_13: vk::PhysicalDeviceVulkan13Features::default().dynamic_rendering(true),
            dynamic_rendering_local_read:
                vk::PhysicalDeviceDynamicRenderingLocalReadFeaturesKHR::default()
                    .dynamic_rendering_local_read(true),
            attachment_access:
                vk::PhysicalDeviceRasterizationOrderAttachmentAccessFeaturesEXT::default()
                    .rasterization_order_color_attachment_access(true),
        }
    }

    /// The extensions to enable.
    pub(super) fn extension_names(&self) -> Vec<*const c_char> {
        let mut names = Vec::new();
        if self.local_read.is_ok() {
            names.push(ash::khr::dynamic_rendering_local_read::NAME.as_ptr());
            if let Ok(name) = self.rasterization_order {
                names.push(name.as_ptr());
            }
        }
        names
    }

    /// What the opened `device` has of them.
    pub(super) fn enabled(
        self,
        instance: &ash::Instance,
        device: &ash::Device,
    ) -> Result<LocalRead, String> {
        self.local_read.map(|()| LocalRead {
            commands: ash::khr::dynamic_rendering_local_read::Device::new(instance, device),
            rasterization_order: self.rasterization_order,
        })
    }
}
