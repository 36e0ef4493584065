//! What `scene!` expands to: a scene compiled at build time into kernel sources, a native evaluator, its parameters'
//! defaults and code that constructs its IR.

use std::sync::OnceLock;

use crate::back::{opencl, wgsl, Entry, Scalar};
use crate::eval::{Env, Evaluator, PacketEvaluator, Sample};
use crate::ir::Scene;
use crate::number::lanes::F32x8;
use crate::number::math::{Real, V3};

/// The native evaluator functions emitted by the Rust writer and compiled by rustc with the user's crate.
#[derive(Clone, Copy, Debug)]
pub struct NativeFns {
    pub distance_f32: fn(V3<f32>, &Env<f32>) -> f32,
    pub distance_f64: fn(V3<f64>, &Env<f64>) -> f64,
    pub sample_f32: fn(V3<f32>, &Env<f32>) -> Sample<f32>,
    pub sample_f64: fn(V3<f64>, &Env<f64>) -> Sample<f64>,
    /// Eight points at a time ([`F32x8`] lanes): the f32 code on packets, lane for lane the same arithmetic.
    pub distance_x8: fn(V3<F32x8>, &Env<F32x8>) -> F32x8,
    pub sample_x8: fn(V3<F32x8>, &Env<F32x8>) -> Sample<F32x8>,
    /// `distance_x8` over slices of one length (x, y, z, out), the loop compiled with the packet instance: one call
    /// for a whole slice ([`crate::eval::packet::each_packet`]).
    pub distance_slice_x8: DistanceSliceFn,
    /// The normal of a scene shaded by its gradient ([`crate::lower::Program::normal`]), in f32, f64 and on
    /// packets; `None` for any other scene.
    pub normal: Option<NormalFns>,
}

/// The native evaluator's normal functions ([`NativeFns::normal`]).
#[derive(Clone, Copy, Debug)]
pub struct NormalFns {
    pub f32: fn(V3<f32>, &Env<f32>) -> V3<f32>,
    pub f64: fn(V3<f64>, &Env<f64>) -> V3<f64>,
    pub x8: fn(V3<F32x8>, &Env<F32x8>) -> V3<F32x8>,
}

/// The native evaluator's packet distance over slices: `(x, y, z, out, env)`, `out[i]` the distance at the i-th point.
pub type DistanceSliceFn = fn(&[f32], &[f32], &[f32], &mut [f32], &Env<F32x8>);

/// The defaults of a scene's parameters in [`Scene::params`] order, in both precisions the native evaluator runs in:
/// the parameter block of [`CompiledScene::distance`], written by the macro as constants.
#[derive(Clone, Copy, Debug)]
pub struct DefaultParams {
    pub f32: &'static [f32],
    pub f64: &'static [f64],
}

impl DefaultParams {
    /// A scene without parameters.
    pub const NONE: DefaultParams = DefaultParams { f32: &[], f64: &[] };
}

/// A precision a [`CompiledScene`] carries its default parameters in: f32 or f64.
pub trait CompiledReal: Real {
    /// The defaults in this precision.
    fn defaults(defaults: &DefaultParams) -> &'static [Self];
}

impl CompiledReal for f32 {
    fn defaults(defaults: &DefaultParams) -> &'static [f32] {
        defaults.f32
    }
}

impl CompiledReal for f64 {
    fn defaults(defaults: &DefaultParams) -> &'static [f64] {
        defaults.f64
    }
}

/// A scene compiled by `scene!`: the OpenCL C and WGSL render kernels, a native evaluator in f32 and f64, the
/// parameters' defaults, and the IR (constructed by code the macro wrote, the first time it is asked for).
#[derive(Debug)]
pub struct CompiledScene {
    source: &'static str,
    opencl: &'static str,
    opencl_f64: &'static str,
    wgsl: &'static str,
    wgsl_f64: &'static str,
    native: NativeFns,
    build: fn() -> Scene,
    defaults: DefaultParams,
    scene: OnceLock<Scene>,
}

impl CompiledScene {
    /// Used by the macro's expansion; `source` is the canonical scene text the kernels were written from, `build`
    /// constructs its IR and `defaults` are its parameters' defaults.
    #[doc(hidden)]
    pub const fn new(
        source: &'static str,
        (opencl, opencl_f64): (&'static str, &'static str),
        (wgsl, wgsl_f64): (&'static str, &'static str),
        native: NativeFns,
        build: fn() -> Scene,
        defaults: DefaultParams,
    ) -> Self {
        CompiledScene { source, opencl, opencl_f64, wgsl, wgsl_f64, native, build, defaults, scene: OnceLock::new() }
    }
    /// The complete OpenCL C program (kernel `render`).
    pub fn opencl(&self) -> &'static str {
        self.opencl
    }
    /// The same OpenCL C program computing in f64, for devices with `cl_khr_fp64` ([`Kernels::opencl_f64`]).
    pub fn opencl_f64(&self) -> &'static str {
        self.opencl_f64
    }
    /// The complete WGSL module (entry point `render`).
    pub fn wgsl(&self) -> &'static str {
        self.wgsl
    }
    /// The same WGSL module computing in f64, for devices with `SHADER_F64` ([`Kernels::wgsl_f64`]).
    pub fn wgsl_f64(&self) -> &'static str {
        self.wgsl_f64
    }
    /// The scene in canonical `.fractal` syntax.
    pub fn source(&self) -> &'static str {
        self.source
    }
    /// The scene's IR, built once on first use.
    pub fn scene(&self) -> &Scene {
        self.scene.get_or_init(self.build)
    }
    /// The native evaluator, for callers that prepare their own [`Env`] (time, parameter values).
    pub fn native(&self) -> NativeFns {
        self.native
    }
    /// Distance at `p` by the native f32 evaluator, at time 0 with parameters at their defaults: one call.
    pub fn distance(&self, p: impl Into<glam::Vec3>) -> f32 {
        (self.native.distance_f32)(p.into().into(), &Env::new(0.0, self.defaults.f32))
    }
    /// Distance at `p` by the native f64 evaluator (the twin for reference work).
    pub fn distance_f64(&self, p: impl Into<glam::DVec3>) -> f64 {
        (self.native.distance_f64)(p.into().into(), &Env::new(0.0, self.defaults.f64))
    }
    /// Parameter defaults in uniform order ([`Scene::params`] order), in precision `F`.
    pub fn default_params<F: CompiledReal>(&self) -> &'static [F] {
        F::defaults(&self.defaults)
    }

    /// Distances at many points by the native evaluator, eight at a time on the calling thread, at time 0 with the
    /// parameters at their defaults: `out[i]` is the distance at `(x[i], y[i], z[i])`, the same as
    /// [`CompiledScene::distance`] gives. Panics if the four slices' lengths differ.
    pub fn distance_slice(&self, x: &[f32], y: &[f32], z: &[f32], out: &mut [f32]) {
        self.native.distance_slice(0.0, self.defaults.f32, x, y, z, out)
    }

    /// [`CompiledScene::distance_slice`] by the f64 evaluator, a point at a time. Panics if the lengths differ.
    pub fn distance_slice_f64(&self, x: &[f64], y: &[f64], z: &[f64], out: &mut [f64]) {
        assert!(
            x.len() == y.len() && y.len() == z.len() && z.len() == out.len(),
            "slices of unequal length: x {}, y {}, z {}, out {}",
            x.len(),
            y.len(),
            z.len(),
            out.len()
        );
        let env = Env::new(0.0, self.defaults.f64);
        for (i, d) in out.iter_mut().enumerate() {
            *d = (self.native.distance_f64)(V3 { x: x[i], y: y[i], z: z[i] }, &env);
        }
    }

    /// Distances and materials at many points, eight at a time; see [`CompiledScene::distance_slice`].
    pub fn sample_slice(&self, x: &[f32], y: &[f32], z: &[f32], out: &mut [Sample<f32>]) {
        self.native.sample_slice(0.0, self.defaults.f32, x, y, z, out)
    }
}

impl NativeFns {
    /// Distances at many points at `time` with parameter values `params` ([`Scene::params`] order), eight at a
    /// time on the calling thread ([`crate::eval::packet`]). Panics if the lengths differ.
    #[allow(clippy::too_many_arguments)]
    pub fn distance_slice(&self, time: f32, params: &[f32], x: &[f32], y: &[f32], z: &[f32], out: &mut [f32]) {
        use crate::eval::packet::{common_length, splat_params};
        common_length(x, y, z, out.len());
        let params = splat_params(params);
        (self.distance_slice_x8)(x, y, z, out, &Env::new(F32x8::splat(time), &params))
    }

    /// Distances and materials at many points; see [`NativeFns::distance_slice`].
    #[allow(clippy::too_many_arguments)]
    pub fn sample_slice(&self, time: f32, params: &[f32], x: &[f32], y: &[f32], z: &[f32], out: &mut [Sample<f32>]) {
        crate::eval::packet::sample_slice(self.sample_x8, time, params, x, y, z, out)
    }
}

impl Evaluator<f32> for NativeFns {
    fn distance(&self, p: V3<f32>, env: &Env<f32>) -> f32 {
        (self.distance_f32)(p, env)
    }
    fn sample(&self, p: V3<f32>, env: &Env<f32>) -> Sample<f32> {
        (self.sample_f32)(p, env)
    }
    fn normal(&self, p: V3<f32>, env: &Env<f32>) -> Option<V3<f32>> {
        self.normal.map(|n| (n.f32)(p, env))
    }
    fn packets(&self) -> Option<&dyn PacketEvaluator> {
        Some(self)
    }
}

impl PacketEvaluator for NativeFns {
    fn distance_x8(&self, p: V3<F32x8>, env: &Env<F32x8>) -> F32x8 {
        (self.distance_x8)(p, env)
    }
    fn sample_x8(&self, p: V3<F32x8>, env: &Env<F32x8>) -> Sample<F32x8> {
        (self.sample_x8)(p, env)
    }
    fn normal_x8(&self, p: V3<F32x8>, env: &Env<F32x8>) -> Option<V3<F32x8>> {
        self.normal.map(|n| (n.x8)(p, env))
    }
}

impl Evaluator<f64> for NativeFns {
    fn distance(&self, p: V3<f64>, env: &Env<f64>) -> f64 {
        (self.distance_f64)(p, env)
    }
    fn sample(&self, p: V3<f64>, env: &Env<f64>) -> Sample<f64> {
        (self.sample_f64)(p, env)
    }
    fn normal(&self, p: V3<f64>, env: &Env<f64>) -> Option<V3<f64>> {
        self.normal.map(|n| (n.f64)(p, env))
    }
}

/// Everything the compiler writes for one scene.
#[derive(Clone, Debug)]
pub struct Kernels {
    /// Canonical scene source.
    pub source: String,
    /// OpenCL C program with kernel `render`.
    pub opencl: String,
    /// The same OpenCL C program computing in f64 ([`crate::back::Scalar::F64`]), for devices with `cl_khr_fp64`.
    pub opencl_f64: String,
    /// WGSL module with entry point `render`.
    pub wgsl: String,
    /// The same WGSL module computing in f64, for devices with `SHADER_F64`.
    pub wgsl_f64: String,
    /// The lowered program (for the probe kernels and the native evaluator's source).
    pub program: crate::lower::Program,
}

impl Kernels {
    /// The same scene's `trace` kernels ([`crate::back::Entry::Trace`]) in place of the render kernels: the render
    /// that also writes each pixel's depth, normal and march, for measuring a GPU's render and for depth images.
    pub fn tracing(&self) -> Kernels {
        Kernels {
            opencl: opencl::write(&self.program, Entry::Trace),
            opencl_f64: opencl::write_in(&self.program, Entry::Trace, Scalar::F64),
            wgsl: wgsl::write(&self.program, Entry::Trace),
            wgsl_f64: wgsl::write_in(&self.program, Entry::Trace, Scalar::F64),
            ..self.clone()
        }
    }
}

/// Compiles a scene: validates it, lowers it once and spells the render kernels in both GPU languages, in f32 and in
/// f64.
pub fn compile(scene: &Scene) -> Result<Kernels, crate::validate::InvalidScene> {
    crate::validate::checked(scene)?;
    let program = crate::lower::lower(scene);
    Ok(Kernels {
        source: crate::print::to_source(scene),
        opencl: opencl::write(&program, Entry::Render),
        opencl_f64: opencl::write_in(&program, Entry::Render, Scalar::F64),
        wgsl: wgsl::write(&program, Entry::Render),
        wgsl_f64: wgsl::write_in(&program, Entry::Render, Scalar::F64),
        program,
    })
}
