//! The bench's dispatchers: one per backend, each running either the scene's generated kernel (a [`RenderJob`]) or
//! the hand-written baseline on one device and timing the kernel and the whole frame.
//!
//! They exist because the renderers return only images: a renderer has no device clock to read, and the baseline
//! kernels take other arguments than the generated ones (the image size instead of the frame uniforms). Both kernels
//! go through the same dispatcher, so the ratio compares kernels, not plumbing.

use fractal_render::device::{Backend, DeviceInfo};
use fractal_render::error::RenderError;
use fractal_render::image::Image;
use fractal_render::renderer::RenderJob;
use fractal_render::select::RendererOptions;

mod cpu;
#[cfg(feature = "opencl")]
mod opencl;
mod wgpu;

/// How a kernel time was measured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KernelClock {
    /// wgpu timestamp queries written at the start and end of the compute pass.
    DeviceTimestamps,
    /// The OpenCL profiling event of the kernel (`CL_PROFILING_COMMAND_START` to `END`).
    ProfilingEvents,
    /// Wall time from submitting the dispatch to the end of the wait for it (no device clock available).
    WallClock,
    /// CPU renderer: the kernel is the whole frame (no device, no read-back).
    WholeFrame,
}

impl KernelClock {
    pub fn name(self) -> &'static str {
        match self {
            KernelClock::DeviceTimestamps => "device-timestamps",
            KernelClock::ProfilingEvents => "opencl-profiling",
            KernelClock::WallClock => "wall-clock",
            KernelClock::WholeFrame => "whole-frame",
        }
    }
    pub fn describe(self) -> &'static str {
        match self {
            KernelClock::DeviceTimestamps => "device time from wgpu timestamp queries around the compute pass",
            KernelClock::ProfilingEvents => "device time from the OpenCL profiling event of the kernel",
            KernelClock::WallClock => {
                "wall time from submit to the end of the wait (the adapter has no timestamp queries)"
            }
            KernelClock::WholeFrame => "CPU renderer: kernel time is the whole frame (no device, no read-back)",
        }
    }
}

/// What to run.
pub(crate) enum Work<'a> {
    /// The scene's generated kernel for the job's frame.
    Generated(RenderJob<'a>),
    /// The hand-written baseline at this size (its camera is built in).
    Baseline { width: u32, height: u32 },
}

/// One timed frame.
pub(crate) struct Timed {
    pub image: Image,
    pub kernel_ms: f64,
    pub frame_ms: f64,
}

/// A dispatcher on one device.
pub(crate) trait Timer {
    fn device(&self) -> DeviceInfo;
    fn clock(&self) -> KernelClock;
    /// Runs `work` and times it; the first run of a kernel also builds it (callers leave that run out of the figures).
    fn run(&mut self, work: &Work) -> Result<Timed, RenderError>;
}

/// Opens the dispatcher of `backend`.
pub(crate) fn open(backend: Backend, options: &RendererOptions) -> Result<Box<dyn Timer>, RenderError> {
    match backend {
        Backend::Wgpu => Ok(Box::new(wgpu::WgpuTimer::new()?)),
        Backend::OpenCl => open_opencl(options),
        Backend::Cpu => Ok(Box::new(cpu::CpuTimer::new())),
    }
}

#[cfg(feature = "opencl")]
fn open_opencl(options: &RendererOptions) -> Result<Box<dyn Timer>, RenderError> {
    Ok(Box::new(opencl::OpenClTimer::new(options.precise)?))
}

#[cfg(not(feature = "opencl"))]
fn open_opencl(_options: &RendererOptions) -> Result<Box<dyn Timer>, RenderError> {
    Err(RenderError::NotBuilt { backend: Backend::OpenCl, hint: "rebuild with `--features opencl`" })
}

pub(crate) fn millis(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
