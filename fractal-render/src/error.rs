//! The renderer's errors: what can go wrong packing a frame, placing a camera, or running a kernel on a device.
//! Nothing here panics on a missing GPU or driver; every failure is one of these values with a message a user can act
//! on.

use crate::device::Backend;
use crate::limits::MAX_TIME;
use fractal_dsl::validate::number_text;

/// A camera that cannot be placed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CameraError {
    #[error("the camera path has no keys")]
    EmptyPath,
    #[error("camera key {index} has a non-finite time, position or target")]
    NonFiniteKey { index: usize },
    #[error("the camera looks at its own position {position:?}: no view direction")]
    NoViewDirection { position: [f64; 3] },
    #[error("camera position or target is not finite at time {time}")]
    NonFinite { time: f64 },
    #[error("field of view {0} degrees is outside (0, 180)")]
    FieldOfView(f64),
}

/// Frame uniforms that cannot be packed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FrameError {
    #[error("image size {width}x{height} is invalid: each side must be 1..={max}")]
    ImageSize { width: u32, height: u32, max: u32 },
    #[error("the scene has {expected} parameters, {got} values were given")]
    ParamCount { expected: usize, got: usize },
    #[error("the parameter values were made for another scene (expected parameter `{expected}`, found `{found}`)")]
    ParamMismatch { expected: String, found: String },
    #[error("the scene has no parameter named `{0}`")]
    UnknownParam(String),
    #[error("parameter `{name}` = {} is outside its range {}..{}", number_text(*.value), number_text(*.min), number_text(*.max))]
    ParamOutOfRange { name: String, value: f64, min: f64, max: f64 },
    /// `index` counts from 0; messages number lights from 1, as the validator does.
    #[error("light {}: {what} is not finite at time {}", index + 1, number_text(*time))]
    NonFiniteLight { index: usize, what: &'static str, time: f64 },
    #[error("`{expr}` is {} at time {}: the shape it sizes or places cannot be drawn then", number_text(*.value), number_text(*.time))]
    NonFiniteValue { expr: String, value: f64, time: f64 },
    #[error("light {}: the direction is zero at time {}", index + 1, number_text(*time))]
    ZeroLightDirection { index: usize, time: f64 },
    #[error("time {} is outside ±{} s: the kernels keep time in f32, which cannot tell frames apart beyond that", number_text(*.0), number_text(MAX_TIME))]
    Time(f64),
    #[error("the frame has {got} slots, its layout needs {expected}")]
    SlotCount { expected: usize, got: usize },
    #[error(transparent)]
    Camera(#[from] CameraError),
}

/// A render or probe that did not produce a result.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// No device of this backend could be opened (no adapter, no platform, no driver).
    #[error("no {backend} device: {reason}")]
    NoDevice { backend: Backend, reason: String },
    /// The backend was left out of this build.
    #[error("the {backend} backend is not in this build: {hint}")]
    NotBuilt { backend: Backend, hint: &'static str },
    /// The driver refused the kernel (compile, validation or link error); `log` is the driver's message.
    #[error("the {backend} driver rejected the kernel:\n{log}")]
    KernelRejected { backend: Backend, log: String },
    /// The job has nothing this backend can run.
    #[error("the job has no {what} for the {backend} backend")]
    MissingKernel { backend: Backend, what: &'static str },
    /// The image or point set does not fit the device's limits.
    #[error("{what} does not fit the {backend} device: {detail}")]
    TooLarge { backend: Backend, what: String, detail: String },
    /// The device failed while running or reading back (device lost, out of memory, driver error).
    #[error("{backend} device error: {message}")]
    Device { backend: Backend, message: String },
    #[error(transparent)]
    Frame(#[from] FrameError),
    /// The scene breaks a rule of the language (only scenes made with the builder can reach a renderer so).
    #[error(transparent)]
    InvalidScene(#[from] fractal_dsl::validate::InvalidScene),
    /// The backend does not draw in the job's precision ([`crate::renderer::Renderer::draws_in`]).
    #[error(
        "the {backend} device does not compute in {precision} (wgpu needs SHADER_F64, OpenCL cl_khr_fp64); \
         the frame renders on the CPU with --backend cpu or auto"
    )]
    Precision { backend: Backend, precision: crate::precision::Precision },
    /// Every backend `auto` tried failed; one line per backend.
    #[error("no backend could render:\n{}", .0.join("\n"))]
    AllBackendsFailed(Vec<String>),
}

impl RenderError {
    /// Whether another backend might succeed where this one failed (the device or its driver is the problem, not the
    /// job).
    pub fn is_backend_specific(&self) -> bool {
        matches!(
            self,
            RenderError::NoDevice { .. }
                | RenderError::NotBuilt { .. }
                | RenderError::KernelRejected { .. }
                | RenderError::MissingKernel { .. }
                | RenderError::TooLarge { .. }
                | RenderError::Device { .. }
        )
    }
}
