//! The scene compiler's kernels on every backend: small scenes built with the builder API, compiled by
//! `fractal_dsl::compile`, drawn by wgpu, OpenCL and the CPU renderer (over the interpreter) from the same frame
//! uniforms, and their probe kernels evaluated at points. This is the plumbing's end-to-end check; the full
//! agreement suite over the built-in scenes lives with the facade.

use fractal_dsl::back::{opencl, wgsl, Entry};
use fractal_dsl::builder::*;
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::{Env, Evaluator};
use fractal_dsl::number::math::v3;
use fractal_dsl::Scene;
use fractal_render::{CpuRenderer, Frame, Image, KernelSources, ParamValues, RenderJob, Renderer, WgpuRenderer};

use crate::common::available;

/// Scenes that between them use time, a parameter, both light kinds, specular, shadows, occlusion, glow and fog.
fn scenes() -> Vec<(&'static str, Scene)> {
    vec![
        ("sphere", scene(sphere(1.0))),
        ("mandelbulb", scene(mandelbulb(8))),
        (
            "sphere over plane",
            scene(union(sphere(0.5).translate([0.0, 0.55, 0.0]), plane([0.0, 1.0, 0.0], 0.0)))
                .camera(camera([0.0, 3.0, -4.0], [0.0, 0.3, 0.0]))
                .light(directional([1.0, 2.0, 0.5], rgb(1.0, 1.0, 1.0)))
                .soft_shadows(8.0)
                .ambient_occlusion(1.0),
        ),
        (
            "animated blend",
            scene(
                smooth_union(
                    sphere(param("radius", 0.8, 0.1..2.0)),
                    box3([0.6, 0.6, 0.6]).translate(vec3(sin(time()), 0.0, 0.0)),
                    0.2,
                )
                .material(rgb(0.9, 0.3, 0.2).specular(0.5)),
            )
            .light(point_light([2.0, 3.0, -2.0], rgb(1.0, 1.0, 1.0)).intensity(12.0))
            .hard_shadows()
            .glow(rgb(0.1, 0.2, 0.4))
            .fog(rgb(0.5, 0.5, 0.6), 0.05),
        ),
    ]
}

/// The frame every backend draws: 64×64 at t = 0.7, with the parameter moved off its default.
fn frame(s: &Scene) -> Frame {
    let mut params = ParamValues::defaults(s);
    if params.get("radius").is_some() {
        params.set("radius", 0.9).expect("in range");
    }
    let pose = fractal_render::Pose::from_camera(&s.camera, 0.7, &|p| params.lookup(p)).expect("camera");
    Frame::new(s, &pose, 0.7, 64, 64, &params).expect("frame")
}

fn check_alike(name: &str, backend: &str, cpu: &Image, other: &Image) {
    let differing = crate::common::fraction_different(cpu, other, 3);
    assert!(
        differing < 0.01,
        "{name}: {:.2} % of {backend} pixels differ from the CPU's by more than 3 levels",
        differing * 100.0
    );
}

#[test]
fn compiled_scenes_render_alike_on_every_backend() {
    let mut gpu = available("wgpu", WgpuRenderer::new());
    #[cfg(feature = "opencl")]
    let mut cl = available("OpenCL", fractal_render::OpenClRenderer::new(false));
    for (name, s) in scenes() {
        let kernels = fractal_dsl::compile(&s).unwrap();
        let interpreter = Interpreter::new(&s).unwrap();
        let frame = frame(&s);
        let cpu = CpuRenderer::new()
            .render(&RenderJob::new(KernelSources::default().with_cpu(&interpreter, &s), &frame))
            .expect("CPU render");
        assert!(!cpu.is_uniform(), "{name}: the CPU image is one colour");
        if let Some(gpu) = gpu.as_mut() {
            let image = gpu.render(&RenderJob::new(KernelSources::compiled(&kernels), &frame));
            check_alike(name, "wgpu", &cpu, &image.unwrap_or_else(|e| panic!("{name}: {e}")));
        }
        #[cfg(feature = "opencl")]
        if let Some(cl) = cl.as_mut() {
            let image = cl.render(&RenderJob::new(KernelSources::compiled(&kernels), &frame));
            check_alike(name, "OpenCL", &cpu, &image.unwrap_or_else(|e| panic!("{name}: {e}")));
        }
    }
}

/// Points on a lattice around the origin, some inside, some outside every scene above.
fn lattice() -> Vec<[f32; 4]> {
    let steps = [-1.3f32, -0.7, -0.2, 0.0, 0.35, 0.9, 1.4];
    let mut out = Vec::new();
    for x in steps {
        for y in steps {
            for z in steps {
                out.push([x, y, z, 0.0]);
            }
        }
    }
    out
}

/// Probe results against the interpreter in f32: distance within 1e-4 (relative beyond 1), material within 1e-4.
fn check_probe(name: &str, backend: &str, s: &Scene, frame: &Frame, points: &[[f32; 4]], got: &[[f32; 8]]) {
    let interpreter = Interpreter::new(s).unwrap();
    let params = frame.params();
    let env = Env::new(frame.time(), &params);
    assert_eq!(got.len(), points.len());
    for (p, g) in points.iter().zip(got) {
        let at = v3(p[0], p[1], p[2]);
        let want = Evaluator::<f32>::sample(&interpreter, at, &env);
        let d = Evaluator::<f32>::distance(&interpreter, at, &env);
        let expected =
            [d, want.ambient, want.diffuse, want.specular, want.albedo.x, want.albedo.y, want.albedo.z, want.shininess];
        for (i, (a, b)) in g.iter().zip(expected).enumerate() {
            let tolerance = 1e-4 * b.abs().max(1.0);
            assert!(
                (a - b).abs() <= tolerance,
                "{name} on {backend}, point {p:?}, field {i}: got {a}, interpreter {b}"
            );
        }
    }
}

#[test]
fn compiled_probes_match_the_interpreter() {
    let mut gpu = available("wgpu", WgpuRenderer::new());
    let points = lattice();
    for (name, s) in scenes() {
        let program = fractal_dsl::lower::lower(&s);
        let frame = frame(&s);
        if let Some(gpu) = gpu.as_mut() {
            let kernel = wgsl::write(&program, Entry::Probe);
            let got =
                gpu.probe((kernel.as_str(), fractal_dsl::back::Scalar::F32), &frame, &points).expect("wgpu probe");
            check_probe(name, "wgpu", &s, &frame, &points, &got);
        }
        #[cfg(feature = "opencl")]
        if let Some(got) = available(
            "OpenCL",
            fractal_render::probe_opencl(&opencl::write(&program, Entry::Probe), &frame, &points, true),
        ) {
            check_probe(name, "OpenCL", &s, &frame, &points, &got);
        }
        #[cfg(not(feature = "opencl"))]
        let _ = opencl::write;
    }
}
