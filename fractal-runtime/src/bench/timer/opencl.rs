//! The OpenCL dispatcher (cargo feature `opencl`): times the generated kernel on the renderer's own render path
//! ([`fractal_render::OpenClRenderer::render_timed`]: kept buffers and kernels, the time from profiling events, with a
//! refine pass from the first pass's start to the refine's end), and the baseline on the same device and profiling
//! queue, built through the renderer's program cache with its options (`-cl-fast-relaxed-math` unless precise, as the
//! generated kernel).

use std::time::Instant;

use fractal_render::backend::opencl::{device_error, image_buffer, rejected, OpenClRenderer};
use fractal_render::device::DeviceInfo;
use fractal_render::error::RenderError;
use fractal_render::image::Image;
use fractal_render::renderer::Renderer;
use ocl::enums::ProfilingInfo;
use ocl::{Buffer, Event, Kernel};

use super::dispatch::{millis, KernelClock, Timed, Timer, Work};
use crate::bench::baseline::BASELINE_OPENCL;

pub(crate) struct OpenClTimer {
    /// Owns the device, context, profiling queue and program cache.
    renderer: OpenClRenderer,
    out: Option<(usize, Buffer<u32>)>,
}

impl OpenClTimer {
    pub fn new(precise: bool) -> Result<OpenClTimer, RenderError> {
        Ok(OpenClTimer { renderer: OpenClRenderer::new(precise)?, out: None })
    }

    fn out(&mut self, count: usize, width: u32, height: u32) -> Result<Buffer<u32>, RenderError> {
        if let Some((n, buffer)) = &self.out {
            if *n == count {
                return Ok(buffer.clone());
            }
        }
        self.out = None;
        let buffer = image_buffer(self.renderer.queue(), width, height)?;
        self.out = Some((count, buffer.clone()));
        Ok(buffer)
    }
}

fn nanos(event: &Event, which: ProfilingInfo) -> Result<u64, RenderError> {
    event.profiling_info(which).and_then(|r| r.time().map_err(ocl::Error::from)).map_err(device_error)
}

impl Timer for OpenClTimer {
    fn device(&self) -> DeviceInfo {
        Renderer::device(&self.renderer)
    }

    fn clock(&self) -> KernelClock {
        KernelClock::ProfilingEvents
    }

    fn computes_f64(&self) -> bool {
        self.renderer.has_fp64()
    }

    fn run(&mut self, work: &Work) -> Result<Timed, RenderError> {
        let (width, height) = match work {
            // The generated kernel is timed on the renderer's own path, the one every render takes.
            Work::Generated(job) => {
                let (image, kernel_ms, frame_ms) = self.renderer.render_timed(job)?;
                return Ok(Timed { image, kernel_ms, frame_ms });
            }
            Work::Baseline { width, height } => (*width, *height),
        };
        let count = width as usize * height as usize;
        let out = self.out(count, width, height)?;

        let start = Instant::now();
        let program = self.renderer.program((BASELINE_OPENCL, false))?;
        let mut builder = Kernel::builder();
        builder.program(&program).name("render").queue(self.renderer.queue().clone());
        builder.global_work_size((width, height)).arg(&out).arg(width as i32).arg(height as i32);
        let kernel = builder.build().map_err(rejected)?;
        let mut event = Event::empty();
        // Safety: `out` holds one u32 per pixel; the kernel writes only pixels inside (width, height).
        unsafe { kernel.cmd().enew(&mut event).enq() }.map_err(device_error)?;
        let mut pixels = vec![0u32; count];
        out.read(&mut pixels).enq().map_err(device_error)?;
        let frame_ms = millis(start.elapsed());
        let kernel_ns = nanos(&event, ProfilingInfo::End)?.saturating_sub(nanos(&event, ProfilingInfo::Start)?);
        Ok(Timed { image: Image { width, height, pixels }, kernel_ms: kernel_ns as f64 / 1e6, frame_ms })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::{mandelbulb, scene};
    use fractal_render::frame::Frame;
    use fractal_render::renderer::{KernelSources, RenderJob, Renderer};
    use fractal_render::OpenClRenderer;

    /// The bench must time what the renderer draws: the same kernel and frame give the same pixels.
    #[test]
    fn the_dispatcher_draws_what_the_renderer_draws() {
        let (mut timer, mut renderer) = match (OpenClTimer::new(false), OpenClRenderer::new(false)) {
            (Ok(t), Ok(r)) => (t, r),
            (Err(e), _) | (_, Err(e)) => {
                let required = fractal_render::device::backends_required();
                assert!(!required, "OpenCL is required but could not be opened: {e}");
                eprintln!("note: skipping, no OpenCL device: {e}");
                return;
            }
        };
        let s = scene(mandelbulb(8));
        let frame = Frame::default_view(&s, 0.0, 24, 16).unwrap();
        // With a second pass too: the time spans both passes and the image is the refined one.
        for kernels in [fractal_dsl::compile(&s).unwrap(), fractal_dsl::compile(&s.clone().samples(8)).unwrap()] {
            let job = RenderJob::new(KernelSources::compiled(&kernels), &frame);
            let timed = timer.run(&Work::Generated(job)).unwrap();
            assert_eq!(timed.image, renderer.render(&job).unwrap());
        }
        let kernels = fractal_dsl::compile(&s).unwrap();
        let job = RenderJob::new(KernelSources::compiled(&kernels), &frame);
        let timed = timer.run(&Work::Generated(job)).unwrap();
        assert!(timed.kernel_ms > 0.0 && timed.kernel_ms <= timed.frame_ms, "{} {}", timed.kernel_ms, timed.frame_ms);
        let baseline = timer.run(&Work::Baseline { width: 24, height: 16 }).unwrap();
        assert!(!baseline.image.is_uniform());
    }
}
