//! The timing's consistency check: times against the order the instruction counts predict.

use gbuffer_core::Named;

use crate::measured::Measured;
use crate::rows::Row;
use crate::{packing, timing};

/// Holds the adapter's times to the order the instruction counts predict, within each family of
/// rows and each format's two packing modes (pack and unpack apart), in each stage. The disagreements, a line each:
/// the report prints them beside the times, which stand (see [`timing::inconsistencies`]).
pub(crate) fn check_consistency(
    rows: &[Row],
    measured: &[Measured],
    packing: &[packing::PackingRow],
) -> Vec<String> {
    let mut families: Vec<&str> = rows.iter().map(|row| row.family).collect();
    families.dedup();
    let mut found = Vec::new();
    for &stage in timing::Stage::ALL {
        let times: Vec<Option<timing::GpuTime>> = measured
            .iter()
            .map(|measured| measured.gpu.get(stage))
            .collect();
        for family in &families {
            let group: Vec<timing::Timed> = rows
                .iter()
                .zip(measured.iter())
                .zip(&times)
                .filter(|((row, _), _)| row.family == *family)
                .map(|((row, measured), time)| timing::Timed {
                    name: format!("{} ({})", row.name, stage.name()),
                    instructions: measured.spirv_instructions,
                    time: time.as_ref(),
                })
                .collect();
            found.extend(timing::inconsistencies(&group));
        }
        for &direction in packing::Direction::ALL {
            let packing_times: Vec<Option<timing::GpuTime>> = packing
                .iter()
                .map(|row| row.time(direction, stage))
                .collect();
            for group in packing::timed_groups(packing, &packing_times, direction, stage) {
                found.extend(timing::inconsistencies(&group));
            }
        }
    }
    found
}
