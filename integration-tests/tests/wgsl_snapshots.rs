//! The generated WGSL is part of the product: these snapshots make every change to it a
//! reviewed diff. Update with `INSTA_UPDATE=always cargo test -p gbuffer-integration-tests --test wgsl_snapshots`
//! (or `cargo insta review`). The seed and engine layouts' WGSL is snapshotted once, as the
//! layout files' output (`codegen_outputs`), which a test there holds equal to the derive's.

use gbuffer::GBufferLayout;
use gbuffer_testkit::{AllFormats, FastFormats, MixedConversions};

#[test]
fn all_formats_wgsl() {
    insta::assert_snapshot!("all_formats", AllFormats::WGSL);
}

#[test]
fn fast_conversions_wgsl() {
    insta::assert_snapshot!("fast_formats", FastFormats::WGSL);
}

#[test]
fn per_field_conversions_wgsl() {
    insta::assert_snapshot!("mixed_conversions", MixedConversions::WGSL);
}
