//! Points per second of each CPU evaluator, one thread, on the expressions the SIMD issue compares with Fidget (a unit
//! sphere, a union of 16 spheres, a Menger sponge of 3 levels) and on built-in scenes: the native evaluator a point
//! at a time (scalar) and eight at a time (`distance_slice`, packets), and the interpreter — what runs a `.fractal`
//! file without rustc — a point at a time and in packets.
//!
//! `cargo bench --bench evaluator`; the points are 2^20 spread over [−1.5, 1.5]³, the same for every evaluator.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use fractal::dsl::eval::interp::Interpreter;
use fractal::dsl::eval::Env;
use fractal::dsl::number::math::V3;
use fractal::dsl::CompiledScene;
use fractal::prelude::*;
use std::hint::black_box;

#[path = "shared/expressions.rs"]
mod expressions;
use expressions::{points, sixteen_spheres, POINTS};

fn evaluators(c: &mut Criterion) {
    let [x, y, z] = points();
    let mut out = vec![0.0f32; POINTS];
    let leak = |s: CompiledScene| -> &'static CompiledScene { Box::leak(Box::new(s)) };
    let mut scenes: Vec<(&str, &CompiledScene)> = vec![
        ("sphere", leak(scene! { sphere(1.0) })),
        ("16 spheres", leak(sixteen_spheres())),
        ("menger 3", leak(scene! { menger(3) })),
    ];
    for name in ["mandelbulb_bench", "mandelbox", "sierpinski_tetrahedron", "mandelbulb"] {
        let compiled = fractal::scenes::ALL.iter().find(|(n, _)| *n == name).expect("a built-in scene").1;
        scenes.push((name, compiled));
    }
    let mut group = c.benchmark_group("points");
    group.throughput(Throughput::Elements(POINTS as u64)).sample_size(10);
    for &(name, compiled) in &scenes {
        let native = compiled.native();
        let params: &[f32] = compiled.default_params();
        let env = Env::new(0.0f32, params);
        group.bench_function(BenchmarkId::new("native scalar", name), |b| {
            b.iter(|| {
                for (i, d) in out.iter_mut().enumerate() {
                    *d = (native.distance_f32)(V3 { x: x[i], y: y[i], z: z[i] }, &env);
                }
                black_box(&out);
            })
        });
        group.bench_function(BenchmarkId::new("native packets", name), |b| {
            b.iter(|| {
                compiled.distance_slice(&x, &y, &z, &mut out);
                black_box(&out);
            })
        });
        let interpreter = Interpreter::new(compiled.scene()).expect("a valid scene");
        group.bench_function(BenchmarkId::new("interpreter scalar", name), |b| {
            b.iter(|| {
                for (i, d) in out.iter_mut().enumerate() {
                    *d = interpreter.distance_in(V3 { x: x[i], y: y[i], z: z[i] }, &env);
                }
                black_box(&out);
            })
        });
        group.bench_function(BenchmarkId::new("interpreter packets", name), |b| {
            b.iter(|| {
                interpreter.distance_slice(0.0, params, &x, &y, &z, &mut out);
                black_box(&out);
            })
        });
    }
    group.finish();
}

criterion_group!(benches, evaluators);
criterion_main!(benches);
