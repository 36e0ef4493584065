//! The wgpu dispatcher: a [`fractal_render::WgpuRenderer`] opened with timestamp queries when the adapter has them.
//! The generated kernel is drawn by the renderer's own frame path ([`WgpuRenderer::render_timed`]; with a refine pass
//! the kernel time spans both passes); the baseline (`main`, binding 1 = `{w, h}`, packed pixels to binding 0) goes
//! through the same path ([`WgpuRenderer::draw_with`]), its bind group layout from the shader.

use fractal_render::backend::wgpu::{capture, Drawn, WgpuRenderer, RENDER_WORKGROUP};
use fractal_render::device::{Backend, DeviceInfo};
use fractal_render::error::RenderError;
use fractal_render::renderer::Renderer;

use super::dispatch::{KernelClock, Timed, Timer, Work};
use crate::bench::baseline::BASELINE_WGSL;

pub(crate) struct WgpuTimer {
    /// Draws the generated kernels, and the baseline through the same frame path.
    renderer: WgpuRenderer,
    /// The baseline's pipeline, made on first use.
    baseline: Option<wgpu::ComputePipeline>,
}

impl WgpuTimer {
    pub fn new() -> Result<WgpuTimer, RenderError> {
        let renderer = WgpuRenderer::with_features(wgpu::Backends::all(), wgpu::Features::TIMESTAMP_QUERY)?;
        Ok(WgpuTimer { renderer, baseline: None })
    }

    fn baseline_pipeline(&mut self) -> Result<wgpu::ComputePipeline, RenderError> {
        if let Some(pipeline) = &self.baseline {
            return Ok(pipeline.clone());
        }
        let device = self.renderer.wgpu_device();
        let (pipeline, error) = capture(device, || {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("baseline"),
                source: wgpu::ShaderSource::Wgsl(BASELINE_WGSL.into()),
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("baseline"),
                layout: None,
                module: &module,
                entry_point: Some("main"),
                compilation_options: Default::default(),
                cache: None,
            })
        });
        if let Some(e) = error {
            return Err(RenderError::KernelRejected { backend: Backend::Wgpu, log: e.to_string() });
        }
        self.baseline = Some(pipeline.clone());
        Ok(pipeline)
    }
}

impl Timer for WgpuTimer {
    fn device(&self) -> DeviceInfo {
        Renderer::device(&self.renderer)
    }

    fn clock(&self) -> KernelClock {
        if self.renderer.wgpu_device().features().contains(wgpu::Features::TIMESTAMP_QUERY) {
            KernelClock::DeviceTimestamps
        } else {
            KernelClock::WallClock
        }
    }

    fn computes_f64(&self) -> bool {
        self.renderer.has_fp64()
    }

    fn run(&mut self, work: &Work) -> Result<Timed, RenderError> {
        let drawn = match work {
            Work::Generated(job) => self.renderer.render_timed(job)?,
            Work::Baseline { width, height } => {
                let pipeline = self.baseline_pipeline()?;
                // `{w: u32, h: u32}`, padded to the 16 bytes of a uniform block.
                let words = [*width, *height, 0, 0];
                let groups = (width.div_ceil(RENDER_WORKGROUP), height.div_ceil(RENDER_WORKGROUP));
                self.renderer.draw_with(
                    bytemuck::cast_slice(&words),
                    (*width, *height),
                    |device, encoder, uniform, out, timestamps| {
                        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                            label: Some("baseline"),
                            layout: &pipeline.get_bind_group_layout(0),
                            entries: &[
                                wgpu::BindGroupEntry { binding: 0, resource: out.as_entire_binding() },
                                wgpu::BindGroupEntry { binding: 1, resource: uniform.as_entire_binding() },
                            ],
                        });
                        let timestamp_writes = timestamps.map(|query_set| wgpu::ComputePassTimestampWrites {
                            query_set,
                            beginning_of_pass_write_index: Some(0),
                            end_of_pass_write_index: Some(1),
                        });
                        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                            label: Some("baseline"),
                            timestamp_writes,
                        });
                        pass.set_pipeline(&pipeline);
                        pass.set_bind_group(0, &bind_group, &[]);
                        pass.dispatch_workgroups(groups.0, groups.1, 1);
                    },
                )?
            }
        };
        let Drawn { image, kernel_ms, frame_ms } = drawn;
        // Without timestamps the kernel's time is the frame's: an upper bound.
        Ok(Timed { image, kernel_ms: kernel_ms.unwrap_or(frame_ms), frame_ms })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::{mandelbulb, scene, sphere, union, vec3, ShapeExt};
    use fractal_render::frame::Frame;
    use fractal_render::renderer::{KernelSources, RenderJob, Renderer};
    use fractal_render::WgpuRenderer;

    fn required() -> bool {
        fractal_render::device::backends_required()
    }

    /// The bench must time what the renderer draws: the same kernel and frame give the same pixels.
    #[test]
    fn the_dispatcher_draws_what_the_renderer_draws() {
        let (timer, renderer) = match (WgpuTimer::new(), WgpuRenderer::new()) {
            (Ok(t), Ok(r)) => (t, r),
            (Err(e), _) | (_, Err(e)) => {
                assert!(!required(), "wgpu is required but could not be opened: {e}");
                eprintln!("note: skipping, no wgpu adapter: {e}");
                return;
            }
        };
        let (mut timer, mut renderer) = (timer, renderer);
        let s = scene(union(mandelbulb(8), sphere(0.5).translate(vec3(1.2, 0.0, 0.0))));
        let frame = Frame::default_view(&s, 0.0, 40, 24).unwrap();
        // With a second pass too: the time spans both passes and the image is the refined one.
        for kernels in [fractal_dsl::compile(&s).unwrap(), fractal_dsl::compile(&s.clone().samples(8)).unwrap()] {
            let job = RenderJob::new(KernelSources::compiled(&kernels), &frame);
            let timed = timer.run(&Work::Generated(job)).unwrap();
            assert_eq!(timed.image, renderer.render(&job).unwrap());
        }
        let kernels = fractal_dsl::compile(&s).unwrap();
        let job = RenderJob::new(KernelSources::compiled(&kernels), &frame);
        let timed = timer.run(&Work::Generated(job)).unwrap();
        assert!(!timed.image.is_uniform());
        assert!(
            timed.kernel_ms > 0.0 && timed.frame_ms >= timed.kernel_ms * 0.5,
            "{} {}",
            timed.kernel_ms,
            timed.frame_ms
        );
        let baseline = timer.run(&Work::Baseline { width: 40, height: 24 }).unwrap();
        assert_eq!((baseline.image.width, baseline.image.height), (40, 24));
        assert!(!baseline.image.is_uniform());
    }
}
