//! Prints the bit report of every seed layout: per field the format, bits and used bits, the
//! total against the budget, and what the same fields cost as separate WebGPU render targets.
//!
//! Run with `cargo run --release -p gbuffer-render --example seed_layouts`; add `-- --wgsl` to print the
//! generated WGSL as well.

use gbuffer_core::report::Report;
use gbuffer_runtime::seed_layouts;

fn main() {
    let print_wgsl = std::env::args()
        .skip(1)
        .any(|argument| argument == "--wgsl");
    for (layout, wgsl) in seed_layouts::all() {
        println!("{}", Report::new(&layout));
        if print_wgsl {
            println!("{wgsl}\n");
        }
    }
}
