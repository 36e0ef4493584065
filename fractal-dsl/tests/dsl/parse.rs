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

mod caps;
mod errors;

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
    let formula = |src: &str| escape_time(fractal_dsl::parse::formula_from_source(src));
    vec![
        // formulas (their own errors and round trips: `formula.rs`)
        (
            "hybrid(|z, c| z * 2.0 + c, |z| box_fold(z, 1.0))",
            s(formula("hybrid(|z, c| z * 2.0 + c, |z| box_fold(z, 1.0))").into()),
        ),
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
        ("scene(sphere(1.0)).samples(16).sample_threshold(0.01)", s(ball()).samples(16).sample_threshold(0.01)),
        (
            "scene(sphere(1.0)).camera(camera(vec3(0, 0, -3), vec3(0, 0, 0)).aperture(0.05).focus(2.5))",
            s(ball()).camera(camera(vec3(0.0, 0.0, -3.0), vec3(0.0, 0.0, 0.0)).aperture(0.05).focus(2.5)),
        ),
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
            FractalArgShape::Formula => {
                let formula = fractal_dsl::parse::formula_from_source(&format!("{}(|z, c| z * z.x + c)", decl.name));
                assert_eq!(formula.maps.len(), 1, "{}", decl.name);
                Fractal::new(decl, FractalArgValue::Formula(Box::new(formula)))
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
