//! The parser's caps on nesting, size and depth, and hostile input that must end in an error, never a panic.

use super::*;

fn nested_parens(levels: usize) -> String {
    format!("sphere({}1.0{})", "(".repeat(levels), ")".repeat(levels))
}

#[test]
fn nesting_up_to_the_cap_parses_on_an_ordinary_thread_stack() {
    // parse_tokens runs on the caller's thread (the test harness gives it 2 MiB).
    let deepest = fractal_dsl::parse::MAX_PAREN_NESTING - 2;
    let tokens = TokenStream::from_str(&nested_parens(deepest)).unwrap();
    assert_eq!(parse_tokens(tokens).unwrap(), scene(sphere(1.0)));
    assert_eq!(parse(&nested_parens(deepest)), scene(sphere(1.0)));
}

#[test]
fn hostile_nesting_is_refused_without_overflowing_the_stack() {
    assert_eq!(error(&nested_parens(100_000)), "1:167: parentheses nest more than 160 levels deep");
    let deep_calls = format!("{}1.0{}", "sin(".repeat(10_000), ")".repeat(10_000));
    assert!(error(&format!("sphere(1.0).translate(vec3({deep_calls}, 0, 0))")).contains("parentheses nest more than"));
    let signs = format!("sphere({}1.0)", "-".repeat(100_000));
    assert!(error(&signs).contains("too many operators in a row"));
    let long_sum = format!("sphere(1.0{})", " + 1.0".repeat(100_000));
    assert!(error(&long_sum).contains("nests too deeply"), "{}", error(&long_sum));
    let long_chain = format!("sphere(1.0){}", ".scale(1.0)".repeat(100_000));
    assert!(error(&long_chain).contains("nests too deeply"));
    let unary_parens = format!("sphere({}1.0{})", "-(".repeat(1000), ")".repeat(1000));
    assert!(error(&unary_parens).contains("parentheses nest more than"));
}

#[test]
fn size_and_depth_caps_have_clear_errors() {
    let sum = format!("sphere(1.0).translate(vec3(0.0{}, 0, 0))", " + 1.0".repeat(70));
    assert_eq!(error(&sum), "1:28: an expression nests more than 64 levels deep");

    let chain = format!("sphere(1.0){}", ".scale(2.0)".repeat(70));
    assert_eq!(error(&chain), "1:706: the shape tree nests more than 64 levels deep");

    let nested = format!("{}sphere(1.0){}", "subtract(".repeat(70), ", sphere(0.5))".repeat(70));
    assert!(error(&nested).ends_with("the shape tree nests more than 64 levels deep"));

    let many = format!("union({})", vec!["sphere(1.0)"; 10_001].join(", "));
    assert!(error(&many).ends_with("the shape tree has more than 10000 nodes"), "{}", error(&many));
    let lights = format!("sphere(1.0){}", ".light(directional(vec3(0, 1, 0), rgb(1, 1, 1)))".repeat(17));
    assert!(error(&lights).ends_with("a scene may have at most 16 lights, found 17"));
}

// ---- no input panics ------------------------------------------------------------------------------------------------

const WORDS: &[&str] = &[
    "sphere",
    "box3",
    "union",
    "smooth_union",
    "mandelbulb",
    "menger",
    "scene",
    "vec3",
    "rgb",
    "param",
    "t",
    "PI",
    "translate",
    "material",
    "iterations",
    "camera_path",
    "key",
    "light",
    "directional",
    "max_steps",
    "x",
    "box",
    "(",
    ")",
    "(",
    ")",
    ",",
    ".",
    "..",
    "+",
    "-",
    "*",
    "/",
    "1.0",
    "0",
    "-1",
    "8",
    "1e400",
    "\"p\"",
    "0.5",
    "//",
    "\n",
    "[",
    "{",
    "#",
    ";",
    "'",
    "\"",
];

fn no_internal_error(src: &str) -> Result<(), TestCaseError> {
    if let Err(e) = parse_str(src) {
        prop_assert!(!e.message.contains("internal error"), "{src:?}: {e}");
        prop_assert!(e.line >= 1 && e.column >= 1);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn random_text_never_panics(src in "[a-z0-9_(),.+*/ \\-\"\n\\[\\]#;]{0,60}") {
        no_internal_error(&src)?;
    }

    #[test]
    fn random_token_soup_never_panics(words in prop::collection::vec(prop::sample::select(WORDS), 0..40)) {
        no_internal_error(&words.join(" "))?;
    }

    #[test]
    fn damaged_scenes_never_panic(
        case in 0..cases().len(),
        at in 0usize..400,
        cut in 0usize..6,
        insert in prop::sample::select(WORDS),
    ) {
        let src = cases()[case].0;
        let chars: Vec<char> = src.chars().collect();
        let at = at.min(chars.len());
        let end = (at + cut).min(chars.len());
        let (head, tail) = (&chars[..at], &chars[end..]);
        let damaged: String = head.iter().copied().chain(insert.chars()).chain(tail.iter().copied()).collect();
        no_internal_error(&damaged)?;
    }
}

/// A non-finite number computed from literals is as wrong as a written one: every slot refuses it at the argument,
/// whatever rule the slot has (it used to slip through slots that only check for finite values).
#[test]
fn computed_non_finite_constants_are_refused_in_every_slot() {
    assert_errors(&[
        ("julia(vec4(0.0 / 0.0, 0, 0, 0))", "1:7: julia constant c: numbers must be finite, found NaN"),
        ("sphere(1.0).translate(vec3(0.0 / 0.0, 0, 0))", "1:23: translate offset: numbers must be finite, found NaN"),
        ("sphere(1.0).rotate_y(0.0 / 0.0)", "1:22: rotate_y angle: numbers must be finite, found NaN"),
        ("sphere(1.0).twist(1e300 * 1e300)", "1:19: twist rate: numbers must be finite, found inf"),
        ("sphere(1.0).material(rgb(0.0 / 0.0, 0, 0))", "1:22: material color: numbers must be finite, found NaN"),
        (
            "sphere(1.0).translate(vec3(t * (0.0 / 0.0), 0, 0))",
            "1:23: translate offset: numbers must be finite, found NaN",
        ),
        ("sphere(1.0 + 0.0 / 0.0)", "1:8: sphere radius: numbers must be finite, found NaN"),
        (
            "scene(sphere(1.0)).light(point_light(vec3(0.0 / 0.0, 1, 0), rgb(1, 1, 1)))",
            "1:38: light position: numbers must be finite, found NaN",
        ),
        (
            "scene(sphere(1.0)).camera(camera(vec3(0, 0, -1e300 * 1e300), vec3(0, 0, 0)))",
            "1:34: camera position: numbers must be finite, found -inf",
        ),
    ]);
}
