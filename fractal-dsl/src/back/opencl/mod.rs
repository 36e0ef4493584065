//! The OpenCL C backend: [`write()`] spells a lowered scene as a complete OpenCL C program.

mod writer;

pub use writer::{functions, write};
