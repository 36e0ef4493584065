//! fractal-dsl: the scene language of fractal — IR, builder API, parser, analyses, code writers and interpreter.

pub mod analyse;
pub mod back;
pub mod builder;
pub mod compiled;
pub mod eval;
pub mod geom;
pub mod ir;
pub mod leaf;
pub mod lower;
pub mod math;
pub mod num;
pub mod parse;
pub mod prims;
pub mod print;
pub mod sdf;
pub mod validate;
pub mod visit;

pub use compiled::{compile, CompiledScene, Kernels, NativeFns};
pub use ir::*;
