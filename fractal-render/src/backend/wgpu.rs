//! The wgpu renderer: runs a scene's WGSL kernel as a compute pass and reads the image back.
//!
//! Bindings follow [`fractal_dsl::back::Entry`]: `render` writes packed pixels to binding 0 and reads the frame
//! uniform at binding 1, in 8×8 workgroups; `probe` writes two vec4 per point to binding 0, reads the frame at 1 and
//! the points at 2, in workgroups of 64; `trace` is `render` that also writes each pixel's march to binding 2; a
//! kernel with a second pass ([`fractal_dsl::back::Pass`]) has its `refine` read the first pass's pixels at 3. Every
//! wgpu call that can fail runs inside error scopes, so a kernel the driver refuses, or a device that cannot
//! allocate, is a [`RenderError`] and never a panic (module `scoped`). Pipelines are cached per source text. A frame
//! goes from uniform upload to pixels on the host in one submission and one wait, with buffers kept while the image
//! size stays the same, and a batch keeps several frames in flight (module `frames`). A job in f64 runs the scene's
//! f64 module where the adapter offers `SHADER_F64` (the device is opened with it).

use fractal_dsl::back::{has_refine, Entry, Pass, Scalar};
use wgpu::util::DeviceExt;

use crate::device::{Backend, DeviceInfo};
use crate::error::RenderError;
use crate::frame::Frame;
use crate::image::Image;
use crate::renderer::{PixelTrace, ProbeSample, RenderJob, Renderer, Traced};

mod frames;
mod scoped;

pub use frames::{check_size, Drawn, FRAMES_IN_FLIGHT, RENDER_WORKGROUP};
use frames::{Frames, InFlight};
pub use scoped::{capture, map_read, read_back};
use scoped::{device_error, Uncaptured};

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
    /// A frame's buffers, kept from frame to frame, and its path from upload to pixels on the host.
    frames: Frames,
    /// The first pass's pixels, which a refine pass reads; kept while the image size stays the same.
    first: Option<(u64, wgpu::Buffer)>,
    /// Errors raised outside any error scope.
    uncaptured: Uncaptured,
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
            // f64 where the adapter has it, for frames that ask for it; where the device's memory is the host's,
            // pixel buffers the host maps without a copy.
            required_features: adapter.features()
                & (wanted | wgpu::Features::SHADER_F64 | frames::unified_memory(&info)),
            // The adapter's own limits, so large images are limited by the device rather than by WebGPU defaults.
            required_limits: adapter.limits(),
            memory_hints: wgpu::MemoryHints::Performance,
            ..Default::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&descriptor)).map_err(|e| {
            RenderError::NoDevice { backend: Backend::Wgpu, reason: format!("{} ({}): {e}", info.name, info.backend) }
        })?;
        let uncaptured = Uncaptured::install(&device);
        let layouts = ENTRY_POINTS.map(|p| pipeline_layout(&device, p));
        let frames = Frames::new(&device, &queue, uncaptured.clone());
        Ok(WgpuRenderer {
            instance,
            adapter,
            device,
            queue,
            info,
            layouts,
            pipelines: Vec::new(),
            frames,
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

    /// Draws one frame through the renderer's own path: `uniform` uploaded, the passes `record` records (given the
    /// device, the encoder, the uniform, the pixel buffer to write and the timestamp queries, where the device has
    /// them) and the pixels read back, in one submission and one wait. The bench times its
    /// baseline kernel through here, so both are timed alike.
    pub fn draw_with(
        &mut self,
        uniform: &[u8],
        size: (u32, u32),
        record: impl FnOnce(&wgpu::Device, &mut wgpu::CommandEncoder, &wgpu::Buffer, &wgpu::Buffer, Option<&wgpu::QuerySet>),
    ) -> Result<Drawn, RenderError> {
        let frame = self.frames.submit((&self.device, &self.queue), uniform, size, (0, true), record)?;
        self.frames.collect(&self.device, frame)
    }

    /// Submits the job's `render` kernel into readback `slot`.
    fn submit_render(&mut self, job: &RenderJob, slot: usize, timed: bool) -> Result<InFlight, RenderError> {
        let (source, scalar) = self.source_of(job)?;
        let size = (job.width(), job.height());
        let passes = self.pixel_passes(Entry::Render, source, size)?;
        let uniform = job.frame.bytes_in(scalar);
        self.frames.submit(
            (&self.device, &self.queue),
            &uniform,
            size,
            (slot, timed),
            |device, encoder, uniform, out, stamps| passes.record_timed(device, encoder, (uniform, out, None), stamps),
        )
    }

    /// Renders the job's frame.
    fn render_one(&mut self, job: &RenderJob) -> Result<Image, RenderError> {
        let frame = self.submit_render(job, 0, false)?;
        Ok(self.frames.collect(&self.device, frame)?.image)
    }

    /// Renders the job's frame and says how long its kernel (on the device's clock, where the device was opened with
    /// timestamp queries) and its whole frame took.
    pub fn render_timed(&mut self, job: &RenderJob) -> Result<Drawn, RenderError> {
        let frame = self.submit_render(job, 0, true)?;
        self.frames.collect(&self.device, frame)
    }

    /// Runs the job's `trace` kernel: the image and [`PixelTrace::KERNEL_WORDS`] words per pixel. Traces are rare
    /// (accuracy and depth images): their buffers are made per call, not kept.
    fn run_trace(&mut self, job: &RenderJob) -> Result<(Image, Vec<f32>), RenderError> {
        let (source, scalar) = self.source_of(job)?;
        let size = (job.width(), job.height());
        let trace_bytes = size.0 as u64 * size.1 as u64 * 4 * PixelTrace::KERNEL_WORDS as u64;
        check_size(&self.device, size, trace_bytes)?;
        let passes = self.pixel_passes(Entry::Trace, source, size)?;
        let (traces, error) =
            capture(&self.device, || (self.storage_buffer("traces", trace_bytes), self.readback_buffer(trace_bytes)));
        self.check(error)?;
        let uniform = job.frame.bytes_in(scalar);
        let drawn = self.draw_with(&uniform, size, |device, encoder, uniform, out, _| {
            passes.record(device, encoder, uniform, out, Some(&traces.0));
            encoder.copy_buffer_to_buffer(&traces.0, 0, &traces.1, 0, trace_bytes);
        })?;
        // The copy was part of the frame's submission, which has completed.
        let (bytes, error) = capture(&self.device, || map_read(&self.device, &traces.1, trace_bytes));
        self.check(error)?;
        let words = bytemuck::pod_collect_to_vec::<u8, f32>(&bytes.map_err(device_error)?);
        Ok((drawn.image, words))
    }

    /// Renders `jobs` keeping up to [`FRAMES_IN_FLIGHT`] frames submitted: the device draws the next ones while the
    /// host reads one.
    fn render_in_flight(&mut self, jobs: &[RenderJob]) -> Vec<Result<Image, RenderError>> {
        let mut drawn = Vec::with_capacity(jobs.len());
        let mut flying = std::collections::VecDeque::new();
        for (i, job) in jobs.iter().enumerate() {
            // The readbacks are made per image size: frames of another size wait for those in flight.
            let resized = flying.back().is_some_and(|f: &InFlight| f.size != (job.width(), job.height()));
            self.collect_until(&mut flying, if resized { 0 } else { FRAMES_IN_FLIGHT - 1 }, &mut drawn);
            match self.submit_render(job, i, false) {
                Ok(frame) => flying.push_back(frame),
                Err(e) => {
                    self.collect_until(&mut flying, 0, &mut drawn);
                    drawn.push(Err(e));
                }
            }
        }
        self.collect_until(&mut flying, 0, &mut drawn);
        drawn
    }

    /// Reads the oldest frames in flight into `drawn` until at most `left` remain.
    fn collect_until(
        &mut self,
        flying: &mut std::collections::VecDeque<InFlight>,
        left: usize,
        drawn: &mut Vec<Result<Image, RenderError>>,
    ) {
        while flying.len() > left {
            let Some(frame) = flying.pop_front() else { break };
            drawn.push(self.frames.collect(&self.device, frame).map(|d| d.image));
        }
    }

    /// Turns a scoped error, or any error that escaped the scopes, into a device error.
    pub fn check(&self, scoped: Option<wgpu::Error>) -> Result<(), RenderError> {
        self.uncaptured.check(scoped)
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
}

impl Renderer for WgpuRenderer {
    fn render(&mut self, job: &RenderJob) -> Result<Image, RenderError> {
        self.render_one(job)
    }

    /// Keeps up to [`FRAMES_IN_FLIGHT`] frames submitted: the device draws the next ones while the host reads one.
    fn render_batch(&mut self, jobs: &[RenderJob]) -> Vec<Result<Image, RenderError>> {
        self.render_in_flight(jobs)
    }

    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError> {
        let (image, words) = self.run_trace(job)?;
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
