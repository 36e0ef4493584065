//! Timing of the wgpu renderer on the Mandelbulb fixture kernel at 1920×1080 (ignored by default; run with
//! `cargo test -p fractal-runtime --test wgpu_timing -- --ignored --nocapture`). The fixture is the hand-written
//! baseline's algorithm reading the frame uniform, so its time compares with the baseline's on the same device.

mod common;

use std::time::Instant;

use common::{available, fixture, mandelbulb_frame};
use fractal_runtime::{KernelSources, RenderJob, Renderer, WgpuRenderer};

#[test]
#[ignore = "a measurement, not a check: run it on purpose"]
fn mandelbulb_fixture_at_1080p() {
    let Some(mut r) = available("wgpu", WgpuRenderer::new()) else { return };
    let source = fixture("mandelbulb_render.wgsl");
    let frame = mandelbulb_frame(1920, 1080);
    let job = RenderJob::new(KernelSources::default().with_wgsl(&source), &frame);
    // The first render compiles the pipeline and allocates the buffers.
    let first = Instant::now();
    let image = r.render(&job).expect("render");
    let first = first.elapsed();
    assert!(!image.is_uniform());
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let start = Instant::now();
            r.render(&job).expect("render");
            start.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    times.sort_by(f64::total_cmp);
    eprintln!(
        "{}: first frame {:.0} ms; then min {:.0} ms, median {:.0} ms, max {:.0} ms (wall time, including read-back)",
        r.device(),
        first.as_secs_f64() * 1e3,
        times[0],
        times[2],
        times[4]
    );
}
