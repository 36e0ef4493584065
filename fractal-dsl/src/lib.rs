//! fractal-dsl: the scene language of fractal — IR, builder API, parser, analyses, code writers and interpreter.
//!
//! A scene read from text, built in Rust, evaluated by the interpreter and compiled into both kernels:
//!
//! ```
//! use fractal_dsl::builder::*;
//! use fractal_dsl::eval::{interp::Interpreter, Env};
//! use fractal_dsl::number::math::v3;
//!
//! // The text of a `.fractal` file, and the same scene from the builder API.
//! let text = "union(sphere(1.0), box3(vec3(0.5, 0.5, 0.5)).translate(vec3(2.0, 0.0, 0.0)))";
//! let parsed = fractal_dsl::parse::parse_str(text).expect("a valid scene");
//! let built = scene(union(sphere(1.0), box3(vec3(0.5, 0.5, 0.5)).translate(vec3(2.0, 0.0, 0.0))));
//! assert_eq!(parsed, built);
//!
//! // The interpreter in f64 is the reference: 3 units from the centre of the unit sphere, 2 from its surface.
//! let reference = Interpreter::new(&parsed).expect("parsed scenes are valid");
//! let d = reference.distance_in(v3(0.0, 0.0, -3.0), &Env::still());
//! assert!((d - 2.0f64).abs() < 1e-12);
//!
//! // The sphere's formula (written once in `formula/shapes.rs`) becomes one named function in each kernel.
//! let kernels = fractal_dsl::compile(&parsed).expect("parsed scenes are valid");
//! assert!(kernels.opencl.contains("float sd_sphere(float3 p, float r) {"));
//! assert!(kernels.wgsl.contains("fn sd_sphere(p: vec3<f32>, r: f32) -> f32 {"));
//! ```
//!
//! `docs/design.md` in the repository follows a scene from text to kernels and names the module that owns each step.

pub mod analyse;
pub mod back;
pub mod builder;
pub mod compiled;
pub mod eval;
pub mod formula;
pub mod geom;
pub mod ir;
pub mod lower;
pub mod number;
pub mod parse;
pub mod print;
pub mod ray;
pub mod sanitise;
pub mod validate;
pub mod visit;
pub mod vocab;

pub use compiled::{compile, CompiledScene, DefaultParams, Kernels, NativeFns, NormalFns};
pub use ir::*;
