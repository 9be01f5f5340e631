//! Every user error of the derive is a spanned compile error, all reported at once; the
//! expected messages are the `.stderr` snapshots beside the cases in `tests/ui/`.
//! Regenerate them with `TRYBUILD=overwrite cargo test -p gbuffer-integration-tests --test compile_errors`.

#[test]
fn user_errors_are_spanned_compile_errors() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("ui/*.rs");
}
