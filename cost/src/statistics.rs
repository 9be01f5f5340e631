//! What a compiler says about one shader, as a typed record, and how each compiler's words are
//! read: Mesa's shader-db lines on GL (`<stage> shader: 38 inst, 0.56 cycles, ...` from
//! panfrost and freedreno, `type: 4, ..., gpr: 6, inst: 24, ...` from nouveau) and Vulkan's
//! pipeline executable statistics (`Instructions = 30` from ACO, `Instruction Count = 47` from
//! turnip). Every value the compiler printed is kept, by its own name, beside the typed fields.

use serde::Serialize;

use crate::target::Compiler;
use crate::Stage;

/// One value as the compiler named it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Statistic {
    /// The compiler's name for it (`inst`, `cycles`, `Inverse Throughput`, ...).
    pub name: String,
    /// Its value.
    pub value: f64,
}

/// Cycles a compiler estimates per thread (one pixel of a fragment shader), split as it
/// splits them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Cycles {
    /// The estimate: the busiest unit's cycles (Mali's `cycles`, the largest of the parts).
    pub total: f64,
    /// Each unit's cycles: Valhall `fma`, `cvt`, `sfu`, `varying`, `texture`, `load_store`;
    /// Bifrost `arithmetic`, `texture`, `varying`, `load_store`.
    pub parts: Vec<Statistic>,
}

/// What one compiler reports for one shader.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Statistics {
    /// Instructions in the compiled shader (for ir3 and turnip, the main shader's, without the
    /// preamble that runs once per draw rather than per pixel).
    pub instructions: u64,
    /// Estimated cycles per thread, where the compiler estimates them (Mali).
    pub cycles: Option<Cycles>,
    /// ACO's estimated latency of one wave, in cycles.
    pub latency_cycles: Option<u64>,
    /// ACO's estimated inverse throughput, in cycles per wave at the occupancy it expects.
    pub inverse_throughput_cycles: Option<u64>,
    /// Registers per thread: full 32-bit registers (ir3, turnip, nouveau's GPRs) or ACO's VGPRs.
    /// Mali's compiler reports none.
    pub registers: Option<u64>,
    /// How many threads or waves can be resident: Mali's threads per core (1, 2 or 4 times the
    /// base), ir3's waves, ACO's subgroups per SIMD.
    pub occupancy: Option<u64>,
    /// Values spilled to memory (Mali's spills and fills, ir3's private stores and loads,
    /// ACO's spilled SGPRs and VGPRs); nouveau reports local memory instead (in `raw`).
    pub spills: Option<u64>,
    /// Everything the compiler printed for the shader, by its own names, in its order.
    pub raw: Vec<Statistic>,
}

impl Cycles {
    /// The busiest arithmetic unit's cycles (Valhall's fma, cvt or sfu; Bifrost's arithmetic):
    /// the part of the estimate a conversion's arithmetic changes, where loads, stores,
    /// varyings or textures bound the total.
    pub fn arithmetic(&self) -> f64 {
        self.parts
            .iter()
            .filter(|part| matches!(part.name.as_str(), "fma" | "cvt" | "sfu" | "arithmetic"))
            .map(|part| part.value)
            .fold(0.0, f64::max)
    }
}

impl Statistics {
    /// The value the compiler called `name`, if it printed one.
    pub fn raw_value(&self, name: &str) -> Option<f64> {
        self.raw
            .iter()
            .find(|statistic| statistic.name == name)
            .map(|statistic| statistic.value)
    }
}

/// What a compiler calls the values the typed fields hold (`None` where it reports none).
struct Names {
    instructions: &'static str,
    registers: Option<&'static str>,
    occupancy: Option<&'static str>,
    /// Two values whose sum is the spills (spills and fills, stores and loads).
    spills: Option<(&'static str, &'static str)>,
    latency: Option<&'static str>,
    inverse_throughput: Option<&'static str>,
    /// Mali's cycles per unit: (the compiler's name, the record's name).
    cycle_parts: &'static [(&'static str, &'static str)],
}

const NO_NAMES: Names = Names {
    instructions: "inst",
    registers: None,
    occupancy: None,
    spills: None,
    latency: None,
    inverse_throughput: None,
    cycle_parts: &[],
};

fn names(compiler: Compiler) -> Names {
    match compiler {
        Compiler::Valhall => Names {
            occupancy: Some("threads"),
            spills: Some(("spills", "fills")),
            cycle_parts: &[
                ("fma", "fma"),
                ("cvt", "cvt"),
                ("sfu", "sfu"),
                ("v", "varying"),
                ("t", "texture"),
                ("ls", "load_store"),
            ],
            ..NO_NAMES
        },
        Compiler::Bifrost => Names {
            occupancy: Some("threads"),
            spills: Some(("spills", "fills")),
            cycle_parts: &[
                ("arith", "arithmetic"),
                ("texture", "texture"),
                ("vary", "varying"),
                ("ldst", "load_store"),
            ],
            ..NO_NAMES
        },
        Compiler::Ir3 => Names {
            registers: Some("full"),
            occupancy: Some("waves"),
            spills: Some(("stp", "ldp")),
            ..NO_NAMES
        },
        Compiler::Turnip => Names {
            instructions: "Instruction Count",
            registers: Some("Registers used"),
            occupancy: Some("Max Waves Per Core"),
            spills: Some(("STP Count", "LDP Count")),
            ..NO_NAMES
        },
        Compiler::Aco => Names {
            instructions: "Instructions",
            registers: Some("VGPRs"),
            occupancy: Some("Subgroups per SIMD"),
            spills: Some(("Spilled SGPRs", "Spilled VGPRs")),
            latency: Some("Latency"),
            inverse_throughput: Some("Inverse Throughput"),
            ..NO_NAMES
        },
        Compiler::Nouveau => Names {
            registers: Some("gpr"),
            ..NO_NAMES
        },
    }
}

/// Reads one shader's statistics from the lines the helper printed for it: `message:` lines
/// (GL) or `executable:`/`statistic:` lines (Vulkan). `None` when no line is the stage's.
pub fn parse(compiler: Compiler, stage: Stage, lines: &[&str]) -> Option<Statistics> {
    let raw = match compiler {
        Compiler::Bifrost | Compiler::Valhall | Compiler::Ir3 => shader_db(lines, stage, compiler)?,
        Compiler::Nouveau => nouveau(lines, stage)?,
        Compiler::Turnip | Compiler::Aco => executable(lines, executable_names(stage))?,
    };
    statistics(compiler, raw)
}

/// Reads the vertex stage's statistics of a Vulkan pipeline from the lines the helper printed
/// for it: its `vertex` (RADV) or `VS` (turnip) executable. `None` for a compiler that reports
/// no pipeline executables, or when no executable is the vertex stage's.
pub fn parse_vertex(compiler: Compiler, lines: &[&str]) -> Option<Statistics> {
    match compiler {
        Compiler::Turnip | Compiler::Aco => {
            statistics(compiler, executable(lines, &["vertex", "vs", "vert"])?)
        }
        Compiler::Bifrost | Compiler::Valhall | Compiler::Ir3 | Compiler::Nouveau => None,
    }
}

/// The named statistics of one stage, from what its compiler printed.
fn statistics(compiler: Compiler, raw: Vec<Statistic>) -> Option<Statistics> {
    let get = |name: &str| {
        raw.iter()
            .find(|statistic| statistic.name == name)
            .map(|statistic| statistic.value)
    };
    let whole = |name: Option<&str>| get(name?).map(|value| value as u64);
    let names = names(compiler);
    let cycles = if names.cycle_parts.is_empty() {
        None
    } else {
        let parts = names
            .cycle_parts
            .iter()
            .map(|(name, meaning)| {
                Some(Statistic {
                    name: meaning.to_string(),
                    value: get(name)?,
                })
            })
            .collect::<Option<_>>()?;
        Some(Cycles {
            total: get("cycles")?,
            parts,
        })
    };
    Some(Statistics {
        instructions: whole(Some(names.instructions))?,
        cycles,
        latency_cycles: whole(names.latency),
        inverse_throughput_cycles: whole(names.inverse_throughput),
        registers: whole(names.registers),
        occupancy: whole(names.occupancy),
        spills: names
            .spills
            .and_then(|(first, second)| Some(whole(Some(first))? + whole(Some(second))?)),
        raw,
    })
}

/// The name a shader-db line gives the stage: panfrost writes Mesa's `MESA_SHADER_FRAGMENT`,
/// ir3 its own `FRAG`, and `CL` for a GL compute shader.
fn shader_db_stage(compiler: Compiler, stage: Stage) -> &'static str {
    match (compiler, stage) {
        (Compiler::Ir3, Stage::Fragment) => "FRAG",
        (Compiler::Ir3, Stage::Compute) => "CL",
        (_, Stage::Fragment) => "MESA_SHADER_FRAGMENT",
        (_, Stage::Compute) => "MESA_SHADER_COMPUTE",
    }
}

/// `message: FRAG shader: 2 inst, 0 nops, ..., 0:0 spills:fills`: each `VALUE NAME` pair, and
/// Mali's `S:F spills:fills` as two values. The first line of the stage counts.
fn shader_db(lines: &[&str], stage: Stage, compiler: Compiler) -> Option<Vec<Statistic>> {
    let prefix = format!("{} shader: ", shader_db_stage(compiler, stage));
    let line = lines.iter().find_map(|line| {
        line.strip_prefix("message: ")?
            .strip_prefix(prefix.as_str())
    })?;
    let mut raw = Vec::new();
    for item in line.split(", ") {
        let (value, name) = item.trim().split_once(' ')?;
        if name == "spills:fills" {
            let (spills, fills) = value.split_once(':')?;
            raw.push(statistic("spills", spills)?);
            raw.push(statistic("fills", fills)?);
        } else {
            raw.push(statistic(name, value)?);
        }
    }
    Some(raw)
}

/// `message: type: 4, local: 0, shared: 0, gpr: 6, inst: 24, bytes: 384, cached: 1456`; the
/// type is nouveau's program type (4 fragment, 5 compute).
fn nouveau(lines: &[&str], stage: Stage) -> Option<Vec<Statistic>> {
    let type_number = match stage {
        Stage::Fragment => "4",
        Stage::Compute => "5",
    };
    let prefix = format!("type: {type_number}, ");
    let line = lines.iter().find_map(|line| {
        line.strip_prefix("message: ")
            .filter(|line| line.starts_with(&prefix))
    })?;
    line.split(", ")
        .map(|item| {
            let (name, value) = item.split_once(": ")?;
            statistic(name, value)
        })
        .collect()
}

/// What RADV (`fragment`, `compute`) and turnip (`FS`, `CS`) call a stage's executable.
fn executable_names(stage: Stage) -> &'static [&'static str] {
    match stage {
        Stage::Fragment => &["fragment", "fs", "frag"],
        Stage::Compute => &["compute", "cs"],
    }
}

/// `executable: NAME` then `statistic: NAME = VALUE` lines: the executable called one of
/// `names` (lower case), or whose name's first word is one (turnip's `Binning VS` is not its
/// `VS`).
fn executable(lines: &[&str], names: &[&str]) -> Option<Vec<Statistic>> {
    let mut raw = None;
    for line in lines {
        if let Some(name) = line.strip_prefix("executable: ") {
            let name = name.to_ascii_lowercase();
            let is_stage = names.iter().any(|stage_name| {
                name == *stage_name || name.split_whitespace().next() == Some(stage_name)
            });
            if raw.is_some() {
                break;
            }
            if is_stage {
                raw = Some(Vec::new());
            }
        } else if let (Some(raw), Some(item)) = (raw.as_mut(), line.strip_prefix("statistic: ")) {
            let (name, value) = item.split_once(" = ")?;
            // The hashes are identifiers, not measures.
            if !name.contains("hash") && !name.contains("Hash") {
                raw.push(statistic(name, value)?);
            }
        }
    }
    raw
}

fn statistic(name: &str, value: &str) -> Option<Statistic> {
    Some(Statistic {
        name: name.to_string(),
        value: value.trim().parse().ok()?,
    })
}

#[cfg(test)]
mod tests {
    //! Lines as the drivers printed them (Mesa 25.0.7), read into records.
    use super::*;

    #[test]
    fn valhall() {
        let lines = [
            "message: MESA_SHADER_POSITION shader: 9 inst, 2.000000 cycles, 0.015625 fma, 0.093750 cvt, 0.000000 sfu, 0.000000 v, 0.000000 t, 2.000000 ls, 8 quadwords, 2 threads, 0 loops, 0:0 spills:fills",
            "message: MESA_SHADER_FRAGMENT shader: 38 inst, 0.562500 cycles, 0.125000 fma, 0.296875 cvt, 0.562500 sfu, 0.000000 v, 0.000000 t, 0.000000 ls, 24 quadwords, 2 threads, 0 loops, 1:2 spills:fills",
        ];
        let statistics = parse(Compiler::Valhall, Stage::Fragment, &lines).unwrap();
        assert_eq!(statistics.instructions, 38);
        let cycles = statistics.cycles.clone().unwrap();
        assert_eq!(cycles.total, 0.5625);
        assert_eq!(cycles.parts[1].name, "cvt");
        assert_eq!(cycles.parts[1].value, 0.296875);
        assert_eq!(statistics.occupancy, Some(2));
        assert_eq!(statistics.spills, Some(3));
        assert_eq!(statistics.cycles.as_ref().unwrap().arithmetic(), 0.5625);
        assert!(parse(Compiler::Valhall, Stage::Compute, &lines).is_none());
    }

    #[test]
    fn bifrost() {
        let lines = ["message: MESA_SHADER_FRAGMENT shader: 32 inst, 20 tuples, 3 clauses, 0.750000 cycles, 0.750000 arith, 0.000000 texture, 0.000000 vary, 0.000000 ldst, 18 quadwords, 2 threads, 0 preloads, 0 loops, 0:0 spills:fills"];
        let statistics = parse(Compiler::Bifrost, Stage::Fragment, &lines).unwrap();
        assert_eq!(statistics.instructions, 32);
        assert_eq!(
            statistics.cycles.as_ref().unwrap().parts[0].name,
            "arithmetic"
        );
        assert_eq!(statistics.raw_value("tuples"), Some(20.0));
    }

    #[test]
    fn ir3() {
        let lines = ["message: FRAG shader: 2 inst, 0 nops, 2 non-nops, 1 mov, 0 cov, 96 dwords, 0 last-baryf, 0 last-helper, 0 half, 2 full, 12 constlen, 1 cat0, 1 cat1, 0 cat2, 0 cat3, 0 cat4, 0 cat5, 0 cat6, 0 cat7, 0 stp, 0 ldp, 0 sstall, 0 (ss), 0 systall, 0 (sy), 16 waves, 0 loops, 47 preamble inst, 0 early-preamble"];
        let statistics = parse(Compiler::Ir3, Stage::Fragment, &lines).unwrap();
        assert_eq!(statistics.instructions, 2);
        assert_eq!(statistics.registers, Some(2));
        assert_eq!(statistics.occupancy, Some(16));
        assert_eq!(statistics.raw_value("preamble inst"), Some(47.0));
    }

    #[test]
    fn nouveau_lines() {
        let lines = [
            "message: type: 0, local: 0, shared: 0, gpr: 6, inst: 7, bytes: 112, cached: 769",
            "message: type: 4, local: 0, shared: 0, gpr: 6, inst: 24, bytes: 384, cached: 1456",
        ];
        let statistics = parse(Compiler::Nouveau, Stage::Fragment, &lines).unwrap();
        assert_eq!(
            (statistics.instructions, statistics.registers),
            (24, Some(6))
        );
    }

    #[test]
    fn executables() {
        let lines = [
            "executable: vertex + fragment",
            "statistic: Instructions = 99",
            "executable: fragment",
            "statistic: Driver pipeline hash = 374849335210133389",
            "statistic: VGPRs = 8",
            "statistic: Spilled SGPRs = 0",
            "statistic: Spilled VGPRs = 1",
            "statistic: Subgroups per SIMD = 32",
            "statistic: Instructions = 30",
            "statistic: Latency = 718",
            "statistic: Inverse Throughput = 45",
        ];
        let statistics = parse(Compiler::Aco, Stage::Fragment, &lines).unwrap();
        assert_eq!(statistics.instructions, 30);
        assert_eq!(statistics.latency_cycles, Some(718));
        assert_eq!(statistics.inverse_throughput_cycles, Some(45));
        assert_eq!(statistics.spills, Some(1));
        assert!(statistics.raw_value("Driver pipeline hash").is_none());
        let turnip = [
            "executable: CS",
            "statistic: Instruction Count = 47",
            "statistic: Registers used = 2",
        ];
        let statistics = parse(Compiler::Turnip, Stage::Compute, &turnip).unwrap();
        assert_eq!(
            (statistics.instructions, statistics.registers),
            (47, Some(2))
        );
        // A Vulkan pipeline's vertex stage: turnip's `VS`, not its `Binning VS`; RADV's `vertex`.
        let pipeline = [
            "executable: VS",
            "statistic: Instruction Count = 9",
            "executable: FS",
            "statistic: Instruction Count = 95",
            "executable: Binning VS",
            "statistic: Instruction Count = 7",
        ];
        let vertex = parse_vertex(Compiler::Turnip, &pipeline).unwrap();
        assert_eq!(vertex.instructions, 9);
        let fragment = parse(Compiler::Turnip, Stage::Fragment, &pipeline).unwrap();
        assert_eq!(fragment.instructions, 95);
        let radv = ["executable: vertex", "statistic: Instructions = 219"];
        assert_eq!(
            parse_vertex(Compiler::Aco, &radv).unwrap().instructions,
            219
        );
        assert!(parse_vertex(Compiler::Aco, &lines[2..]).is_none());
        assert!(parse_vertex(Compiler::Valhall, &pipeline).is_none());
    }
}
