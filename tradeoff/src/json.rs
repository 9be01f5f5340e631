//! The report's `report.json`: every row's figures, timings and compilers' columns.

use gbuffer_core::Named;

use crate::measured::{Measured, ROW_TARGETS};
use crate::rows::Row;
use crate::timing;

/// The report's JSON: `{"adapter", "rows": [...]}` with the schema of the issue.
pub(crate) fn json_report(rows: &[Row], measured: &[Measured], adapter: &str) -> serde_json::Value {
    let rows: Vec<serde_json::Value> = rows
        .iter()
        .zip(measured)
        .map(|(row, measured)| {
            let mut entry = serde_json::json!({
                "family": row.family,
                "name": row.name,
                "domain": row.domain,
                "unit": row.unit,
                "max_error": row.errors.max,
                "rms_error": row.errors.rms,
                "naga_expressions": measured.naga_expressions,
                "spirv_instructions": measured.spirv_instructions,
                "gpu_ns_per_eval": measured.gpu.compute.filter(timing::GpuTime::resolved).map(|time| time.ns.median),
                "timings": timings_json(&measured.gpu),
                "cpu_ns_per_eval": measured.cpu_ns_per_eval,
                "compilers": ROW_TARGETS.iter().zip(&measured.compilers).map(|(target, figure)| (target.to_string(), serde_json::json!(figure))).collect::<serde_json::Map<_, _>>(),
            });
            if let Some(bits) = row.bits {
                entry["bits"] = serde_json::json!(bits);
            }
            entry
        })
        .collect();
    serde_json::json!({ "adapter": adapter, "rows": rows })
}

/// The report's timing objects of a row: one per stage measured.
pub(crate) fn timings_json(times: &timing::StageTimes) -> serde_json::Value {
    let objects: Vec<serde_json::Value> = timing::Stage::ALL
        .iter()
        .copied()
        .filter_map(|stage| times.get(stage))
        .map(|time| {
            // A time that does not resolve has no median of its own (less the harness's, it
            // may read negative): only its upper bound is written.
            let resolved = time.resolved();
            let bound = time.upper_bound_ns();
            serde_json::json!({
                "stage": time.stage.name(),
                "clock": time.clock.name(),
                "evaluations_per_second": resolved.then(|| time.evaluations_per_second()),
                "evaluations_per_second_at_least": bound.map(|bound| 1e9 / bound),
                "evaluations_per_run": time.evaluations_per_run(),
                "chain": time.chain,
                "chains": time.chains,
                "run_ms": time.run_ms,
                "doubling_ratio": time.doubling_ratio,
                "median_ns": resolved.then_some(time.ns.median),
                "min_ns": resolved.then_some(time.ns.min),
                "max_ns": resolved.then_some(time.ns.max),
                "upper_bound_ns": bound,
                "resolved": resolved,
            })
        })
        .collect();
    serde_json::json!(objects)
}
