//! The wgpu renderer's frame path: a frame's uniform uploaded, its passes recorded, its pixels copied out (or, where
//! the device's memory is the host's, written straight into a mappable buffer) and its timestamps resolved, in one
//! submission and one wait; a batch keeps several frames in flight. Buffers live as long as the image size does and
//! the frame uniform is rewritten in place, so a frame allocates nothing on the device but a trace's buffers.

use std::sync::mpsc;
use std::time::Instant;

use super::scoped::{capture, device_error, map_read, Uncaptured};
use crate::device::Backend;
use crate::error::RenderError;
use crate::image::Image;

/// Workgroup edge of the `render` entry point (8×8).
pub const RENDER_WORKGROUP: u32 = 8;

/// The frames a batch keeps in flight ([`crate::renderer::Renderer::render_batch`]): while the host copies one
/// frame's pixels, the device draws the next ones.
pub const FRAMES_IN_FLIGHT: usize = 3;

/// The pixel buffers the kernel writes and the mappable buffers the host reads them from, one per frame in flight;
/// kept while the image size stays the same. On a device whose memory is the host's (a CPU or integrated GPU, with
/// `MAPPABLE_PRIMARY_BUFFERS`) the kernel writes into the mappable buffers themselves; elsewhere frames in flight
/// share one pixel buffer, each submission copying it out before the next one's kernel runs (a queue runs its
/// submissions in order).
struct Targets {
    bytes: u64,
    /// One buffer, or one per frame in flight where the kernel writes the mappable buffers.
    outs: Vec<wgpu::Buffer>,
    readbacks: Vec<wgpu::Buffer>,
}

impl Targets {
    /// Whether the kernel writes the buffer the host maps (no copy).
    fn direct(&self) -> bool {
        self.outs.len() > 1
    }
}

/// Timestamp queries around a frame's kernel, where the device has them ([`WgpuRenderer::with_features`] with
/// `TIMESTAMP_QUERY`): written by the passes, resolved and copied out in the frame's own submission.
struct Stamps {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    read: wgpu::Buffer,
    period_ns: f64,
}

/// A frame submitted and not yet read: its submission and the readback being mapped ([`Frames::submit`]).
pub struct InFlight {
    submission: wgpu::SubmissionIndex,
    mapped: mpsc::Receiver<Result<(), wgpu::BufferAsyncError>>,
    /// The readback's index in [`Targets::readbacks`].
    slot: usize,
    /// The image size.
    pub size: (u32, u32),
    /// Whether the submission also resolved the kernel's timestamps.
    stamped: bool,
    /// When the host began the frame: the frame time runs from here to its pixels in host memory.
    started: Instant,
}

/// One frame drawn through the renderer's own path ([`super::WgpuRenderer::draw_with`]): its pixels, the kernel's
/// device time where timestamps were written, and the frame's host time, from the uniform upload to the pixels in
/// host memory.
#[derive(Clone, Debug)]
pub struct Drawn {
    pub image: Image,
    pub kernel_ms: Option<f64>,
    pub frame_ms: f64,
}

impl Stamps {
    /// The queries and buffers, where the device was opened with timestamp queries.
    fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> Option<Stamps> {
        device.features().contains(wgpu::Features::TIMESTAMP_QUERY).then(|| Stamps {
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
            period_ns: f64::from(queue.get_timestamp_period()),
        })
    }
}

/// What a frame needs on the device beyond its kernel, kept from frame to frame: the pixel buffers and readbacks,
/// the frame uniform (rewritten per frame: `Queue::write_buffer` lands at the next submission, in queue order, so
/// frames in flight may share it) and the timestamp queries.
pub struct Frames {
    targets: Option<Targets>,
    uniform: Option<wgpu::Buffer>,
    stamps: Option<Stamps>,
    errors: Uncaptured,
}

impl Frames {
    /// Nothing made yet but the timestamp queries, where the device has them; `errors` are the device's.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, errors: Uncaptured) -> Frames {
        Frames { targets: None, uniform: None, stamps: Stamps::new(device, queue), errors }
    }

    /// The pixel buffer and readbacks for images of `bytes`, made where the kept ones have another size.
    fn ensure_targets(&mut self, device: &wgpu::Device, bytes: u64) -> Result<(), RenderError> {
        if self.targets.as_ref().is_some_and(|t| t.bytes == bytes) {
            return Ok(());
        }
        self.targets = None;
        let direct = device.features().contains(wgpu::Features::MAPPABLE_PRIMARY_BUFFERS);
        let buffer = |label, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        let (targets, error) = capture(device, || {
            let readbacks: Vec<wgpu::Buffer> = (0..FRAMES_IN_FLIGHT)
                .map(|_| match direct {
                    true => buffer("pixels", wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::MAP_READ),
                    false => buffer("readback", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST),
                })
                .collect();
            let outs = match direct {
                true => readbacks.clone(),
                false => vec![buffer("pixels", wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC)],
            };
            Targets { bytes, outs, readbacks }
        });
        self.errors.check(error)?;
        self.targets = Some(targets);
        Ok(())
    }

    /// The frame uniform, holding `contents` once the next submission starts; made anew where its size changes.
    fn write_uniform(&mut self, (device, queue): (&wgpu::Device, &wgpu::Queue), contents: &[u8]) -> wgpu::Buffer {
        let size = contents.len() as u64;
        let uniform = match self.uniform.take() {
            Some(kept) if kept.size() == size => kept,
            _ => device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame"),
                size,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        queue.write_buffer(&uniform, 0, contents);
        self.uniform = Some(uniform.clone());
        uniform
    }

    /// Submits one frame whose pixels land in readback `slot`: uploads `uniform`, lets `record` record the passes
    /// that write the pixel buffer (given the device, the encoder, the uniform, the pixel buffer and, where `timed`
    /// and the device has them, the timestamp queries to write), copies the pixels out and starts mapping them, all
    /// in one submission.
    pub fn submit(
        &mut self,
        (device, queue): (&wgpu::Device, &wgpu::Queue),
        uniform: &[u8],
        size: (u32, u32),
        (slot, timed): (usize, bool),
        record: impl FnOnce(&wgpu::Device, &mut wgpu::CommandEncoder, &wgpu::Buffer, &wgpu::Buffer, Option<&wgpu::QuerySet>),
    ) -> Result<InFlight, RenderError> {
        let started = Instant::now();
        let bytes = size.0 as u64 * size.1 as u64 * 4;
        check_size(device, size, 0)?;
        self.ensure_targets(device, bytes)?;
        let (submitted, error) = capture(device, || {
            let uniform = self.write_uniform((device, queue), uniform);
            let targets = self.targets.as_ref()?;
            let stamps = self.stamps.as_ref().filter(|_| timed);
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("frame") });
            let readback = &targets.readbacks[slot % FRAMES_IN_FLIGHT];
            let out = if targets.direct() { readback } else { &targets.outs[0] };
            record(device, &mut encoder, &uniform, out, stamps.map(|s| &s.set));
            if !targets.direct() {
                encoder.copy_buffer_to_buffer(out, 0, readback, 0, bytes);
            }
            if let Some(s) = stamps {
                encoder.resolve_query_set(&s.set, 0..2, &s.resolve, 0);
                encoder.copy_buffer_to_buffer(&s.resolve, 0, &s.read, 0, 16);
            }
            let submission = queue.submit([encoder.finish()]);
            let (sender, mapped) = mpsc::channel();
            readback.slice(..bytes).map_async(wgpu::MapMode::Read, move |result| {
                let _ = sender.send(result);
            });
            Some(InFlight {
                submission,
                mapped,
                slot: slot % FRAMES_IN_FLIGHT,
                size,
                stamped: stamps.is_some(),
                started,
            })
        });
        if let Err(e) = self.errors.check(error) {
            // A readback may be left mapping: make the buffers anew next time.
            self.targets = None;
            return Err(e);
        }
        submitted.ok_or_else(|| device_error("output buffers were not created"))
    }

    /// Waits for a submitted frame and copies its pixels (and kernel time) to host memory.
    pub fn collect(&mut self, device: &wgpu::Device, frame: InFlight) -> Result<Drawn, RenderError> {
        let wait = wgpu::PollType::Wait { submission_index: Some(frame.submission), timeout: None };
        let read = || -> Result<(Vec<u32>, Option<f64>), String> {
            device.poll(wait).map_err(|e| e.to_string())?;
            frame.mapped.recv().map_err(|e| e.to_string())?.map_err(|e| e.to_string())?;
            let targets = self.targets.as_ref().ok_or("output buffers were dropped")?;
            let readback = &targets.readbacks[frame.slot];
            let pixels = {
                let view = readback.slice(..targets.bytes).get_mapped_range().map_err(|e| e.to_string())?;
                bytemuck::pod_collect_to_vec::<u8, u32>(&view)
            };
            readback.unmap();
            let kernel_ms = match (frame.stamped, self.stamps.as_ref()) {
                (true, Some(s)) => kernel_time(device, s)?,
                _ => None,
            };
            Ok((pixels, kernel_ms))
        };
        let (pixels, kernel_ms) = match read() {
            Ok(read) => read,
            Err(e) => {
                self.targets = None;
                return Err(device_error(e));
            }
        };
        self.errors.check(None)?;
        let (width, height) = frame.size;
        let frame_ms = frame.started.elapsed().as_secs_f64() * 1e3;
        Ok(Drawn { image: Image { width, height, pixels }, kernel_ms, frame_ms })
    }
}

/// Refuses an image of `size` (with `trace_bytes` of traces) the device cannot hold or dispatch.
pub fn check_size(device: &wgpu::Device, (width, height): (u32, u32), trace_bytes: u64) -> Result<(), RenderError> {
    let bytes = width as u64 * height as u64 * 4;
    let limits = device.limits();
    let groups = (width.div_ceil(RENDER_WORKGROUP), height.div_ceil(RENDER_WORKGROUP));
    let max_groups = limits.max_compute_workgroups_per_dimension;
    let max_bytes = limits.max_storage_buffer_binding_size.min(limits.max_buffer_size);
    if bytes.max(trace_bytes) <= max_bytes && groups.0 <= max_groups && groups.1 <= max_groups {
        return Ok(());
    }
    Err(RenderError::TooLarge {
        backend: Backend::Wgpu,
        what: if trace_bytes > max_bytes {
            format!("the trace buffer of a {width}x{height} image ({trace_bytes} bytes)")
        } else {
            format!("a {width}x{height} image")
        },
        detail: format!("storage buffers up to {max_bytes} bytes, {max_groups} workgroups per dimension"),
    })
}

/// The kernel time the timestamps of a completed submission hold, or `None` where the device wrote none usable
/// (zero or reordered).
fn kernel_time(device: &wgpu::Device, stamps: &Stamps) -> Result<Option<f64>, String> {
    let bytes = map_read(device, &stamps.read, 16)?;
    let words: Vec<u64> = bytemuck::pod_collect_to_vec(&bytes);
    Ok((words[1] > words[0]).then(|| (words[1] - words[0]) as f64 * stamps.period_ns / 1e6))
}

/// `MAPPABLE_PRIMARY_BUFFERS` on an adapter whose memory is the host's (a CPU or an integrated GPU), where the host
/// reading the buffer the kernel wrote costs less than a copy; none elsewhere (on a discrete GPU such buffers sit in
/// host memory, where the kernel would write across the bus).
pub fn unified_memory(info: &wgpu::AdapterInfo) -> wgpu::Features {
    match info.device_type {
        wgpu::DeviceType::Cpu | wgpu::DeviceType::IntegratedGpu => wgpu::Features::MAPPABLE_PRIMARY_BUFFERS,
        _ => wgpu::Features::empty(),
    }
}
