//! The names of the renderer's option values (`mobile-metallic`, `two-pass`, `ggx`), written
//! once: the examples' command lines, the bench's rows, the report's tables and the messages all
//! spell a value through [`Named`]. The renderer is a library; the command-line parsers live in
//! the examples and in `gbuffer-cli`, which take these names as their possible values.

use crate::gbuffers::{LayoutArgument, PackedLayout};
use crate::on_tile::{Backend, Path};
use crate::options::{IblForm, SunForm};

/// An option value with one name, in kebab case.
pub trait Named: Copy + Sized + 'static {
    /// Every value, in the order a command line lists them.
    const ALL: &'static [Self];

    /// The value's name.
    fn name(self) -> &'static str;

    /// The value a name stands for.
    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|value| value.name() == name)
    }

    /// Every name, in [`Self::ALL`]'s order.
    fn names() -> Vec<&'static str> {
        Self::ALL.iter().map(|value| value.name()).collect()
    }
}

impl Named for PackedLayout {
    /// The seeds, the engines', the coarse one and the lossless one.
    const ALL: &'static [Self] = &[
        PackedLayout::MobileMetallic,
        PackedLayout::SpecularWorkflow,
        PackedLayout::FutureMetallic,
        PackedLayout::FutureSpecular,
        PackedLayout::ArmTileBlock,
        PackedLayout::BevyDeferred,
        PackedLayout::HdrpLit,
        PackedLayout::CoarseNormals,
        PackedLayout::Lossless,
    ];

    fn name(self) -> &'static str {
        match self {
            PackedLayout::MobileMetallic => "mobile-metallic",
            PackedLayout::SpecularWorkflow => "specular-workflow",
            PackedLayout::FutureMetallic => "future-metallic",
            PackedLayout::FutureSpecular => "future-specular",
            PackedLayout::ArmTileBlock => "arm-tile-block",
            PackedLayout::BevyDeferred => "bevy-deferred",
            PackedLayout::HdrpLit => "hdrp-lit",
            PackedLayout::CoarseNormals => "coarse-normals",
            PackedLayout::Lossless => "lossless",
        }
    }
}

impl Named for LayoutArgument {
    /// Every packed layout, in its order, then the classic targets.
    const ALL: &'static [Self] = &{
        const PACKED: &[PackedLayout] = PackedLayout::ALL;
        let mut all = [LayoutArgument::Classic; PACKED.len() + 1];
        let mut index = 0;
        while index < PACKED.len() {
            all[index] = LayoutArgument::Packed(PACKED[index]);
            index += 1;
        }
        all
    };

    fn name(self) -> &'static str {
        match self {
            LayoutArgument::Packed(layout) => layout.name(),
            LayoutArgument::Classic => "classic",
        }
    }
}

impl Named for Backend {
    const ALL: &'static [Self] = &[Backend::Wgpu, Backend::Gles, Backend::Vulkan];

    fn name(self) -> &'static str {
        match self {
            Backend::Wgpu => "wgpu",
            Backend::Gles => "gles",
            Backend::Vulkan => "vulkan",
        }
    }
}

impl Named for Path {
    const ALL: &'static [Self] = &[
        Path::FetchNative,
        Path::FetchPacked,
        Path::Subpass,
        Path::TwoPass,
    ];

    fn name(self) -> &'static str {
        match self {
            Path::FetchNative => "fetch-native",
            Path::FetchPacked => "fetch-packed",
            Path::Subpass => "subpass",
            Path::TwoPass => "two-pass",
        }
    }
}

impl Named for SunForm {
    const ALL: &'static [Self] = &[SunForm::Ggx, SunForm::Approx];

    fn name(self) -> &'static str {
        match self {
            SunForm::Ggx => "ggx",
            SunForm::Approx => "approx",
        }
    }
}

impl Named for IblForm {
    const ALL: &'static [Self] = &[IblForm::Lut, IblForm::Approx];

    fn name(self) -> &'static str {
        match self {
            IblForm::Lut => "lut",
            IblForm::Approx => "approx",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_round_trip<T: Named + PartialEq + std::fmt::Debug>() {
        let names = T::names();
        for (index, value) in T::ALL.iter().enumerate() {
            assert_eq!(T::from_name(value.name()), Some(*value));
            assert!(
                !names[..index].contains(&value.name()),
                "{} named twice",
                value.name()
            );
        }
        assert_eq!(T::from_name("no-such-value"), None);
    }

    #[test]
    fn every_name_reads_back_as_its_value_and_no_two_values_share_one() {
        check_round_trip::<PackedLayout>();
        check_round_trip::<LayoutArgument>();
        check_round_trip::<Backend>();
        check_round_trip::<Path>();
        check_round_trip::<SunForm>();
        check_round_trip::<IblForm>();
    }
}
