//! The vocabulary of the scene language, each item declared once: primitives, operators and fractal families, with
//! their arguments' rules, bounds and builder functions. Everything after the IR (parser, printer, validation, bounds,
//! evaluators, kernels) reads these declarations rather than naming items itself.

pub mod fractals;
pub mod ops;
pub mod prims;
pub mod radius;
