//! Validation tests: builder-made scenes with broken rules get messages that name the node path, the parameter and
//! its allowed range; the parser reports the same messages for the same scenes written as text; caps hold without
//! recursion.

use fractal_dsl::builder::*;
use fractal_dsl::ir::*;
use fractal_dsl::parse::parse_str;
use fractal_dsl::print::to_source;
use fractal_dsl::validate::{validate, ValidationError};
use glam::DVec3;

fn errors(s: &Scene) -> Vec<String> {
    validate(s).err().unwrap_or_default().iter().map(ValidationError::to_string).collect()
}

fn lit_scene() -> Scene {
    scene(smooth_union(
        box3(vec3(1.0, 1.0, 1.0)),
        sphere(1.2).translate(vec3(0.0, 0.5, 0.0)).material(rgb(0.9, 0.2, 0.1).specular(0.4)),
        0.25,
    ))
    .light(directional(vec3(0.6, 0.8, -0.4), rgb(1.0, 1.0, 1.0)))
    .camera(camera(vec3(0.0, 1.0, -4.0), vec3(0.0, 0.0, 0.0)).fov(50.0))
    .soft_shadows(16.0)
    .ambient_occlusion(1.0)
}

#[test]
fn valid_scenes_pass() {
    assert_eq!(validate(&lit_scene()), Ok(()));
    assert_eq!(validate(&scene(mandelbulb(8).iterations(12).bailout(2.0))), Ok(()));
    assert_eq!(validate(&scene(mandelbox(-1.5).min_radius(0.5).fold_limit(1.0))), Ok(()));
    assert_eq!(validate(&scene(menger(8))), Ok(()));
    assert_eq!(validate(&scene(sierpinski_tetrahedron(24))), Ok(()));
    let path = camera_path([key(0.0, DVec3::new(0.0, 0.0, -4.0), DVec3::ZERO), key(1.0, DVec3::X * 4.0, DVec3::ZERO)]);
    assert_eq!(validate(&scene(sphere(1.0)).camera(path)), Ok(()));
    // Edges that are allowed: round radius 0, torus major 0, cone with one tip, round_box radius = smallest half.
    let edges = union_all([
        sphere(1.0).round(0.0),
        torus(0.0, 0.5),
        cone(1.0, 0.5, 0.0),
        round_box(vec3(1.0, 0.5, 1.0), 0.5),
        sphere(1.0).repeat(vec3(0.0, 0.0, 2.0)),
    ]);
    assert_eq!(validate(&scene(edges)), Ok(()));
}

#[test]
fn a_broken_node_is_named_by_its_path() {
    let s = scene(union(sphere(1.0), sphere(-1.0).translate(vec3(1.0, 0.0, 0.0))));
    assert_eq!(errors(&s), ["union > child 2 > translate > sphere: sphere radius must be > 0, found -1"]);

    let s = scene(mandelbulb(8).iterations(0));
    assert_eq!(errors(&s), ["mandelbulb: mandelbulb iterations must be in 1..=64, found 0"]);

    let s = scene(mandelbulb(1.5));
    assert_eq!(errors(&s), ["mandelbulb: mandelbulb power must be >= 2, found 1.5"]);
}

#[test]
fn every_broken_rule_is_reported() {
    let s = scene(union(sphere(0.0), torus(1.0, 0.0)).scale(0.0));
    assert_eq!(
        errors(&s),
        [
            "scale: scale factor must be > 0, found 0",
            "scale > union > child 1 > sphere: sphere radius must be > 0, found 0",
            "scale > union > child 2 > torus: torus minor radius must be > 0, found 0",
        ]
    );

    let s = scene(sphere(1.0))
        .light(directional(vec3(0.0, 0.0, 0.0), rgb(1.0, 1.0, 1.0)))
        .light(point_light(vec3(0.0, 1.0, 0.0), rgb(1.0, 1.0, 1.0)).intensity(-1.0))
        .camera(camera(vec3(0.0, 0.0, -3.0), vec3(0.0, 0.0, 0.0)).fov(0.0).aperture(-0.1).focus(0.0))
        .max_steps(0)
        .samples(0)
        .sample_threshold(2.0)
        .epsilon(0.0)
        .gamma(0.0);
    assert_eq!(
        errors(&s),
        [
            "light 1: light direction must be non-zero, found vec3(0, 0, 0)",
            "light 2: light intensity must be >= 0, found -1",
            "camera: camera fov must be in (0, 180), found 0",
            "camera: camera aperture must be in [0, 1000000000], found -0.1",
            "camera: camera focus must be in (0, 1000000000], found 0",
            "scene: max_steps must be in 1..=10000, found 0",
            "scene: epsilon must be > 0, found 0",
            "scene: samples must be in 1..=256, found 0",
            "scene: sample_threshold must be in [0, 1], found 2",
            "scene: gamma must be > 0, found 0",
        ]
    );
}

#[test]
fn rules_of_every_kind() {
    let cases: Vec<(Scene, &str)> = vec![
        (scene(box3(vec3(1.0, 1.0, -0.5))), "box3: box3 half extent z must be > 0, found -0.5"),
        (
            scene(round_box(vec3(1.0, 0.5, 1.0), 0.6)),
            "round_box: round_box radius must be in [0, 0.5], found 0.6 (the rounding cannot exceed the smallest half \
                extent)",
        ),
        (scene(torus(-1.0, 0.5)), "torus: torus major radius must be >= 0, found -1"),
        (scene(capsule(vec3(0.0, 0.0, 0.0), vec3(0.0, 1.0, 0.0), 0.0)), "capsule: capsule radius must be > 0, found 0"),
        (scene(cylinder(0.0, 1.0)), "cylinder: cylinder radius must be > 0, found 0"),
        (scene(cone(0.0, 1.0, 0.5)), "cone: cone half_height must be > 0, found 0"),
        (scene(cone(1.0, 0.0, 0.0)), "cone: cone radii bottom and top cannot both be 0"),
        (scene(cone(1.0, -0.5, 0.5)), "cone: cone bottom radius must be >= 0, found -0.5"),
        (scene(plane(vec3(0.0, 0.0, 0.0), 0.0)), "plane: plane normal must be non-zero, found vec3(0, 0, 0)"),
        (scene(octahedron(-2.0)), "octahedron: octahedron size must be > 0, found -2"),
        (scene(ellipsoid(vec3(1.0, 0.0, 1.0))), "ellipsoid: ellipsoid radius y must be > 0, found 0"),
        (scene(mandelbulb(65.0)), "mandelbulb: mandelbulb power must be <= 64, found 65"),
        (scene(mandelbulb(8).bailout(0.0)), "mandelbulb: mandelbulb bailout must be > 0, found 0"),
        (scene(mandelbulb(8).step_factor(4.5)), "mandelbulb: mandelbulb step_factor must be in (0, 4], found 4.5"),
        (scene(menger(0)), "menger: menger levels must be in 1..=8, found 0"),
        (scene(menger(9)), "menger: menger levels must be in 1..=8, found 9"),
        (
            scene(sierpinski_tetrahedron(25)),
            "sierpinski_tetrahedron: sierpinski_tetrahedron levels must be in 1..=24, \
            found 25",
        ),
        (scene(julia(vec4(0.0, 0.0, 0.0, 0.0)).iterations(65)), "julia: julia iterations must be in 1..=64, found 65"),
        (scene(julia(vec4(0.0, 0.0, 0.0, 0.0)).bailout(-4.0)), "julia: julia bailout must be > 0, found -4"),
        (scene(mandelbox(1.0)), "mandelbox: mandelbox |scale| must be in [1.05, 8], found 1"),
        (scene(mandelbox(-9.0)), "mandelbox: mandelbox |scale| must be in [1.05, 8], found -9"),
        (scene(mandelbox(2.0).min_radius(0.0)), "mandelbox: mandelbox min_radius must be in (0, 1), found 0"),
        (scene(mandelbox(2.0).fold_limit(-1.0)), "mandelbox: mandelbox fold_limit must be > 0, found -1"),
        (
            scene(mandelbox(2.0).bailout(4.0)),
            "mandelbox: `bailout` applies only to mandelbulb, julia, juliabulb, escape_time and fold, not mandelbox",
        ),
        (scene(mandelbulb(8).min_radius(0.5)), "mandelbulb: `min_radius` applies only to mandelbox, not mandelbulb"),
        (
            scene(sierpinski_tetrahedron(8).fold_limit(1.0)),
            "sierpinski_tetrahedron: `fold_limit` applies only to \
            mandelbox, not sierpinski_tetrahedron",
        ),
        (scene(union_all([])), "union: union needs at least 1 shape"),
        (
            scene(smooth_union(sphere(1.0), sphere(2.0), -0.1)),
            "smooth_union: smooth_union blend radius k must be >= 0, \
            found -0.1",
        ),
        (
            scene(smooth_intersect(sphere(1.0), sphere(2.0), -0.1)),
            "smooth_intersect: smooth_intersect blend radius k \
            must be >= 0, found -0.1",
        ),
        (
            scene(smooth_subtract(sphere(1.0), sphere(2.0), -0.1)),
            "smooth_subtract: smooth_subtract blend radius k must \
            be >= 0, found -0.1",
        ),
        (scene(sphere(1.0).rotate(DVec3::ZERO, 1.0)), "rotate: rotate axis must be non-zero, found vec3(0, 0, 0)"),
        (
            scene(sphere(1.0).repeat(vec3(0.0, 0.0, 0.0))),
            "repeat: repeat period must be non-zero on at least one axis \
            (0 leaves an axis unrepeated)",
        ),
        (scene(sphere(1.0).repeat(vec3(-1.0, 1.0, 0.0))), "repeat: repeat period x must be >= 0, found -1"),
        (
            scene(sphere(1.0).repeat_limited(vec3(2.0, 2.0, 2.0), [1, 1, 1001])),
            "repeat_limited: repeat_limited count z \
            must be <= 1000, found 1001",
        ),
        (scene(sphere(1.0).onion(0.0)), "onion: onion thickness must be > 0, found 0"),
        (scene(sphere(1.0).round(-1.0)), "round: round radius must be >= 0, found -1"),
        (scene(sphere(1.0).elongate(vec3(0.0, -1.0, 0.0))), "elongate: elongate length y must be >= 0, found -1"),
        (
            scene(sphere(1.0).material(rgb(1.0, 1.0, 1.0).shininess(-2.0))),
            "material: material shininess must be >= 0, \
            found -2",
        ),
        (
            scene(sphere(1.0).material(phong(rgb(1.0, 1.0, 1.0), 0.1, -0.8, 0.0, 8.0))),
            "material: material diffuse must \
            be >= 0, found -0.8",
        ),
        (
            scene(sphere(1.0).translate(vec3(f64::NAN, 0.0, 0.0))),
            "translate: translate offset: numbers must be finite, \
            found NaN",
        ),
        (scene(sphere(f64::INFINITY)), "sphere: sphere radius: numbers must be finite, found inf"),
        (scene(sphere(1.0).twist(f64::NEG_INFINITY)), "twist: twist rate: numbers must be finite, found -inf"),
        (
            scene(sphere(1.0)).camera(camera(vec3(1.0, 1.0, 1.0), vec3(1.0, 1.0, 1.0))),
            "camera: camera target must \
            differ from the camera position",
        ),
        (scene(sphere(1.0)).camera(camera_path([])), "camera: camera_path needs at least 2 keys, found 0"),
        (
            scene(sphere(1.0)).camera(camera_path([key(1.0, DVec3::X, DVec3::ZERO), key(0.5, DVec3::Y, DVec3::ZERO)])),
            "camera: camera key times must increase strictly: key 2 at 0.5 follows 1",
        ),
        (
            scene(sphere(1.0)).camera(camera_path([key(0.0, DVec3::X, DVec3::X), key(1.0, DVec3::Y, DVec3::ZERO)])),
            "camera: camera key 1: target must differ from the position",
        ),
        (
            scene(sphere(1.0)).camera(camera(vec3(0.0, 0.0, -3.0), vec3(0.0, 0.0, 0.0)).fov(180.0)),
            "camera: camera fov \
            must be in (0, 180), found 180",
        ),
        (scene(sphere(1.0)).max_steps(10_001), "scene: max_steps must be in 1..=10000, found 10001"),
        (scene(sphere(1.0)).max_distance(-1.0), "scene: max_distance must be in (0, 1000000000], found -1"),
        (scene(sphere(1.0)).max_distance(1e12), "scene: max_distance must be in (0, 1000000000], found 1000000000000"),
        (
            scene(sphere(1.0)).max_distance(1e39),
            "scene: max_distance: numbers must lie within ±3.4e38 (the kernels compute in f32), found 1e39",
        ),
        (scene(sphere(1.0)).pixel_epsilon(0.0), "scene: pixel_epsilon must be > 0, found 0"),
        (scene(sphere(1.0)).normal_pixel_epsilon(-0.5), "scene: normal_pixel_epsilon must be > 0, found -0.5"),
        (
            scene(sphere(1.0)).membership_hits(),
            "scene: the scene has no fractal to take hits on; it takes mandelbulb, julia, juliabulb",
        ),
        (
            scene(union(mandelbulb(2.0), menger(3))).membership_hits(),
            "scene: menger's estimate has no membership sign; it takes mandelbulb, julia, juliabulb",
        ),
        (scene(sphere(1.0)).over_relaxation(0.9), "scene: over_relaxation must be in [1, 2], found 0.9"),
        (scene(sphere(1.0)).over_relaxation(2.5), "scene: over_relaxation must be in [1, 2], found 2.5"),
        (scene(sphere(1.0)).soft_shadows(0.0), "scene: soft_shadows k must be > 0, found 0"),
        (scene(sphere(1.0)).ambient_occlusion(0.0), "scene: ambient_occlusion strength must be in (0, 10], found 0"),
        (scene(sphere(1.0)).fog(rgb(0.5, 0.5, 0.5), -0.1), "scene: fog density must be > 0, found -0.1"),
        (scene(sphere(1.0)).max_distance(1e308 * 10.0), "scene: max_distance: numbers must be finite, found inf"),
        (scene(sphere(1.0)).gamma(-1e-9), "scene: gamma must be > 0, found -1e-9"),
    ];
    let mut failures = Vec::new();
    for (s, expected) in &cases {
        let got = errors(s);
        if got != [*expected] {
            failures.push(format!("expected [{expected}]\n     got {got:?}"));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn params_are_declared_consistently() {
    let s = scene(sphere(1.0).translate(vec3(
        param("a", 0.0, -1.0..1.0),
        param("a", 1.0, -1.0..1.0),
        param("b", 5.0, 0.0..1.0),
    )));
    assert_eq!(
        errors(&s),
        [
            "param \"a\": param \"a\" is declared twice with different values: default 0 in -1..1 and default 1 in \
                -1..1",
            "param \"b\": param \"b\" default must be within 0..1, found 5",
        ]
    );
    let s = scene(sphere(1.0).translate(vec3(param("", 0.0, 1.0..1.0), 0.0, 0.0)));
    assert_eq!(
        errors(&s),
        [
            "param \"\": param name must be an identifier of at most 64 letters, digits and `_`, found \"\"",
            "param \"\": param \"\" range must have min < max, found 1..1",
        ]
    );
    // The same declaration twice is one uniform, not a conflict.
    let s = scene(sphere(1.0).translate(vec3(param("a", 0.0, -1.0..1.0), param("a", 0.0, -1.0..1.0), 0.0)));
    assert_eq!(validate(&s), Ok(()));
}

#[test]
fn animated_values_are_checked_over_their_range() {
    let s = scene(sphere(param("r", 1.0, 0.5..2.0)));
    assert_eq!(validate(&s), Ok(()));
    let s = scene(sphere(param("r", 1.0, -1.0..2.0)));
    assert_eq!(errors(&s), ["sphere: sphere radius must be > 0, but it can go down to -1 (its range is -1..2)"]);
    let s = scene(mandelbulb(param("power", 8.0, 1.0..16.0)));
    assert_eq!(errors(&s), ["mandelbulb: mandelbulb power must be >= 2, but it can go down to 1 (its range is 1..16)"]);
    let s = scene(mandelbulb(param("power", 8.0, 2.0..100.0)));
    assert_eq!(
        errors(&s),
        ["mandelbulb: mandelbulb power must be <= 64, but it can go up to 100 (its range is 2..100)"]
    );
    // t >= 0 grows without bound: a radius of t can be 0, one of 1 + t has no upper limit to break.
    assert_eq!(validate(&scene(sphere(Expr::Lit(1.0) + time()))), Ok(()));
    let s = scene(sphere(time()));
    assert_eq!(errors(&s), ["sphere: sphere radius must be > 0, but it can go down to 0 (its range is 0..inf)"]);
    let s = scene(mandelbulb(Expr::Lit(2.0) + time()));
    assert_eq!(
        errors(&s),
        ["mandelbulb: mandelbulb power must be <= 64, but no upper bound is known for its value, so it may leave that \
            range"]
    );
}

#[test]
fn caps_are_checked_without_recursion() {
    let mut deep = sphere(1.0);
    for _ in 0..200_000 {
        deep = deep.translate(vec3(0.0, 0.0, 0.0));
    }
    let s = scene(deep);
    assert_eq!(errors(&s), ["scene: the shape tree has more than 10000 nodes"]);
    let mut deep = sphere(1.0);
    for _ in 0..100 {
        deep = deep.translate(vec3(0.0, 0.0, 0.0));
    }
    assert_eq!(errors(&scene(deep)), ["scene: the shape tree nests more than 64 levels deep"]);

    let s = scene(union_all((0..10_001).map(|_| sphere(1.0))));
    assert_eq!(errors(&s), ["scene: the shape tree has more than 10000 nodes"]);

    let mut e = time();
    for _ in 0..70 {
        e = -e;
    }
    let s = scene(sphere(1.0).translate(vec3(e, 0.0, 0.0)));
    assert_eq!(errors(&s), ["scene: an expression nests more than 64 levels deep"]);

    let mut s = scene(sphere(1.0));
    for _ in 0..17 {
        s = s.light(directional(vec3(0.0, 1.0, 0.0), rgb(1.0, 1.0, 1.0)));
    }
    assert_eq!(errors(&s), ["scene: a scene may have at most 16 lights, found 17"]);
}

/// The parser applies the same rules, with the same messages, to the same scenes written as text.
#[test]
fn the_parser_reports_what_validation_reports() {
    let broken = [
        scene(union(sphere(1.0), sphere(-1.0).translate(vec3(1.0, 0.0, 0.0)))),
        scene(mandelbulb(1.5)),
        scene(mandelbulb(8).iterations(0)),
        scene(menger(9)),
        scene(mandelbox(1.0)),
        scene(mandelbox(2.0).min_radius(1.5)),
        scene(menger(3).bailout(2.0)),
        scene(round_box(vec3(1.0, 0.5, 1.0), 0.6)),
        scene(cone(1.0, 0.0, 0.0)),
        scene(smooth_union(sphere(1.0), sphere(2.0), -0.1)),
        scene(sphere(1.0).repeat_limited(vec3(2.0, 2.0, 2.0), [1, 1, 1001])),
        scene(sphere(1.0).elongate(vec3(0.0, -1.0, 0.0))),
        scene(sphere(1.0).material(rgb(1.0, 1.0, 1.0).shininess(-2.0))),
        scene(sphere(1.0)).light(point_light(vec3(0.0, 1.0, 0.0), rgb(1.0, 1.0, 1.0)).intensity(-1.0)),
        scene(sphere(1.0)).camera(camera_path([key(1.0, DVec3::X, DVec3::ZERO), key(0.5, DVec3::Y, DVec3::ZERO)])),
        scene(sphere(1.0)).fog(rgb(0.5, 0.5, 0.5), -0.1),
        scene(sphere(1.0)).ambient_occlusion(10.5),
        scene(sphere(1.0).translate(vec3(param("b", 5.0, 0.0..1.0), 0.0, 0.0))),
    ];
    for s in broken {
        let from_validate: Vec<String> = validate(&s).unwrap_err().into_iter().map(|e| e.message).collect();
        let src = to_source(&s);
        let from_parser = parse_str(&src).expect_err(&src).message;
        assert_eq!(from_validate, [from_parser], "{src}");
    }
}
