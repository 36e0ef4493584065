//! The WGSL backend: [`write`] spells a lowered scene as a complete WGSL module.

pub mod library;
mod writer;

pub use writer::write;
