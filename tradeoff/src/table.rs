//! The report's table on standard output.

use crate::compilers;
use crate::measured::Measured;
use crate::rows::Row;
use crate::stdout::report_line;

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
        let [naga, spirv, compute, fragment, cpu, mali, adreno, navi] = measured.cells();
        report_line!(
            "{:<17} {:<34} {:>4} {:>11.3e} {:>11.3e} {:<24} {naga:>5} {spirv:>5} {compute:>8} {fragment:>8} {cpu:>8} {mali:>7} {adreno:>6} {navi:>6}",
            row.family,
            row.name,
            row.bits_cell(),
            row.errors.max,
            row.errors.rms,
            row.unit,
        );
    }
}
