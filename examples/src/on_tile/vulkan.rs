//! The on-tile renderer on Vulkan (to come).

use super::recording::Recording;
use super::TileOptions;
use crate::renderer::Frame;

/// Placeholder until the Vulkan backend lands.
pub struct VulkanRenderer;

impl VulkanRenderer {
    /// Not yet.
    pub fn new(_progress: &dyn Fn(&str)) -> Result<VulkanRenderer, String> {
        Err("the Vulkan backend is not built yet".into())
    }
    /// Not yet.
    pub fn render(&self, _tile: &TileOptions) -> Result<(Frame, Recording), String> {
        Err("the Vulkan backend is not built yet".into())
    }
}
