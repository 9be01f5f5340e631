//! The packing conversions' trade, per format and mode (exact, fast): SPIR-V instructions after
//! `spirv-opt -O` and conditional branches (`crate::packing_cost`), the largest error
//! in codes and the fraction of channel codes that differ from exact, measured on the adapter
//! over edge cases and random values in fast conversions' domain, and the adapter's time to
//! pack a million texels and to unpack a million, each timed apart: a renderer packs in one pass
//! and unpacks in another, so no compiler ever sees the round trip whole.

use crate::stdout::report_line;
use std::fmt::Write as _;

use crate::packing_cost::{deviation, layout_cost, one_field, Cost, Deviation, CONVERTED_FORMATS};
use gbuffer_codegen::wgsl::emit_with;
use gbuffer_core::Conversions;
use gbuffer_core::Format;
use gbuffer_core::Named;
use gbuffer_gpu::Gpu;

use crate::timing;

/// Texels packed on the adapter per row to measure the deviation.
const TEXELS: usize = 1 << 20;

/// One format under one mode.
pub struct PackingRow {
    format: Format,
    conversions: Conversions,
    /// None where spirv-opt is missing or failed (the reason was printed).
    cost: Option<Cost>,
    deviation: Deviation,
    /// The adapter's times to pack a texel and to unpack one in both stages, less the
    /// harness's and the direction's glue: nanoseconds per texel are milliseconds per million.
    pack: timing::StageTimes,
    unpack: timing::StageTimes,
}

/// Which half of a conversion a time is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// A texel's values into its word.
    Pack,
    /// A word into the texel's values.
    Unpack,
}

// Both, in the table's order.
gbuffer_core::named!(
    /// `pack` or `unpack`.
    Direction {
        Pack => "pack",
        Unpack => "unpack",
    }
);

impl PackingRow {
    /// The time of `direction` in `stage`.
    pub fn time(&self, direction: Direction, stage: timing::Stage) -> Option<timing::GpuTime> {
        self.times(direction).get(stage)
    }

    fn times(&self, direction: Direction) -> &timing::StageTimes {
        match direction {
            Direction::Pack => &self.pack,
            Direction::Unpack => &self.unpack,
        }
    }

    fn mode(&self) -> &'static str {
        self.conversions.name()
    }
}

/// `row_eval` for the timing harness, one direction of the conversion alone in each step of
/// the harness's dependent chain, so that no compiler can fold a pack into the unpack after it:
///
/// - pack: the input's components packed as one texel of the format; the word goes on as a
///   fraction (`f32(word) / 2^32`), which every bit of it reaches, so no channel's code is
///   dead;
/// - unpack: a word the compiler cannot predict, hashed from the input's bits (Knuth's
///   multiplicative hash, then an exclusive or), with the top exponent bit of each float
///   channel cleared so that it decodes to a finite value (under 2), unpacked as one texel and
///   padded back to four components.
///
/// Each direction's glue alone is timed too ([`glue_wgsl`]) and taken off its rows' times.
fn row_wgsl(format: Format, conversions: Conversions, direction: Direction) -> String {
    let layout = one_field(format);
    let (value, rest) = match layout.fields[0].ty.components {
        2 => ("x.xy", ", x.zw"),
        3 => ("x.xyz", ", x.w"),
        _ => ("x", ""),
    };
    let body = match direction {
        Direction::Pack => format!(
            "let word = pack_texel(Texel({value}))[0];\n    \
             return vec4<f32>(f32(word) * 2.3283064e-10, x.yzw);"
        ),
        Direction::Unpack => format!(
            "let word = (bitcast<u32>(x.x) * 2654435761u ^ bitcast<u32>(x.y)) & {:#010x}u;\n    \
             let texel = unpack_texel(array<u32, 1>(word));\n    \
             return vec4<f32>(texel.value{rest});",
            finite_mask(format)
        ),
    };
    format!(
        "{}\n\nfn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    {body}\n}}\n",
        emit_with(&layout, conversions)
    )
}

/// `row_eval` for the glue of `direction`'s rows with no conversion, whose time is taken off
/// theirs: the pack rows' word, here the input's first component's bits, on as a fraction; the
/// unpack rows' hashed word as the first component, its low 23 bits the mantissa of a float in
/// [1, 2) (never a denormal, which a CPU's float unit may take a hundred cycles over).
fn glue_wgsl(direction: Direction) -> String {
    let body = match direction {
        Direction::Pack => {
            "let word = bitcast<u32>(x.x);\n    \
             return vec4<f32>(f32(word) * 2.3283064e-10, x.yzw);"
        }
        Direction::Unpack => {
            "let word = (bitcast<u32>(x.x) * 2654435761u ^ bitcast<u32>(x.y)) & 0x007fffffu;\n    \
             return vec4<f32>(bitcast<f32>(word | 0x3f800000u), x.yzw);"
        }
    };
    format!("fn row_eval(x: vec4<f32>) -> vec4<f32> {{\n    {body}\n}}\n")
}

/// The bits an unpack row keeps of its hashed word: all, but the top exponent bit of each float
/// channel (rg16f's two halves at bits 14 and 30; r11f_g11f_b10f's 5-bit exponents, whose top
/// bits are 10, 21 and 31), so that every word decodes to a finite value.
pub(crate) fn finite_mask(format: Format) -> u32 {
    match format {
        Format::Rg16f => !(1 << 14 | 1 << 30),
        Format::R11fG11fB10f => !(1 << 10 | 1 << 21 | 1 << 31),
        _ => u32::MAX,
    }
}

/// Every format and mode the packing table has, in its order.
pub(crate) fn modes() -> impl Iterator<Item = (Format, Conversions)> {
    CONVERTED_FORMATS.into_iter().flat_map(|format| {
        [Conversions::Exact, Conversions::Fast].map(|conversions| (format, conversions))
    })
}

/// Adds each direction's glue, then each format's pack and unpack in both modes, to `timer`;
/// their indices in the timer's times, in that order (the glue's pack and unpack, then per
/// row of the table its pack and its unpack), for [`conversion_times`].
pub fn time_rows(timer: &mut timing::Timer) -> Vec<usize> {
    let conversions: Vec<(Format, Conversions)> = modes().collect();
    time_rows_of(timer, &conversions)
}

/// As [`time_rows`], for `conversions` alone (in their order): the glue, then each one's pack
/// and unpack.
pub(crate) fn time_rows_of(
    timer: &mut timing::Timer,
    conversions: &[(Format, Conversions)],
) -> Vec<usize> {
    let mut indices: Vec<usize> = Direction::ALL
        .iter()
        .map(|&direction| {
            let name = format!("{} glue", direction.name());
            timer.add(&name, &glue_wgsl(direction), &[], 1)
        })
        .collect();
    for &(format, conversions) in conversions {
        for &direction in Direction::ALL {
            let name = format!(
                "{} {} {}",
                format.name(),
                conversions.name(),
                direction.name()
            );
            let wgsl = row_wgsl(format, conversions, direction);
            indices.push(timer.add(&name, &wgsl, &[], 1));
        }
    }
    indices
}

/// Per row of the table, in its order (each format's exact, then fast), its pack's and its
/// unpack's times less their glue's, from `times` in [`time_rows`]' order.
pub fn conversion_times(
    times: &[timing::StageTimes],
) -> Vec<(timing::StageTimes, timing::StageTimes)> {
    let (glue, rows) = times.split_at(2);
    rows.chunks(2)
        .map(|pair| (pair[0].less(&glue[0]), pair[1].less(&glue[1])))
        .collect()
}

/// Measures both modes of every format fast conversions change, with their `times` (in
/// [`time_rows`]'s order). The error is wgpu's, where it rejected a harness.
pub fn measure(gpu: &Gpu, times: &[timing::StageTimes]) -> Result<Vec<PackingRow>, String> {
    let mut rows = Vec::new();
    for ((format, conversions), (pack, unpack)) in modes().zip(conversion_times(times)) {
        eprintln!("packing: {} ({conversions:?})", format.name());
        let layout = one_field(format);
        let cost = layout_cost(&layout, conversions)
            .map_err(|error| eprintln!("  no instruction count: {error}"))
            .ok();
        let wgsl = emit_with(&layout, conversions);
        let deviation = deviation(gpu, &layout, &wgsl, TEXELS, 91)?;
        rows.push(PackingRow {
            format,
            conversions,
            cost,
            deviation,
            pack,
            unpack,
        });
    }
    Ok(rows)
}

/// The rows as the consistency check groups them in `stage` and `direction`: each format's two
/// modes, with `times` (one per row, the stage's and direction's), by the instructions of the
/// whole conversion (pack and unpack), which exact and fast split alike.
pub fn timed_groups<'a>(
    rows: &'a [PackingRow],
    times: &'a [Option<timing::GpuTime>],
    direction: Direction,
    stage: timing::Stage,
) -> Vec<Vec<timing::Timed<'a>>> {
    CONVERTED_FORMATS
        .iter()
        .map(|format| {
            rows.iter()
                .zip(times)
                .filter(|(row, _)| row.format == *format)
                .filter_map(|(row, time)| {
                    Some(timing::Timed {
                        name: format!(
                            "{} {} {} ({})",
                            row.format.name(),
                            row.mode(),
                            direction.name(),
                            stage.name()
                        ),
                        instructions: row.cost?.instructions,
                        time: time.as_ref(),
                    })
                })
                .collect()
        })
        .collect()
}

/// What the time column means on this adapter: a software rasteriser's times are a CPU's.
fn time_note(gpu: &Gpu) -> &'static str {
    if gpu.info.device_type == wgpu::DeviceType::Cpu {
        "The adapter is a software rasteriser: its times are a CPU's, not a GPU's."
    } else {
        "Times are the adapter's."
    }
}

/// A row's cells: format, mode, instructions, branches, largest error, differing, and the
/// pack and unpack times in compute, then in fragment.
fn cells(row: &PackingRow) -> [String; 10] {
    let count = |pick: fn(Cost) -> usize| {
        row.cost
            .map_or_else(|| "n/a".to_string(), |cost| pick(cost).to_string())
    };
    [
        row.format.name().to_string(),
        row.mode().to_string(),
        count(|cost| cost.instructions),
        count(|cost| cost.conditional_branches),
        row.deviation.largest_code_error().to_string(),
        format!("{:.3}%", 100.0 * row.deviation.differing_fraction()),
        crate::measured::format_time(row.pack.compute),
        crate::measured::format_time(row.unpack.compute),
        crate::measured::format_time(row.pack.fragment),
        crate::measured::format_time(row.unpack.fragment),
    ]
}

/// The table on standard output.
pub fn print(rows: &[PackingRow], gpu: &Gpu) {
    report_line!("\npacking conversions ({})", time_note(gpu));
    let line = |cells: &[String; 10]| {
        format!(
            "{:<16} {:<6} {:>12} {:>8} {:>11} {:>10} {:>11} {:>11} {:>11} {:>11}",
            cells[0],
            cells[1],
            cells[2],
            cells[3],
            cells[4],
            cells[5],
            cells[6],
            cells[7],
            cells[8],
            cells[9]
        )
    };
    let header = [
        "format",
        "mode",
        "instructions",
        "branches",
        "max codes",
        "differing",
        "pack",
        "unpack",
        "frag pack",
        "frag unpack",
    ];
    report_line!("(times in ms per million texels, each direction in its own dependent chain)");
    report_line!("{}", line(&header.map(str::to_string)));
    for row in rows {
        report_line!("{}", line(&cells(row)));
    }
}

/// The report's section.
pub fn markdown(rows: &[PackingRow], gpu: &Gpu) -> String {
    let mut out = String::from("\n## Packing conversions\n\n");
    let _ = writeln!(out, "Per format and mode: SPIR-V instructions of a compute shader that packs one texel and unpacks one (naga, then `spirv-opt -O`; about 14 are the harness's) and its conditional branches; the largest difference between a channel's code and the exact one, and the fraction of channel codes that differ, over {TEXELS} texels packed on the adapter (edge cases, then random values: finite, within f16's range); the adapter's milliseconds to pack a million texels and to unpack a million, each direction timed apart in a dependent chain of its own (a renderer packs in one pass and unpacks in another, so no compiler sees the round trip whole: the packed word goes on as a fraction every bit of it reaches, and unpack is fed words hashed from the chain's values, which no compiler can predict; that glue, two or three instructions, is timed alone and taken off each time), in a compute dispatch and in a fullscreen draw's fragment shader. {}\n", time_note(gpu));
    out.push_str(
        "| format | mode | instructions | branches | largest error (codes) | differing | pack ms per million texels (compute) | unpack ms per million texels (compute) | pack ms per million texels (fragment) | unpack ms per million texels (fragment) |\n",
    );
    out.push_str("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for row in rows {
        let _ = writeln!(out, "| {} |", cells(row).join(" | "));
    }
    out
}

/// The report's JSON entries.
pub fn json(rows: &[PackingRow]) -> serde_json::Value {
    serde_json::json!(rows
        .iter()
        .map(|row| serde_json::json!({
            "format": row.format.name(),
            "mode": row.mode(),
            "spirv_instructions": row.cost.map(|cost| cost.instructions),
            "conditional_branches": row.cost.map(|cost| cost.conditional_branches),
            "largest_code_error": row.deviation.largest_code_error(),
            "differing_fraction": row.deviation.differing_fraction(),
            "pack_ms_per_million_texels": row.pack.compute.filter(timing::GpuTime::resolved).map(|time| time.ns.median),
            "unpack_ms_per_million_texels": row.unpack.compute.filter(timing::GpuTime::resolved).map(|time| time.ns.median),
            "timings": {
                "pack": crate::json::timings_json(&row.pack),
                "unpack": crate::json::timings_json(&row.unpack),
            },
        }))
        .collect::<Vec<_>>())
}

/// The targets of the packing table's compiler columns.
pub const COMPILER_TARGETS: [&str; 4] = ["mali-g610", "mali-g52", "adreno-740", "amd-navi21"];

/// The packing conversions on the GPUs' compilers: per converted format its exact, fast and
/// builtin forms, and per seed and engine layout its exact and fast ones, each in the compute
/// harness the SPIR-V column counts (pack one texel, unpack one), each invocation its own.
pub struct CompiledPacking {
    /// Per shader: the format's or layout's name, and its mode (`exact`, `fast`, `builtin`).
    pub rows: Vec<(String, &'static str)>,
    /// The compilers' columns.
    pub compiled: crate::compilers::Compiled,
}

/// Compiles the packing harnesses on [`COMPILER_TARGETS`].
pub fn compile_on_compilers() -> CompiledPacking {
    let mut rows = Vec::new();
    let mut shaders = Vec::new();
    let harness = |wgsl: &str, words: usize| {
        gbuffer_cost::Shader::wgsl(
            &crate::packing_cost::invocation_harness(wgsl, words),
            "main",
        )
    };
    for format in CONVERTED_FORMATS {
        let layout = one_field(format);
        for conversions in [Conversions::Exact, Conversions::Fast] {
            rows.push((format.name().to_string(), conversions.name()));
            shaders.push(harness(&emit_with(&layout, conversions), 1));
        }
        if let Some(builtin) = crate::packing_cost::builtin_form(format) {
            rows.push((format.name().to_string(), "builtin"));
            shaders.push(harness(&builtin, 1));
        }
    }
    for (layout, _) in gbuffer_runtime::seed_layouts::all()
        .into_iter()
        .chain(gbuffer_runtime::engine_layouts::all())
    {
        let mut renamed = layout.clone();
        renamed.name = "Texel".into();
        for conversions in [Conversions::Exact, Conversions::Fast] {
            rows.push((layout.name.clone(), conversions.name()));
            shaders.push(harness(&emit_with(&renamed, conversions), renamed.words()));
        }
    }
    CompiledPacking {
        rows,
        compiled: crate::compilers::compile(
            &shaders,
            &COMPILER_TARGETS,
            crate::compilers::MaliCycles::Arithmetic,
        ),
    }
}

impl CompiledPacking {
    /// Exact's figure over fast's on column `column` for row `index` (an exact row), where both
    /// are there.
    fn ratio(&self, column: &crate::compilers::Column, index: usize) -> Option<f64> {
        let (name, mode) = &self.rows[index];
        if *mode != "exact" {
            return None;
        }
        let fast = self
            .rows
            .iter()
            .position(|(other, other_mode)| other == name && *other_mode == "fast")?;
        Some(column.figure(index)? / column.figure(fast)?)
    }

    /// The table in markdown: a row per shader, a column per target, and for exact rows their
    /// ratio to fast on Mali-G610 (cycles) and Adreno 740 (instructions).
    pub fn markdown(&self) -> String {
        let mut out = String::from("\n## Packing conversions on GPU compilers\n\n");
        let _ = writeln!(out, "The packing harness above (pack one texel, unpack one, in a compute shader; here each invocation its own texel, which no compiler can hoist) compiled by the GPUs' own compilers: Mali's estimated arithmetic cycles per invocation (the busiest arithmetic unit's; the harness's loads and stores, alike for every form, bound Mali's total), Adreno's and AMD's instructions. `exact / fast` is exact's figure over fast's. {}\n", self.compiled.provenance());
        let columns = self.compiled.columns();
        let mut heading = String::from("| format or layout | mode |");
        let mut rule = String::from("| --- | --- |");
        for column in columns {
            let _ = write!(heading, " {} |", column.heading());
            rule.push_str(" ---: |");
        }
        heading.push_str(" exact / fast (mali-g610, adreno-740) |\n");
        rule.push_str(" ---: |\n");
        out.push_str(&heading);
        out.push_str(&rule);
        for (index, (name, mode)) in self.rows.iter().enumerate() {
            let _ = write!(out, "| {name} | {mode} |");
            for column in columns {
                let _ = write!(
                    out,
                    " {} |",
                    crate::compilers::format_figure(column.figure(index))
                );
            }
            let ratios: Vec<String> = columns
                .iter()
                .filter(|column| matches!(column.target, "mali-g610" | "adreno-740"))
                .map(|column| match self.ratio(column, index) {
                    Some(ratio) => format!("{ratio:.2}x"),
                    None => "-".to_string(),
                })
                .collect();
            let _ = writeln!(out, " {} |", ratios.join(", "));
        }
        out
    }

    /// The report's JSON: per shader its name, mode and each compiler's statistics.
    pub fn json(&self) -> serde_json::Value {
        serde_json::json!({
            "compilers": self.compiled.provenance_json(),
            "rows": self.rows.iter().enumerate().map(|(index, (name, mode))| serde_json::json!({
                "name": name,
                "mode": mode,
                "compilers": self.compiled.json(index),
            })).collect::<Vec<_>>(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every format, mode and direction, and each direction's glue, makes a valid shader in
    /// both of the timer's harnesses.
    #[test]
    fn every_direction_of_every_conversion_is_a_valid_harness() {
        let glue = Direction::ALL.iter().map(|&direction| {
            (
                Format::Rgba8,
                Conversions::Exact,
                direction,
                glue_wgsl(direction),
            )
        });
        let rows = modes().flat_map(|(format, conversions)| {
            Direction::ALL.iter().map(move |&direction| {
                let row = row_wgsl(format, conversions, direction);
                (format, conversions, direction, row)
            })
        });
        for (format, conversions, direction, row) in glue.chain(rows) {
            {
                for shader in [timing::harness(&row), timing::fragment_harness(&row)] {
                    if let Err(problem) = gbuffer_validator::validate_wgsl(&shader) {
                        panic!("{format:?} {conversions:?} {direction:?}: {problem}");
                    }
                }
            }
        }
    }

    /// Neither direction's row calls the other direction's function: the chain holds a pack or
    /// an unpack, never the round trip a compiler could fold.
    #[test]
    fn a_row_times_one_direction_alone() {
        for (format, conversions) in modes() {
            let layout_text = emit_with(&one_field(format), conversions);
            let eval = |direction| {
                let row = row_wgsl(format, conversions, direction);
                row[layout_text.len()..].to_string()
            };
            let (pack, unpack) = (eval(Direction::Pack), eval(Direction::Unpack));
            assert!(
                pack.contains("pack_texel(") && !pack.contains("unpack_texel("),
                "{pack}"
            );
            assert!(
                unpack.contains("unpack_texel(") && !unpack.contains(" pack_texel("),
                "{unpack}"
            );
        }
    }

    /// The unpack row's words decode to finite values under 2 on every channel, as the Rust
    /// mirror decodes them, whatever the hash gives: 65,536 words of a pseudo-random walk, and
    /// the word with every bit the mask keeps.
    #[test]
    fn the_unpack_rows_words_decode_finite() {
        for format in CONVERTED_FORMATS {
            let mask = finite_mask(format);
            let mut word = 0x9e37_79b9u32;
            for _ in 0..1 << 16 {
                word = word.wrapping_mul(2_654_435_761).rotate_left(7) ^ 0x5bd1_e995;
                let values: [f32; 4] = format.decode(word & mask);
                assert!(
                    values
                        .iter()
                        .all(|value| value.is_finite() && value.abs() < 2.0),
                    "{format:?}: {:#010x} decodes to {values:?}",
                    word & mask
                );
            }
            // Every bit the mask keeps set at once: the largest exponents it allows.
            let all: [f32; 4] = format.decode(mask);
            assert!(
                all.iter().all(|value| value.is_finite()),
                "{format:?}: {all:?}"
            );
        }
    }
}
