//! What a `CompiledScene` holds is what its source says, built at compile time: the IR the macro's expansion
//! constructs equals the IR its canonical source reads back as, its default parameter block is the scene's parameter
//! defaults in uniform order, `distance()` is the native evaluator called with that block at time 0, and the bulk
//! `distance_slice` / `sample_slice` (packets of eight) give what `distance()` gives point by point.

use fractal::dsl::eval::Env;
use fractal::dsl::parse::parse_str;
use fractal::prelude::*;
use fractal::scenes;

const POINTS: [[f32; 3]; 6] =
    [[0.0, 0.0, 0.0], [1.5, 0.0, 0.0], [0.3, -0.7, 0.2], [-1.2, 0.4, 2.5], [2.0, 2.0, -2.0], [0.05, 1.1, -0.6]];

/// Checks the IR, the defaults and both `distance` twins of `compiled` against what its source text says.
fn check(name: &str, compiled: &CompiledScene) {
    let parsed = parse_str(compiled.source()).unwrap_or_else(|e| panic!("{name}: canonical source reads back: {e}"));
    assert_eq!(compiled.scene(), &parsed, "{name}: the constructed IR differs from the parsed source");

    let defaults_f64: Vec<f64> = parsed.params().iter().map(|p| p.default).collect();
    let defaults_f32: Vec<f32> = defaults_f64.iter().map(|&d| d as f32).collect();
    assert_eq!(compiled.default_params::<f64>(), defaults_f64.as_slice(), "{name}: f64 defaults");
    assert_eq!(compiled.default_params::<f32>(), defaults_f32.as_slice(), "{name}: f32 defaults");

    let native = compiled.native();
    let env_f32 = Env::new(0.0f32, &defaults_f32);
    let env_f64 = Env::new(0.0f64, &defaults_f64);
    for p in POINTS {
        let (single, double) = (Vec3::from_array(p), DVec3::from_array(p.map(f64::from)));
        let expected = (native.distance_f32)(single.into(), &env_f32);
        assert_eq!(compiled.distance(single).to_bits(), expected.to_bits(), "{name} at {p:?}");
        let expected = (native.distance_f64)(double.into(), &env_f64);
        assert_eq!(compiled.distance_f64(double).to_bits(), expected.to_bits(), "{name} at {p:?} (f64)");
    }
}

#[test]
fn every_built_in_scene_holds_its_source_ir_and_defaults() {
    for (name, compiled) in scenes::ALL {
        check(name, compiled);
    }
}

#[test]
fn distance_reads_the_build_time_parameter_defaults() {
    let compiled = scene! {
        union(
            sphere(param("radius", 0.75, 0.5..2.0)).translate(vec3(param("x", -0.3, -1.0..1.0), 0.0, 0.0)),
            box3(vec3(0.25, 0.25, 0.25)).translate(vec3(1.5, 0.0, 0.0)),
        )
    };
    check("params", &compiled);
    // `Scene::params` order: a transform's own values come before its child's.
    assert_eq!(compiled.default_params::<f32>(), &[-0.3f32, 0.75f32][..]);
    assert_eq!(compiled.default_params::<f64>(), &[-0.3, 0.75][..]);
    // At the sphere's centre, (-0.3, 0, 0): one radius inside.
    assert!((compiled.distance(Vec3::new(-0.3, 0.0, 0.0)) + 0.75).abs() < 1e-6);
    assert!((compiled.distance_f64(DVec3::new(-0.3, 0.0, 0.0)) + 0.75).abs() < 1e-12);
    // Other values through an environment of the caller's own.
    let moved = (compiled.native().distance_f32)(Vec3::new(-0.3, 0.0, 0.0).into(), &Env::new(0.0, &[0.0, 1.5]));
    assert!((moved - (0.3 - 1.5)).abs() < 1e-6, "{moved}");
}

#[test]
fn every_kind_of_ir_value_is_constructed_exactly() {
    let compiled = scene! {
        scene(union(
            smooth_union(sphere(0.5 + 0.25 * sin(t)), box3(vec3(0.4, 0.3, 0.2)).rotate_x(0.3), 0.1),
            smooth_intersect(round_box(vec3(0.5, 0.5, 0.5), 0.05), torus(0.6, 0.2).rotate_y(-0.4), 0.05)
                .translate(vec3(2.0, 0.0, 0.0)),
            smooth_subtract(capsule(vec3(0.0, -0.5, 0.0), vec3(0.0, 0.5, 0.0), 0.2), cylinder(0.1, 1.0), 0.05)
                .rotate_z(-(cos(t) / 3.0)),
            intersect(cone(0.5, 0.4, 0.1), octahedron(0.6)).translate(vec3(-2.0, 0.0, 0.0)),
            subtract(ellipsoid(vec3(0.5, 0.3, 0.4)), plane(vec3(0.0, 1.0, 1.0), -0.1)).rotate(vec3(1.0, 1.0, 0.0), 0.7),
            sphere(0.2).repeat(vec3(3.0, 0.0, 3.0)).translate(vec3(0.0, -3.0, 0.0)),
            sphere(clamp(abs(0.1 - t), 0.05, 0.2))
                .repeat_limited(vec3(0.5, 0.5, 0.0), vec3(2, 1, 0))
                .twist(0.5)
                .bend(0.1)
                .round(0.01)
                .onion(0.02)
                .elongate(vec3(0.1, 0.0, 0.0))
                .scale(param("size", 1.5, 0.5..3.0))
                .material(phong(rgb(0.2, 0.8, 0.3), 0.1, 0.8, 0.3, 24.0)),
            mandelbulb(8)
                .iterations(6)
                .bailout(4.0)
                .material(orbit_trap(rgb(1.0, 0.5, 0.2), rgb(0.1, 0.2, 0.9)).specular(0.5).shininess(16.0))
                .translate(vec3(0.0, 3.0, 0.0)),
            menger(3).scale(0.5).translate(vec3(3.0, 3.0, 0.0)),
            sierpinski_tetrahedron(5).translate(vec3(-3.0, 3.0, 0.0)),
            julia(vec4(-0.2, 0.6, 0.2, 0.0)).translate(vec3(0.0, 6.0, 0.0)),
            mandelbox(-1.5).min_radius(0.4).fold_limit(1.1).scale(0.2).translate(vec3(0.0, -6.0, 0.0)),
            sphere(max(0.1, min(sqrt(0.09), pow(0.5, 2.0))) * mix(1.0, 2.0, 0.5)).material(rgb(0.9, 0.9, 0.9).ambient(0.2).diffuse(0.7)),
        ))
        .light(directional(vec3(0.6, 0.8, -0.4), rgb(1.0, 0.9, 0.8)).intensity(1.2))
        .light(point_light(vec3(0.0, 4.0, 0.0), rgb(0.5, 0.5, 1.0)).intensity(param("lamp", 2.0, 0.0..5.0)))
        .camera(
            camera_path(
                key(0.0, vec3(0.0, 1.0, -5.0), vec3(0.0, 0.0, 0.0)),
                key(2.0, vec3(5.0, 1.0, 0.0), vec3(0.0, 0.0, 0.0)),
            )
            .linear()
            .looped()
            .fov(60.0)
        )
        .max_steps(200)
        .max_distance(50.0)
        .pixel_epsilon(1.5)
        .normal_pixel_epsilon(0.75)
        .soft_shadows(8.0)
        .ambient_occlusion(0.5)
        .glow(rgb(0.1, 0.2, 0.3))
        .fog(rgb(0.5, 0.5, 0.5), 0.05)
        .background(rgb(0.0, 0.0, 0.0))
        .gamma(2.2)
    };
    check("every kind", &compiled);
    // Geometry's parameters first, then the lights'.
    assert_eq!(compiled.default_params::<f64>(), &[1.5, 2.0][..]);
}

/// The bulk API: `distance_slice` (packets of eight, the last one padded) gives what `distance` gives point by point
/// on every built-in scene, for lengths that are and are not multiples of eight; the f64 slice is the f64 evaluator's;
/// `sample_slice` carries the same distances.
#[test]
fn distance_slices_match_point_by_point_evaluation() {
    for (name, scene) in fractal::scenes::ALL {
        for n in [1usize, 7, 8, 9, 61] {
            let point = |i: usize| [0.37 * i as f32 - 1.1, 0.21 * (i % 5) as f32 - 0.4, 0.5 - 0.13 * i as f32];
            let [x, y, z]: [Vec<f32>; 3] = std::array::from_fn(|axis| (0..n).map(|i| point(i)[axis]).collect());
            let mut out = vec![f32::NAN; n];
            scene.distance_slice(&x, &y, &z, &mut out);
            let mut samples = vec![
                fractal::dsl::eval::Sample {
                    distance: 0.0f32,
                    albedo: fractal::dsl::number::math::v3(0.0, 0.0, 0.0),
                    ambient: 0.0,
                    diffuse: 0.0,
                    specular: 0.0,
                    shininess: 0.0,
                };
                n
            ];
            scene.sample_slice(&x, &y, &z, &mut samples);
            let wide = |v: &Vec<f32>| v.iter().map(|&c| f64::from(c)).collect::<Vec<f64>>();
            let mut out64 = vec![f64::NAN; n];
            scene.distance_slice_f64(&wide(&x), &wide(&y), &wide(&z), &mut out64);
            for i in 0..n {
                let p = Vec3::new(x[i], y[i], z[i]);
                let scalar = scene.distance(p);
                // The same arithmetic lane for lane; LLVM may still fold a libm call with constant arguments in
                // one instance and not the other, so a last-bit difference is allowed.
                let tolerance = 4.0 * f32::EPSILON * scalar.abs().max(p.length()).max(1.0);
                assert!(
                    (out[i] - scalar).abs() <= tolerance,
                    "{name}, {n} points: point {i} {p}: {} vs {scalar}",
                    out[i]
                );
                assert_eq!(samples[i].distance.to_bits(), out[i].to_bits(), "{name}: sample_slice's distance");
                assert_eq!(out64[i], scene.distance_f64(p.as_dvec3()), "{name}: the f64 slice");
            }
        }
    }
}

#[test]
#[should_panic(expected = "slices of unequal length")]
fn distance_slice_refuses_slices_of_unequal_length() {
    let (_, scene) = fractal::scenes::ALL[0];
    scene.distance_slice(&[0.0; 3], &[0.0; 3], &[0.0; 2], &mut [0.0; 3]);
}

/// A built-in scene is shaded by its gradient exactly where its interpreter is (an escape-time formula), and there
/// the native evaluator's normal — traced from the same walk in dual numbers — is the interpreter's in f64 and f32
/// (to a few ulps of the orbit's rounding: the native code is the traced one, folded), and its packets' lane for lane.
#[test]
fn native_normals_are_the_interpreters() {
    use fractal::dsl::eval::interp::Interpreter;
    use fractal::dsl::eval::{Evaluator, PacketEvaluator};
    use fractal::dsl::number::lanes::F32x8;
    use fractal::dsl::number::math::v3;
    // Divided by the lengths: an f32 unit vector is 10⁻⁷ off unit length, which acos near 1 reads as 0.03°.
    let angle = |a: [f64; 3], b: [f64; 3]| {
        let dot: f64 = a.iter().zip(&b).map(|(x, y)| x * y).sum();
        let len = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        (dot / (len(a) * len(b))).clamp(-1.0, 1.0).acos().to_degrees()
    };
    let mut shaded = 0;
    for (name, compiled) in scenes::ALL {
        let interp = Interpreter::new(compiled.scene()).unwrap();
        let native = compiled.native();
        let defaults: Vec<f64> = compiled.scene().params().iter().map(|p| p.default).collect();
        let defaults_f32: Vec<f32> = defaults.iter().map(|&d| d as f32).collect();
        let (env, env_f32) = (Env::new(0.0f64, &defaults), Env::new(0.0f32, &defaults_f32));
        let origin = v3(0.3, -0.2, 0.1);
        let by_interp = Evaluator::<f64>::normal(&interp, origin, &env);
        assert_eq!(by_interp.is_some(), native.normal.is_some(), "{name}: shaded by its gradient on one only");
        let Some(fns) = native.normal else { continue };
        shaded += 1;
        for p in POINTS {
            let q = v3(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
            let (a, b) = (Evaluator::<f64>::normal(&interp, q, &env).unwrap(), (fns.f64)(q, &env));
            assert!(angle([a.x, a.y, a.z], [b.x, b.y, b.z]) < 1e-4, "{name} at {p:?}: {a:?} against {b:?}");
            let single = v3(p[0], p[1], p[2]);
            let (a, b) = (Evaluator::<f32>::normal(&interp, single, &env_f32).unwrap(), (fns.f32)(single, &env_f32));
            let wide = |v: fractal::dsl::number::math::V3<f32>| [v.x, v.y, v.z].map(f64::from);
            assert!(angle(wide(a), wide(b)) < 0.01, "{name} at {p:?} (f32): {a:?} against {b:?}");
            let lanes = v3(F32x8::splat(p[0]), F32x8::splat(p[1]), F32x8::splat(p[2]));
            let env_x8 = Env::new(F32x8::splat(0.0), &[]);
            let params_x8: Vec<F32x8> = defaults_f32.iter().map(|&d| F32x8::splat(d)).collect();
            let env_x8 = Env { params: &params_x8, ..env_x8 };
            let n = (fns.x8)(lanes, &env_x8);
            assert_eq!([n.x.0[5], n.y.0[5], n.z.0[5]], [b.x, b.y, b.z], "{name} at {p:?} (packets)");
            let _ = PacketEvaluator::normal_x8(&native, lanes, &env_x8).expect("the packet instance has it too");
        }
    }
    assert!(shaded >= 10, "{shaded} built-in scenes shaded by their gradient");
}
