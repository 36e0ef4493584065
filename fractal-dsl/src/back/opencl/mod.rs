//! The OpenCL C backend: [`write`] spells a lowered scene as a complete OpenCL C program.

pub mod library;
mod writer;

pub use writer::write;
