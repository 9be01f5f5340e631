//! The trade's speed side on the compilers of the GPUs users ship on (`gbuffer-cost`: Mesa's
//! panfrost, freedreno and ACO run through drm-shim): the same shaders whose SPIR-V the other
//! columns count, compiled for Mali, Adreno and AMD, each compiler's own figure in a column.
//! Without the setup (`scripts/cost-setup.sh`) the columns are absent and the report says why.

use gbuffer_cost::{measure, CostError, Shader, Statistics, Target};

/// Which of Mali's cycle estimates a column shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MaliCycles {
    /// The estimate: the busiest unit's cycles, loads, stores, varyings and textures included.
    Total,
    /// The busiest arithmetic unit's: for harnesses whose loads and stores, the same for every
    /// form measured, would bound the total and hide the arithmetic.
    Arithmetic,
}

/// One target's column: the driver's own name and version, and each shader's statistics
/// (`None` where that shader failed on it: the reason was printed).
pub struct Column {
    /// The target's name (`mali-g610`).
    pub target: &'static str,
    /// Which cycles a Mali column shows.
    pub mali_cycles: MaliCycles,
    /// The driver's name and version.
    pub device: String,
    /// Per shader, in the order given.
    pub statistics: Vec<Option<Statistics>>,
}

impl Column {
    /// The column's heading: the target and [`Column::unit`].
    pub fn heading(&self) -> String {
        format!("{} {}", self.target, self.unit())
    }

    /// What the column's figures count: Mali's estimated cycles per thread ([`MaliCycles`]),
    /// or the others' instructions.
    pub fn unit(&self) -> &'static str {
        match self.mali_cycles {
            _ if !self.is_mali() => "instructions",
            MaliCycles::Total => "cycles",
            MaliCycles::Arithmetic => "arithmetic cycles",
        }
    }

    fn is_mali(&self) -> bool {
        self.target.starts_with("mali")
    }

    /// Shader `index`'s figure, in [`Column::unit`].
    pub fn figure(&self, index: usize) -> Option<f64> {
        let statistics = self.statistics.get(index)?.as_ref()?;
        Some(match (&statistics.cycles, self.mali_cycles) {
            (Some(cycles), MaliCycles::Total) if self.is_mali() => cycles.total,
            (Some(cycles), MaliCycles::Arithmetic) if self.is_mali() => cycles.arithmetic(),
            _ => statistics.instructions as f64,
        })
    }
}

/// The compilers' columns for a set of shaders, or why there are none.
pub enum Compiled {
    /// One column per target, in the order asked.
    Columns(Vec<Column>),
    /// The setup is missing (or a driver did not start): the reason.
    Unavailable(String),
}

impl Compiled {
    /// The columns; none where unavailable.
    pub fn columns(&self) -> &[Column] {
        match self {
            Compiled::Columns(columns) => columns,
            Compiled::Unavailable(_) => &[],
        }
    }

    /// The compilers' names and versions, or why there are none, as a sentence for reports.
    pub fn provenance(&self) -> String {
        match self {
            Compiled::Columns(columns) => {
                let names: Vec<String> = columns
                    .iter()
                    .map(|column| format!("{} = {}", column.target, column.device))
                    .collect();
                format!(
                    "Compilers (Mesa's, through drm-shim): {}.",
                    names.join("; ")
                )
            }
            Compiled::Unavailable(reason) => {
                format!("No compiler columns: {reason}.")
            }
        }
    }

    /// The JSON of shader `index`'s figures: `{target: {instructions, cycles, ...}}`.
    pub fn json(&self, index: usize) -> serde_json::Value {
        let mut object = serde_json::Map::new();
        for column in self.columns() {
            if let Some(Some(statistics)) = column.statistics.get(index) {
                object.insert(
                    column.target.to_string(),
                    serde_json::to_value(statistics).unwrap_or_default(),
                );
            }
        }
        serde_json::Value::Object(object)
    }

    /// The JSON of the compilers: `{available, reason | devices}`.
    pub fn provenance_json(&self) -> serde_json::Value {
        match self {
            Compiled::Columns(columns) => serde_json::json!({
                "available": true,
                "devices": columns.iter().map(|column| (column.target.to_string(), serde_json::json!(column.device))).collect::<serde_json::Map<_, _>>(),
            }),
            Compiled::Unavailable(reason) => serde_json::json!({
                "available": false,
                "reason": reason,
            }),
        }
    }
}

/// Compiles `shaders` on each of `targets`, one run of each driver; Mali columns show
/// `mali_cycles`. A shader that could not be made (`Err`, its reason printed once) has no
/// statistics in any column.
pub fn compile(
    shaders: &[Result<Shader, String>],
    targets: &[&str],
    mali_cycles: MaliCycles,
) -> Compiled {
    for error in shaders.iter().filter_map(|shader| shader.as_ref().err()) {
        eprintln!("  not compiled: {error}");
    }
    let made: Vec<Shader> = shaders
        .iter()
        .filter_map(|shader| shader.clone().ok())
        .collect();
    let mut columns = Vec::new();
    for name in targets {
        let target = match Target::named(name) {
            Ok(target) => target,
            Err(error) => return Compiled::Unavailable(error),
        };
        eprintln!("compiling {} shaders for {name}...", made.len());
        let results = match measure(&made, &target, false) {
            Ok(results) => results,
            Err(
                error
                @ (CostError::NotSetUp(_) | CostError::Driver(_) | CostError::Fallback { .. }),
            ) => {
                return Compiled::Unavailable(error.to_string());
            }
        };
        let mut device = String::new();
        let mut results = results.into_iter();
        let statistics = shaders
            .iter()
            .map(|shader| match shader.as_ref().map(|_| results.next()) {
                Err(_) | Ok(None) => None,
                Ok(Some(result)) => match result {
                    Ok(measurement) => {
                        device = measurement.device;
                        Some(measurement.statistics)
                    }
                    Err(error) => {
                        eprintln!("  {name}: {error}");
                        None
                    }
                },
            })
            .collect();
        columns.push(Column {
            target: target.name,
            mali_cycles,
            device,
            statistics,
        });
    }
    Compiled::Columns(columns)
}

/// A figure for a table: cycles with up to three decimals, instructions whole; `-` where
/// there is none.
pub fn format_figure(value: Option<f64>) -> String {
    match value {
        None => "-".to_string(),
        Some(value) if value.fract() == 0.0 => format!("{value:.0}"),
        Some(value) => {
            let text = format!("{value:.3}");
            text.trim_end_matches('0').to_string()
        }
    }
}
