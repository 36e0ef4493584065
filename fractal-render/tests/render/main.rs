//! The renderer's integration tests, in one binary: the CPU renderer against analytic answers, the wgpu and OpenCL
//! renderers on kernels written without the compiler (the bench's hand-written baseline reading the frame, and the
//! sphere probes in `tests/kernels`), backend selection, the scene compiler's kernels
//! drawn by every backend, and samples per pixel and the lens on every backend.

mod common;
mod cpu_renderer;
mod generated_kernels;
#[cfg(feature = "opencl")]
mod opencl_renderer;
mod samples;
mod select;
mod wgpu_renderer;
