//! fractal: a scene compiler and renderer for 3D fractals and signed-distance scenes.
//!
//! This crate is the front door: it names what a program that writes, renders and exports scenes needs, and the
//! [`prelude`] holds what a scene is written with. The layers beneath are crates of their own — the scene language and
//! compiler ([`dsl`], `fractal-dsl`), the renderers ([`render`], `fractal-render`) and the tools around them
//! ([`runtime`], `fractal-runtime`: the `fractal` program, viewer, bench, accuracy, meshes, engine packages) — and are
//! re-exported whole for programs that need more than the front door names.
//!
//! **Write a scene** once, as a Rust expression; `scene!` compiles it at build time into an OpenCL C kernel, a WGSL
//! kernel and a native CPU evaluator that agree with each other:
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
//! **Read a scene file** (`.fractal`, the same syntax) at run time, **compile** it, and **evaluate** it with the f64
//! interpreter, the reference every other evaluator is tested against:
//!
//! ```
//! use fractal::{compile, parse_str, v3, Env, Interpreter};
//!
//! let scene = parse_str("sphere(1.0).translate(vec3(0.0, 2.0, 0.0))")?;
//! let kernels = compile(&scene)?;
//! assert!(kernels.wgsl.contains("fn sd_sphere"));
//! let reference = Interpreter::new(&scene)?;
//! assert_eq!(reference.distance_in(v3(0.0, 0.0, 0.0), &Env::still()), 1.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! **Render an image** on the CPU (or [`WgpuRenderer`], `OpenClRenderer` with the `opencl` feature, or whichever
//! [`select()`] finds) and **write it** as a PNG:
//!
//! ```
//! use fractal::prelude::*;
//! use fractal::{write_png, CpuRenderer, Frame, KernelSources, RenderJob, Renderer};
//!
//! let s = scene! { sphere(1.0) };
//! let native = s.native();
//! let frame = Frame::default_view(s.scene(), 0.0, 64, 36)?;
//! let job = RenderJob::new(KernelSources::default().with_cpu(&native, s.scene()), &frame);
//! let image = CpuRenderer::new().render(&job)?;
//! assert_eq!((image.width, image.height), (64, 36));
//! let path = std::env::temp_dir().join(format!("fractal-doc-{}.png", std::process::id()));
//! write_png(&path, &image)?;
//! # std::fs::remove_file(&path)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! **Export** the render kernel for another API, or a package for an engine:
//!
//! ```
//! use fractal::prelude::*;
//! use fractal::{export_compiled, package, Engine, Target};
//!
//! let s = scene! { torus(1.0, 0.25) };
//! let glsl = export_compiled(&s, Target::Glsl)?;
//! assert!(String::from_utf8_lossy(glsl.as_bytes()).contains("#version 450"));
//! let godot = package(s.scene(), "torus", Engine::Godot)?;
//! assert!(godot.files.iter().any(|f| f.name.ends_with(".gdshader")));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! `cargo run --example sierpinski` opens the interactive viewer ([`view`]).

pub use fractal_dsl as dsl;
pub use fractal_render as render;
pub use fractal_runtime as runtime;
pub use scenes;

// Writing, reading and compiling scenes.
pub use fractal_dsl::parse::{parse_str, SourceError};
pub use fractal_dsl::validate::InvalidScene;
pub use fractal_dsl::{compile, CompiledScene, Kernels, Node, Scene};
pub use fractal_macros::{scene, scene_file};

// Evaluating a scene's distance and material.
pub use fractal_dsl::eval::interp::Interpreter;
pub use fractal_dsl::eval::{Env, Evaluator, Sample};
pub use fractal_dsl::number::math::{v3, V3};

// Rendering images.
#[cfg(feature = "opencl")]
pub use fractal_render::OpenClRenderer;
pub use fractal_render::{
    select, Backend, BackendChoice, CpuRenderer, Frame, Image, KernelSources, Pose, RenderError, RenderJob, Renderer,
    RendererOptions, WgpuRenderer,
};

// Writing images and exporting.
pub use fractal_runtime::export::{export_compiled, export_scene, Exported, Target};
pub use fractal_runtime::mesh::{extract, write_mesh, Mesh, MeshFormat, MeshSettings};
pub use fractal_runtime::output::write_png;
pub use fractal_runtime::package::{package, Engine, Package};

/// The interactive viewer: a window onto a scene, or a PNG where there is no display.
pub mod view {
    pub use fractal_runtime::viewer::{example_main, run_or_render, ViewerOptions, ViewerScene};
}

/// Everything needed to write scenes: the builder functions, the IR types, the macros and glam vectors.
pub mod prelude {
    pub use crate::{scene, scene_file};
    pub use fractal_dsl::builder::*;
    pub use fractal_dsl::eval::Evaluator;
    pub use fractal_dsl::{CompiledScene, Fractal, Material, Node, Scene};
    pub use glam::{DVec3, Vec3};
}
