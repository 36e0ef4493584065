//! The OpenCL renderer and probe runner on the first OpenCL platform (pocl without a GPU), with kernels written
//! without the compiler ([`crate::common::mandelbulb_fixture`], the sphere probe in `tests/kernels`).

use fractal_render::{
    probe_opencl, Backend, KernelSources, OpenClRenderer, RenderError, RenderJob, Renderer, WgpuRenderer,
};

use crate::common::*;

fn renderer(precise: bool) -> Option<OpenClRenderer> {
    available("OpenCL", OpenClRenderer::new(precise))
}

#[test]
fn renders_the_mandelbulb_fixture() {
    let Some(mut r) = renderer(false) else { return };
    let info = r.device();
    assert_eq!(info.backend, Backend::OpenCl);
    assert!(!info.name.is_empty(), "{info}");
    eprintln!("OpenCL device: {info}");
    assert_eq!(r.build_options(), "-cl-fast-relaxed-math");

    let source = mandelbulb_fixture("cl");
    let frame = mandelbulb_frame(64, 64);
    let image = r.render(&RenderJob::new(KernelSources::default().with_opencl(&source), &frame)).expect("render");
    assert_eq!((image.width, image.height, image.pixels.len()), (64, 64, 64 * 64));
    assert!(!image.is_uniform(), "the image is one colour");
    let centre = image.rgba(32, 32).unwrap();
    let corner = image.rgba(0, 0).unwrap();
    assert!(centre[0] > corner[0] + 40, "centre {centre:?} vs corner {corner:?}");

    // Precise mode builds without fast math and draws (nearly) the same picture.
    r.set_precise(true);
    assert_eq!(r.build_options(), "");
    let precise = r.render(&RenderJob::new(KernelSources::default().with_opencl(&source), &frame)).expect("precise");
    assert!(fraction_different(&image, &precise, 2) < 0.01);

    // Odd sizes: the kernel's bounds check, global size = image size.
    let odd = mandelbulb_frame(37, 21);
    let image = r.render(&RenderJob::new(KernelSources::default().with_opencl(&source), &odd)).expect("render");
    assert_eq!(image.pixels.len(), 37 * 21);
}

#[test]
fn build_errors_carry_the_build_log() {
    let Some(mut r) = renderer(false) else { return };
    let frame = mandelbulb_frame(16, 16);
    let broken = mandelbulb_fixture("cl").replace("float3 ro = frame->camera_position.xyz;", "float3 ro = nope;");
    match r.render(&RenderJob::new(KernelSources::default().with_opencl(&broken), &frame)) {
        Err(RenderError::KernelRejected { backend: Backend::OpenCl, log }) => {
            assert!(log.contains("nope"), "build log does not name the error: {log}");
            assert!(!log.contains("####"), "banner left in the log: {log}");
            eprintln!("OpenCL build log:\n{log}");
        }
        other => panic!("expected a rejected kernel, got {other:?}"),
    }
    let err = r.render(&RenderJob::new(KernelSources::default().with_wgsl("fn render() {}"), &frame)).unwrap_err();
    assert!(matches!(err, RenderError::MissingKernel { backend: Backend::OpenCl, .. }), "{err}");
}

#[test]
fn probes_return_the_sphere_distance() {
    let source = fixture("sphere_probe.cl");
    let points = probe_points();
    for (radius, precise) in [(1.0, false), (0.75, true)] {
        let Some(samples) = available("OpenCL", probe_opencl(&source, &sphere_probe_frame(radius), &points, precise))
        else {
            return;
        };
        check_sphere_probe(&samples, &points, radius);
    }
}

/// Whether a pixel of the Mandelbulb fixture shows the bulb: it differs from that row's background gradient.
fn fixture_hit(image: &fractal_render::Image, x: u32, y: u32) -> bool {
    let v = -(2.0 * (y as f32 + 0.5) - image.height as f32) / image.height as f32;
    let background = [0.08f32, 0.09, 0.12].map(|c| ((c + 0.08 * v).clamp(0.0, 1.0).sqrt() * 255.0 + 0.5) as u8);
    let got = image.rgba(x, y).unwrap();
    got.iter().zip(background).any(|(g, b)| g.abs_diff(b) > 2)
}

#[test]
fn opencl_and_wgpu_draw_the_same_fixture() {
    let (Some(mut cl), Some(mut gpu)) = (renderer(true), available("wgpu", WgpuRenderer::new())) else { return };
    let frame = mandelbulb_frame(96, 96);
    let (cl_src, wgsl_src) = (mandelbulb_fixture("cl"), mandelbulb_fixture("wgsl"));
    let a = cl.render(&RenderJob::new(KernelSources::default().with_opencl(&cl_src), &frame)).expect("OpenCL");
    let b = gpu.render(&RenderJob::new(KernelSources::default().with_wgsl(&wgsl_src), &frame)).expect("wgpu");
    // The same pose from the same uniforms: the hit masks agree except where the two drivers' pow/acos/atan2 round
    // differently on the fractal's finest detail, and colours agree on average (the fixture's step-count occlusion
    // makes every extra march step a visible shade, so exact equality is not expected; ~3 levels measured).
    let (mut agree, mut hits, mut colour_error) = (0, 0, 0u64);
    for y in 0..96 {
        for x in 0..96 {
            let (ha, hb) = (fixture_hit(&a, x, y), fixture_hit(&b, x, y));
            agree += (ha == hb) as usize;
            if ha && hb {
                hits += 1;
                let (pa, pb) = (a.rgba(x, y).unwrap(), b.rgba(x, y).unwrap());
                colour_error += pa.iter().zip(pb).map(|(p, q)| p.abs_diff(q) as u64).sum::<u64>();
            }
        }
    }
    let agreement = agree as f64 / (96.0 * 96.0);
    assert!(agreement >= 0.99, "hit masks agree on {:.2} % of pixels", agreement * 100.0);
    assert!(hits > 96 * 96 / 10, "only {hits} hit pixels");
    let mean_error = colour_error as f64 / (3.0 * hits as f64);
    assert!(mean_error < 5.0, "mean colour difference {mean_error:.2} levels over hit pixels");
}
