//! The Rust backend: [`write`] spells a lowered scene as the native evaluator's source, for the `scene!` macro.

mod writer;

pub use writer::{write, DISTANCE_FN, SAMPLE_FN};
