//! Milliseconds per frame of the CPU renderer on the benchmark Mandelbulb (`mandelbulb_bench`, the hand-written
//! baseline's scene and camera): eight pixels a ray packet (`render_packets`, what `fractal render --backend cpu`
//! runs) and a ray at a time (`render_scene`), on all cores, at the viewer's 480×270 and at 960×540.
//!
//! `cargo bench --bench renderer`; `fractal bench mandelbulb_bench --backend cpu|wgpu` times 1080p against lavapipe.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use fractal::render::backend::cpu::render_packets;
use fractal::render::{render_scene, Frame};
use std::hint::black_box;

fn renderer(c: &mut Criterion) {
    let compiled = fractal::scenes::ALL.iter().find(|(n, _)| *n == "mandelbulb_bench").expect("a built-in scene").1;
    let scene = compiled.scene();
    let native = compiled.native();
    let mut group = c.benchmark_group("cpu frame");
    group.sample_size(10);
    for (width, height) in [(480, 270), (960, 540)] {
        let frame = Frame::default_view(scene, 0.0, width, height).expect("a frame");
        let size = format!("{width}x{height}");
        group.bench_function(BenchmarkId::new("packets", &size), |b| {
            b.iter(|| black_box(render_packets(&native, scene, &frame).expect("a render")))
        });
        group.bench_function(BenchmarkId::new("a ray at a time", &size), |b| {
            b.iter(|| black_box(render_scene::<f32, _>(&native, scene, &frame).expect("a render")))
        });
    }
    group.finish();
}

criterion_group!(benches, renderer);
criterion_main!(benches);
