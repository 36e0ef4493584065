//! Hostile input through the public API: scenes made with the builder that break the language's rules, are too big
//! or too deep, or hold computed non-finite values. Every way in — `compile`, the interpreter, the viewer — refuses
//! them with the validator's message; nothing panics, overflows the stack (building, checking or dropping) or takes
//! more than linear time. The same cases through the `fractal` program are in `tests/cli.rs`.

use std::time::{Duration, Instant};

use fractal::dsl::eval::interp::Interpreter;
use fractal::dsl::validate::InvalidScene;
use fractal::dsl::{compile, Node, Scene};
use fractal::prelude::*;
use fractal::runtime::viewer::ViewerScene;

/// Every entry point's error for `s`; they must all refuse it with the same message.
#[track_caller]
fn refused(s: Scene) -> String {
    let by_compile = refusal(compile(&s), "compile");
    let by_interpreter = refusal(Interpreter::new(&s), "the interpreter");
    let by_viewer = refusal(ViewerScene::built("hostile", s), "the viewer");
    assert_eq!(by_compile, by_interpreter);
    assert_eq!(by_compile, by_viewer);
    by_compile.to_string()
}

#[track_caller]
fn refusal<T>(result: Result<T, InvalidScene>, by: &str) -> InvalidScene {
    match result {
        Ok(_) => panic!("{by} accepted the scene"),
        Err(e) => e,
    }
}

#[track_caller]
fn assert_refused(s: Scene, substance: &str) {
    let message = refused(s);
    assert!(message.contains(substance), "expected {substance:?} in: {message}");
}

#[test]
fn empty_combinations_are_refused_not_indexed() {
    assert_refused(scene(union_all([])), "union needs at least 1 shape");
    assert_refused(scene(intersect_all([])), "intersect needs at least 1 shape");
    assert_refused(scene(smooth_union_all([], 0.1)), "smooth_union needs at least 1 shape");
}

#[test]
fn out_of_range_fractal_settings_and_nan_sizes_are_refused() {
    assert_refused(scene(menger(100)), "menger");
    assert_refused(scene(mandelbulb(8.0).iterations(u32::MAX)), "iterations");
    assert_refused(scene(sphere(f32::NAN)), "sphere radius");
    assert_refused(scene(sphere(1.0).translate(vec3(f32::NAN, 0.0, 0.0))), "translate");
}

#[test]
fn a_tree_deeper_than_the_stack_is_refused_and_dropped() {
    // Built, checked and dropped on a test thread's small stack: nothing may recurse once per level.
    let mut deep = sphere(1.0);
    for _ in 0..1_000_000 {
        deep = deep.translate(vec3(0.0, 0.0, 1.0));
    }
    assert_refused(scene(deep), "more than 10000 nodes");

    let mut deep = sphere(1.0);
    for _ in 0..100 {
        deep = deep.translate(vec3(0.0, 0.0, 1.0));
    }
    assert_refused(scene(deep), "nests more than 64 levels deep");

    let mut e = time();
    for _ in 0..1_000_000 {
        e = e + 1.0;
    }
    assert_refused(scene(sphere(1.0).translate(vec3(e, 0.0, 0.0))), "an expression nests more than 64 levels deep");

    // A chain of materials has no operator between its levels.
    let mut painted: Node = sphere(1.0);
    for _ in 0..1_000_000 {
        painted = painted.material(rgb(1.0, 0.5, 0.0));
    }
    drop(painted);
}

/// Building a union one shape at a time, from either side, is linear (quadratic took 21 s for 20 000 shapes and never
/// finished 100 000). The time limit only catches a hang: the loop takes milliseconds.
#[test]
fn unions_built_in_a_loop_from_either_side_stay_linear() {
    let limit = Duration::from_secs(20);
    let start = Instant::now();
    let mut left = sphere(1.0);
    for i in 0..100_000 {
        left = union(left, sphere(1.0).translate(vec3(i as f32, 0.0, 0.0)));
    }
    let mut right = sphere(1.0);
    for i in 0..100_000 {
        right = union(sphere(1.0).translate(vec3(i as f32, 0.0, 0.0)), right);
    }
    assert!(start.elapsed() < limit, "building took {:?}", start.elapsed());
    assert_refused(scene(left), "more than 10000 nodes");
    assert_refused(scene(right), "more than 10000 nodes");

    // Within the cap, both sides flatten into one union, in source order.
    let mut right = sphere(3.0);
    for r in [2.0, 1.0] {
        right = union(sphere(r), right);
    }
    assert_eq!(right, union_all([sphere(1.0), sphere(2.0), sphere(3.0)]));
}

/// The error type carries every broken rule, not only the first.
#[test]
fn every_broken_rule_reaches_the_caller() {
    let s = scene(union(sphere(-1.0), box3(vec3(1.0, -2.0, 1.0))));
    let InvalidScene(errors) = refusal(compile(&s), "compile");
    assert_eq!(errors.len(), 2, "{errors:?}");
}

/// A number that goes bad only at run time — `sqrt(t - 5)` before t = 5, a `param` divided into 0 — is refused when the
/// frame is packed, which every backend does the same way, instead of drawing NaN geometry (nothing on one backend,
/// something on another). The same scene draws where the number is finite.
#[test]
fn numbers_that_go_bad_at_run_time_refuse_the_frame_on_every_backend() {
    use fractal::render::{Frame, FrameError, ParamValues, Pose};
    let s = scene(sphere(1.0).translate(vec3(sqrt(time() - 5.0), 0.0, 0.0)));
    let pose = Pose::look_at(glam::DVec3::new(0.0, 0.0, -4.0), glam::DVec3::ZERO, 50.0).unwrap();
    let params = ParamValues::defaults(&s);
    match Frame::new(&s, &pose, 0.0, 8, 8, &params) {
        Err(e @ FrameError::NonFiniteValue { .. }) => {
            assert_eq!(
                e.to_string(),
                "`sqrt(t - 5.0)` is NaN at time 0: the shape it sizes or places cannot be drawn then"
            )
        }
        other => panic!("expected a refused frame, got {other:?}"),
    }
    assert!(Frame::new(&s, &pose, 6.0, 8, 8, &params).is_ok());

    let s = scene(sphere(1.0 / param("r", 1.0, 0.0..2.0)));
    let mut zero = ParamValues::defaults(&s);
    zero.set("r", 0.0).unwrap();
    let e = Frame::new(&s, &pose, 0.0, 8, 8, &zero).unwrap_err();
    assert!(e.to_string().starts_with("`1.0 / param(\"r\", 1.0, 0.0..2.0)` is inf at time 0"), "{e}");
}
