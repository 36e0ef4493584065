//! Parse and validation errors: the problem named at `line:column` in files and at the token in `scene!`.

use super::*;

#[test]
fn errors_name_the_problem_at_line_and_column() {
    let cases: &[(&str, &str)] = &[
        // vocabulary
        ("spher(1.0)", "1:1: unknown function `spher`; did you mean `sphere`?"),
        (
            "sphere(1.0).tranlate(vec3(0, 0, 0))",
            "1:13: unknown method `tranlate` on a shape; did you mean `translate`?",
        ),
        ("sphere(1.0).frobnicate()", "1:13: unknown method `frobnicate` on a shape"),
        (
            "box(vec3(1.0, 1.0, 1.0))",
            "1:1: `box` is a Rust keyword: the box primitive is `box3(half_extents)`, e.g. \
            box3(vec3(1.0, 1.0, 1.0))",
        ),
        ("translate(vec3(1, 0, 0))", "1:1: `translate` is a method, not a function: write shape.translate(..)"),
        ("sphere(1.0).vec3(1, 2, 3)", "1:13: `vec3` is a function, not a method: call it as vec3(..)"),
        ("sphere", "1:1: `sphere` is a function: call it, e.g. sphere(..)"),
        ("sphere(tt)", "1:8: unknown name `tt`; did you mean `t`?"),
        ("sphere(radius)", "1:8: unknown name `radius` (the names are `t`, the time in seconds, and `PI`)"),
        // arity
        ("sphere(1.0, 2.0)", "1:13: `sphere` takes 1 argument (radius: number), found 2"),
        ("torus(1.0)", "1:1: `torus` takes 2 arguments (major: number, minor: number), found 1"),
        ("union()", "1:1: `union` takes at least 1 argument (shapes: shape...), found 0"),
        (
            "smooth_union(sphere(1.0))",
            "1:1: `smooth_union` takes at least 2 arguments (shapes: shape..., k: number), \
            found 1",
        ),
        ("scene(sphere(1.0)).hard_shadows(2.0)", "1:33: `hard_shadows` takes no arguments, found 1"),
        // types
        ("sphere(vec3(1, 1, 1))", "1:8: `sphere` argument `radius` must be a number, found a vec3"),
        ("union(sphere(1.0), 2.0)", "1:20: `union` argument `shapes` must be a shape, found a number"),
        (
            "smooth_union(sphere(1.0), sphere(2.0), sphere(3.0))",
            "1:40: `smooth_union` argument `k` must be a number, \
            found a shape",
        ),
        ("sphere(1.0).material(sphere(1.0))", "1:22: `material` argument `material` must be a material, found a shape"),
        ("sphere(1.0).iterations(3)", "1:13: `iterations` is a method of a fractal, found a shape"),
        ("sphere(1.0) + 1.0", "1:1: `+` applies to numbers, found a shape"),
        ("sphere(-vec3(1, 1, 1))", "1:9: `-` applies to numbers, found a vec3"),
        ("menger(2.5)", "1:8: `menger` argument `levels` must be a non-negative integer literal, found `2.5`"),
        ("menger(-2)", "1:8: `menger` argument `levels` must be a non-negative integer literal, found `-2`"),
        ("menger(99999999999)", "1:8: the integer `99999999999` is too large"),
        (
            "sphere(1.0).repeat_limited(vec3(1, 1, 1), vec3(1, 2.0, 3))",
            "1:51: `repeat_limited` argument `count` must be vec3(..) of non-negative integer literals, e.g. vec3(2, \
                2, 0), found `2.0`",
        ),
        ("vec3(1, 2, 3)", "1:1: a scene must be a shape or scene(..), found a vec3"),
        ("sphere(\"one\")", "1:8: a string appears only as the name in param(\"name\", default, min..max)"),
        (
            "sphere(0.0..1.0)",
            "1:8: a range `min..max` appears only as the last argument of param(\"name\", default, \
            min..max)",
        ),
        ("sphere(1.0e400)", "1:8: the number `1.0e400` is out of range (numbers must be finite)"),
        ("sphere(1.0u8x)", "1:8: unknown number suffix `u8x`"),
        (
            "scene(sphere(1.0).max_steps(10))",
            "1:7: `scene` argument `shape` must be a shape, found a scene: settings such as max_steps go on \
             scene(..), e.g. scene(sphere(1.0)).max_steps(200)",
        ),
        ("sphere(300u8)", "1:8: integer suffixes such as `u8` are not part of the scene language: write `300`"),
        ("menger(3u32)", "1:8: integer suffixes such as `u32` are not part of the scene language: write `3`"),
        ("sphere(1.0).linear()", "1:13: `linear` is a method of a camera, found a shape"),
        (
            "scene(sphere(1.0)).camera(camera(vec3(0, 0, -3), vec3(0, 0, 0)).looped())",
            "1:65: `looped` applies only to cameras made with camera_path(..)",
        ),
        // constants
        (
            "scene(sphere(1.0)).max_distance(t)",
            "1:33: `max_distance` argument `distance` must be a constant: `t` and \
            `param(..)` cannot be used here",
        ),
        (
            "scene(sphere(1.0)).gamma(param(\"g\", 2.0, 1.0..3.0))",
            "1:26: `gamma` argument `gamma` must be a constant: `t` and `param(..)` cannot be used here",
        ),
        (
            "scene(sphere(1.0)).max_distance(1.0 / 0.0)",
            "1:33: `max_distance` argument `distance` must be finite, found \
            inf",
        ),
        (
            "sphere(1.0).rotate(vec3(t, 0, 1), 0.5)",
            "1:20: `rotate` argument `axis` must be a constant: `t` and \
            `param(..)` cannot be used here",
        ),
        // syntax outside the language
        ("let x = 1; x", "1:1: `let` is a Rust keyword and not part of the scene language"),
        ("sphere([1.0])", "1:8: `[` is not part of the scene language: write vectors as vec3(x, y, z)"),
        ("sphere(1.0); sphere(2.0)", "1:12: a scene is a single expression: remove the `;`"),
        (
            "sphere(1.0) /// doc",
            "1:13: attributes and doc comments (`///`, `//!`, `/** */`) are not part of the scene \
            language; use `//` comments",
        ),
        (
            "sphere(2.0 % 1.0)",
            "1:12: `%` is not part of the scene language (its operators are + - * / and `..` in \
            param ranges)",
        ),
        ("sphere(1.0 - - -1.0)", "1:16: too many operators in a row: use parentheses, e.g. `a * -b` or `-(-a)`"),
        ("sphere(1.0).translate(vec3(1, 0, 0).x)", "1:23: fields (`v.x`) are not part of the scene language"),
        // lexing and syn
        ("", "1:1: the scene is empty: write a shape"),
        ("// nothing but a comment\n", "1:1: the scene is empty: write a shape"),
        ("sphere(1.0", "1:7: this `(` is never closed"),
        ("sphere(1.0))", "1:12: this `)` closes nothing"),
        ("sphere(1.0) +", "1:14: unexpected end of input, expected an expression"),
        ("sphere(1.0) sphere(2.0)", "1:13: unexpected token"),
    ];
    assert_errors(cases);
}

#[test]
fn validation_errors_point_at_the_argument() {
    let cases: &[(&str, &str)] = &[
        ("sphere(-1)", "1:8: sphere radius must be > 0, found -1"),
        ("mandelbulb(1.5)", "1:12: mandelbulb power must be >= 2, found 1.5"),
        ("mandelbulb(100)", "1:12: mandelbulb power must be <= 64, found 100"),
        ("mandelbulb(8).iterations(0)", "1:26: mandelbulb iterations must be in 1..=64, found 0"),
        ("menger(9)", "1:8: menger levels must be in 1..=8, found 9"),
        ("menger(3).iterations(0)", "1:22: menger levels must be in 1..=8, found 0"),
        ("sierpinski_tetrahedron(25)", "1:24: sierpinski_tetrahedron levels must be in 1..=24, found 25"),
        ("menger(3).min_radius(0.5)", "1:11: `min_radius` applies only to mandelbox, not menger"),
        ("menger(3).bailout(4.0)", "1:11: `bailout` applies only to mandelbulb, julia, juliabulb, escape_time and fold, not menger"),
        ("mandelbox(1.0)", "1:11: mandelbox |scale| must be in [1.05, 8], found 1"),
        ("mandelbox(2.0).min_radius(1.5)", "1:27: mandelbox min_radius must be in (0, 1), found 1.5"),
        ("mandelbox(2.0).fold_limit(0.0)", "1:27: mandelbox fold_limit must be > 0, found 0"),
        ("juliabulb(vec3(0.1, 0.2, 0.3)).power(1.5)", "1:38: juliabulb power must be >= 2, found 1.5"),
        ("octahedral_kifs(2.0).power(3.0)", "1:22: `power` applies only to juliabulb, not octahedral_kifs"),
        ("octahedral_kifs(0.9)", "1:17: octahedral_kifs scale must be >= 1.1, found 0.9"),
        ("sphere(1.0 + x)", "1:1: `x` (the point) can be read only in a displacement or a material: shape.displace(..), shape.material(..)"),
        ("sphere(1.0).material(rgb(mandelbrot(x, z, 0), 0.5, 0.5))", "1:13: mandelbrot iterations must be a whole number from 1 to 7500"),
        ("sphere(1.0).displace(x)", "1:22: displace amount must stay within a bounded range (wrap the point in noise, sin, clamp, ..)"),
        ("sphere(1.0).displace(0.1 * sqrt(noise2(x, y) + 1.0))", "1:22: displace amount must change with the point at a bounded rate (no division by a value that can be 0, no sqrt reaching 0, no pow with a varying exponent)"),
        ("sphere(1.0).displace(fbm2(x, y, 40))", "1:13: fbm2 octaves must be a whole number from 1 to 12"),
        ("sphere(1.0).polar_repeat(2.5)", "1:26: polar_repeat count must be a whole number from 1 to 1000"),
        ("sphere(1.0).abs_fold(vec3(1, 2, 0))", "1:22: abs_fold axes y must be <= 1, found 2"),
        ("julia(vec4(0, 0, 0, 0)).bailout(-1.0)", "1:33: julia bailout must be > 0, found -1"),
        ("menger(3).step_factor(0.0)", "1:23: menger step_factor must be in (0, 4], found 0"),
        ("torus(1.0, 0.0)", "1:12: torus minor radius must be > 0, found 0"),
        ("torus(-1.0, 0.5)", "1:7: torus major radius must be >= 0, found -1"),
        ("box3(vec3(1, -1, 1))", "1:6: box3 half extent y must be > 0, found -1"),
        (
            "round_box(vec3(1.0, 0.5, 1.0), 0.75)",
            "1:32: round_box radius must be in [0, 0.5], found 0.75 (the rounding cannot exceed the smallest half \
                extent)",
        ),
        ("cone(1.0, 0.0, 0.0)", "1:1: cone radii bottom and top cannot both be 0"),
        ("cylinder(0.5, -1.0)", "1:15: cylinder half_height must be > 0, found -1"),
        ("plane(vec3(0, 0, 0), 1.0)", "1:7: plane normal must be non-zero, found vec3(0, 0, 0)"),
        ("smooth_union(sphere(1.0), sphere(2.0), -0.5)", "1:40: smooth_union blend radius k must be >= 0, found -0.5"),
        ("sphere(1.0).scale(0.0)", "1:19: scale factor must be > 0, found 0"),
        (
            "sphere(1.0).repeat(vec3(0, 0, 0))",
            "1:20: repeat period must be non-zero on at least one axis (0 leaves an \
            axis unrepeated)",
        ),
        ("sphere(1.0).repeat(vec3(1, -2, 0))", "1:20: repeat period y must be >= 0, found -2"),
        (
            "sphere(1.0).repeat_limited(vec3(2, 2, 2), vec3(1, 2000, 1))",
            "1:43: repeat_limited count y must be <= 1000, found 2000",
        ),
        ("sphere(1.0).onion(0)", "1:19: onion thickness must be > 0, found 0"),
        ("sphere(1.0).round(-0.1)", "1:19: round radius must be >= 0, found -0.1"),
        ("sphere(1.0).rotate(vec3(0, 0, 0), 1.0)", "1:20: rotate axis must be non-zero, found vec3(0, 0, 0)"),
        (
            "sphere(1.0).material(phong(rgb(1, 1, 1), -0.1, 0.8, 0.2, 8.0))",
            "1:42: material ambient must be >= 0, found -0.1",
        ),
        ("scene(sphere(1.0)).max_steps(0)", "1:30: max_steps must be in 1..=10000, found 0"),
        ("scene(sphere(1.0)).fog(rgb(1, 1, 1), 0.0)", "1:38: fog density must be > 0, found 0"),
        ("scene(sphere(1.0)).ambient_occlusion(11.0)", "1:38: ambient_occlusion strength must be in (0, 10], found 11"),
        (
            "scene(sphere(1.0)).camera(camera(vec3(0, 0, -3), vec3(0, 0, 0)).fov(180))",
            "1:69: camera fov must be in (0, 180), found 180",
        ),
        (
            "scene(sphere(1.0)).camera(camera(vec3(1, 2, 3), vec3(1, 2, 3)))",
            "1:49: camera target must differ from the camera position",
        ),
        (
            "scene(sphere(1.0)).camera(camera_path(key(0.0, vec3(0, 0, -3), vec3(0, 0, 0))))",
            "1:27: camera_path needs at least 2 keys, found 1",
        ),
        (
            "scene(sphere(1.0)).camera(camera_path(key(1.0, vec3(0, 0, -3), vec3(0, 0, 0)), key(1.0, vec3(0, 0, 3), \
                vec3(0, 0, 0))))",
            "1:80: camera key times must increase strictly: key 2 at 1 follows 1",
        ),
        (
            "scene(sphere(1.0)).light(directional(vec3(0, 0, 0), rgb(1, 1, 1)))",
            "1:38: light direction must be non-zero, found vec3(0, 0, 0)",
        ),
        (
            "sphere(1.0).translate(vec3(param(\"x\", 2.0, -1.0..1.0), 0, 0))",
            "1:39: param \"x\" default must be within -1..1, found 2",
        ),
        (
            "sphere(1.0).translate(vec3(param(\"x\", 0.0, 1.0..-1.0), 0, 0))",
            "1:44: param \"x\" range must have min < max, found 1..-1",
        ),
        (
            "sphere(1.0).translate(vec3(param(\"x y\", 0.0, -1.0..1.0), 0, 0))",
            "1:34: param name must be an identifier \
            of at most 64 letters, digits and `_`, found \"x y\"",
        ),
        (
            "sphere(1.0).translate(vec3(param(\"x\", 0.0, -1.0..1.0), param(\"x\", 0.5, -1.0..1.0), 0))",
            "1:56: param \"x\" is declared twice with different values: default 0 in -1..1 and default 0.5 in -1..1",
        ),
    ];
    assert_errors(cases);
}

#[test]
fn errors_in_a_multi_line_file_carry_its_line_and_column() {
    let src = "\
// sphere_box, with one mistake
scene(
    smooth_union(
        box3(vec3(1.0, 1.0, 1.0)),
        sphere(1.2).translate(vec3(0.0, 0.5, 0.0)),
        torus(1.5, -0.2),
        0.25,
    ),
)
.soft_shadows(16.0)
";
    assert_eq!(
        parse_str(src),
        Err(SourceError { line: 6, column: 20, message: "torus minor radius must be > 0, found -0.2".into() })
    );

    let src = "scene(sphere(1.0))\n    .max_steps(64)\n    .gamma(t)\n";
    assert_eq!(
        error(src),
        "3:12: `gamma` argument `gamma` must be a constant: `t` and `param(..)` cannot be used here"
    );

    // Columns count characters, not bytes.
    let src = "// ünïcödé\nsphere(1.0).translate(vec3(0, 0, 0)) // ★\n    .scale(-2.0)";
    assert_eq!(error(src), "3:12: scale factor must be > 0, found -2");

    let src = "union(\n    sphere(1.0),\n    sphere(2.0)\n    sphere(3.0),\n)";
    assert_eq!(error(src), "4:5: expected `,`");
}

#[test]
fn token_errors_carry_the_span_of_the_offending_argument() {
    let at = |src: &str| {
        let tokens = TokenStream::from_str(src).unwrap();
        let e = parse_tokens(tokens).unwrap_err();
        let start = e.span().start();
        (start.line, start.column, e.to_string())
    };
    assert_eq!(at("torus(1.0, -0.5)"), (1, 11, "torus minor radius must be > 0, found -0.5".to_string()));
    assert_eq!(
        at("sphere(1.0)\n  .translate(vec3(1.0, 0.0))"),
        (2, 13, "`vec3` takes 3 arguments (x: number, y: number, z: number), found 2".to_string())
    );
    assert_eq!(at("box(vec3(1.0, 1.0, 1.0))").0, 1);
}
