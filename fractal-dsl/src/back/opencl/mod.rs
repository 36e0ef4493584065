//! The OpenCL C backend: [`write()`] spells a lowered scene as a complete OpenCL C program, in f32 or
//! ([`write_in`]) f64.

mod writer;

pub use writer::{functions, write, write_in};
