//! Bad models are compile errors that point at the user's tokens and say how
//! to fix them. Each `tests/ui/*.stderr` was reviewed like code.

#[test]
fn bad_models_are_compile_errors() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*.rs");
}
