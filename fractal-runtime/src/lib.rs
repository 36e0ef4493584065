//! fractal-runtime: turns compiled scenes into pixels on whatever the machine has.
//!
//! - [`frame`]: the uniforms every kernel reads (camera, time, lights, parameters), packed on the host.
//! - [`camera`]: poses from a scene's camera, fixed or keyed path (Catmull-Rom / linear positions, slerped views).
//! - [`Renderer`]: one interface, three implementations — [`WgpuRenderer`] (WGSL compute), `OpenClRenderer`
//!   (OpenCL C, cargo feature `opencl`) and [`CpuRenderer`] (a scene evaluator on rayon) — plus [`select()`], which
//!   picks one or chains them (`auto`).
//! - probes ([`WgpuRenderer::probe`], `OpenClRenderer::probe`): a kernel's distance and material at points, for
//!   agreement tests.
//!
//! The runtime never writes kernel text; it runs what the scene compiler (`fractal_dsl::back`) wrote.
//!
//! The modules form layers, each using only modules listed before it: [`device`] (the [`Backend`] families and
//! [`DeviceInfo`]), [`image`], [`export`], [`output`], [`error`], [`camera`], [`frame`], [`renderer`], [`backend`],
//! [`select`](mod@select), [`quality`], [`truth`], [`accuracy`], [`bench`](mod@bench), [`viewer`], [`cli`].
//!
//! Accuracy: [`truth`] renders a ground truth that never reads a distance estimate (each fractal's own membership
//! test, exact distances for primitives), [`accuracy`] measures renders against it and sweeps the [`quality`]
//! settings for `fractal accuracy`.
//!
//! ```
//! use fractal_dsl::builder::{scene, sphere};
//! use fractal_dsl::eval::{Env, Evaluator, Sample};
//! use fractal_dsl::math::{length, v3, V3};
//! use fractal_runtime::{CpuRenderer, Frame, KernelSources, ParamValues, Pose, RenderJob, Renderer};
//!
//! /// A unit sphere, evaluated by hand (the `scene!` macro generates evaluators like this one).
//! struct UnitSphere;
//! impl Evaluator<f32> for UnitSphere {
//!     fn distance(&self, p: V3<f32>, _: &Env<f32>) -> f32 {
//!         length(p) - 1.0
//!     }
//!     fn sample(&self, p: V3<f32>, env: &Env<f32>) -> Sample<f32> {
//!         let (ambient, diffuse, specular, shininess) = (0.15, 0.85, 0.0, 32.0);
//!         Sample { distance: self.distance(p, env), albedo: v3(1.0, 0.5, 0.2), ambient, diffuse, specular, shininess }
//!     }
//! }
//!
//! let s = scene(sphere(1.0));
//! let pose = Pose::from_camera(&s.camera, 0.0, &|p| p.default)?;
//! let frame = Frame::new(&s, &pose, 0.0, 32, 32, &ParamValues::defaults(&s))?;
//! let job = RenderJob::new(KernelSources::default().with_cpu(&UnitSphere, &s), &frame);
//! let image = CpuRenderer::new().render(&job)?;
//! assert_eq!((image.width, image.height), (32, 32));
//! assert!(!image.is_uniform());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod accuracy;
pub mod backend;
pub mod bench;
pub mod camera;
pub mod cli;
pub mod device;
pub mod error;
pub mod export;
pub mod frame;
pub mod image;
pub mod limits;
pub mod mesh;
pub mod output;
pub mod package;
pub mod quality;
pub mod renderer;
pub mod select;
pub mod text;
pub mod truth;
pub mod viewer;

pub use backend::cpu::{render_scene, CpuRenderer};
#[cfg(feature = "opencl")]
pub use backend::opencl::{probe_opencl, OpenClRenderer};
pub use backend::wgpu::{probe_wgsl, WgpuRenderer};
pub use camera::{CameraPath, Pose};
pub use device::{Backend, DeviceInfo};
pub use error::{CameraError, FrameError, RenderError};
pub use frame::{Frame, LightSlot, ParamValues, MAX_IMAGE_SIDE};
pub use image::Image;
pub use renderer::{CpuKernel, KernelSources, PixelTrace, ProbeSample, RenderJob, Renderer, Traced};
pub use select::{select, AutoRenderer, BackendChoice, RendererOptions, UnknownBackend};
