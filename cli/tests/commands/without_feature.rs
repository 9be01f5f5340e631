//! A `gbuffer` built without `report` or `cost` names the feature that brings it, as a usage
//! error (exit 2), and lists the subcommand in its help.

use crate::{gbuffer, Run};

#[test]
fn a_subcommand_left_out_names_its_feature() {
    for (subcommand, built) in [
        ("report", cfg!(feature = "report")),
        ("cost", cfg!(feature = "cost")),
    ] {
        if built {
            continue;
        }
        let output = gbuffer(subcommand).arg("anything.wgsl").fails_with(2);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.contains(&format!(
                "cargo install --locked --path cli --features {subcommand}"
            )),
            "{stderr}"
        );
    }
    let output = crate::gbuffer("--help").succeed();
    let help = String::from_utf8_lossy(&output.stdout);
    assert!(help.contains("report") && help.contains("cost"), "{help}");
}
