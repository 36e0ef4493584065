//! The WGSL backend: [`write()`] spells a lowered scene as a complete WGSL module (in f32, or [`write_in`] f64),
//! [`library`] as a function library.

mod writer;

pub use writer::{functions, library, write, write_in};
