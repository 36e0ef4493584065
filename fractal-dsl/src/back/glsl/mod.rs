//! The GLSL backend: [`library`] spells a lowered scene as a function library in the GLSL both GLSL 4.50 and
//! GLSL ES 3.00 accept (so Godot's shading language, a subset of it, takes it too). Compute kernels in GLSL are
//! naga's translation of the WGSL kernel, not written here.

mod writer;

pub use writer::library;
