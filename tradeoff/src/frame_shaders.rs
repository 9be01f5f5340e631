//! The frame table's shaders on the GPUs' compilers: per layout the on-tile renderer keeps, its
//! G-buffer pass and its per-pixel lighting in three forms, compiled as GLES drivers see them
//! (`gbuffer-cost`):
//!
//! - two-pass: the on-tile backends' two passes translated to GLSL ES, the G-buffer read back
//!   as textures (`gbuffer_main`; `lighting_resolve_main`, the environment, the sun, the 32
//!   point lights and the tone mapping on every pixel, with positions from the texel as on GL);
//! - fused packed and fused native: the fused GLES programs, the G-buffer read by framebuffer
//!   fetch as packed words or in its formats (the geometry stage; the lighting stage, the same
//!   light, and the resolve, summed).
//!
//! The decals are left out of those sums (they shade only the pixels their volumes cover); a
//! second table gives each fused stage alone (geometry, decal, lighting, resolve, sky), the
//! compilers' side of the bench's stage times. A fused native form whose
//! attachments and output pass the eight draw buffers both drivers offer is left out, as the
//! renderer refuses it.

use std::fmt::Write as _;

use gbuffer_core::Named;
use gbuffer_cost::Shader;
use gbuffer_render::fused_programs::{fused_programs, FusedDialect};
use gbuffer_render::gbuffers::GBuffer;
use gbuffer_render::on_tile::{Path as TilePath, Stage};
use gbuffer_render::shaders::{gbuffer_wgsl, lighting_pass_wgsl, Positions};

use crate::compilers::{compile, format_figure, Compiled, MaliCycles};

/// The compilers of the frame's shaders.
pub const TARGETS: [&str; 3] = ["mali-g610", "mali-g52", "adreno-740"];

/// The draw buffers GLES guarantees, and Mali and Adreno offer.
const MAX_DRAW_BUFFERS: usize = 8;

/// The three forms, by name.
const FORMS: [&str; 3] = ["two-pass", "fused packed", "fused native"];

/// One layout in one form: the indices of its shaders among those compiled, per pass (the
/// G-buffer pass, then the lighting draws, summed).
struct FormShaders {
    layout: String,
    form: &'static str,
    gbuffer: Vec<usize>,
    lighting: Vec<usize>,
    /// A fused form's stages, each with its shader's index (empty for two-pass).
    stages: Vec<(Stage, usize)>,
}

/// The frame's shaders of every layout the on-tile paths keep, compiled.
pub struct FrameShaders {
    forms: Vec<FormShaders>,
    compiled: Compiled,
}

/// Compiles the G-buffer and lighting passes of the frame table's layouts in every form they
/// render in.
pub fn compile_frames() -> FrameShaders {
    let mut shaders: Vec<Result<Shader, String>> = Vec::new();
    let mut forms = Vec::new();
    let mut add = |shader: Result<Shader, String>| {
        shaders.push(shader);
        shaders.len() - 1
    };
    for (layout, _) in crate::frames::packed_layouts() {
        let options = crate::frames::options(GBuffer::Packed(layout));
        let Ok(lighting_wgsl) = lighting_pass_wgsl(&options, Positions::Texel) else {
            continue;
        };
        let translated = |wgsl: &str, entry: &str| {
            Shader::wgsl(wgsl, entry).map_err(|error| format!("{}: {error}", layout.name()))
        };
        let gbuffer = add(translated(&gbuffer_wgsl(&options, -1.0), "gbuffer_main"));
        let lighting = add(translated(&lighting_wgsl, "lighting_resolve_main"));
        forms.push(FormShaders {
            layout: layout.name().to_string(),
            form: FORMS[0],
            gbuffer: vec![gbuffer],
            lighting: vec![lighting],
            stages: Vec::new(),
        });
        for (path, form) in [
            (TilePath::FetchPacked, FORMS[1]),
            (TilePath::FetchNative, FORMS[2]),
        ] {
            let Some(Ok(fused)) =
                FusedDialect::of(path).map(|dialect| fused_programs(&options, dialect))
            else {
                continue;
            };
            if fused.interface.attachments.len() + 1 > MAX_DRAW_BUFFERS {
                continue;
            }
            let stages: Vec<(Stage, usize)> = fused
                .programs
                .iter()
                .map(|program| {
                    let shader = program.glsl_vertex().map(|vertex| {
                        Shader::glsl(gbuffer_cost::Stage::Fragment, &program.fragment)
                            .with_vertex(vertex)
                    });
                    (program.stage, add(shader))
                })
                .collect();
            let of = |stage: Stage| {
                stages
                    .iter()
                    .find(|(s, _)| *s == stage)
                    .map(|(_, index)| *index)
                    .expect("every stage is compiled")
            };
            forms.push(FormShaders {
                layout: layout.name().to_string(),
                form,
                gbuffer: vec![of(Stage::Geometry)],
                lighting: vec![of(Stage::Lighting), of(Stage::Resolve)],
                stages,
            });
        }
    }
    FrameShaders {
        forms,
        compiled: compile(&shaders, &TARGETS, MaliCycles::Total),
    }
}

impl FrameShaders {
    /// The sum of `indices`' figures on `target`, with Mali's split (arithmetic, load/store,
    /// texture) where `target` is a Mali.
    fn pass(&self, target: &str, indices: &[usize]) -> Option<(f64, Option<[f64; 3]>)> {
        let column = self
            .compiled
            .columns()
            .iter()
            .find(|column| column.target == target)?;
        let mut total = 0.0;
        let mut split = [0.0; 3];
        let mut has_split = false;
        for &index in indices {
            total += column.figure(index)?;
            if let Some(Some(statistics)) = column.statistics.get(index) {
                if let Some(cycles) = &statistics.cycles {
                    let part = |name: &str| {
                        cycles
                            .parts
                            .iter()
                            .find(|part| part.name == name)
                            .map_or(0.0, |part| part.value)
                    };
                    split[0] += cycles.arithmetic();
                    split[1] += part("load_store");
                    split[2] += part("texture");
                    has_split = true;
                }
            }
        }
        Some((total, has_split.then_some(split)))
    }

    fn cell(&self, target: &str, indices: &[usize]) -> String {
        match self.pass(target, indices) {
            None => "-".to_string(),
            Some((total, Some([arithmetic, load_store, texture]))) => format!(
                "{} ({} / {} / {})",
                format_figure(Some(total)),
                format_figure(Some(arithmetic)),
                format_figure(Some(load_store)),
                format_figure(Some(texture))
            ),
            Some((total, None)) => format_figure(Some(total)),
        }
    }

    /// A form's cost per pixel on Mali-G610: its G-buffer pass and lighting, in cycles.
    fn g610_per_pixel(&self, form: &FormShaders) -> Option<f64> {
        Some(self.pass("mali-g610", &form.gbuffer)?.0 + self.pass("mali-g610", &form.lighting)?.0)
    }

    /// Per layout, the form that costs least per pixel on Mali-G610, and by how much.
    fn least(&self) -> Vec<String> {
        let mut layouts: Vec<&str> = self.forms.iter().map(|form| form.layout.as_str()).collect();
        layouts.dedup();
        layouts
            .into_iter()
            .filter_map(|layout| {
                let mut costs: Vec<(&str, f64)> = self
                    .forms
                    .iter()
                    .filter(|form| form.layout == layout)
                    .filter_map(|form| Some((form.form, self.g610_per_pixel(form)?)))
                    .collect();
                costs.sort_by(|a, b| a.1.total_cmp(&b.1));
                let (best, cost) = *costs.first()?;
                let others: Vec<String> = costs[1..]
                    .iter()
                    .map(|(form, other)| format!("{form} {:.2}x", other / cost))
                    .collect();
                let against = if others.is_empty() {
                    "the only form here".to_string()
                } else {
                    others.join(", ")
                };
                Some(format!(
                    "{layout}: {best} costs least on Mali-G610, {} cycles a pixel ({against})",
                    format_figure(Some(cost)),
                ))
            })
            .collect()
    }

    /// The table in markdown.
    pub fn markdown(&self) -> String {
        let mut out = String::from("\n## Frames on GPU compilers\n\n");
        let _ = writeln!(out, "Per layout the on-tile paths keep: the G-buffer pass and the lighting every pixel gets (the environment, the sun, the 32 point lights and the tone mapping; the decals are left out) as GLES drivers compile them. Two-pass: the on-tile backends' two passes translated, the G-buffer read as textures; fused: the GLES programs, the G-buffer read by framebuffer fetch as packed words or in its formats. Mali's estimated cycles per pixel with (arithmetic / load-store / texture), Adreno's instructions. The bandwidth units are the frame table's. {}\n", self.compiled.provenance());
        out.push_str("| layout | form |");
        for target in TARGETS {
            let _ = write!(out, " G-buffer pass {target} | lighting {target} |");
        }
        out.push('\n');
        out.push_str("| --- | --- |");
        out.push_str(&" ---: | ---: |".repeat(TARGETS.len()));
        out.push('\n');
        for form in &self.forms {
            let _ = write!(out, "| {} | {} |", form.layout, form.form);
            for target in TARGETS {
                let _ = write!(
                    out,
                    " {} | {} |",
                    self.cell(target, &form.gbuffer),
                    self.cell(target, &form.lighting)
                );
            }
            out.push('\n');
        }
        out.push('\n');
        for line in self.least() {
            let _ = writeln!(out, "- {line}");
        }
        out.push_str(&self.stages_markdown());
        out
    }

    /// Each fused form's stages alone, a row each: what the bench's stage times are made of on
    /// the compilers (a decal or a light volume's figure is per pixel it covers).
    fn stages_markdown(&self) -> String {
        let mut out = String::from("\n### Fused stages on GPU compilers\n\n");
        let _ = writeln!(out, "Each stage of the fused GLES programs alone, per pixel it shades: the geometry over the mesh, a decal over its volume, the lighting and the resolve over the surfaces, the sky where there is none. Mali's estimated cycles with (arithmetic / load-store / texture), Adreno's instructions.\n");
        out.push_str("| layout | form | stage |");
        for target in TARGETS {
            let _ = write!(out, " {target} |");
        }
        out.push_str("\n| --- | --- | --- |");
        out.push_str(&" ---: |".repeat(TARGETS.len()));
        out.push('\n');
        for form in &self.forms {
            for (stage, index) in &form.stages {
                let _ = write!(
                    out,
                    "| {} | {} | {} |",
                    form.layout,
                    form.form,
                    stage.name()
                );
                for target in TARGETS {
                    let _ = write!(out, " {} |", self.cell(target, &[*index]));
                }
                out.push('\n');
            }
        }
        out
    }

    /// The report's JSON: the compilers, and per layout and form each pass's figure per target.
    pub fn json(&self) -> serde_json::Value {
        let figure = |target: &str, indices: &[usize]| {
            self.pass(target, indices).map(|(total, split)| {
                serde_json::json!({
                    "total": total,
                    "arithmetic_cycles": split.map(|split| split[0]),
                    "load_store_cycles": split.map(|split| split[1]),
                    "texture_cycles": split.map(|split| split[2]),
                })
            })
        };
        serde_json::json!({
            "compilers": self.compiled.provenance_json(),
            "least": self.least(),
            "rows": self.forms.iter().map(|form| serde_json::json!({
                "layout": form.layout,
                "form": form.form,
                "gbuffer_pass": TARGETS.iter().map(|target| (target.to_string(), serde_json::json!(figure(target, &form.gbuffer)))).collect::<serde_json::Map<_, _>>(),
                "lighting": TARGETS.iter().map(|target| (target.to_string(), serde_json::json!(figure(target, &form.lighting)))).collect::<serde_json::Map<_, _>>(),
                "stages": form.stages.iter().map(|(stage, index)| (stage.name().to_string(), serde_json::json!(TARGETS.iter().map(|target| (target.to_string(), serde_json::json!(figure(target, &[*index])))).collect::<serde_json::Map<_, _>>()))).collect::<serde_json::Map<_, _>>(),
            })).collect::<Vec<_>>(),
        })
    }
}
