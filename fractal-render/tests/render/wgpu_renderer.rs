//! The wgpu renderer and WGSL probe runner on whatever adapter wgpu finds (lavapipe without a GPU), with kernels
//! written without the compiler ([`crate::common::mandelbulb_fixture`], the sphere probe in `tests/kernels`).

use fractal_render::{probe_wgsl, Backend, KernelSources, RenderError, RenderJob, Renderer, WgpuRenderer};

use crate::common::*;

fn renderer() -> Option<WgpuRenderer> {
    available("wgpu", WgpuRenderer::new())
}

#[test]
fn renders_the_mandelbulb_fixture() {
    let Some(mut r) = renderer() else { return };
    let info = r.device();
    assert_eq!(info.backend, Backend::Wgpu);
    assert!(!info.name.is_empty(), "{info}");
    eprintln!("wgpu device: {info}");

    let source = mandelbulb_fixture("wgsl");
    let frame = mandelbulb_frame(64, 64);
    let image = r.render(&RenderJob::new(KernelSources::default().with_wgsl(&source), &frame)).expect("render");
    assert_eq!((image.width, image.height, image.pixels.len()), (64, 64, 64 * 64));
    assert!(!image.is_uniform(), "the image is one colour");
    // The bulb fills the middle; the corners are background (blue-grey, darker than any lit surface).
    let centre = image.rgba(32, 32).unwrap();
    let corner = image.rgba(0, 0).unwrap();
    assert!(centre[0] > corner[0] + 40, "centre {centre:?} vs corner {corner:?}");
    assert!(image.pixels.iter().all(|p| p >> 24 == 255), "alpha must be opaque");

    // Same job again: the cached pipeline and reused buffers give the same image.
    let again = r.render(&RenderJob::new(KernelSources::default().with_wgsl(&source), &frame)).expect("render");
    assert_eq!(again, image);
}

#[test]
fn sizes_that_are_not_multiples_of_the_workgroup_render() {
    let Some(mut r) = renderer() else { return };
    let source = mandelbulb_fixture("wgsl");
    let small = mandelbulb_frame(37, 21);
    let image = r.render(&RenderJob::new(KernelSources::default().with_wgsl(&source), &small)).expect("render");
    assert_eq!(image.pixels.len(), 37 * 21);
    assert!(!image.is_uniform());
    // Switching sizes back and forth reallocates the output buffers.
    let big = mandelbulb_frame(64, 48);
    let image = r.render(&RenderJob::new(KernelSources::default().with_wgsl(&source), &big)).expect("render");
    assert_eq!(image.pixels.len(), 64 * 48);
}

#[test]
fn broken_kernels_are_errors_with_locations() {
    let Some(mut r) = renderer() else { return };
    let frame = mandelbulb_frame(16, 16);
    let broken = mandelbulb_fixture("wgsl").replace("let ro = frame.camera_position.xyz;", "let ro = nope;");
    match r.render(&RenderJob::new(KernelSources::default().with_wgsl(&broken), &frame)) {
        Err(RenderError::KernelRejected { backend: Backend::Wgpu, log }) => {
            assert!(log.contains("nope"), "{log}");
            eprintln!("wgpu rejection:\n{log}");
            let line = broken.lines().position(|l| l.contains("= nope;")).unwrap() + 1;
            assert!(log.contains(&format!("{line}:")), "no line {line} in: {log}");
        }
        other => panic!("expected a rejected kernel, got {other:?}"),
    }
    // A module without the `render` entry point.
    let probe_only = fixture("sphere_probe.wgsl");
    let err = r.render(&RenderJob::new(KernelSources::default().with_wgsl(&probe_only), &frame)).unwrap_err();
    assert!(matches!(err, RenderError::KernelRejected { .. }), "{err}");
    // The renderer still works after rejecting kernels.
    let good = mandelbulb_fixture("wgsl");
    assert!(r.render(&RenderJob::new(KernelSources::default().with_wgsl(&good), &frame)).is_ok());
}

#[test]
fn jobs_without_wgsl_are_errors() {
    let Some(mut r) = renderer() else { return };
    let frame = mandelbulb_frame(8, 8);
    let err = r.render(&RenderJob::new(KernelSources::default().with_opencl("kernel"), &frame)).unwrap_err();
    assert!(matches!(err, RenderError::MissingKernel { backend: Backend::Wgpu, .. }), "{err}");
}

#[test]
fn probes_return_the_sphere_distance() {
    let Some(mut r) = renderer() else { return };
    let source = fixture("sphere_probe.wgsl");
    let points = probe_points();
    for radius in [1.0, 0.75] {
        let samples = probe_wgsl(&mut r, &source, &sphere_probe_frame(radius), &points).expect("probe");
        check_sphere_probe(&samples, &points, radius);
    }
    let f32_source = (source.as_str(), fractal_dsl::back::Scalar::F32);
    assert!(r.probe(f32_source, &sphere_probe_frame(1.0), &[]).expect("empty probe").is_empty());
}
