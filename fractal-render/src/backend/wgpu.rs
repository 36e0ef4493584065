//! The wgpu renderer: runs a scene's WGSL kernel as a compute pass and reads the image back.
//!
//! Bindings follow [`fractal_dsl::back::Entry`]: `render` writes packed pixels to binding 0 and reads the frame
//! uniform at binding 1, in 8×8 workgroups; `probe` writes two vec4 per point to binding 0, reads the frame at 1 and
//! the points at 2, in workgroups of 64; `trace` is `render` that also writes each pixel's march to binding 2; a
//! kernel with a second pass ([`fractal_dsl::back::Pass`]) has its `refine` read the first pass's pixels at 3. Every
//! wgpu call that can fail runs inside error scopes, so a kernel the driver refuses, or a device that cannot
//! allocate, is a [`RenderError`] and never a panic. Pipelines are cached
//! per source text; output buffers are reused while the image size stays the same. A job in f64 runs the scene's f64
//! module where the adapter offers `SHADER_F64` (the device is opened with it).

use std::sync::{mpsc, Arc, Mutex};

use fractal_dsl::back::{has_refine, Entry, Pass, Scalar};
use wgpu::util::DeviceExt;

use crate::device::{Backend, DeviceInfo};
use crate::error::RenderError;
use crate::frame::Frame;
use crate::image::Image;
use crate::renderer::{PixelTrace, ProbeSample, RenderJob, Renderer, Traced};

/// Workgroup edge of the `render` entry point (8×8).
pub const RENDER_WORKGROUP: u32 = 8;
/// Workgroup size of the `probe` entry point.
pub const PROBE_WORKGROUP: u32 = 64;
/// Pipelines kept per renderer; a hot-reloading viewer compiles a new one per edit.
const PIPELINE_CACHE: usize = 8;

/// Renders WGSL kernels on a wgpu device.
pub struct WgpuRenderer {
    instance: wgpu::Instance,
    adapter: wgpu::Adapter,
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    /// The bind group and pipeline layouts of each entry point, in [`ENTRY_POINTS`]' order.
    layouts: [Layouts; 5],
    pipelines: Vec<(EntryPoint, String, wgpu::ComputePipeline)>,
    targets: Option<Targets>,
    /// The first pass's pixels, which a refine pass reads; kept while the image size stays the same.
    first: Option<(u64, wgpu::Buffer)>,
    /// Errors raised outside any error scope (wgpu would otherwise panic on them).
    uncaptured: Arc<Mutex<Vec<String>>>,
}

/// An entry point of a kernel: its entry and pass.
type EntryPoint = (Entry, Pass);
type Layouts = (wgpu::BindGroupLayout, wgpu::PipelineLayout);
/// Every entry point a kernel has.
const ENTRY_POINTS: [EntryPoint; 5] = [
    (Entry::Render, Pass::First),
    (Entry::Render, Pass::Refine),
    (Entry::Trace, Pass::First),
    (Entry::Trace, Pass::Refine),
    (Entry::Probe, Pass::First),
];

/// Output and read-back buffers of one size.
struct Targets {
    bytes: u64,
    out: wgpu::Buffer,
    readback: wgpu::Buffer,
}

fn device_error(message: impl ToString) -> RenderError {
    RenderError::Device { backend: Backend::Wgpu, message: message.to_string() }
}

impl WgpuRenderer {
    /// Opens the preferred adapter of the default backends (the `WGPU_BACKEND` environment variable may narrow them).
    pub fn new() -> Result<WgpuRenderer, RenderError> {
        WgpuRenderer::with_backends(wgpu::Backends::all())
    }

    /// Opens the preferred adapter among `backends`.
    pub fn with_backends(backends: wgpu::Backends) -> Result<WgpuRenderer, RenderError> {
        WgpuRenderer::with_features(backends, wgpu::Features::empty())
    }

    /// Opens the preferred adapter among `backends` and asks for those of `wanted` features the adapter has (the
    /// bench wants timestamp queries where they exist).
    pub fn with_features(backends: wgpu::Backends, wanted: wgpu::Features) -> Result<WgpuRenderer, RenderError> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = backends.with_env();
        // Release-build flags in every build: validation layers would make debug builds measure something else.
        // WGPU_DEBUG / WGPU_VALIDATION still turn them on.
        desc.flags = wgpu::InstanceFlags::VALIDATION_INDIRECT_CALL.with_env();
        let instance = wgpu::Instance::new(desc);
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        };
        let adapter = pollster::block_on(instance.request_adapter(&options))
            .map_err(|e| RenderError::NoDevice { backend: Backend::Wgpu, reason: e.to_string() })?;
        let info = adapter.get_info();
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("fractal"),
            // f64 where the adapter has it, for frames that ask for it.
            required_features: adapter.features() & (wanted | wgpu::Features::SHADER_F64),
            // The adapter's own limits, so large images are limited by the device rather than by WebGPU defaults.
            required_limits: adapter.limits(),
            memory_hints: wgpu::MemoryHints::Performance,
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor)).map_err(|e| {
            RenderError::NoDevice { backend: Backend::Wgpu, reason: format!("{} ({}): {e}", info.name, info.backend) }
        })?;
        let uncaptured = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&uncaptured);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut errors) = sink.lock() {
                errors.push(e.to_string());
            }
        }));
        let layouts = ENTRY_POINTS.map(|p| pipeline_layout(&device, p));
        Ok(WgpuRenderer {
            instance,
            adapter,
            device,
            queue,
            info,
            layouts,
            pipelines: Vec::new(),
            targets: None,
            first: None,
            uncaptured,
        })
    }

    /// The wgpu objects, for callers that draw to a surface with the same device.
    pub fn instance(&self) -> &wgpu::Instance {
        &self.instance
    }
    pub fn adapter(&self) -> &wgpu::Adapter {
        &self.adapter
    }
    pub fn wgpu_device(&self) -> &wgpu::Device {
        &self.device
    }
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }
    pub fn adapter_info(&self) -> &wgpu::AdapterInfo {
        &self.info
    }

    /// The bind group and pipeline layouts of entry point `point` (a probe kernel has one pass).
    fn layouts(&self, point: EntryPoint) -> &Layouts {
        let at = match point {
            (Entry::Render, Pass::First) => 0,
            (Entry::Render, Pass::Refine) => 1,
            (Entry::Trace, Pass::First) => 2,
            (Entry::Trace, Pass::Refine) => 3,
            (Entry::Probe, _) => 4,
        };
        &self.layouts[at]
    }

    /// Compiles (or finds in the cache) the pipeline of `entry`'s `pass` in `source`.
    pub fn pipeline(&mut self, (entry, pass): EntryPoint, source: &str) -> Result<wgpu::ComputePipeline, RenderError> {
        let point = (entry, pass);
        if let Some(i) = self.pipelines.iter().position(|(p, s, _)| *p == point && s == source) {
            let hit = self.pipelines.remove(i);
            let pipeline = hit.2.clone();
            self.pipelines.push(hit);
            return Ok(pipeline);
        }
        let layout = &self.layouts(point).1;
        let ((module, pipeline), error) = capture(&self.device, || {
            let module = self.device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("fractal kernel"),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
            let pipeline = self.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry.entry_point(pass)),
                layout: Some(layout),
                module: &module,
                entry_point: Some(entry.entry_point(pass)),
                compilation_options: Default::default(),
                cache: None,
            });
            (module, pipeline)
        });
        if let Some(error) = error {
            let info = pollster::block_on(module.get_compilation_info());
            let located: Vec<String> = info
                .messages
                .iter()
                .filter(|m| m.message_type == wgpu::CompilationMessageType::Error)
                .map(|m| match &m.location {
                    Some(at) => format!("{}:{}: {}", at.line_number, at.line_position, m.message),
                    None => m.message.clone(),
                })
                .collect();
            let log = if located.is_empty() { error.to_string() } else { located.join("\n") };
            return Err(RenderError::KernelRejected { backend: Backend::Wgpu, log });
        }
        if self.pipelines.len() >= PIPELINE_CACHE {
            self.pipelines.remove(0);
        }
        self.pipelines.push((point, source.to_string(), pipeline.clone()));
        Ok(pipeline)
    }

    /// Whether the device computes in f64 (`SHADER_F64`): then it draws jobs in f64 with their f64 modules.
    pub fn has_fp64(&self) -> bool {
        self.device.features().contains(wgpu::Features::SHADER_F64)
    }

    /// The job's module for its precision and the number type it computes in; a job in a precision the device lacks
    /// is refused ([`Renderer::draws_in`]).
    pub fn source_of<'j>(&self, job: &RenderJob<'j>) -> Result<(&'j str, Scalar), RenderError> {
        job.gpu_program((Backend::Wgpu, "WGSL kernel"), [job.kernels.wgsl, job.kernels.wgsl_f64], self.has_fp64())
    }

    /// Evaluates a probe kernel (entry `probe`) computing in `scalar` at `points` of the scene (xyz; w ignored; the
    /// kernel takes them relative to the frame's anchor): one [`ProbeSample`] per point.
    pub fn probe(
        &mut self,
        (source, scalar): (&str, Scalar),
        frame: &Frame,
        points: &[[f32; 4]],
    ) -> Result<Vec<ProbeSample>, RenderError> {
        if points.is_empty() {
            return Ok(Vec::new());
        }
        let groups = (points.len() as u64).div_ceil(PROBE_WORKGROUP as u64);
        let out_bytes = points.len() as u64 * 32;
        let limits = self.device.limits();
        if groups > limits.max_compute_workgroups_per_dimension as u64
            || out_bytes > limits.max_storage_buffer_binding_size
        {
            return Err(RenderError::TooLarge {
                backend: Backend::Wgpu,
                what: format!("{} probe points", points.len()),
                detail: format!("at most {} workgroups of 64", limits.max_compute_workgroups_per_dimension),
            });
        }
        let pipeline = self.pipeline((Entry::Probe, Pass::First), source)?;
        let (buffers, error) = capture(&self.device, || {
            let uniform = self.uniform_buffer(frame, scalar);
            let input = self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("probe points"),
                contents: bytemuck::cast_slice(&frame.relative_to_anchor(points)),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let out = self.storage_buffer("probe out", out_bytes);
            let readback = self.readback_buffer(out_bytes);
            let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("probe"),
                layout: &self.layouts((Entry::Probe, Pass::First)).0,
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: out.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: uniform.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: input.as_entire_binding() },
                ],
            });
            let mut encoder = self.encoder();
            record(&mut encoder, (&pipeline, &bind_group), (groups as u32, 1), None);
            self.queue.submit([encoder.finish()]);
            (out, readback)
        });
        self.check(error)?;
        let floats: Vec<f32> = self.read(&buffers.0, &buffers.1, out_bytes)?.into_iter().map(f32::from_bits).collect();
        Ok(floats.chunks_exact(8).map(|c| std::array::from_fn(|i| c[i])).collect())
    }

    /// The frame's slots as a module computing in `scalar` reads them.
    fn uniform_buffer(&self, frame: &Frame, scalar: Scalar) -> wgpu::Buffer {
        self.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("frame"),
            contents: &frame.bytes_in(scalar),
            usage: wgpu::BufferUsages::UNIFORM,
        })
    }

    fn storage_buffer(&self, label: &str, bytes: u64) -> wgpu::Buffer {
        self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        })
    }

    fn readback_buffer(&self, bytes: u64) -> wgpu::Buffer {
        self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: bytes,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    fn encoder(&self) -> wgpu::CommandEncoder {
        self.device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("fractal") })
    }

    /// Copies `bytes` of `out` into `readback`, waits for the GPU and returns them as u32 words.
    fn read(&self, out: &wgpu::Buffer, readback: &wgpu::Buffer, bytes: u64) -> Result<Vec<u32>, RenderError> {
        let (words, error) = capture(&self.device, || read_back(&self.device, &self.queue, out, readback, bytes));
        self.check(error)?;
        words.map_err(device_error)
    }

    /// Turns a scoped error, or any error that escaped the scopes, into a device error.
    pub fn check(&self, scoped: Option<wgpu::Error>) -> Result<(), RenderError> {
        let mut messages: Vec<String> = scoped.into_iter().map(|e| e.to_string()).collect();
        if let Ok(mut escaped) = self.uncaptured.lock() {
            messages.append(&mut escaped);
        }
        if messages.is_empty() {
            Ok(())
        } else {
            Err(device_error(messages.join("\n")))
        }
    }
}

/// Copies `bytes` of `source` into `readback` (a MAP_READ | COPY_DST buffer of at least `bytes`), waits for the device
/// and returns them as u32 words.
pub fn read_back(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
    readback: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u32>, String> {
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("readback") });
    encoder.copy_buffer_to_buffer(source, 0, readback, 0, bytes);
    queue.submit([encoder.finish()]);
    let data = map_read(device, readback, bytes)?;
    Ok(data.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
}

/// Waits for the device and returns the first `bytes` of a MAP_READ buffer, which is unmapped again afterwards.
pub fn map_read(device: &wgpu::Device, buffer: &wgpu::Buffer, bytes: u64) -> Result<Vec<u8>, String> {
    let slice = buffer.slice(..bytes);
    let (sender, receiver) = mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| e.to_string())?;
    receiver.recv().map_err(|e| e.to_string())?.map_err(|e| e.to_string())?;
    let data = slice.get_mapped_range().map_err(|e| e.to_string())?.to_vec();
    buffer.unmap();
    Ok(data)
}

/// Runs `f` inside validation, out-of-memory and internal error scopes and returns the first error they caught, so a
/// kernel, buffer or surface the driver refuses is an error value rather than a panic.
pub fn capture<T>(device: &wgpu::Device, f: impl FnOnce() -> T) -> (T, Option<wgpu::Error>) {
    let internal = device.push_error_scope(wgpu::ErrorFilter::Internal);
    let memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let value = f();
    // Scopes pop innermost first.
    let errors = [validation.pop(), memory.pop(), internal.pop()].map(pollster::block_on);
    (value, errors.into_iter().flatten().next())
}

/// Records one dispatch of `pipeline` with `bind_group` over `groups` workgroups.
fn record(
    encoder: &mut wgpu::CommandEncoder,
    (pipeline, bind_group): (&wgpu::ComputePipeline, &wgpu::BindGroup),
    groups: (u32, u32),
    timestamp_writes: Option<wgpu::ComputePassTimestampWrites>,
) {
    let mut pass =
        encoder.begin_compute_pass(&wgpu::ComputePassDescriptor { label: Some("fractal"), timestamp_writes });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind_group, &[]);
    pass.dispatch_workgroups(groups.0, groups.1, 1);
}

fn pipeline_layout(device: &wgpu::Device, (entry, pass): EntryPoint) -> Layouts {
    let buffer = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
        count: None,
    };
    let out = buffer(0, wgpu::BufferBindingType::Storage { read_only: false });
    let frame = buffer(1, wgpu::BufferBindingType::Uniform);
    let mut entries = match entry {
        Entry::Render => vec![out, frame],
        Entry::Probe => vec![out, frame, buffer(2, wgpu::BufferBindingType::Storage { read_only: true })],
        Entry::Trace => vec![out, frame, buffer(2, wgpu::BufferBindingType::Storage { read_only: false })],
    };
    if pass == Pass::Refine {
        entries.push(buffer(3, wgpu::BufferBindingType::Storage { read_only: true }));
    }
    let label = Some(entry.entry_point(pass));
    let bind_group_layout =
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label, entries: &entries });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label,
        bind_group_layouts: &[Some(&bind_group_layout)],
        immediate_size: 0,
    });
    (bind_group_layout, layout)
}

/// The compute passes that draw a frame's pixels with one kernel ([`fractal_dsl::back::Pass`]): the first pass,
/// and where the kernel has one the refine pass, which reads the first pass's pixels from a buffer the renderer keeps.
pub struct PixelPasses {
    first: (wgpu::ComputePipeline, wgpu::BindGroupLayout),
    /// The refine pass's pipeline and layout, and the buffer the first pass writes for it.
    refine: Option<(wgpu::ComputePipeline, wgpu::BindGroupLayout, wgpu::Buffer)>,
    groups: (u32, u32),
}

impl PixelPasses {
    /// Records the passes: the image into `out` and, with a trace kernel, the traces into `traces`, reading the frame
    /// from `uniform`.
    pub fn record(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        uniform: &wgpu::Buffer,
        out: &wgpu::Buffer,
        traces: Option<&wgpu::Buffer>,
    ) {
        self.record_timed(device, encoder, (uniform, out, traces), None);
    }

    /// [`PixelPasses::record`], writing timestamps 0 and 1 of `timestamps` where the passes begin and end.
    pub fn record_timed(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
        (uniform, out, traces): (&wgpu::Buffer, &wgpu::Buffer, Option<&wgpu::Buffer>),
        timestamps: Option<&wgpu::QuerySet>,
    ) {
        let stamp = |begin: bool, end: bool| {
            timestamps.map(|query_set| wgpu::ComputePassTimestampWrites {
                query_set,
                beginning_of_pass_write_index: begin.then_some(0),
                end_of_pass_write_index: end.then_some(1),
            })
        };
        let bind = |layout: &wgpu::BindGroupLayout, target: &wgpu::Buffer, input: Option<&wgpu::Buffer>| {
            let mut entries = vec![
                wgpu::BindGroupEntry { binding: 0, resource: target.as_entire_binding() },
                wgpu::BindGroupEntry { binding: 1, resource: uniform.as_entire_binding() },
            ];
            let extra = [(2, traces), (3, input)];
            for (binding, buffer) in extra.into_iter().filter_map(|(b, buffer)| buffer.map(|buffer| (b, buffer))) {
                entries.push(wgpu::BindGroupEntry { binding, resource: buffer.as_entire_binding() });
            }
            device.create_bind_group(&wgpu::BindGroupDescriptor { label: Some("pixels"), layout, entries: &entries })
        };
        let (pipeline, layout) = &self.first;
        match &self.refine {
            None => record(encoder, (pipeline, &bind(layout, out, None)), self.groups, stamp(true, true)),
            Some((refine, refine_layout, first)) => {
                record(encoder, (pipeline, &bind(layout, first, None)), self.groups, stamp(true, false));
                let group = bind(refine_layout, out, Some(first));
                record(encoder, (refine, &group), self.groups, stamp(false, true));
            }
        }
    }
}

impl WgpuRenderer {
    /// The passes of `entry`'s kernel `source` (`render` or `trace`) for an image of `size`: their pipelines
    /// compiled and, for a refine pass, its input buffer made.
    pub fn pixel_passes(&mut self, entry: Entry, source: &str, size: (u32, u32)) -> Result<PixelPasses, RenderError> {
        let first = (self.pipeline((entry, Pass::First), source)?, self.layouts((entry, Pass::First)).0.clone());
        let groups = (size.0.div_ceil(RENDER_WORKGROUP), size.1.div_ceil(RENDER_WORKGROUP));
        if !has_refine(source) {
            return Ok(PixelPasses { first, refine: None, groups });
        }
        let pipeline = self.pipeline((entry, Pass::Refine), source)?;
        let bytes = size.0 as u64 * size.1 as u64 * 4;
        if self.first.as_ref().is_none_or(|(b, _)| *b != bytes) {
            self.first = None;
            let (buffer, error) = capture(&self.device, || self.storage_buffer("first pass", bytes));
            self.check(error)?;
            self.first = Some((bytes, buffer));
        }
        let Some((_, buffer)) = self.first.as_ref() else {
            return Err(device_error("the first pass's buffer was not created"));
        };
        let layout = self.layouts((entry, Pass::Refine)).0.clone();
        Ok(PixelPasses { first, refine: Some((pipeline, layout, buffer.clone())), groups })
    }

    /// Runs the job's `entry` kernel (`render` or `trace`) over the frame's pixels: the image, and the trace
    /// kernel's [`PixelTrace::KERNEL_WORDS`] words per pixel.
    fn run_pixels(&mut self, job: &RenderJob, entry: Entry) -> Result<(Image, Vec<f32>), RenderError> {
        let (source, scalar) = self.source_of(job)?;
        let (width, height) = (job.width(), job.height());
        let bytes = width as u64 * height as u64 * 4;
        let trace_bytes = if entry == Entry::Trace { bytes * PixelTrace::KERNEL_WORDS as u64 } else { 0 };
        let limits = self.device.limits();
        let groups = (width.div_ceil(RENDER_WORKGROUP), height.div_ceil(RENDER_WORKGROUP));
        let max_groups = limits.max_compute_workgroups_per_dimension;
        let max_bytes = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
        if bytes.max(trace_bytes) > max_bytes || groups.0 > max_groups || groups.1 > max_groups {
            return Err(RenderError::TooLarge {
                backend: Backend::Wgpu,
                what: if trace_bytes > max_bytes {
                    format!("the trace buffer of a {width}x{height} image ({trace_bytes} bytes)")
                } else {
                    format!("a {width}x{height} image")
                },
                detail: format!("storage buffers up to {max_bytes} bytes, {max_groups} workgroups per dimension"),
            });
        }
        let passes = self.pixel_passes(entry, source, (width, height))?;
        if self.targets.as_ref().is_none_or(|t| t.bytes != bytes) {
            self.targets = None;
            let (targets, error) = capture(&self.device, || Targets {
                bytes,
                out: self.storage_buffer("pixels", bytes),
                readback: self.readback_buffer(bytes),
            });
            self.check(error)?;
            self.targets = Some(targets);
        }
        let Some(targets) = self.targets.as_ref() else {
            return Err(device_error("output buffers were not created"));
        };
        // The traces are rare (accuracy and depth images): their buffers are made per call, not kept.
        let (traces, error) = capture(&self.device, || {
            let uniform = self.uniform_buffer(job.frame, scalar);
            let traces = (trace_bytes > 0)
                .then(|| (self.storage_buffer("traces", trace_bytes), self.readback_buffer(trace_bytes)));
            let mut encoder = self.encoder();
            passes.record(&self.device, &mut encoder, &uniform, &targets.out, traces.as_ref().map(|t| &t.0));
            self.queue.submit([encoder.finish()]);
            traces
        });
        self.check(error)?;
        let pixels = self.read(&targets.out, &targets.readback, bytes)?;
        let words = match &traces {
            Some((buffer, readback)) => {
                self.read(buffer, readback, trace_bytes)?.into_iter().map(f32::from_bits).collect()
            }
            None => Vec::new(),
        };
        Ok((Image { width, height, pixels }, words))
    }
}

impl Renderer for WgpuRenderer {
    fn render(&mut self, job: &RenderJob) -> Result<Image, RenderError> {
        Ok(self.run_pixels(job, Entry::Render)?.0)
    }

    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError> {
        let (image, words) = self.run_pixels(job, Entry::Trace)?;
        Ok(Traced::from_kernel(image, &words))
    }

    fn device(&self) -> DeviceInfo {
        let driver = match (self.info.driver.is_empty(), self.info.driver_info.is_empty()) {
            (false, false) => format!("{} {}", self.info.driver, self.info.driver_info),
            (false, true) => self.info.driver.clone(),
            (true, _) => self.info.driver_info.clone(),
        };
        DeviceInfo {
            backend: Backend::Wgpu,
            api: format!("{:?}", self.info.backend),
            name: self.info.name.clone(),
            driver,
            device_type: format!("{:?}", self.info.device_type),
        }
    }

    fn draws_in(&self, job: &RenderJob) -> bool {
        job.gpu_draws([job.kernels.wgsl, job.kernels.wgsl_f64], self.has_fp64())
    }
}

/// Evaluates a WGSL probe kernel at `points` on `renderer`'s device; see [`WgpuRenderer::probe`].
pub fn probe_wgsl(
    renderer: &mut WgpuRenderer,
    source: &str,
    frame: &Frame,
    points: &[[f32; 4]],
) -> Result<Vec<ProbeSample>, RenderError> {
    renderer.probe((source, Scalar::F32), frame, points)
}
