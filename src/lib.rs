//! fractal: a scene compiler and renderer for 3D fractals and signed-distance scenes.
//!
//! A scene is written once, as a Rust expression, and `scene!` compiles it at build time into an OpenCL C kernel, a
//! WGSL kernel and a native CPU evaluator that agree with each other:
//!
//! ```
//! use fractal::prelude::*;
//!
//! let s = scene! {
//!     union(
//!         mandelbulb(8),
//!         sphere(1.0).translate(vec3(1.5, 0.0, 0.0)).material(rgb(0.9, 0.2, 0.1)),
//!     )
//! };
//! assert!(s.opencl().contains("__kernel void render"));
//! assert!(s.wgsl().contains("fn render"));
//! // The native evaluator: inside the sphere, one unit from its surface at its centre.
//! assert!((s.distance(Vec3::new(1.5, 0.0, 0.0)) + 1.0).abs() < 1e-6);
//! ```
//!
//! The same syntax in a `.fractal` file loads at run time with [`dsl::parse::parse_str`].

pub use fractal_dsl as dsl;
pub use fractal_macros::{scene, scene_file};
pub use fractal_render as render;
pub use fractal_runtime as runtime;
pub use scenes;

/// Everything needed to write scenes: the builder functions, the IR types, the macros and glam vectors.
pub mod prelude {
    pub use crate::{scene, scene_file};
    pub use fractal_dsl::builder::*;
    pub use fractal_dsl::eval::Evaluator;
    pub use fractal_dsl::{CompiledScene, Fractal, Material, Node, Scene};
    pub use glam::{DVec3, Vec3};
}
