//! Backend selection: explicit choices, and `auto` falling back along wgpu → OpenCL → CPU when a backend cannot draw
//! a job.

use fractal_dsl::builder::{scene, sphere};
use fractal_dsl::eval::{Env, Evaluator, Sample};
use fractal_dsl::number::math::{length, v3, V3};
use fractal_render::{select, Backend, BackendChoice, Frame, KernelSources, RenderJob, RendererOptions};

struct UnitSphere;

impl Evaluator<f32> for UnitSphere {
    fn distance(&self, p: V3<f32>, _: &Env<f32>) -> f32 {
        length(p) - 1.0
    }
    fn sample(&self, p: V3<f32>, env: &Env<f32>) -> Sample<f32> {
        let d = self.distance(p, env);
        Sample { distance: d, albedo: v3(1.0, 1.0, 1.0), ambient: 0.2, diffuse: 0.8, specular: 0.0, shininess: 1.0 }
    }
}

#[test]
fn cpu_can_be_chosen() {
    let r = select(BackendChoice::Only(Backend::Cpu), &RendererOptions::default()).expect("CPU always opens");
    assert_eq!(r.device().backend, Backend::Cpu);
}

#[test]
fn auto_falls_back_to_the_backend_the_job_can_run_on() {
    let s = scene(sphere(1.0));
    let frame = Frame::default_view(&s, 0.0, 24, 24).expect("frame");
    let mut r = select(BackendChoice::Auto, &RendererOptions::default()).expect("auto opens something");
    let opened = r.take_notes();
    assert!(opened.iter().any(|n| n.starts_with("using ")), "{opened:?}");

    // A WGSL kernel no driver accepts and no OpenCL kernel: only the CPU can draw this job.
    let kernels = KernelSources::default().with_wgsl("this is not WGSL").with_cpu(&UnitSphere, &s);
    let image = r.render(&RenderJob::new(kernels, &frame)).expect("auto reaches the CPU");
    assert!(!image.is_uniform());
    assert_eq!(r.device().backend, Backend::Cpu);
    let notes = r.take_notes().join("\n");
    assert!(notes.contains("using cpu"), "{notes}");
    if crate::common::backends_required() {
        assert!(notes.contains("wgpu failed, falling back"), "{notes}");
    }
}

#[test]
fn auto_reports_every_failure_when_nothing_can_draw() {
    let s = scene(sphere(1.0));
    let frame = Frame::default_view(&s, 0.0, 8, 8).expect("frame");
    let mut r = select(BackendChoice::Auto, &RendererOptions::default()).expect("auto opens something");
    let err = r.render(&RenderJob::new(KernelSources::default(), &frame)).unwrap_err();
    let message = err.to_string();
    assert!(message.contains("no backend could render"), "{message}");
    assert!(message.contains("cpu: the job has no CPU evaluator"), "{message}");
}
