//! What `scene!` expands to: a scene compiled at build time into kernel sources and a native evaluator.

use std::sync::OnceLock;

use crate::eval::{Env, Evaluator, Sample};
use crate::ir::Scene;
use crate::math::V3;

/// The native evaluator functions emitted by the Rust writer and compiled by rustc with the user's crate.
#[derive(Clone, Copy, Debug)]
pub struct NativeFns {
    pub distance_f32: fn(V3<f32>, &Env<f32>) -> f32,
    pub distance_f64: fn(V3<f64>, &Env<f64>) -> f64,
    pub sample_f32: fn(V3<f32>, &Env<f32>) -> Sample<f32>,
    pub sample_f64: fn(V3<f64>, &Env<f64>) -> Sample<f64>,
}

/// A scene compiled by `scene!`: the OpenCL C and WGSL render kernels, a native evaluator in f32 and f64, and the IR
/// (re-read from the canonical source the first time it is asked for).
#[derive(Debug)]
pub struct CompiledScene {
    source: &'static str,
    opencl: &'static str,
    wgsl: &'static str,
    native: NativeFns,
    scene: OnceLock<Scene>,
}

impl CompiledScene {
    /// Used by the macro's expansion; `source` is the canonical scene text the kernels were written from.
    #[doc(hidden)]
    pub const fn new(source: &'static str, opencl: &'static str, wgsl: &'static str, native: NativeFns) -> Self {
        CompiledScene { source, opencl, wgsl, native, scene: OnceLock::new() }
    }
    /// The complete OpenCL C program (kernel `render`).
    pub fn opencl(&self) -> &'static str {
        self.opencl
    }
    /// The complete WGSL module (entry point `render`).
    pub fn wgsl(&self) -> &'static str {
        self.wgsl
    }
    /// The scene in canonical `.fractal` syntax.
    pub fn source(&self) -> &'static str {
        self.source
    }
    /// The scene's IR.
    pub fn scene(&self) -> &Scene {
        self.scene.get_or_init(|| {
            crate::parse::parse_str(self.source)
                .unwrap_or_else(|e| unreachable!("canonical scene text written by the compiler reads back: {e}"))
        })
    }
    pub fn native(&self) -> NativeFns {
        self.native
    }
    /// Distance at `p` by the native f32 evaluator, at time 0 with parameters at their defaults.
    pub fn distance(&self, p: impl Into<glam::Vec3>) -> f32 {
        let params = self.default_params::<f32>();
        (self.native.distance_f32)(p.into().into(), &Env { time: 0.0, params: &params })
    }
    /// Distance at `p` by the native f64 evaluator (the twin for reference work).
    pub fn distance_f64(&self, p: impl Into<glam::DVec3>) -> f64 {
        let params = self.default_params::<f64>();
        (self.native.distance_f64)(p.into().into(), &Env { time: 0.0, params: &params })
    }
    /// Parameter defaults in uniform order.
    pub fn default_params<F: crate::math::Real>(&self) -> Vec<F> {
        self.scene().params().iter().map(|p| F::c(p.default)).collect()
    }
}

impl Evaluator<f32> for NativeFns {
    fn distance(&self, p: V3<f32>, env: &Env<f32>) -> f32 {
        (self.distance_f32)(p, env)
    }
    fn sample(&self, p: V3<f32>, env: &Env<f32>) -> Sample<f32> {
        (self.sample_f32)(p, env)
    }
}

impl Evaluator<f64> for NativeFns {
    fn distance(&self, p: V3<f64>, env: &Env<f64>) -> f64 {
        (self.distance_f64)(p, env)
    }
    fn sample(&self, p: V3<f64>, env: &Env<f64>) -> Sample<f64> {
        (self.sample_f64)(p, env)
    }
}

/// Everything the compiler writes for one scene.
#[derive(Clone, Debug)]
pub struct Kernels {
    /// Canonical scene source.
    pub source: String,
    /// OpenCL C program with kernel `render`.
    pub opencl: String,
    /// WGSL module with entry point `render`.
    pub wgsl: String,
    /// The lowered program (for the probe kernels and the native evaluator's source).
    pub program: crate::lower::Program,
}

/// Compiles a scene: lowers it once and spells the render kernels in both GPU languages.
pub fn compile(scene: &Scene) -> Kernels {
    let program = crate::lower::lower(scene);
    Kernels {
        source: crate::print::to_source(scene),
        opencl: crate::back::opencl::write(&program, crate::back::Entry::Render),
        wgsl: crate::back::wgsl::write(&program, crate::back::Entry::Render),
        program,
    }
}
