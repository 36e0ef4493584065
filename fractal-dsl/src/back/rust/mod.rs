//! The Rust backend, for the `scene!` macro: [`write()`] spells a lowered scene as the native evaluator's source, and
//! [`ir_tokens`] spells the IR itself (and its parameters' defaults) as Rust that constructs it.

pub mod ir_tokens;
mod writer;

pub use writer::{write, DISTANCE_FN, NORMAL_FN, SAMPLE_FN};
