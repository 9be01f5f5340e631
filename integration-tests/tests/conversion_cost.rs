//! What the generated conversions cost once compiled (`gbuffer_tradeoff::packing_cost`: naga,
//! then `spirv-opt -O`, instructions in function bodies). The contract of the issue on packing
//! cost, per format and for a 4-word layout: exact conversions never branch and cost at most 3.5x
//! the fast ones; fast conversions cost at most 1.25x the engines' idiom (WGSL's builtins where
//! a format has one). The table prints with `-- --nocapture`, and
//! is written to `target/figures/conversion-cost.md` for the guide.

use gbuffer::layout::{Format, Layout};
use gbuffer_core::Conversions;
use gbuffer_core::Named;
use gbuffer_tradeoff::packing_cost::{builtin_form, cost, harness, layout_cost, one_field, Cost};

fn measured(layout: &Layout, conversions: Conversions) -> Cost {
    layout_cost(layout, conversions).unwrap_or_else(|error| panic!("{}: {error}", layout.name))
}

#[test]
fn exact_conversions_never_branch_and_cost_at_most_three_and_a_half_times_the_fast_ones() {
    let mut layouts: Vec<(String, Layout)> = Format::ALL
        .iter()
        .map(|&format| (format.name().to_string(), one_field(format)))
        .collect();
    let mut four_words = gbuffer::seed_layouts::all()[1].0.clone();
    four_words.name = "Texel".into();
    layouts.push(("Listing 2.2 (4 words)".into(), four_words));
    println!(
        "{:<24} {:>6} {:>9} {:>6} {:>9} {:>8}",
        "layout", "exact", "branches", "fast", "branches", "builtin"
    );
    let mut failures = Vec::new();
    let mut figures = Vec::new();
    for (name, layout) in &layouts {
        let exact = measured(layout, Conversions::Exact);
        let fast = measured(layout, Conversions::Fast);
        let builtin = match layout.fields.as_slice() {
            [field] => field.format().and_then(builtin_form).map(|wgsl| {
                cost(&harness(&wgsl, 1)).unwrap_or_else(|error| panic!("{name}: {error}"))
            }),
            _ => None,
        };
        println!(
            "{name:<24} {:>6} {:>9} {:>6} {:>9} {:>8}",
            exact.instructions,
            exact.conditional_branches,
            fast.instructions,
            fast.conditional_branches,
            builtin.map_or_else(|| "-".to_string(), |cost| cost.instructions.to_string())
        );
        figures.push(vec![
            name.clone(),
            exact.instructions.to_string(),
            fast.instructions.to_string(),
            builtin.map_or_else(|| "-".to_string(), |cost| cost.instructions.to_string()),
        ]);
        if exact.conditional_branches != 0 {
            failures.push(format!("{name}: exact conversions branch"));
        }
        // exact <= 3.5 fast, in integers: the half floats' tie-free rounding of denormals
        // (floor and fraction in place of `round`) takes rg16f to about 3.1x.
        if 2 * exact.instructions > 7 * fast.instructions {
            failures.push(format!(
                "{name}: exact {} instructions, over 3.5x fast {}",
                exact.instructions, fast.instructions
            ));
        }
        if let Some(builtin) = builtin {
            // fast <= 1.25 builtin, in integers.
            if 4 * fast.instructions > 5 * builtin.instructions {
                failures.push(format!(
                    "{name}: fast {} instructions, over 1.25x the builtin form's {}",
                    fast.instructions, builtin.instructions
                ));
            }
        }
    }
    // The guide's table (the layout contract's "what each costs").
    let header = ["format", "exact", "fast", "engines' idiom"];
    gbuffer_testkit::write_figures("conversion-cost", &header, &figures);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
