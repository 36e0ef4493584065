//! The one interface every renderer implements: a [`RenderJob`] (the scene's kernels plus the frame uniforms) in,
//! an [`Image`] out — or, from the scene's trace kernels, the image and each pixel's march ([`Traced`]: depth,
//! normal, steps) — and a description of the device that drew it ([`DeviceInfo`], which lives with [`Backend`] in
//! [`crate::device`] and is re-exported here).
//!
//! A job carries every form of the scene a caller has (WGSL, OpenCL C, a CPU evaluator); each renderer takes the one
//! it runs, so the same job can be handed to whichever backend was selected, or retried on the next one.

use std::fmt;

use fractal_dsl::back::Scalar;
use fractal_dsl::eval::Evaluator;
use fractal_dsl::Scene;

pub use crate::device::{Backend, DeviceInfo};
use crate::error::RenderError;
use crate::frame::Frame;
use crate::image::Image;
use crate::precision::Precision;

/// One probe result: `[distance, ambient, diffuse, specular, albedo.r, albedo.g, albedo.b, shininess]`.
pub type ProbeSample = [f32; 8];

/// What the CPU renderer runs: an f32 evaluator of the scene (native or interpreted), the f64 one where the caller
/// has it (for frames drawn in [`Precision::F64`]), and the scene itself (for its render settings, bound and
/// materials).
#[derive(Clone, Copy)]
pub struct CpuKernel<'a> {
    pub evaluator: &'a dyn Evaluator<f32>,
    pub wide: Option<&'a dyn Evaluator<f64>>,
    pub scene: &'a Scene,
}

impl fmt::Debug for CpuKernel<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("CpuKernel").finish_non_exhaustive()
    }
}

/// The forms of one scene a job carries; a renderer uses the one for its backend.
#[derive(Clone, Copy, Debug, Default)]
pub struct KernelSources<'a> {
    /// WGSL module with entry `render` (see [`fractal_dsl::back::Entry::Render`]).
    pub wgsl: Option<&'a str>,
    /// The same WGSL module in f64 ([`fractal_dsl::back::Scalar::F64`]), for a job in f64.
    pub wgsl_f64: Option<&'a str>,
    /// OpenCL C program with kernel `render`.
    pub opencl: Option<&'a str>,
    /// The same OpenCL C program in f64 ([`fractal_dsl::back::Scalar::F64`]), for a job in f64.
    pub opencl_f64: Option<&'a str>,
    pub cpu: Option<CpuKernel<'a>>,
}

impl<'a> KernelSources<'a> {
    /// The WGSL and OpenCL C render kernels the scene compiler wrote ([`fractal_dsl::compile`]).
    pub fn compiled(kernels: &'a fractal_dsl::Kernels) -> Self {
        KernelSources {
            wgsl: Some(&kernels.wgsl),
            wgsl_f64: Some(&kernels.wgsl_f64),
            opencl: Some(&kernels.opencl),
            opencl_f64: Some(&kernels.opencl_f64),
            cpu: None,
        }
    }
    pub fn with_wgsl(mut self, source: &'a str) -> Self {
        self.wgsl = Some(source);
        self
    }
    /// The WGSL module in f64 ([`KernelSources::wgsl_f64`]).
    pub fn with_wgsl_f64(mut self, source: &'a str) -> Self {
        self.wgsl_f64 = Some(source);
        self
    }
    pub fn with_opencl(mut self, source: &'a str) -> Self {
        self.opencl = Some(source);
        self
    }
    /// The OpenCL C program in f64 ([`KernelSources::opencl_f64`]).
    pub fn with_opencl_f64(mut self, source: &'a str) -> Self {
        self.opencl_f64 = Some(source);
        self
    }
    pub fn with_cpu(mut self, evaluator: &'a dyn Evaluator<f32>, scene: &'a Scene) -> Self {
        self.cpu = Some(CpuKernel { evaluator, wide: None, scene });
        self
    }
    /// The CPU kernel's f64 evaluator (after [`KernelSources::with_cpu`]; without a CPU kernel it is not kept).
    pub fn with_cpu_wide(mut self, wide: &'a dyn Evaluator<f64>) -> Self {
        if let Some(cpu) = &mut self.cpu {
            cpu.wide = Some(wide);
        }
        self
    }
}

/// One image to render. Its size is the frame's: the kernels read it from the uniforms.
#[derive(Clone, Copy, Debug)]
pub struct RenderJob<'a> {
    pub kernels: KernelSources<'a>,
    pub frame: &'a Frame,
    /// The number type to draw it in ([`crate::precision`]); f32 unless set.
    pub precision: Precision,
}

impl<'a> RenderJob<'a> {
    pub fn new(kernels: KernelSources<'a>, frame: &'a Frame) -> Self {
        RenderJob { kernels, frame, precision: Precision::F32 }
    }
    pub fn with_precision(mut self, precision: Precision) -> Self {
        self.precision = precision;
        self
    }
    /// Whether a GPU device draws this job from its program `forms` (f32, f64): in f32 always, in f64 where the
    /// device computes in it (`fp64`) and the job carries the f64 program.
    pub fn gpu_draws(&self, forms: [Option<&'a str>; 2], fp64: bool) -> bool {
        match self.precision {
            Precision::F32 => true,
            Precision::F64 => fp64 && forms[1].is_some(),
        }
    }
    /// The program of the job's precision among `forms` (f32, f64) for a GPU `backend` (whose program is named
    /// `what`), and the number type it computes in; refused where the device lacks the precision ([`Self::gpu_draws`]).
    pub fn gpu_program(
        &self,
        (backend, what): (Backend, &'static str),
        forms: [Option<&'a str>; 2],
        fp64: bool,
    ) -> Result<(&'a str, Scalar), RenderError> {
        if !self.gpu_draws(forms, fp64) {
            return Err(self.refused(backend));
        }
        let (source, scalar) = match self.precision {
            Precision::F32 => (forms[0], Scalar::F32),
            Precision::F64 => (forms[1], Scalar::F64),
        };
        Ok((source.ok_or(RenderError::MissingKernel { backend, what })?, scalar))
    }
    /// What `backend` says of a job it does not draw in the job's precision ([`Renderer::draws_in`]).
    pub fn refused(&self, backend: Backend) -> RenderError {
        RenderError::Precision { backend, precision: self.precision }
    }
    pub fn width(&self) -> u32 {
        self.frame.width()
    }
    pub fn height(&self) -> u32 {
        self.frame.height()
    }
}

/// What the render algorithm did at one pixel, beside its colour: the figures accuracy work compares with the truth,
/// and the depth and normal images a render writes beside its colours.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelTrace {
    /// Linear colour before display (NaN or Inf here is a broken pixel even when packing hides it): the centre ray's
    /// with one sample, else the mean of the samples clamped to [0, 1] ([`fractal_dsl::ray::pixel`]).
    pub colour: [f64; 3],
    /// Samples the pixel took. The other fields are its centre ray's (sample 0).
    pub samples: u32,
    /// Whether the march hit the surface.
    pub hit: bool,
    /// Where the march stopped: the hit, or the last t of a miss (past the end of the ray, or where the steps ran
    /// out); NaN for a ray that misses the scene bound.
    pub t: f64,
    /// March steps taken.
    pub steps: u32,
    /// The march used all its steps without hitting or leaving the ray.
    pub out_of_steps: bool,
    /// The shading normal at a hit.
    pub normal: Option<[f64; 3]>,
    /// Distance evaluations for the whole pixel (march, normal, occlusion, shadows), where the renderer counts them
    /// (the CPU's; a kernel does not).
    pub evaluations: Option<u64>,
}

impl Default for PixelTrace {
    fn default() -> Self {
        PixelTrace {
            colour: [0.0; 3],
            samples: 1,
            hit: false,
            t: f64::NAN,
            steps: 0,
            out_of_steps: false,
            normal: None,
            evaluations: None,
        }
    }
}

impl PixelTrace {
    /// Words per pixel of a `trace` kernel's output ([`fractal_dsl::back::Entry::Trace`]): three float4 slots.
    pub const KERNEL_WORDS: usize = 12;

    /// A pixel as a `trace` kernel wrote it: (normal, t), (steps, hit, out of steps, samples), (colour, 0).
    pub fn from_kernel(words: &[f32]) -> PixelTrace {
        let w = |i: usize| f64::from(words[i]);
        let (hit, steps) = (words[5] > 0.5, words[4] as u32);
        PixelTrace {
            colour: [w(8), w(9), w(10)],
            samples: words[7] as u32,
            hit,
            // A ray that misses the scene's bound takes no step; the CPU's trace has no t for it either.
            t: if hit || steps > 0 { w(3) } else { f64::NAN },
            steps,
            out_of_steps: words[6] > 0.5,
            normal: hit.then(|| [w(0), w(1), w(2)]),
            evaluations: None,
        }
    }
}

/// A render with every pixel's march ([`Renderer::trace`]).
#[derive(Clone, Debug)]
pub struct Traced {
    pub image: Image,
    /// Row-major, one per pixel of the image.
    pub pixels: Vec<PixelTrace>,
}

impl Traced {
    /// A trace kernel's image and its output words, [`PixelTrace::KERNEL_WORDS`] per pixel.
    pub fn from_kernel(image: Image, words: &[f32]) -> Traced {
        Traced { image, pixels: words.chunks_exact(PixelTrace::KERNEL_WORDS).map(PixelTrace::from_kernel).collect() }
    }
}

/// A renderer: draws jobs on one device. `Send`, so a viewer can keep it on a render thread.
pub trait Renderer: Send {
    /// Renders the job's scene into an image of the frame's size.
    fn render(&mut self, job: &RenderJob) -> Result<Image, RenderError>;
    /// Renders each job, results in the jobs' order: a sequence's next frames. A GPU renderer keeps several frames
    /// in flight, drawing the next ones while the host reads one; the default renders them one after another.
    fn render_batch(&mut self, jobs: &[RenderJob]) -> Vec<Result<Image, RenderError>> {
        jobs.iter().map(|job| self.render(job)).collect()
    }
    /// Renders the job's scene and keeps what the march did at each pixel. A GPU renderer runs the job's `trace`
    /// kernels ([`fractal_dsl::Kernels::tracing`]) in place of its render kernels; the CPU renderer its evaluator.
    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError>;
    /// The device this renderer draws on.
    fn device(&self) -> DeviceInfo;
    /// Whether this renderer draws `job` in the job's precision: f32 everywhere; f64 where the backend's device
    /// computes in it and the job carries the kernel for it. A job it does not draw is refused
    /// ([`RenderError::Precision`]), and the auto renderer draws it on the CPU.
    fn draws_in(&self, job: &RenderJob) -> bool {
        job.precision == Precision::F32
    }
    /// Messages about backend changes since the last call (a fallback chain reports which backend failed and why).
    fn take_notes(&mut self) -> Vec<String> {
        Vec::new()
    }
}

impl<R: Renderer + ?Sized> Renderer for Box<R> {
    fn render(&mut self, job: &RenderJob) -> Result<Image, RenderError> {
        (**self).render(job)
    }
    fn render_batch(&mut self, jobs: &[RenderJob]) -> Vec<Result<Image, RenderError>> {
        (**self).render_batch(jobs)
    }
    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError> {
        (**self).trace(job)
    }
    fn device(&self) -> DeviceInfo {
        (**self).device()
    }
    fn draws_in(&self, job: &RenderJob) -> bool {
        (**self).draws_in(job)
    }
    fn take_notes(&mut self) -> Vec<String> {
        (**self).take_notes()
    }
}
