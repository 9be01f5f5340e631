//! The wgpu side of a layout (feature `wgpu`): what a renderer needs to create, bind and check
//! a layout's packed render targets, derived from the layout so that no format or count is
//! written by hand.
//!
//! The G-buffer pass writes the struct that `pack_<snake>_targets` returns: words 4t to 4t + 3
//! in target t. Every target is `Rgba32Uint` except the last, which is as narrow as the words it
//! holds (`R32Uint` for one, `Rg32Uint` for two), so a layout costs the bytes per sample its
//! words take: 36 for nine words, where nine separate `R32Float` targets would also need nine
//! attachments.
//!
//! ```no_run
//! # extern crate gbuffer_runtime as gbuffer; // as the facade re-exports it, with the derive
//! # use gbuffer_macros::GBufferLayout;
//! use gbuffer::{GBufferLayout, GBufferTargets, glam::{Vec3, Vec4}, wgpu};
//!
//! #[derive(GBufferLayout, Clone, Copy)]
//! struct MobileMetallic {
//!     #[pls(rgb10_a2)] light_accumulation: Vec3,
//!     #[pls(r32f)]     depth: f32,
//!     #[pls(rgba8)]    normals_roughness: Vec4,
//!     #[pls(rgba8)]    albedo_metallic: Vec4,
//! }
//!
//! # fn renderer(adapter: &wgpu::Adapter, device: &wgpu::Device) -> Result<(), gbuffer::LimitError> {
//! MobileMetallic::check_limits(&adapter.limits())?; // or request MobileMetallic::required_limits(...)
//! let targets = MobileMetallic::create_targets(device, 1280, 720, wgpu::TextureUsages::empty());
//! let colour_targets = MobileMetallic::color_targets(); // the G-buffer pipeline's targets
//! let entries = MobileMetallic::bind_group_layout_entries(0, wgpu::ShaderStages::FRAGMENT);
//! let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
//!     label: Some("G-buffer"),
//!     entries: &entries,
//! });
//! let bind_group = MobileMetallic::create_bind_group(device, &layout, 0, &targets);
//! // The lighting shader: MobileMetallic::WGSL, then MobileMetallic::lighting_wgsl(0, 0), then
//! // code that calls `read_mobile_metallic_targets(pixel)`.
//! # Ok(())
//! # }
//! ```

use std::fmt;

use wgpu::{
    BindGroup, BindGroupEntry, BindGroupLayout, BindGroupLayoutEntry, BindingResource, BindingType,
    Color, ColorTargetState, ColorWrites, Device, Extent3d, Limits, LoadOp, Operations,
    RenderPassColorAttachment, ShaderStages, StoreOp, Texture, TextureDescriptor, TextureDimension,
    TextureFormat, TextureSampleType, TextureUsages, TextureView, TextureViewDimension,
};

use crate::layout::{Layout, PackedTarget};
use crate::GBufferLayout;

/// The most targets [`packed_target_formats`] describes: 16, twice what any adapter allows, so
/// that [`GBufferTargets::check_limits`] reports a layout too big for one as an error.
pub const MAX_PACKED_TARGETS: usize = 16;

/// The packed target formats for a layout of `words` words: `Rgba32Uint` for every four, the
/// last as narrow as the words it holds, as [`layout::Layout::packed_target_formats`] names
/// them. A layout of more than 64 words is a compile-time error where its formats are used.
///
/// [`layout::Layout::packed_target_formats`]: crate::layout::Layout::packed_target_formats
pub const fn packed_target_formats(words: usize) -> &'static [TextureFormat] {
    const WIDE: TextureFormat = texture_format(PackedTarget::FourWords);
    const fn ending(last: TextureFormat) -> [TextureFormat; MAX_PACKED_TARGETS] {
        let mut formats = [WIDE; MAX_PACKED_TARGETS];
        formats[MAX_PACKED_TARGETS - 1] = last;
        formats
    }
    const ENDING_WIDE: [TextureFormat; MAX_PACKED_TARGETS] = ending(WIDE);
    const ENDING_ONE: [TextureFormat; MAX_PACKED_TARGETS] =
        ending(texture_format(PackedTarget::OneWord));
    const ENDING_TWO: [TextureFormat; MAX_PACKED_TARGETS] =
        ending(texture_format(PackedTarget::TwoWords));
    let targets = PackedTarget::count_for_words(words);
    assert!(
        targets <= MAX_PACKED_TARGETS,
        "a layout of more than 64 words needs more than 16 render targets"
    );
    let formats: &'static [TextureFormat; MAX_PACKED_TARGETS] =
        match PackedTarget::last_for_words(words) {
            PackedTarget::OneWord => &ENDING_ONE,
            PackedTarget::TwoWords => &ENDING_TWO,
            PackedTarget::FourWords => &ENDING_WIDE,
        };
    formats.split_at(MAX_PACKED_TARGETS - targets).1
}

/// The wgpu format of a packed target of the format table: the one place the table's packed
/// targets become wgpu's enum.
pub const fn texture_format(target: PackedTarget) -> TextureFormat {
    match target {
        PackedTarget::OneWord => TextureFormat::R32Uint,
        PackedTarget::TwoWords => TextureFormat::Rg32Uint,
        PackedTarget::FourWords => TextureFormat::Rgba32Uint,
    }
}

/// A layout's render targets: one texture and its view per target format.
#[derive(Debug)]
pub struct GBufferTextures {
    /// One texture per target format.
    pub textures: Vec<Texture>,
    /// A view of each texture, in the same order.
    pub views: Vec<TextureView>,
}

impl GBufferTextures {
    /// The colour attachments of a pass that writes the G-buffer (`color_attachments` of its
    /// `RenderPassDescriptor`): every target cleared to `clear` and stored, in the order of
    /// [`GBufferTargets::color_targets`]. A packed target is an unsigned integer texture, so
    /// `clear`'s channels are integers (`f64::from(u32::MAX)` for all ones).
    pub fn color_attachments(&self, clear: Color) -> Vec<Option<RenderPassColorAttachment<'_>>> {
        self.views
            .iter()
            .map(|view| {
                Some(RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: Operations {
                        load: LoadOp::Clear(clear),
                        store: StoreOp::Store,
                    },
                })
            })
            .collect()
    }
}

/// A layout's targets exceed an adapter's limits: what they need against what the limits
/// allow. Its `Display` names both; [`GBufferTargets::required_limits`] gives limits that fit.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LimitError {
    /// The layout's name.
    pub layout: String,
    /// Colour attachments the targets need, and `max_color_attachments`.
    pub attachments: u32,
    /// `max_color_attachments` of the limits given.
    pub max_attachments: u32,
    /// Bytes per sample the targets need, and `max_color_attachment_bytes_per_sample`.
    pub bytes_per_sample: u32,
    /// `max_color_attachment_bytes_per_sample` of the limits given.
    pub max_bytes_per_sample: u32,
}

impl fmt::Display for LimitError {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            out,
            "G-buffer layout `{}` needs {} colour attachments (max_color_attachments allows {}) \
             and {} bytes per sample (max_color_attachment_bytes_per_sample allows {}): request \
             the layout's required_limits from an adapter that offers them, or shrink the layout",
            self.layout,
            self.attachments,
            self.max_attachments,
            self.bytes_per_sample,
            self.max_bytes_per_sample
        )
    }
}

impl std::error::Error for LimitError {}

/// The wgpu helpers of every [`GBufferLayout`]: its packed targets' formats, colour target
/// states, textures, bindings for the lighting pass and limits. Implemented for every layout;
/// `use gbuffer::GBufferTargets` (or `use gbuffer::*`) brings the items into scope.
///
/// What needs no device: five words take a four-word target and a one-word one, 20 bytes a
/// sample, within WebGPU's default limits (32 bytes) and refused by a device that allows 16:
///
/// ```
/// # extern crate gbuffer_runtime as gbuffer; // as the facade re-exports it, with the derive
/// # use gbuffer_macros::GBufferLayout;
/// use gbuffer::{GBufferLayout, GBufferTargets, glam::{Vec3, Vec4}, wgpu};
///
/// #[derive(GBufferLayout)]
/// #[gbuffer(budget = 160)]
/// struct SpecularWorkflow {
///     #[pls(rgb10_a2)] light: Vec3,
///     #[pls(r32f)]     depth: f32,
///     #[pls(rgba8)]    normal_roughness: Vec4,
///     #[pls(rgba8)]    base_colour: Vec3,
///     #[pls(rgba8)]    specular_colour: Vec3,
/// }
///
/// use wgpu::TextureFormat::{R32Uint, Rgba32Uint};
/// assert_eq!(SpecularWorkflow::TARGET_FORMATS, [Rgba32Uint, R32Uint]);
/// assert_eq!(SpecularWorkflow::bytes_per_sample(), 20);
/// assert!(SpecularWorkflow::check_limits(&wgpu::Limits::default()).is_ok());
/// let small = wgpu::Limits {
///     max_color_attachment_bytes_per_sample: 16,
///     ..wgpu::Limits::downlevel_webgl2_defaults()
/// };
/// let error = SpecularWorkflow::check_limits(&small).unwrap_err();
/// assert!(error.to_string().contains("20"), "{error}");
/// // What to request from an adapter whose limits go further than `small`.
/// let limits = SpecularWorkflow::required_limits(small);
/// assert_eq!(limits.max_color_attachment_bytes_per_sample, 20);
/// let lighting = SpecularWorkflow::lighting_wgsl(0, 0);
/// assert!(lighting.contains("fn read_specular_workflow_targets(pixel: vec2<u32>) -> SpecularWorkflow"));
/// ```
pub trait GBufferTargets: GBufferLayout {
    /// The formats of the targets `pack_<snake>_targets` writes, in location order.
    const TARGET_FORMATS: &'static [TextureFormat] = packed_target_formats(Self::WORDS);

    /// The G-buffer pipeline's colour targets: the formats, no blending, every channel written.
    fn color_targets() -> Vec<Option<ColorTargetState>> {
        Self::TARGET_FORMATS
            .iter()
            .map(|&format| {
                Some(ColorTargetState {
                    format,
                    blend: None,
                    write_mask: ColorWrites::ALL,
                })
            })
            .collect()
    }

    /// Creates the targets at `width` x `height`, usable as render attachments and as textures
    /// the lighting pass binds, plus `usage` (e.g. `COPY_SRC` to read them back).
    fn create_targets(
        device: &Device,
        width: u32,
        height: u32,
        usage: TextureUsages,
    ) -> GBufferTextures {
        create_targets(device, &Self::layout(), width, height, usage)
    }

    /// Bind group layout entries for the targets as unfiltered `texture_2d<u32>`s at bindings
    /// `first_binding`, `first_binding + 1`, ..., as [`Self::lighting_wgsl`] declares them.
    fn bind_group_layout_entries(
        first_binding: u32,
        visibility: ShaderStages,
    ) -> Vec<BindGroupLayoutEntry> {
        (0..Self::TARGET_FORMATS.len() as u32)
            .map(|index| BindGroupLayoutEntry {
                binding: first_binding + index,
                visibility,
                ty: BindingType::Texture {
                    sample_type: TextureSampleType::Uint,
                    view_dimension: TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            })
            .collect()
    }

    /// The bind group entries of the targets' views, at the bindings of
    /// [`Self::bind_group_layout_entries`]; add them to a group with other resources.
    fn bind_group_entries(
        first_binding: u32,
        targets: &GBufferTextures,
    ) -> Vec<BindGroupEntry<'_>> {
        bind_group_entries(first_binding, targets)
    }

    /// A bind group of the targets alone, for a layout made from
    /// [`Self::bind_group_layout_entries`] with the same `first_binding`.
    fn create_bind_group(
        device: &Device,
        layout: &BindGroupLayout,
        first_binding: u32,
        targets: &GBufferTextures,
    ) -> BindGroup {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("{} targets", Self::layout().name)),
            layout,
            entries: &Self::bind_group_entries(first_binding, targets),
        })
    }

    /// The lighting pass's WGSL for the targets, to put after [`GBufferLayout::WGSL`]: one
    /// `texture_2d<u32>` per target (`<snake>_target<t>`, in `group`, from `first_binding`),
    /// `load_<snake>_targets(pixel: vec2<u32>) -> <Name>Targets`, the words as stored, and
    /// `read_<snake>_targets(pixel: vec2<u32>) -> <Name>`, which loads and unpacks a texel.
    fn lighting_wgsl(group: u32, first_binding: u32) -> String {
        lighting_wgsl(&Self::layout(), group, first_binding)
    }

    /// Bytes per sample of the targets, as wgpu counts them against
    /// `max_color_attachment_bytes_per_sample`.
    fn bytes_per_sample() -> u32 {
        Self::layout().packed_target_bytes()
    }

    /// Whether `limits` allow the targets: colour attachments and bytes per sample. Counted
    /// from the words, so a layout too big for any adapter is an error here too.
    fn check_limits(limits: &Limits) -> Result<(), LimitError> {
        let attachments = PackedTarget::count_for_words(Self::WORDS) as u32;
        let bytes = Self::bytes_per_sample();
        if attachments <= limits.max_color_attachments
            && bytes <= limits.max_color_attachment_bytes_per_sample
        {
            return Ok(());
        }
        Err(LimitError {
            layout: Self::layout().name,
            attachments,
            max_attachments: limits.max_color_attachments,
            bytes_per_sample: bytes,
            max_bytes_per_sample: limits.max_color_attachment_bytes_per_sample,
        })
    }

    /// `base` raised where the targets need more: the limits to request from an adapter.
    fn required_limits(base: Limits) -> Limits {
        Limits {
            max_color_attachments: base
                .max_color_attachments
                .max(PackedTarget::count_for_words(Self::WORDS) as u32),
            max_color_attachment_bytes_per_sample: base
                .max_color_attachment_bytes_per_sample
                .max(Self::bytes_per_sample()),
            ..base
        }
    }
}

impl<T: GBufferLayout> GBufferTargets for T {}

// The helpers for a layout known at run time (a solved or loaded one, as a renderer that
// switches layouts holds them): what the trait's methods call with `Self::layout()`.

/// [`GBufferTargets::create_targets`] for `layout`.
pub fn create_targets(
    device: &Device,
    layout: &Layout,
    width: u32,
    height: u32,
    usage: TextureUsages,
) -> GBufferTextures {
    let textures: Vec<Texture> = packed_target_formats(layout.words())
        .iter()
        .enumerate()
        .map(|(index, &format)| {
            device.create_texture(&TextureDescriptor {
                label: Some(&format!("{} target {index}", layout.name)),
                size: Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: TextureDimension::D2,
                format,
                usage: usage | TextureUsages::RENDER_ATTACHMENT | TextureUsages::TEXTURE_BINDING,
                view_formats: &[],
            })
        })
        .collect();
    let views = textures
        .iter()
        .map(|texture| texture.create_view(&Default::default()))
        .collect();
    GBufferTextures { textures, views }
}

/// [`GBufferTargets::lighting_wgsl`] for a layout known at run time (a checked one): the WGSL
/// back end's `lighting_targets`, over the layout lowered here.
pub fn lighting_wgsl(layout: &Layout, group: u32, first_binding: u32) -> String {
    let lowered = gbuffer_codegen::LoweredLayout::new(layout);
    gbuffer_codegen::wgsl::lighting_targets(&lowered, group, first_binding)
}

/// [`GBufferTargets::bind_group_entries`]: the targets' views from `first_binding` on.
pub fn bind_group_entries(
    first_binding: u32,
    targets: &GBufferTextures,
) -> Vec<BindGroupEntry<'_>> {
    targets
        .views
        .iter()
        .enumerate()
        .map(|(index, view)| BindGroupEntry {
            binding: first_binding + index as u32,
            resource: BindingResource::TextureView(view),
        })
        .collect()
}
