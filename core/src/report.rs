//! The bit report of a layout, and what the same fields would cost as separate WebGPU render
//! targets: users choose between packed `Rgba32Uint` targets (one per 128 bits) and several
//! native-format targets, and WebGPU limits the bytes a sample may carry across all targets.

use std::fmt;

use crate::format::WebGpuTarget;
use crate::layout::Layout;

/// WebGPU's default `maxColorAttachmentBytesPerSample`.
pub const WEBGPU_BYTES_PER_SAMPLE_LIMIT: u32 = 32;
/// WebGPU's default `maxColorAttachments`.
pub const WEBGPU_COLOR_ATTACHMENT_LIMIT: usize = 8;
/// WebGL2's colour attachments in wgpu (`Limits::downlevel_webgl2_defaults`): 4. Its bytes per
/// sample are WebGPU's 32.
pub const WEBGL2_COLOR_ATTACHMENT_LIMIT: usize = 4;

/// The planes every implementation of WebGL's draft pixel local storage offers.
pub const WEBGL_DRAFT_PLANES: usize = 4;
/// The planes Chromium offers (on SwiftShader and on GPUs): planes and the shader's colour
/// outputs share this one limit (`MAX_COMBINED_DRAW_BUFFERS_AND_PIXEL_LOCAL_STORAGE_PLANES`).
pub const CHROMIUM_PLANES: usize = 8;

/// What WebGL's pixel local storage says to `planes` planes (one per word): one line.
pub fn webgl_planes(planes: usize) -> String {
    let plural = if planes == 1 { "" } else { "s" };
    if planes <= WEBGL_DRAFT_PLANES {
        format!(
            "{planes} plane{plural}: within the {WEBGL_DRAFT_PLANES} every implementation offers"
        )
    } else if planes <= CHROMIUM_PLANES {
        format!(
            "{planes} planes: over the {WEBGL_DRAFT_PLANES} the draft promises, within Chromium's \
             {CHROMIUM_PLANES} (planes and colour outputs together)"
        )
    } else {
        format!(
            "{planes} planes: over Chromium's {CHROMIUM_PLANES}; the include does not link there"
        )
    }
}

/// The bytes per sample of a list of render targets, as WebGPU validates it: for each target
/// in order, round the total up to its alignment, then add its cost.
pub fn bytes_per_sample(targets: impl IntoIterator<Item = WebGpuTarget>) -> u32 {
    targets.into_iter().fold(0, |total, target| {
        total.next_multiple_of(target.alignment) + target.byte_cost
    })
}

/// Tile memory budgets of mobile GPUs, for the "fits" column.
pub const TILE_BUDGETS: [(&str, u32); 3] = [
    ("PowerVR Series6", 128),
    ("PowerVR Series6XT and later", 256),
    ("Arm Mali PLS", 128),
];

/// A layout's bit report. Its `Display` is the text the examples and `gbuffer codegen` print.
#[derive(Clone, Debug)]
pub struct Report {
    /// The layout reported on.
    pub layout: Layout,
}

impl Report {
    /// The report of `layout`.
    pub fn new(layout: &Layout) -> Self {
        Report {
            layout: layout.clone(),
        }
    }

    /// Bytes per sample if every word were its own render target (a whole-word field in its
    /// format, a word of bit fields as `r32uint`).
    pub fn separate_targets_bytes(&self) -> u32 {
        bytes_per_sample(
            self.layout
                .word_contents()
                .iter()
                .map(|word| word.format.target().webgpu),
        )
    }

    /// Bytes per sample of the packed form ([`Layout::packed_target_bytes`]).
    pub fn packed_targets_bytes(&self) -> u32 {
        self.layout.packed_target_bytes()
    }
}

/// A layout's fields, one row each: the word, the name, the storage, the Rust type, the bit
/// range and the bits used, then the total. The bit report and the solver's summary print it.
pub struct FieldTable<'a>(pub &'a Layout);

impl FieldTable<'_> {
    /// The width of the name column: the longest name, at least that of `field`.
    fn name_width(&self) -> usize {
        self.0
            .fields
            .iter()
            .map(|field| field.name.len())
            .max()
            .unwrap_or(0)
            .max(5)
    }
}

impl fmt::Display for FieldTable<'_> {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let layout = self.0;
        let width = self.name_width();
        let storage_width = layout
            .fields
            .iter()
            .map(|field| field.storage_name().len())
            .max()
            .unwrap_or(0)
            .max(15);
        writeln!(
            out,
            "  {:<4} {:<width$} {:<storage_width$} {:<6} {:>5} {:>4}",
            "word", "field", "storage", "type", "bits", "used"
        )?;
        for (field, (word, member)) in layout.fields.iter().zip(layout.field_locations()) {
            let range = member.bit_range();
            writeln!(
                out,
                "  {word:<4} {:<width$} {:<storage_width$} {:<6} {range:>5} {:>4}",
                field.name,
                field.storage_name(),
                field.ty.rust_name(),
                field.used_bits()
            )?;
        }
        writeln!(
            out,
            "  {:<total_width$} {:>5} {:>4}",
            "total",
            layout.bits(),
            layout.used_bits(),
            total_width = width + storage_width + 14
        )
    }
}

impl fmt::Display for Report {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        let layout = &self.layout;
        let bits = layout.bits();
        writeln!(
            out,
            "{}: {} words, {bits} bits, {} used, budget {}",
            layout.name,
            layout.words(),
            layout.used_bits(),
            layout.budget
        )?;
        let table = FieldTable(layout);
        write!(out, "{table}")?;
        if bits <= layout.budget {
            writeln!(
                out,
                "  fits the {}-bit budget with {} bits of headroom",
                layout.budget,
                layout.budget - bits
            )?;
        } else {
            writeln!(
                out,
                "  OVER the {}-bit budget: {} > {}, {} bits spill",
                layout.budget,
                bits,
                layout.budget,
                bits - layout.budget
            )?;
        }
        let fits: Vec<&str> = TILE_BUDGETS
            .iter()
            .filter(|(_, budget)| bits <= *budget)
            .map(|(gpu, _)| *gpu)
            .collect();
        writeln!(
            out,
            "  tile memory: fits {}",
            if fits.is_empty() {
                "none of the listed GPUs".to_string()
            } else {
                fits.join(", ")
            }
        )?;

        writeln!(out, "  as separate WebGPU render targets (one per word):")?;
        let words = layout.word_contents();
        let word_names: Vec<String> = words
            .iter()
            .map(|word| layout.field_names(word).join(", "))
            .collect();
        let width = word_names
            .iter()
            .map(String::len)
            .max()
            .unwrap_or(0)
            .max(table.name_width());
        for (word, names) in words.iter().zip(&word_names) {
            let target = word.format.target().webgpu;
            let note = match target.feature {
                Some(feature) => format!("  (renderable only with the {feature} feature)"),
                None => String::new(),
            };
            writeln!(
                out,
                "    {names:<width$} {:<15} {} bytes{note}",
                target.name, target.byte_cost
            )?;
        }
        let separate = self.separate_targets_bytes();
        let verdict = if separate > WEBGPU_BYTES_PER_SAMPLE_LIMIT {
            "exceeds"
        } else {
            "within"
        };
        writeln!(out, "    total {separate} bytes per sample: {verdict} the default limit of {WEBGPU_BYTES_PER_SAMPLE_LIMIT}")?;
        if words.len() > WEBGPU_COLOR_ATTACHMENT_LIMIT {
            writeln!(out, "    {} targets exceed the default limit of {WEBGPU_COLOR_ATTACHMENT_LIMIT} colour attachments", words.len())?;
        }
        let packed = self.packed_targets_bytes();
        let verdict = if packed > WEBGPU_BYTES_PER_SAMPLE_LIMIT {
            "exceeds"
        } else {
            "within"
        };
        writeln!(
            out,
            "  packed: {} = {packed} bytes per sample: {verdict} the default limit",
            layout.packed_target_formats().join(" + ")
        )?;
        writeln!(out, "  {}", self.webgl2())?;
        writeln!(
            out,
            "  WebGL pixel local storage: {}",
            webgl_planes(self.layout.words())
        )
    }
}

impl Report {
    /// What WebGL2 (wgpu's `Limits::downlevel_webgl2_defaults`) says to the packed targets: one
    /// line, naming the limit they pass or break.
    pub fn webgl2(&self) -> String {
        let targets = self.layout.targets();
        let bytes = self.packed_targets_bytes();
        let mut broken = Vec::new();
        if targets > WEBGL2_COLOR_ATTACHMENT_LIMIT {
            broken.push(format!(
                "{targets} colour attachments, over max_color_attachments {WEBGL2_COLOR_ATTACHMENT_LIMIT}"
            ));
        }
        if bytes > WEBGPU_BYTES_PER_SAMPLE_LIMIT {
            broken.push(format!(
                "{bytes} bytes per sample, over max_color_attachment_bytes_per_sample \
                 {WEBGPU_BYTES_PER_SAMPLE_LIMIT}"
            ));
        }
        match broken.is_empty() {
            true => format!(
                "WebGL2: the packed targets fit ({targets} of {WEBGL2_COLOR_ATTACHMENT_LIMIT} \
                 colour attachments, {bytes} of {WEBGPU_BYTES_PER_SAMPLE_LIMIT} bytes per sample); \
                 its GLSL ES 3.00 has fragment passes only"
            ),
            false => format!("WebGL2: the packed targets need {}", broken.join(" and ")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field_type::FieldType;
    use crate::format::Format;
    use crate::layout::{Field, Storage};

    #[test]
    fn separate_targets_follow_webgpu_alignment_rules() {
        let rg16f = Format::Rg16f.target().webgpu;
        let rgba8 = Format::Rgba8.target().webgpu;
        let r32f = Format::R32f.target().webgpu;
        // rgba8unorm (8, align 1) then r32float (4, align 4): 8 is aligned, 12.
        assert_eq!(bytes_per_sample([rgba8, r32f]), 12);
        // rg16float (4) then rgba8uint (4, align 1) then r32float: 4 + 4 = 8, aligned, 12.
        assert_eq!(
            bytes_per_sample([rg16f, Format::Rgba8ui.target().webgpu, r32f]),
            12
        );
        // rgba8sint (4, align 1) then rg16float (align 2) then rg11b10ufloat (8, align 4).
        assert_eq!(
            bytes_per_sample([
                Format::Rgba8i.target().webgpu,
                rg16f,
                Format::R11fG11fB10f.target().webgpu
            ]),
            16
        );
    }

    #[test]
    fn mobile_metallic_costs_28_bytes_separate_and_16_packed() {
        let ty = |name| FieldType::from_rust_name(name).unwrap();
        let layout = Layout {
            name: "MobileMetallic".into(),
            budget: 128,
            fields: vec![
                Field {
                    name: "light_accumulation".into(),
                    storage: Storage::Word(Format::Rgb10A2),
                    ty: ty("Vec3"),
                    conversions: None,
                },
                Field {
                    name: "depth".into(),
                    storage: Storage::Word(Format::R32f),
                    ty: ty("f32"),
                    conversions: None,
                },
                Field {
                    name: "normals_roughness".into(),
                    storage: Storage::Word(Format::Rgba8),
                    ty: ty("Vec4"),
                    conversions: None,
                },
                Field {
                    name: "albedo_metallic".into(),
                    storage: Storage::Word(Format::Rgba8),
                    ty: ty("Vec4"),
                    conversions: None,
                },
            ],
        };
        let report = Report::new(&layout);
        assert_eq!(report.separate_targets_bytes(), 28);
        assert_eq!(report.packed_targets_bytes(), 16);
        let text = report.to_string();
        assert!(
            text.contains("4 words, 128 bits, 126 used, budget 128"),
            "{text}"
        );
        assert!(text.contains("total 28 bytes per sample: within"), "{text}");
    }
}
