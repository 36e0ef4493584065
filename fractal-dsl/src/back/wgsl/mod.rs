//! The WGSL backend: [`write()`] spells a lowered scene as a complete WGSL module, [`library`] as a function library.

mod writer;

pub use writer::{functions, library, write};
