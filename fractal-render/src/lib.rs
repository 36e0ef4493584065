//! fractal-render: the renderer a program embeds to turn a compiled scene into pixels on whatever the machine has.
//!
//! It owns what a render needs and nothing more: the frame uniforms every kernel reads ([`frame`]), the camera poses
//! they are packed from ([`camera`]), one [`Renderer`] interface with its three backends — [`WgpuRenderer`] (WGSL
//! compute), `OpenClRenderer` (OpenCL C, cargo feature `opencl`) and [`CpuRenderer`] (a scene evaluator on rayon) —
//! and [`select()`], which picks one or chains them (`auto`). The tools around it (command line, viewer, bench,
//! accuracy, output, export) live in `fractal-runtime`, so a program that only renders links no window system,
//! argument parser or plotting library.
//!
//! It never writes kernel text; it runs what the scene compiler (`fractal_dsl::back`) wrote.
//!
//! The modules form layers, each using only modules listed before it: [`device`] (the [`Backend`] families and
//! [`DeviceInfo`]), [`image`], [`limits`], [`error`], [`camera`], [`frame`], [`renderer`], [`backend`],
//! [`select`](mod@select).
//!
//! ```
//! use fractal_dsl::builder::{scene, sphere};
//! use fractal_dsl::eval::{Env, Evaluator, Sample};
//! use fractal_dsl::number::math::{length, v3, V3};
//! use fractal_render::{CpuRenderer, Frame, KernelSources, RenderJob, Renderer};
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
//! let frame = Frame::default_view(&s, 0.0, 32, 32)?;
//! let job = RenderJob::new(KernelSources::default().with_cpu(&UnitSphere, &s), &frame);
//! let image = CpuRenderer::new().render(&job)?;
//! assert_eq!((image.width, image.height), (32, 32));
//! assert!(!image.is_uniform());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod backend;
pub mod camera;
pub mod choose_precision;
pub mod device;
pub mod error;
pub mod frame;
pub mod image;
pub mod limits;
pub mod precision;
pub mod progressive;
pub mod renderer;
pub mod select;

pub use backend::cpu::{render_scene, CpuRenderer};
#[cfg(feature = "opencl")]
pub use backend::opencl::{probe_opencl, OpenClRenderer};
pub use backend::wgpu::{probe_wgsl, WgpuRenderer};
pub use camera::{CameraPath, Pose};
pub use device::{Backend, DeviceInfo};
pub use error::{CameraError, FrameError, RenderError};
pub use frame::{Frame, LightSlot, ParamValues, MAX_IMAGE_SIDE, MAX_TIME};
pub use image::Image;
pub use precision::{Chosen, Precision, PrecisionChoice};
pub use renderer::{CpuKernel, KernelSources, PixelTrace, ProbeSample, RenderJob, Renderer, Traced};
pub use select::{select, AutoRenderer, BackendChoice, RendererOptions, UnknownBackend};
