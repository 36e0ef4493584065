//! Getting frames into the window, upscaled from the render size to the window size by nearest pixel (module
//! `stretch`, the rule both presenters share, so they show identical pixels).
//!
//! - [`GpuPresenter`] (module `gpu`): the WGSL kernel computes into a storage buffer and a full-screen pass (module
//!   `blit`) draws that buffer to the window's wgpu surface in the same submission; nothing crosses back to the host
//!   except screenshots. A host image (a progressive picture) is uploaded into the same buffer and drawn the same way.
//! - [`SoftPresenter`] (module `soft`): any image on the host (CPU and OpenCL frames, wgpu frames read back) copied
//!   into a softbuffer surface.
//!
//! Both have a form without a window (`fractal view --headless`): a texture of the window's size, or host memory.

mod blit;
mod gpu;
mod soft;
mod stretch;
#[cfg(test)]
mod ui_agreement;

pub use gpu::{GpuFrameError, GpuPresenter, PassTimes};
pub use soft::SoftPresenter;
