//! The renderer implementations, one module per backend: `wgpu` (WGSL compute), `opencl` (OpenCL C, cargo feature
//! `opencl`) and `cpu` (a scene evaluator on rayon).

pub mod cpu;
#[cfg(feature = "opencl")]
pub mod opencl;
pub mod wgpu;
