//! The packed render targets a layout's words need, and their cost against WebGPU's limit.

use crate::format::PackedTarget;

use super::Layout;

impl Layout {
    /// Number of packed render targets the words need: one per four words.
    pub fn targets(&self) -> usize {
        self.words().div_ceil(4)
    }

    /// The packed render targets: `rgba32uint` for every four words, the last as narrow as the
    /// words it holds ([`PackedTarget::for_words`]).
    pub fn packed_targets(&self) -> Vec<PackedTarget> {
        PackedTarget::for_words(self.words())
    }

    /// The WebGPU names of the packed render targets, e.g. `["rgba32uint", "r32uint"]`.
    pub fn packed_target_formats(&self) -> Vec<&'static str> {
        self.packed_targets()
            .into_iter()
            .map(|target| target.target().webgpu.name)
            .collect()
    }

    /// Bytes per sample of the packed render targets, as WebGPU counts them against
    /// `maxColorAttachmentBytesPerSample`: 4 per 32-bit channel.
    pub fn packed_target_bytes(&self) -> u32 {
        self.packed_targets()
            .into_iter()
            .map(|target| target.target().webgpu.byte_cost)
            .sum()
    }
}
