//! The HLSL backend: [`library`] spells a lowered scene as a function library in HLSL (shader model 5 and later,
//! as Unity and Unreal compile it). Compute kernels in HLSL are naga's translation of the WGSL kernel, not written
//! here.

mod writer;

pub use writer::library;
