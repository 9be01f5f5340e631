//! The report's table on standard output, and how its times are written.

use crate::compilers;
use crate::measured::Measured;
use crate::rows::Row;
use crate::stdout::report_line;
use crate::timing;

/// Prints the rows' table: error, cost and time side by side, after the adapter and the
/// compilers' provenance.
pub(crate) fn print_table(
    rows: &[Row],
    measured: &[Measured],
    adapter: &str,
    compiled: &compilers::Compiled,
) {
    report_line!("adapter: {adapter}");
    report_line!("{}", compiled.provenance());
    report_line!(
        "{:<17} {:<34} {:>4} {:>11} {:>11} {:<24} {:>5} {:>5} {:>8} {:>8} {:>8} {:>7} {:>6} {:>6}",
        "family",
        "row",
        "bits",
        "max error",
        "rms error",
        "unit",
        "naga",
        "spirv",
        "gpu ns",
        "frag ns",
        "cpu ns",
        "G610 cy",
        "A740",
        "navi21"
    );
    for (row, measured) in rows.iter().zip(measured) {
        report_line!(
            "{:<17} {:<34} {:>4} {:>11.3e} {:>11.3e} {:<24} {:>5} {:>5} {:>8} {:>8} {:>8.2} {:>7} {:>6} {:>6}",
            row.family,
            row.name,
            row.bits
                .map_or_else(|| "-".to_string(), |bits| bits.to_string()),
            row.errors.max,
            row.errors.rms,
            row.unit,
            measured.naga_expressions,
            measured.spirv_instructions,
            format_time(measured.gpu.compute),
            format_time(measured.gpu.fragment),
            measured.cpu_ns_per_eval,
            compilers::format_figure(measured.compilers[0]),
            compilers::format_figure(measured.compilers[1]),
            compilers::format_figure(measured.compilers[2]),
        );
    }
}

/// A time with three significant digits; `<X` where it is below the harness's resolution (X
/// the upper bound), "n/r" where the run's times were not trusted, "n/a" where it could not be
/// measured.
pub(crate) fn format_time(time: Option<timing::GpuTime>) -> String {
    match time {
        None => "n/a".to_string(),
        Some(time) if time.resolved() => significant(time.median_ns),
        Some(time) => match time.upper_bound_ns() {
            Some(bound) => format!("<{}", significant(bound)),
            None => "n/r".to_string(),
        },
    }
}

/// `value` with three significant digits.
fn significant(value: f64) -> String {
    let digits = (2 - value.abs().log10().floor() as i32).max(0) as usize;
    format!("{value:.digits$}")
}
