//! The OpenCL renderer (cargo feature `opencl`): builds a scene's OpenCL C program on the preferred device of all
//! platforms (a GPU before an accelerator before the CPU) and runs its `render`, `trace` or `probe` kernel
//! ([`fractal_dsl::back::Entry`]), in f32, or in f64 where the device has `cl_khr_fp64` and the job asks for it.
//!
//! Programs are built with `-cl-fast-relaxed-math` unless the renderer is precise; a build failure returns the
//! driver's build log. Programs are cached per source text and precision; a render's buffers and kernels are kept
//! for the next frame of the same kernel and size.

use std::sync::Mutex;
use std::time::Instant;

use fractal_dsl::back::{has_refine, Entry, Pass, Scalar};
use ocl::enums::{DeviceInfo as ClDeviceInfo, DeviceInfoResult, ProfilingInfo};
use ocl::flags::DeviceType;
use ocl::{flags, Buffer, Context, Device, Event, Kernel, Platform, Program, Queue};

use crate::device::{Backend, DeviceInfo};
use crate::error::RenderError;
use crate::frame::Frame;
use crate::image::Image;
use crate::renderer::{PixelTrace, ProbeSample, RenderJob, Renderer, Traced};

/// The build option that trades strict IEEE semantics for speed; off in precise mode.
pub const FAST_MATH: &str = "-cl-fast-relaxed-math";
const PROGRAM_CACHE: usize = 8;

/// Renders OpenCL C kernels on an OpenCL device.
pub struct OpenClRenderer {
    device: Device,
    context: Context,
    queue: Queue,
    precise: bool,
    programs: Vec<(String, bool, Program)>,
    info: DeviceInfo,
    /// Whether the device computes in f64 (`cl_khr_fp64`): then it draws jobs in f64 with their f64 kernels.
    fp64: bool,
    /// The last render's buffers and kernels, for the next frame of the same kernel and size.
    kept: Option<Kept>,
}

/// A render's image and frame buffers and its kernels (their arguments set), kept while the kernel, image size and
/// number type stay the same: a frame then writes its uniform, runs the kernels and reads the image, allocating
/// nothing.
struct Kept {
    /// The kernel's source, whether it is built strict, the image size and the frame's bytes.
    key: (String, bool, (u32, u32), usize),
    out: Buffer<u32>,
    frame: Buffer<u8>,
    kernels: Vec<Kernel>,
}

fn no_device(reason: impl ToString) -> RenderError {
    RenderError::NoDevice { backend: Backend::OpenCl, reason: reason.to_string() }
}

/// An OpenCL call that failed on the device, as a [`RenderError::Device`].
pub fn device_error(e: ocl::Error) -> RenderError {
    RenderError::Device { backend: Backend::OpenCl, message: brief(&e) }
}

/// A program or kernel the driver refused, as a [`RenderError::KernelRejected`] with its log.
pub fn rejected(e: ocl::Error) -> RenderError {
    RenderError::KernelRejected { backend: Backend::OpenCl, log: brief(&e) }
}

/// An ocl error without its banners: an API failure in one line ("clGetDeviceIDs: CL_DEVICE_NOT_FOUND (-1)"), a
/// build failure as the build log.
pub(crate) fn brief(e: &ocl::Error) -> String {
    let text = e.to_string();
    let field = |label: &str| text.lines().find_map(|l| l.trim().strip_prefix(label)).map(|v| v.trim().to_string());
    match (field("Error executing function:"), field("Status error code:")) {
        (Some(function), Some(status)) => format!("{function}: {status}"),
        _ => {
            let lines: Vec<&str> = text.lines().filter(|l| !l.trim_start().starts_with("####")).collect();
            lines.join("\n").trim().to_string()
        }
    }
}

/// Every device of every platform, then the [`preferred`] one. The ICD loader lists platforms in no promised order,
/// so on a machine with a GPU driver and a CPU runtime (pocl) beside it the first platform's first device may be the
/// CPU.
fn preferred_device() -> Result<(Platform, Device), RenderError> {
    let ids = ocl::core::get_platform_ids()
        .map_err(|e| no_device(format!("listing platforms: {}", brief(&ocl::Error::from(e)))))?;
    let mut candidates = Vec::new();
    let mut failures = Vec::new();
    for platform in Platform::list_from_core(ids) {
        match Device::list_all(platform) {
            Ok(devices) => candidates.extend(devices.into_iter().map(|device| {
                let kind = match device.info(ClDeviceInfo::Type) {
                    Ok(DeviceInfoResult::Type(kind)) => kind,
                    _ => DeviceType::empty(),
                };
                ((platform, device), kind)
            })),
            Err(e) => failures.push(brief(&e)),
        }
    }
    preferred(candidates).ok_or_else(|| {
        let why = if failures.is_empty() { "no platform has a device".to_string() } else { failures.join("; ") };
        no_device(format!("listing devices: {why}"))
    })
}

/// The device a renderer wants most among `candidates` (each with its type), the first listed among equals: a GPU,
/// then an accelerator, then a device of another or unknown type, the CPU last.
fn preferred<T>(candidates: impl IntoIterator<Item = (T, DeviceType)>) -> Option<T> {
    let rank = |kind: DeviceType| {
        if kind.contains(DeviceType::GPU) {
            0
        } else if kind.contains(DeviceType::ACCELERATOR) {
            1
        } else if kind.contains(DeviceType::CPU) {
            3
        } else {
            2
        }
    };
    candidates.into_iter().min_by_key(|(_, kind)| rank(*kind)).map(|(candidate, _)| candidate)
}

impl OpenClRenderer {
    /// Opens the preferred device of all platforms (a GPU first); `precise` leaves out `-cl-fast-relaxed-math`.
    pub fn new(precise: bool) -> Result<OpenClRenderer, RenderError> {
        // Some platforms (pocl) report no devices to a thread that asks while another thread initialises them.
        static OPENING: Mutex<()> = Mutex::new(());
        let _opening = OPENING.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        let (platform, device) = preferred_device()?;
        let context = Context::builder()
            .platform(platform)
            .devices(device)
            .build()
            .map_err(|e| no_device(format!("creating a context: {}", brief(&e))))?;
        let queue = Queue::new(&context, device, Some(flags::QUEUE_PROFILING_ENABLE))
            .map_err(|e| no_device(format!("creating a queue: {}", brief(&e))))?;
        let text = |r: ocl::Result<String>| r.unwrap_or_else(|e| format!("unknown ({e})"));
        let info_text = |kind| match device.info(kind) {
            Ok(DeviceInfoResult::Type(t)) => format!("{t:?}"),
            Ok(other) => other.to_string(),
            Err(e) => format!("unknown ({e})"),
        };
        let info = DeviceInfo {
            backend: Backend::OpenCl,
            api: text(platform.version()),
            name: text(device.name()),
            driver: format!("{} {}", text(platform.name()), info_text(ClDeviceInfo::DriverVersion)),
            device_type: info_text(ClDeviceInfo::Type),
        };
        let fp64 = match device.info(ClDeviceInfo::Extensions) {
            Ok(DeviceInfoResult::Extensions(list)) => list.split_whitespace().any(|e| e == "cl_khr_fp64"),
            _ => false,
        };
        Ok(OpenClRenderer { device, context, queue, precise, programs: Vec::new(), info, fp64, kept: None })
    }

    /// The renderer's queue (created with profiling enabled), for dispatchers that share its device.
    pub fn queue(&self) -> &Queue {
        &self.queue
    }

    pub fn precise(&self) -> bool {
        self.precise
    }

    /// Switches fast math off (`true`) or on; programs are rebuilt on next use.
    pub fn set_precise(&mut self, precise: bool) {
        self.precise = precise;
        self.kept = None;
    }

    /// The build options programs get.
    pub fn build_options(&self) -> &'static str {
        if self.precise {
            ""
        } else {
            FAST_MATH
        }
    }

    /// Whether `frame` must be drawn without fast math whatever the renderer's mode: an anchored frame
    /// ([`Frame::anchor`]) subtracts the scene's translations from the anchor before adding the point, and fast
    /// math's reassociation would add the point first and lose what the anchor keeps.
    pub fn strict_for(frame: &Frame) -> bool {
        frame.anchor() != [0.0; 3]
    }

    /// Builds (or finds in the cache) `source`, without fast math where the renderer is precise or `strict`; a failed
    /// build returns the build log.
    pub fn program(&mut self, (source, strict): (&str, bool)) -> Result<Program, RenderError> {
        let precise = self.precise || strict;
        if let Some(i) = self.programs.iter().position(|(s, p, _)| *p == precise && s == source) {
            let hit = self.programs.remove(i);
            let program = hit.2.clone();
            self.programs.push(hit);
            return Ok(program);
        }
        let mut builder = Program::builder();
        builder.src(source).devices(self.device);
        if !precise {
            builder.cmplr_opt(FAST_MATH);
        }
        let program = builder.build(&self.context).map_err(rejected)?;
        if self.programs.len() >= PROGRAM_CACHE {
            self.programs.remove(0);
        }
        self.programs.push((source.to_string(), precise, program.clone()));
        Ok(program)
    }

    /// Whether the device computes in f64 (`cl_khr_fp64`).
    pub fn has_fp64(&self) -> bool {
        self.fp64
    }

    /// The frame's uniform slots, as a kernel computing in `scalar` reads them, in a read-only buffer on the
    /// renderer's queue.
    pub fn frame_buffer(&self, frame: &Frame, scalar: Scalar) -> Result<Buffer<u8>, RenderError> {
        let bytes = frame.bytes_in(scalar);
        Buffer::<u8>::builder()
            .queue(self.queue.clone())
            .flags(flags::MEM_READ_ONLY)
            .len(bytes.len())
            .copy_host_slice(&bytes)
            .build()
            .map_err(device_error)
    }

    /// The job's program for its precision and the number type that program computes in; a job in a precision the
    /// device lacks is refused ([`Renderer::draws_in`]).
    pub fn source_of<'j>(&self, job: &RenderJob<'j>) -> Result<(&'j str, Scalar), RenderError> {
        job.gpu_program((Backend::OpenCl, "OpenCL kernel"), [job.kernels.opencl, job.kernels.opencl_f64], self.fp64)
    }

    /// Evaluates a probe kernel (`probe(points, out, frame, n)`) computing in `scalar` at `points` of the scene (xyz;
    /// w ignored; the kernel takes them relative to the frame's anchor).
    pub fn probe(
        &mut self,
        (source, scalar): (&str, Scalar),
        frame: &Frame,
        points: &[[f32; 4]],
    ) -> Result<Vec<ProbeSample>, RenderError> {
        if points.is_empty() {
            return Ok(Vec::new());
        }
        let n = u32::try_from(points.len()).map_err(|_| RenderError::TooLarge {
            backend: Backend::OpenCl,
            what: format!("{} probe points", points.len()),
            detail: "at most 2^32 - 1".to_string(),
        })?;
        let program = self.program((source, Self::strict_for(frame)))?;
        let relative = frame.relative_to_anchor(points);
        let flat: &[f32] = bytemuck::cast_slice(&relative);
        let input = Buffer::<f32>::builder()
            .queue(self.queue.clone())
            .flags(flags::MEM_READ_ONLY)
            .len(flat.len())
            .copy_host_slice(flat)
            .build()
            .map_err(device_error)?;
        let out = Buffer::<f32>::builder()
            .queue(self.queue.clone())
            .flags(flags::MEM_WRITE_ONLY)
            .len(points.len() * 8)
            .build()
            .map_err(device_error)?;
        let frame_buffer = self.frame_buffer(frame, scalar)?;
        let kernel = Kernel::builder()
            .program(&program)
            .name(Entry::Probe.name())
            .queue(self.queue.clone())
            .global_work_size(points.len())
            .arg(&input)
            .arg(&out)
            .arg(&frame_buffer)
            .arg(n)
            .build()
            .map_err(rejected)?;
        // Safety: the kernel's arguments are live buffers of the sizes its interface promises to stay within.
        unsafe { kernel.enq() }.map_err(device_error)?;
        let mut floats = vec![0.0f32; points.len() * 8];
        out.read(&mut floats).enq().map_err(device_error)?;
        Ok(floats.chunks_exact(8).map(|c| std::array::from_fn(|i| c[i])).collect())
    }

    /// The kernels of `entry`'s passes in `source` ([`fractal_dsl::back::Pass`]) over a `size` image, in the order
    /// they run: the image into `out` (and a trace kernel's traces into `traces`), with the frame from `frame`. With a
    /// refine pass the first pass writes a buffer of its own, which the refine pass reads.
    pub fn pixel_kernels(
        &mut self,
        entry: Entry,
        source: (&str, bool),
        (width, height): (u32, u32),
        (out, frame, traces): (&Buffer<u32>, &Buffer<u8>, Option<&Buffer<f32>>),
    ) -> Result<Vec<Kernel>, RenderError> {
        let program = self.program(source)?;
        let first = has_refine(source.0).then(|| image_buffer(&self.queue, width, height)).transpose()?;
        let kernel = |pass: Pass, target: &Buffer<u32>| {
            let mut builder = Kernel::builder();
            builder
                .program(&program)
                .name(entry.entry_point(pass))
                .queue(self.queue.clone())
                .global_work_size((width as usize, height as usize))
                .arg(target)
                .arg(frame);
            if let Some(traces) = traces {
                builder.arg(traces);
            }
            if let (Pass::Refine, Some(first)) = (pass, &first) {
                builder.arg(first);
            }
            builder.build().map_err(rejected)
        };
        match &first {
            None => Ok(vec![kernel(Pass::First, out)?]),
            Some(first) => Ok(vec![kernel(Pass::First, first)?, kernel(Pass::Refine, out)?]),
        }
    }

    /// Renders the job's frame and says how long its kernels took on the device (from the first pass's start to the
    /// last pass's end, by the queue's profiling events) and how long the whole frame took on the host, from the
    /// uniform's upload to the pixels in host memory. The bench times this path: the one every render takes.
    pub fn render_timed(&mut self, job: &RenderJob) -> Result<(Image, f64, f64), RenderError> {
        let start = Instant::now();
        let mut events = Vec::new();
        let image = self.render_kept(job, Some(&mut events))?;
        let frame_ms = start.elapsed().as_secs_f64() * 1e3;
        let (Some(first), Some(last)) = (events.first(), events.last()) else {
            return Err(device_error(ocl::Error::from("no kernel ran")));
        };
        let nanos = |event: &Event, which| {
            event.profiling_info(which).and_then(|r| r.time().map_err(ocl::Error::from)).map_err(device_error)
        };
        let kernel_ns = nanos(last, ProfilingInfo::End)?.saturating_sub(nanos(first, ProfilingInfo::Start)?);
        Ok((image, kernel_ns as f64 / 1e6, frame_ms))
    }

    /// Renders the job's frame with the kept buffers and kernels where they fit it, making them anew where not; with
    /// `events`, each kernel's profiling event is pushed there.
    fn render_kept(&mut self, job: &RenderJob, mut events: Option<&mut Vec<Event>>) -> Result<Image, RenderError> {
        let (source, scalar) = self.source_of(job)?;
        let size = (job.width(), job.height());
        let bytes = job.frame.bytes_in(scalar);
        let strict = Self::strict_for(job.frame);
        let fits = |k: &Kept| k.key.0 == source && k.key.1 == strict && k.key.2 == size && k.key.3 == bytes.len();
        let kept = match self.kept.take() {
            Some(kept) if fits(&kept) => {
                kept.frame.write(&bytes).enq().map_err(device_error)?;
                kept
            }
            _ => {
                let out = image_buffer(&self.queue, size.0, size.1)?;
                let frame = self.frame_buffer(job.frame, scalar)?;
                let kernels = self.pixel_kernels(Entry::Render, (source, strict), size, (&out, &frame, None))?;
                Kept { key: (source.to_string(), strict, size, bytes.len()), out, frame, kernels }
            }
        };
        for kernel in &kept.kernels {
            let mut event = Event::empty();
            // Safety: `out` and the first pass's buffer hold one u32 per pixel, and the kernels write only pixels
            // inside the frame's size.
            unsafe { kernel.cmd().enew(&mut event).enq() }.map_err(device_error)?;
            if let Some(events) = events.as_deref_mut() {
                events.push(event);
            }
        }
        let mut pixels = vec![0u32; size.0 as usize * size.1 as usize];
        kept.out.read(&mut pixels).enq().map_err(device_error)?;
        self.kept = Some(kept);
        Ok(Image { width: size.0, height: size.1, pixels })
    }

    /// Runs the job's `entry` kernel (`render` or `trace`) over the frame's pixels: the image, and the trace
    /// kernel's [`PixelTrace::KERNEL_WORDS`] words per pixel.
    fn run_pixels(&mut self, job: &RenderJob, entry: Entry) -> Result<(Image, Vec<f32>), RenderError> {
        let (source, scalar) = self.source_of(job)?;
        let (width, height) = (job.width(), job.height());
        let count = width as usize * height as usize;
        let out = image_buffer(&self.queue, width, height)?;
        let frame_buffer = self.frame_buffer(job.frame, scalar)?;
        let words = if entry == Entry::Trace { count * PixelTrace::KERNEL_WORDS } else { 0 };
        let traces = (words > 0)
            .then(|| Buffer::<f32>::builder().queue(self.queue.clone()).flags(flags::MEM_WRITE_ONLY).len(words).build())
            .transpose()
            .map_err(|e| RenderError::TooLarge {
                backend: Backend::OpenCl,
                what: format!("the trace buffer of a {width}x{height} image"),
                detail: brief(&e),
            })?;
        let strict = Self::strict_for(job.frame);
        let passes =
            self.pixel_kernels(entry, (source, strict), (width, height), (&out, &frame_buffer, traces.as_ref()))?;
        for kernel in passes {
            // Safety: `out` and `first` hold one u32 per pixel, `traces` (the trace kernel's) twelve floats per
            // pixel, and the kernels write only pixels inside the frame's size.
            unsafe { kernel.enq() }.map_err(device_error)?;
        }
        let mut pixels = vec![0u32; count];
        out.read(&mut pixels).enq().map_err(device_error)?;
        let mut floats = vec![0.0f32; words];
        if let Some(traces) = &traces {
            traces.read(&mut floats).enq().map_err(device_error)?;
        }
        Ok((Image { width, height, pixels }, floats))
    }
}

impl Renderer for OpenClRenderer {
    fn render(&mut self, job: &RenderJob) -> Result<Image, RenderError> {
        self.render_kept(job, None)
    }

    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError> {
        let (image, words) = self.run_pixels(job, Entry::Trace)?;
        Ok(Traced::from_kernel(image, &words))
    }

    fn device(&self) -> DeviceInfo {
        self.info.clone()
    }

    fn draws_in(&self, job: &RenderJob) -> bool {
        job.gpu_draws([job.kernels.opencl, job.kernels.opencl_f64], self.fp64)
    }
}

/// Evaluates an OpenCL probe kernel (f32) at `points` on the preferred OpenCL device, with fast math unless
/// `precise`.
pub fn probe_opencl(
    source: &str,
    frame: &Frame,
    points: &[[f32; 4]],
    precise: bool,
) -> Result<Vec<ProbeSample>, RenderError> {
    OpenClRenderer::new(precise)?.probe((source, Scalar::F32), frame, points)
}

/// A write-only buffer for a packed RGBA8 image of `width`×`height`; too large for the device is
/// [`RenderError::TooLarge`].
pub fn image_buffer(queue: &Queue, width: u32, height: u32) -> Result<Buffer<u32>, RenderError> {
    Buffer::<u32>::builder()
        .queue(queue.clone())
        .flags(flags::MEM_WRITE_ONLY)
        .len(width as usize * height as usize)
        .build()
        .map_err(|e| RenderError::TooLarge {
            backend: Backend::OpenCl,
            what: format!("a {width}x{height} image"),
            detail: brief(&e),
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_gpu_is_preferred_to_the_cpu_whatever_the_platform_order() {
        let listed = [("pocl cpu", DeviceType::CPU), ("gpu", DeviceType::GPU), ("second gpu", DeviceType::GPU)];
        assert_eq!(preferred(listed), Some("gpu"));
        let listed = [("cpu", DeviceType::CPU), ("accelerator", DeviceType::ACCELERATOR)];
        assert_eq!(preferred(listed), Some("accelerator"));
        let listed = [("cpu", DeviceType::CPU), ("unknown", DeviceType::empty())];
        assert_eq!(preferred(listed), Some("unknown"));
        assert_eq!(preferred([("cpu", DeviceType::CPU | DeviceType::DEFAULT)]), Some("cpu"));
        assert_eq!(preferred(Vec::<(&str, DeviceType)>::new()), None);
    }
}
