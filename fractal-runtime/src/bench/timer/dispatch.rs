//! What every dispatcher shares: the work it is handed, the timed frame it returns, the [`Timer`] interface and the
//! clocks a kernel time can come from.
//!
//! Apart from the facade (`timer.rs`), which opens the dispatchers, so each dispatcher reads these without reading
//! its caller.

use fractal_render::device::DeviceInfo;
use fractal_render::error::RenderError;
use fractal_render::image::Image;
use fractal_render::renderer::RenderJob;

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
    /// Whether it times frames in f64 in f64 (the CPU; an OpenCL device with `cl_khr_fp64`); otherwise such frames
    /// are timed in f32.
    fn computes_f64(&self) -> bool {
        false
    }
    /// Runs `work` and times it; the first run of a kernel also builds it (callers leave that run out of the figures).
    fn run(&mut self, work: &Work) -> Result<Timed, RenderError>;
}

pub(crate) fn millis(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
