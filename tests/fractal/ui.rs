//! A malformed scene is a compile error at the offending token, with a message naming the parameter and its range.
//! Each `tests/ui/*.rs` holds one; its `.stderr` beside it is the exact error it must produce.

#[test]
fn malformed_scenes_are_compile_errors_at_the_token() {
    trybuild::TestCases::new().compile_fail("tests/ui/*.rs");
}
