//! fractal-dsl: the scene language of fractal — IR, builder API, parser, analyses, code writers and interpreter.

pub mod builder;
pub mod ir;
pub mod math;
pub mod sdf;
pub mod visit;

pub use ir::*;
