//! Barriers: what one access wrote, made visible to the next (memory, an image's layout, the
//! host's read back, a subpass reading what it wrote).

use ash::vk;

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

/// A draw's colour writes, then a later one's input attachment reads (in the next subpass, or
/// in the same subpass or dynamic rendering behind [`feedback_barrier`]).
pub const FEEDBACK: (Access, Access) = (
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
