//! The bench's dispatchers: one per backend, each running either the scene's generated kernel (a
//! [`RenderJob`](fractal_render::RenderJob)) or the hand-written baseline on one device and timing the kernel and the
//! whole frame.
//!
//! They exist because the renderers return only images: a renderer has no device clock to read, and the baseline
//! kernels take other arguments than the generated ones (the image size instead of the frame uniforms). Both kernels
//! go through the same dispatcher, so the ratio compares kernels, not plumbing.

use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::select::RendererOptions;

mod cpu;
mod dispatch;
#[cfg(feature = "opencl")]
mod opencl;
mod wgpu;

pub use dispatch::KernelClock;
pub(crate) use dispatch::{Timer, Work};

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
