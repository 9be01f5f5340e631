//! Layouts declared through `macro_rules!`: options that reach the derive as macro fragments
//! (`$budget:literal`, `$conversions:expr`) arrive wrapped in invisible groups, and must mean
//! what they mean when written out.

use gbuffer::glam::Vec4;
use gbuffer::GBufferLayout;

macro_rules! layout_with {
    ($name:ident, $budget:literal, $conversions:expr) => {
        /// A one-field layout of these options.
        #[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
        #[gbuffer(budget = $budget, conversions = $conversions)]
        pub struct $name {
            /// A colour.
            #[pls(rgba8)]
            pub colour: Vec4,
        }
    };
}

layout_with!(FromMacro, 256, fast);

/// The same layout, written out.
#[derive(GBufferLayout, Clone, Copy, Debug, PartialEq)]
#[gbuffer(budget = 256, conversions = fast)]
pub struct WrittenOut {
    /// A colour.
    #[pls(rgba8)]
    pub colour: Vec4,
}

#[test]
fn options_from_macro_fragments_take_effect() {
    assert_eq!(FromMacro::layout().budget, 256);
    // Fast conversions pack rgba8 with WGSL's builtin; exact ones never call it.
    assert!(
        FromMacro::WGSL.contains("pack4x8unorm("),
        "{}",
        FromMacro::WGSL
    );
    assert_eq!(
        FromMacro::WGSL
            .replace("FromMacro", "WrittenOut")
            .replace("from_macro", "written_out")
            .replace("FROM_MACRO", "WRITTEN_OUT"),
        WrittenOut::WGSL
    );
}
