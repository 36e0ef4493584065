//! Parser tests: every word of the vocabulary builds the same IR as the builder API; errors carry exact messages at
//! `line:column` in files and at the offending token for macro tokens; caps refuse hostile input; no input panics.

use std::f64::consts::PI;
use std::str::FromStr;

use fractal_dsl::builder::*;
use fractal_dsl::ir::arg::{ArgDecl, ArgShape, Rule};
use fractal_dsl::ir::op::Operands;
use fractal_dsl::ir::*;
use fractal_dsl::parse::{parse_str, parse_tokens, vocabulary, SourceError};
use glam::DVec3;
use proc_macro2::TokenStream;
use proptest::prelude::*;

fn parse(src: &str) -> Scene {
    parse_str(src).unwrap_or_else(|e| panic!("{src}\n{e}"))
}

fn error(src: &str) -> String {
    match parse_str(src) {
        Ok(s) => panic!("{src} parsed as {s:?}"),
        Err(e) => e.to_string(),
    }
}

/// Checks every `(source, expected error)` pair and reports all mismatches at once.
fn assert_errors(cases: &[(&str, &str)]) {
    let mut failures = Vec::new();
    for (src, expected) in cases {
        let got = error(src);
        if got != *expected {
            failures.push(format!("{src}\n  expected {expected}\n  got      {got}"));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

fn unit_box() -> Node {
    box3(vec3(1.0, 1.0, 1.0))
}

/// Sources and the scenes the builder makes for them; together they use every word of the vocabulary.
fn cases() -> Vec<(&'static str, Scene)> {
    let s = |n: Node| scene(n);
    let ball = || sphere(1.0);
    vec![
        // numbers
        ("sphere(2)", s(sphere(2.0))),
        ("sphere(1.5f32)", s(sphere(1.5f32))),
        (
            "sphere(0.5).translate(vec3(t, -t, -(1.0)))",
            s(sphere(0.5).translate(vec3(time(), -time(), -Expr::Lit(1.0)))),
        ),
        ("sphere(1.0).translate(vec3(-1.0, -(-1.0), -0.0))", s(ball().translate(vec3(-1.0, -Expr::Lit(-1.0), -0.0)))),
        (
            "sphere(1.0).translate(vec3(sin(t), cos(t), abs(-2.0)))",
            s(ball().translate(vec3(sin(time()), cos(time()), abs(-2.0)))),
        ),
        (
            "sphere(1.0).translate(vec3(sqrt(2.0), min(t, 1.0), max(t, 1.0)))",
            s(ball().translate(vec3(sqrt(2.0), min(time(), 1.0), max(time(), 1.0)))),
        ),
        (
            "sphere(1.0).translate(vec3(pow(t, 2.0), clamp(t, 0.0, 1.0), mix(0.0, 2.0, t)))",
            s(ball().translate(vec3(pow(time(), 2.0), clamp(time(), 0.0, 1.0), mix(0.0, 2.0, time())))),
        ),
        (
            "sphere(1.0).translate(vec3(1.0 + 2.0 * t, (1.0 + 2.0) * t, t / 2.0 - 1.0))",
            s(ball().translate(vec3(
                Expr::Lit(1.0) + Expr::Lit(2.0) * time(),
                (Expr::Lit(1.0) + 2.0) * time(),
                time() / 2.0 - 1.0,
            ))),
        ),
        ("sphere(1.0).rotate_x(PI / 2.0)", s(ball().rotate_x(Expr::Lit(PI) / 2.0))),
        (
            "sphere(1.0).translate(vec3(param(\"x\", 0.5, -1.0..1.0), 0, 0))",
            s(ball().translate(vec3(param("x", 0.5, -1.0..1.0), 0.0, 0.0))),
        ),
        // primitives
        ("box3(vec3(1, 2, 3))", s(box3(vec3(1.0, 2.0, 3.0)))),
        ("round_box(vec3(1.0, 1.0, 1.0), 0.25)", s(round_box(vec3(1.0, 1.0, 1.0), 0.25))),
        ("torus(1.0, 0.25)", s(torus(1.0, 0.25))),
        (
            "capsule(vec3(0.0, -1.0, 0.0), vec3(0.0, 1.0, 0.0), 0.5)",
            s(capsule(vec3(0.0, -1.0, 0.0), vec3(0.0, 1.0, 0.0), 0.5)),
        ),
        ("cylinder(0.5, 1.0)", s(cylinder(0.5, 1.0))),
        ("cone(1.0, 0.5, 0.0)", s(cone(1.0, 0.5, 0.0))),
        ("plane(vec3(0.0, 2.0, 0.0), 1.0)", s(plane(vec3(0.0, 2.0, 0.0), 1.0))),
        ("octahedron(1.0)", s(octahedron(1.0))),
        ("ellipsoid(vec3(1.0, 0.5, 0.25))", s(ellipsoid(vec3(1.0, 0.5, 0.25)))),
        // fractals
        ("mandelbulb(8)", scene(mandelbulb(8))),
        ("mandelbulb(8.0).iterations(12).bailout(4.0)", scene(mandelbulb(8.0).iterations(12).bailout(4.0))),
        ("mandelbulb(8).step_factor(1.0)", scene(mandelbulb(8).step_factor(1.0))),
        ("menger(3)", scene(menger(3))),
        ("sierpinski_tetrahedron(10)", scene(sierpinski_tetrahedron(10))),
        (
            "julia(vec4(-0.2, 0.6, 0.2, 0.0)).iterations(10).bailout(4.0)",
            scene(julia(vec4(-0.2, 0.6, 0.2, 0.0)).iterations(10).bailout(4.0)),
        ),
        (
            "mandelbox(-1.5).min_radius(0.25).fold_limit(1.2).iterations(15)",
            scene(mandelbox(-1.5).min_radius(0.25).fold_limit(1.2).iterations(15)),
        ),
        // CSG
        (
            "union(sphere(1.0), box3(vec3(1.0, 1.0, 1.0)), torus(1.0, 0.2))",
            s(union_all([ball(), unit_box(), torus(1.0, 0.2)])),
        ),
        ("union(union(sphere(1.0), sphere(2.0)), sphere(3.0))", s(union(union(ball(), sphere(2.0)), sphere(3.0)))),
        ("union(sphere(1.0))", s(union_all([ball()]))),
        ("union(mandelbulb(8), sphere(0.5))", s(union(mandelbulb(8), sphere(0.5)))),
        ("intersect(sphere(1.0), box3(vec3(1.0, 1.0, 1.0)))", s(intersect(ball(), unit_box()))),
        ("subtract(box3(vec3(1.0, 1.0, 1.0)), sphere(1.2))", s(subtract(unit_box(), sphere(1.2)))),
        ("smooth_union(sphere(1.0), box3(vec3(1.0, 1.0, 1.0)), 0.25)", s(smooth_union(ball(), unit_box(), 0.25))),
        (
            "smooth_union(sphere(1.0), sphere(2.0), sphere(3.0), 0.5)",
            s(smooth_union_all([ball(), sphere(2.0), sphere(3.0)], 0.5)),
        ),
        ("smooth_intersect(sphere(1.0), box3(vec3(1.0, 1.0, 1.0)), 0.1)", s(smooth_intersect(ball(), unit_box(), 0.1))),
        (
            "smooth_intersect(sphere(1.0), sphere(2.0), sphere(3.0), 0.1)",
            s(smooth_intersect_all([ball(), sphere(2.0), sphere(3.0)], 0.1)),
        ),
        (
            "smooth_subtract(box3(vec3(1.0, 1.0, 1.0)), sphere(1.2), 0.1)",
            s(smooth_subtract(unit_box(), sphere(1.2), 0.1)),
        ),
        // transforms and domain operations
        ("mandelbulb(8).translate(vec3(1, 0, 0))", s(mandelbulb(8).translate(vec3(1.0, 0.0, 0.0)))),
        ("sphere(1.0).rotate_y(t * 0.5).rotate_z(0.25)", s(ball().rotate_y(time() * 0.5).rotate_z(0.25))),
        ("sphere(1.0).rotate(vec3(1.0, 1.0, 0.0), 0.5)", s(ball().rotate(DVec3::new(1.0, 1.0, 0.0), 0.5))),
        ("sphere(1.0).scale(2.0)", s(ball().scale(2.0))),
        ("sphere(1.0).repeat(vec3(4.0, 0.0, 4.0))", s(ball().repeat(vec3(4.0, 0.0, 4.0)))),
        (
            "sphere(1.0).repeat_limited(vec3(3, 3, 3), vec3(2, 1, 0))",
            s(ball().repeat_limited(vec3(3.0, 3.0, 3.0), [2, 1, 0])),
        ),
        ("sphere(1.0).twist(0.5).bend(0.3)", s(ball().twist(0.5).bend(0.3))),
        ("sphere(1.0).round(0.1).onion(0.05)", s(ball().round(0.1).onion(0.05))),
        ("sphere(1.0).elongate(vec3(0.5, 0.0, 0.0))", s(ball().elongate(vec3(0.5, 0.0, 0.0)))),
        ("sphere(1.0).plane_fold(vec3(0.0, 2.0, 0.0))", s(ball().plane_fold(DVec3::new(0.0, 1.0, 0.0)))),
        ("sphere(1.0).abs_fold(vec3(1, 0, 1))", s(ball().abs_fold([1, 0, 1]))),
        ("sphere(1.0).box_fold(0.5 + t)", s(ball().box_fold(Expr::Lit(0.5) + Expr::Time))),
        ("sphere(1.0).sphere_fold(0.25, 1.0)", s(ball().sphere_fold(0.25, 1.0))),
        ("sphere(1.0).polar_repeat(6)", s(ball().polar_repeat(6))),
        (
            "sphere(1.0).material(rgb(mandelbrot(x, z, 64), y, 0.5))",
            s(ball().material(rgb(mandelbrot(x(), z(), 64), y(), 0.5))),
        ),
        (
            "sphere(1.0).displace(0.1 * noise3(x * 4.0, y * 4.0, z * 4.0) + 0.05 * noise2(x, t))",
            s(ball().displace(
                Expr::from(0.1) * noise3(x() * 4.0, y() * 4.0, z() * 4.0) + Expr::from(0.05) * noise2(x(), time()),
            )),
        ),
        (
            "plane(vec3(0.0, 1.0, 0.0), 0.0).displace(fbm2(x, z, 5) + 0.1 * fbm3(x, y, z, 2))",
            s(plane(vec3(0.0, 1.0, 0.0), 0.0).displace(fbm2(x(), z(), 5) + Expr::from(0.1) * fbm3(x(), y(), z(), 2))),
        ),
        ("juliabulb(vec3(0.1, 0.2, 0.3)).power(5.0).bailout(3.0)", scene(juliabulb(vec3(0.1, 0.2, 0.3)).power(5.0).bailout(3.0))),
        ("octahedral_kifs(2.0).angle(0.25).iterations(9)", scene(octahedral_kifs(2.0).angle(0.25).iterations(9))),
        // materials
        ("sphere(1.0).material(rgb(0.9, 0.2, 0.1))", s(ball().material(rgb(0.9, 0.2, 0.1)))),
        (
            "sphere(1.0).material(phong(rgb(1.0, 0.5, 0.25), 0.1, 0.8, 0.5, 16.0))",
            s(ball().material(phong(rgb(1.0, 0.5, 0.25), 0.1, 0.8, 0.5, 16.0))),
        ),
        (
            "mandelbulb(8).material(orbit_trap(rgb(1, 0, 0), rgb(0, 0, \
                1)).ambient(0.2).diffuse(0.7).specular(0.3).shininess(8.0))",
            s(mandelbulb(8).material(
                orbit_trap(rgb(1.0, 0.0, 0.0), rgb(0.0, 0.0, 1.0))
                    .ambient(0.2)
                    .diffuse(0.7)
                    .specular(0.3)
                    .shininess(8.0),
            )),
        ),
        (
            "sphere(1.0).material(rgb(0.9, 0.9, 0.9).specular(0.5))",
            s(ball().material(rgb(0.9, 0.9, 0.9).specular(0.5))),
        ),
        // lights
        (
            "scene(sphere(1.0)).light(directional(vec3(1.0, 1.0, -1.0), rgb(1.0, 1.0, 1.0)))",
            s(ball()).light(directional(vec3(1.0, 1.0, -1.0), rgb(1.0, 1.0, 1.0))),
        ),
        (
            "sphere(1.0).light(point_light(vec3(0.0, 3.0, 0.0), rgb(1.0, 0.8, \
                0.6)).intensity(2.0)).light(directional(vec3(0.0, 1.0, 0.0), rgb(0.2, 0.2, 0.3)))",
            s(ball())
                .light(point_light(vec3(0.0, 3.0, 0.0), rgb(1.0, 0.8, 0.6)).intensity(2.0))
                .light(directional(vec3(0.0, 1.0, 0.0), rgb(0.2, 0.2, 0.3))),
        ),
        // cameras
        (
            "scene(sphere(1.0)).camera(camera(vec3(0.0, 1.0, -4.0), vec3(0.0, 0.0, 0.0)).fov(60.0))",
            s(ball()).camera(camera(vec3(0.0, 1.0, -4.0), vec3(0.0, 0.0, 0.0)).fov(60.0)),
        ),
        (
            "scene(sphere(1.0)).camera(camera_path(key(0.0, vec3(0, 0, -4), vec3(0, 0, 0)), key(5.0, vec3(4, 0, 0), \
                vec3(0, 0, 0))).linear().looped())",
            s(ball()).camera(
                camera_path([
                    key(0.0, DVec3::new(0.0, 0.0, -4.0), DVec3::ZERO),
                    key(5.0, DVec3::new(4.0, 0.0, 0.0), DVec3::ZERO),
                ])
                    .linear()
                    .looped(),
            ),
        ),
        (
            "scene(sphere(1.0)).camera(camera_path(key(0.0, vec3(0, 0, -4), vec3(0, 0, 0)), key(2.5, vec3(4, 0, 0), \
                vec3(0, 1, 0))))",
            s(ball()).camera(camera_path([
                key(0.0, DVec3::new(0.0, 0.0, -4.0), DVec3::ZERO),
                key(2.5, DVec3::new(4.0, 0.0, 0.0), DVec3::Y),
            ])),
        ),
        // render settings
        (
            "scene(sphere(1.0)).max_steps(200).max_distance(50.0).epsilon(0.001).hard_shadows().ambient_occlusion(1.0)",
            s(ball()).max_steps(200).max_distance(50.0).epsilon(0.001).hard_shadows().ambient_occlusion(1.0),
        ),
        (
            "scene(sphere(1.0)).pixel_epsilon(1.5).soft_shadows(16.0).glow(rgb(0.1, 0.2, 0.3)).fog(rgb(0.5, 0.5, 0.5), \
                0.05)",
            s(ball()).pixel_epsilon(1.5).soft_shadows(16.0).glow(rgb(0.1, 0.2, 0.3)).fog(rgb(0.5, 0.5, 0.5), 0.05),
        ),
        ("scene(sphere(1.0)).over_relaxation(1.3)", s(ball()).over_relaxation(1.3)),
        ("scene(sphere(1.0)).normal_pixel_epsilon(0.5)", s(ball()).normal_pixel_epsilon(0.5)),
        ("scene(julia(vec4(-0.2, 0.8, 0.0, 0.0))).membership_hits()", scene(julia(vec4(-0.2, 0.8, 0.0, 0.0))).membership_hits()),
        (
            "scene(sphere(1.0)).soft_shadows(8.0).no_shadows().background(rgb(0, 0, 0)).gamma(2.2)",
            s(ball()).soft_shadows(8.0).no_shadows().background(rgb(0.0, 0.0, 0.0)).gamma(2.2),
        ),
        // scene settings are constants: literal arithmetic folds
        ("scene(sphere(1.0)).max_distance(10.0 * 2.0).gamma(-(-2.2))", s(ball()).max_distance(20.0).gamma(2.2)),
        // comments and trailing commas in files
        (
            "// a lit ball\nscene(\n    sphere(1.0), // the ball\n)\n/* block comment */\n.gamma(2.2)\n",
            s(ball()).gamma(2.2),
        ),
    ]
}

#[test]
fn every_case_builds_what_the_builder_builds() {
    for (src, expected) in cases() {
        assert_eq!(parse(src), expected, "{src}");
    }
}

/// A value each argument rule accepts, for building every declared primitive and operator.
fn example(arg: &ArgDecl, index: usize) -> ArgValue {
    let n = 0.5 + 0.125 * index as f64;
    let value = match arg.rule {
        Rule::Direction => return ArgValue::Vec3(vec3(0.0, 1.0, 0.0)),
        Rule::AtMost(most) => return ArgValue::Vec3(vec3(1.0, 0.0, f64::from(most.min(2)))),
        Rule::CountUpTo(most) => f64::from(most.min(5)),
        Rule::RoundingOf(_) => 0.125,
        _ => n,
    };
    match arg.shape {
        ArgShape::Number => ArgValue::Num(Expr::Lit(value)),
        _ => ArgValue::Vec3(vec3(value, value + 0.25, value + 0.5)),
    }
}

/// Operators are read from their declarations (`fractal_dsl::vocab::ops`) too, each over the shapes it takes.
#[test]
fn every_declared_operator_reads_back_from_its_printed_source() {
    for decl in fractal_dsl::vocab::ops::decl::OPS {
        let shapes = match decl.operands {
            Operands::Many => vec![sphere(1.0), box3(vec3(1.0, 1.0, 1.0)), torus(1.0, 0.2)],
            Operands::Two => vec![box3(vec3(1.0, 1.0, 1.0)), sphere(1.2)],
            Operands::Receiver => vec![box3(vec3(1.0, 1.0, 1.0))],
        };
        let node = decl.node(shapes, decl.args.iter().enumerate().map(|(i, a)| example(a, i)).collect());
        let written = scene(node);
        let src = fractal_dsl::print::to_source(&written);
        assert!(src.contains(&format!("{}(", decl.name)), "{src}");
        assert_eq!(parse(&src), written, "{src}");
        assert!(fractal_dsl::validate::validate(&written).is_ok(), "{src}");
    }
}

/// Primitives are read from their declarations (`fractal_dsl::vocab::prims`), so the parser knows each one it is given.
#[test]
fn every_declared_primitive_reads_back_from_its_printed_source() {
    for decl in fractal_dsl::vocab::prims::decl::PRIMS {
        let node = decl.node(decl.args.iter().enumerate().map(|(i, a)| example(a, i)).collect());
        let written = scene(node);
        let src = fractal_dsl::print::to_source(&written);
        assert!(src.contains(&format!("{}(", decl.name)), "{src}");
        assert_eq!(parse(&src), written, "{src}");
    }
}

/// Fractal families are read from their declarations (`fractal_dsl::vocab::fractals`) too.
#[test]
fn every_declared_fractal_family_reads_back_from_its_printed_source() {
    use fractal_dsl::ir::fractal::{FractalArgShape, FractalArgValue, FractalRule};
    for decl in fractal_dsl::vocab::fractals::families::FRACTALS {
        let value = match decl.arg.rule {
            FractalRule::Between(lo, hi) | FractalRule::AbsBetween(lo, hi) => 0.5 * (lo + hi),
            FractalRule::Finite | FractalRule::Count => 0.25,
        };
        let fractal = match decl.arg.shape {
            FractalArgShape::Number => Fractal::new(decl, FractalArgValue::Num(Expr::Lit(value))),
            FractalArgShape::Vec3 => Fractal::new(decl, FractalArgValue::Vec3(vec3(value, -value, 0.5 * value))),
            FractalArgShape::Vec4 => Fractal::new(decl, FractalArgValue::Vec4(vec4(value, -value, 0.5 * value, 0.0))),
            FractalArgShape::Levels => {
                Fractal { iterations: Some(decl.iterations.min + 1), ..Fractal::new(decl, FractalArgValue::Levels) }
            }
        };
        let written = scene(fractal);
        let src = fractal_dsl::print::to_source(&written);
        assert!(src.contains(&format!("{}(", decl.name)), "{src}");
        assert_eq!(parse(&src), written, "{src}");
    }
}

#[test]
fn the_cases_use_every_word_of_the_vocabulary() {
    let sources: String = cases().into_iter().map(|(src, _)| src).collect::<Vec<_>>().join("\n");
    let words = vocabulary();
    assert!(words.len() > 70, "vocabulary unexpectedly small: {}", words.len());
    for sig in &words {
        let head = sig.split(['(', ' ']).next().unwrap_or_default();
        if fractal_dsl::vocab::prims::decl::by_name(head).is_some()
            || fractal_dsl::vocab::fractals::families::by_name(head).is_some()
        {
            continue; // covered for every declaration by the tests above
        }
        let (needle, word) = match head.split_once('.') {
            Some((_, method)) => (format!(".{method}("), method),
            None if !sig.contains('(') => (head.to_string(), head),
            None => (format!("{head}("), head),
        };
        assert!(sources.contains(&needle), "no test case uses `{word}` ({sig})");
    }
}

#[test]
fn vocabulary_lists_signatures() {
    let words = vocabulary();
    for expected in [
        "sphere(radius: number) -> shape",
        "union(shapes: shape...) -> shape",
        "smooth_union(shapes: shape..., k: number) -> shape",
        "shape.translate(offset: vec3) -> shape",
        "shape.repeat_limited(period: vec3, count: vec3 of integers) -> shape",
        "scene.max_steps(steps: integer) -> scene",
        "param(name: string, default: constant, range: range) -> number",
        "t -> number",
    ] {
        assert!(words.iter().any(|w| w == expected), "missing {expected}");
    }
}

#[test]
fn bare_shapes_and_fractals_become_scenes() {
    assert_eq!(parse("sphere(1.0)"), scene(sphere(1.0)));
    assert_eq!(parse("menger(2)"), scene(menger(2)));
    assert_eq!(parse("scene(menger(2))"), scene(menger(2)));
}

#[test]
fn macro_tokens_and_file_text_build_the_same_scene() {
    let tokens = quote::quote! {
        union(
            mandelbulb(8),
            sphere(1.0).translate(vec3(1.5, 0.0, 0.0)).material(rgb(0.9, 0.2, 0.1)),
        )
    };
    let from_tokens = parse_tokens(tokens).unwrap();
    let from_text =
        parse("union(mandelbulb(8), sphere(1.0).translate(vec3(1.5, 0.0, 0.0)).material(rgb(0.9, 0.2, 0.1)))");
    assert_eq!(from_tokens, from_text);
    let expected = scene(union(mandelbulb(8), sphere(1.0).translate(vec3(1.5, 0.0, 0.0)).material(rgb(0.9, 0.2, 0.1))));
    assert_eq!(from_tokens, expected);
}

// ---- errors ---------------------------------------------------------------------------------------------------------

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
        ("menger(3).bailout(4.0)", "1:11: `bailout` applies only to mandelbulb, julia and juliabulb, not menger"),
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

// ---- caps -----------------------------------------------------------------------------------------------------------

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
