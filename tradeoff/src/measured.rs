//! A row's measurements besides its error: its cost in naga expressions and SPIR-V
//! instructions, its time on the adapter and on the CPU, and what the GPUs' own compilers make
//! of it.

use gbuffer_shading::env_brdf_lut::EnvBrdfLut;

use crate::compilers;
use crate::rows::Row;
use crate::timing;

/// A row's measurements besides its error.
pub(crate) struct Measured {
    /// naga IR expressions reachable from the row's function.
    pub(crate) naga_expressions: usize,
    /// SPIR-V instructions the row adds to the timing harness.
    pub(crate) spirv_instructions: usize,
    /// The adapter's times in both stages, less the harness's.
    pub(crate) gpu: timing::StageTimes,
    /// The f32 mirror's time per evaluation on the CPU, in nanoseconds.
    pub(crate) cpu_ns_per_eval: f64,
    /// Per [`ROW_TARGETS`] column, what the row adds to the fragment harness: Mali's cycles,
    /// the others' instructions (`None` where it failed or the compilers are not set up).
    pub(crate) compilers: Vec<Option<f64>>,
}

impl Measured {
    /// The measured columns as the table and `report.md` write them: naga expressions, SPIR-V
    /// instructions, the compute and fragment times ([`format_time`]), the CPU's nanoseconds
    /// and the [`ROW_TARGETS`] compilers' figures.
    pub(crate) fn cells(&self) -> [String; 8] {
        let [mali, adreno, navi] =
            [0, 1, 2].map(|column| compilers::format_figure(self.compilers[column]));
        [
            self.naga_expressions.to_string(),
            self.spirv_instructions.to_string(),
            format_time(self.gpu.compute),
            format_time(self.gpu.fragment),
            format!("{:.2}", self.cpu_ns_per_eval),
            mali,
            adreno,
            navi,
        ]
    }
}

/// The GPU compilers the rows are costed on.
pub(crate) const ROW_TARGETS: [&str; 3] = ["mali-g610", "adreno-740", "amd-navi21"];

/// Each row's fragment harness (one evaluation, after the baseline's) on [`ROW_TARGETS`].
pub(crate) fn compile_rows(rows: &[Row]) -> compilers::Compiled {
    let shaders: Vec<Result<gbuffer_cost::Shader, String>> = std::iter::once(timing::BASELINE_ROW)
        .chain(rows.iter().map(|row| row.wgsl.as_str()))
        .map(|wgsl| gbuffer_cost::Shader::wgsl(&timing::fragment_harness(wgsl), "bench_fragment"))
        .collect();
    compilers::compile(&shaders, &ROW_TARGETS, compilers::MaliCycles::Total)
}

/// The SPIR-V of a row's timing harness, without the library functions the row does not
/// reach (naga writes every function of a module), and its naga module.
pub(crate) fn compile(row_wgsl: &str) -> Result<(naga::Module, Vec<u32>), String> {
    gbuffer_validator::cost::compile_compacted(&timing::harness(row_wgsl))
}

/// Adds every row to `timer`, each with the LUT it samples; their indices in the timer's
/// times, in the rows' order.
pub(crate) fn time_rows(timer: &mut timing::Timer, rows: &[Row]) -> Vec<usize> {
    let luts: Vec<(usize, Vec<[f32; 2]>)> = [16, 32]
        .into_iter()
        .map(|size| (size, EnvBrdfLut::bake(size, 1024).texels))
        .collect();
    rows.iter()
        .map(|row| {
            let (lut_size, lut) = match row.lut_size {
                Some(size) => luts
                    .iter()
                    .find(|(lut_size, _)| *lut_size == size)
                    .map(|(size, texels)| (*size, texels.as_slice()))
                    .unwrap_or((1, &[])),
                None => (1, &[][..]),
            };
            timer.add(&row.name, &row.wgsl, lut, lut_size)
        })
        .collect()
}

/// Every row's measurements: its times on the adapter (`gpu_times`, one per row, less the
/// harness's), on the CPU, and on the GPU compilers from `row_compilers` (less the
/// baseline's).
pub(crate) fn measure_rows(
    rows: &[Row],
    gpu_times: &[timing::StageTimes],
    row_compilers: &compilers::Compiled,
) -> Vec<Measured> {
    let (_, baseline_spirv) = compile(timing::BASELINE_ROW).expect("the baseline harness compiles");
    let baseline_instructions = gbuffer_validator::cost::spirv_instructions(&baseline_spirv);
    let mut measured = Vec::new();
    for (index, (row, gpu_time)) in rows.iter().zip(gpu_times).enumerate() {
        let (module, spirv) =
            compile(&row.wgsl).unwrap_or_else(|error| panic!("{}: {error}", row.name));
        measured.push(Measured {
            naga_expressions: gbuffer_validator::cost::naga_expressions(&module, "row_eval"),
            spirv_instructions: gbuffer_validator::cost::spirv_instructions(&spirv)
                .saturating_sub(baseline_instructions),
            gpu: *gpu_time,
            cpu_ns_per_eval: timing::cpu_ns_per_eval(&row.cpu),
            compilers: ROW_TARGETS
                .iter()
                .map(|target| {
                    let column = row_compilers
                        .columns()
                        .iter()
                        .find(|column| column.target == *target)?;
                    Some(column.figure(index + 1)? - column.figure(0)?)
                })
                .collect(),
        });
    }
    measured
}

/// A time with three significant digits; `<X` where it does not resolve (X the upper bound),
/// "n/a" where it could not be measured.
pub(crate) fn format_time(time: Option<timing::GpuTime>) -> String {
    match time {
        None => "n/a".to_string(),
        Some(time) => match time.upper_bound_ns() {
            Some(bound) => format!("<{}", significant(bound)),
            None => significant(time.ns.median),
        },
    }
}

/// `value` with three significant digits.
fn significant(value: f64) -> String {
    let digits = (2 - value.abs().log10().floor() as i32).max(0) as usize;
    format!("{value:.digits$}")
}
