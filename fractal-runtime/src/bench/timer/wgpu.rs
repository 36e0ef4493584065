//! The wgpu dispatcher: runs on the device of a [`fractal_render::WgpuRenderer`] opened with timestamp queries when the
//! adapter has them, and runs a WGSL compute kernel the way the renderer does (uniform upload, 8×8 workgroups, copy to
//! a read-back buffer, map). The generated kernel's passes are the renderer's own
//! ([`fractal_render::backend::wgpu::PixelPasses`]; with a refine pass the time spans both); the baseline (`main`,
//! binding 1 = `{w, h}`) writes packed pixels to binding 0 as they do, its bind group layout from the shader.

use std::time::Instant;

use fractal_dsl::back::Entry;
use fractal_render::backend::wgpu::{capture, read_back, WgpuRenderer};
use fractal_render::device::{Backend, DeviceInfo};
use fractal_render::error::RenderError;
use fractal_render::image::Image;
use fractal_render::renderer::Renderer;
use wgpu::util::DeviceExt;

use super::dispatch::{millis, KernelClock, Timed, Timer, Work};
use crate::bench::baseline::BASELINE_WGSL;

const WORKGROUP: u32 = 8;

fn device_error(message: impl ToString) -> RenderError {
    RenderError::Device { backend: Backend::Wgpu, message: message.to_string() }
}

struct Timestamps {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    period_ns: f64,
}

struct Targets {
    bytes: u64,
    out: wgpu::Buffer,
    readback: wgpu::Buffer,
}

pub(crate) struct WgpuTimer {
    /// Owns the device, queue and error sink; its own pipelines and buffers are not used.
    renderer: WgpuRenderer,
    timestamps: Option<Timestamps>,
    pipelines: Vec<(String, &'static str, wgpu::ComputePipeline)>,
    targets: Option<Targets>,
}

impl WgpuTimer {
    pub fn new() -> Result<WgpuTimer, RenderError> {
        let renderer = WgpuRenderer::with_features(wgpu::Backends::all(), wgpu::Features::TIMESTAMP_QUERY)?;
        let (device, queue) = (renderer.wgpu_device(), renderer.queue());
        let timestamps = device.features().contains(wgpu::Features::TIMESTAMP_QUERY).then(|| Timestamps {
            set: device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("kernel time"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            read: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps readback"),
                size: 16,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            period_ns: queue.get_timestamp_period() as f64,
        });
        Ok(WgpuTimer { renderer, timestamps, pipelines: Vec::new(), targets: None })
    }

    fn device(&self) -> &wgpu::Device {
        self.renderer.wgpu_device()
    }

    fn pipeline(&mut self, source: &str, entry: &'static str) -> Result<wgpu::ComputePipeline, RenderError> {
        if let Some((_, _, p)) = self.pipelines.iter().find(|(s, e, _)| s == source && *e == entry) {
            return Ok(p.clone());
        }
        let device = self.device();
        let (pipeline, error) = capture(device, || {
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(entry),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: None,
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
        });
        if let Some(e) = error {
            return Err(RenderError::KernelRejected { backend: Backend::Wgpu, log: e.to_string() });
        }
        self.pipelines.push((source.to_string(), entry, pipeline.clone()));
        Ok(pipeline)
    }

    fn targets(&mut self, width: u32, height: u32) -> Result<(), RenderError> {
        let bytes = width as u64 * height as u64 * 4;
        let limits = self.device().limits();
        let max_bytes = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        let max_groups = limits.max_compute_workgroups_per_dimension;
        if bytes > max_bytes || width.div_ceil(WORKGROUP) > max_groups || height.div_ceil(WORKGROUP) > max_groups {
            return Err(RenderError::TooLarge {
                backend: Backend::Wgpu,
                what: format!("a {width}x{height} image"),
                detail: format!("storage buffers up to {max_bytes} bytes, {max_groups} workgroups per dimension"),
            });
        }
        if self.targets.as_ref().is_some_and(|t| t.bytes == bytes) {
            return Ok(());
        }
        self.targets = None;
        let device = self.device();
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        let (targets, error) = capture(device, || Targets {
            bytes,
            out: buffer("pixels", wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC),
            readback: buffer("readback", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
        });
        self.renderer.check(error)?;
        self.targets = Some(targets);
        Ok(())
    }

    fn wait(&self) -> Result<(), RenderError> {
        self.device().poll(wgpu::PollType::wait_indefinitely()).map(|_| ()).map_err(device_error)
    }
}

impl Timer for WgpuTimer {
    fn device(&self) -> DeviceInfo {
        Renderer::device(&self.renderer)
    }

    fn clock(&self) -> KernelClock {
        if self.timestamps.is_some() {
            KernelClock::DeviceTimestamps
        } else {
            KernelClock::WallClock
        }
    }

    fn computes_f64(&self) -> bool {
        self.renderer.has_fp64()
    }

    fn run(&mut self, work: &Work) -> Result<Timed, RenderError> {
        let (source, entry, uniform, width, height) = match work {
            Work::Generated(job) => {
                let (source, scalar) = self.renderer.source_of(job)?;
                (source, "render", job.frame.bytes_in(scalar), job.width(), job.height())
            }
            Work::Baseline { width, height } => {
                // `{w: u32, h: u32}`, padded to the 16 bytes of a uniform block.
                let words = [*width, *height, 0, 0];
                (BASELINE_WGSL, "main", bytemuck::cast_slice(&words).to_vec(), *width, *height)
            }
        };
        // The generated kernel's passes are the renderer's; the baseline is one pipeline of its own.
        let passes = match work {
            Work::Generated(_) => Some(self.renderer.pixel_passes(Entry::Render, source, (width, height))?),
            Work::Baseline { .. } => None,
        };
        let pipeline = if passes.is_none() { Some(self.pipeline(source, entry)?) } else { None };
        self.targets(width, height)?;
        let (Some(targets), ts) = (self.targets.as_ref(), self.timestamps.as_ref()) else {
            return Err(device_error("output buffers were not created"));
        };
        let bytes = targets.bytes;

        let (device, queue) = (self.renderer.wgpu_device(), self.renderer.queue());

        let start = Instant::now();
        let (encoder, error) = capture(device, || {
            let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("uniforms"),
                contents: &uniform,
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(entry) });
            if let Some(passes) = &passes {
                passes.record_timed(device, &mut encoder, (&uniform, &targets.out, None), ts.map(|t| &t.set));
            }
            if let Some(pipeline) = &pipeline {
                let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some(entry),
                    layout: &pipeline.get_bind_group_layout(0),
                    entries: &[
                        wgpu::BindGroupEntry { binding: 0, resource: targets.out.as_entire_binding() },
                        wgpu::BindGroupEntry { binding: 1, resource: uniform.as_entire_binding() },
                    ],
                });
                let timestamp_writes = ts.map(|t| wgpu::ComputePassTimestampWrites {
                    query_set: &t.set,
                    beginning_of_pass_write_index: Some(0),
                    end_of_pass_write_index: Some(1),
                });
                let mut pass =
                    encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some(entry), timestamp_writes });
                pass.set_pipeline(pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(width.div_ceil(WORKGROUP), height.div_ceil(WORKGROUP), 1);
            }
            if let Some(t) = ts {
                encoder.resolve_query_set(&t.set, 0..2, &t.resolve, 0);
            }
            encoder.finish()
        });
        self.renderer.check(error)?;
        let submitted = Instant::now();
        queue.submit([encoder]);
        self.wait()?;
        let kernel_wall = millis(submitted.elapsed());

        let pixels = read_back(device, queue, &targets.out, &targets.readback, bytes).map_err(device_error)?;
        let frame_ms = millis(start.elapsed());
        self.renderer.check(None)?;

        let kernel_ms = match ts {
            Some(t) => {
                let words = read_back(device, queue, &t.resolve, &t.read, 16).map_err(device_error)?;
                let tick = |i: usize| u64::from(words[2 * i]) | u64::from(words[2 * i + 1]) << 32;
                let (begin, end) = (tick(0), tick(1));
                // A device that wrote no usable timestamps (reordered or zero) still gets the wall time.
                if end > begin {
                    (end - begin) as f64 * t.period_ns / 1e6
                } else {
                    kernel_wall
                }
            }
            None => kernel_wall,
        };
        Ok(Timed { image: Image { width, height, pixels }, kernel_ms, frame_ms })
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
