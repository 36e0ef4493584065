//! The WGSL backend: [`write`] spells a lowered scene as a complete WGSL module.

mod writer;

pub use writer::{functions, write};
