//! Every user error of the derive is a spanned compile error, all reported at once; the
//! expected messages are the `.stderr` snapshots beside the cases in `ui/`. Regenerate them
//! with `TRYBUILD=overwrite cargo test --test compile_errors`. The test lives beside the derive:
//! trybuild compiles its cases with this package's dependencies, the facade and little else.

#[test]
fn user_errors_are_spanned_compile_errors() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("ui/*.rs");
}
