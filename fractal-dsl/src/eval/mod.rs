//! Evaluating a scene: the [`plan`] (a scene prepared for evaluation), the [`walk`]er that gives every node its
//! meaning in any [`Num`] — run by the interpreter in f32/f64 and traced by the lowering into the kernels — and the
//! [`Evaluator`] interface shared by the interpreter (runtime scenes, the f64 accuracy reference) and the native
//! evaluator the `scene!` macro generates.
//!
//! Semantics every evaluator and kernel follows (written once, in [`walk`]):
//! - union: children in [`crate::analyse::union_order`] order; the nearest child's material wins (first on ties);
//!   a child containing a fractal with a finite bound is skipped while the point is at least as far from its bound as
//!   the nearest distance so far (its distance cannot be nearer);
//! - intersect: the farthest child's material; subtract and smooth subtract: the left operand's material;
//! - smooth union / intersect: materials mixed by [`crate::formula::blend_weight`];
//! - fractal leaves: estimate × [`crate::Fractal::step_factor_or_default`]; an orbit-trap material mixes its two
//!   colours by the trap; other leaves under an orbit-trap material take its first colour;
//! - the innermost `.material(..)` wins; geometry under none gets [`crate::Material::default_surface`].

pub mod interp;
pub mod packet;
pub mod plan;
pub mod walk;

use crate::number::math::{Num, Real, V3};

/// What an expression may read besides literals: the time, the parameter values (in [`crate::Scene::params`]
/// order), and — where a frame provides one — the perturbation reference of deep Mandelbrot patterns.
#[derive(Clone, Copy, Debug)]
pub struct Env<'a, F> {
    pub time: F,
    pub params: &'a [F],
    /// The frame's perturbation reference at the point being sampled; `None` evaluates those patterns around the
    /// reference point 0, which is the plain iteration
    /// ([`crate::formula::mandelbrot`](mod@crate::formula::mandelbrot)).
    pub reference: Option<Reference<'a, F>>,
    /// The frame's anchor A where the point is given relative to it: the scene is evaluated at A + p, and a
    /// translation by T met before any other operation subtracts T from A first, so a scene far from the origin
    /// seen from nearby keeps the precision it has at the origin (`None`: the point is the scene's own).
    pub anchor: Option<V3<F>>,
}

/// A frame's perturbation reference, as the sample at one point reads it. The reference point is the camera's
/// position R (held by the host in f64); a pattern `mandelbrot(x, z, n)` on a shape in world coordinates computes
/// c = (R.x + offset.x, R.z + offset.z) by perturbation around `orbit`, the orbit of (R.x, R.z).
#[derive(Clone, Copy, Debug)]
pub struct Reference<'a, F> {
    /// The point minus R: along a camera ray, the ray direction times t, exact to the precision of t however far
    /// the camera has zoomed in.
    pub offset: V3<F>,
    /// The orbit of the reference point's pattern coordinates ([`crate::formula::mandelbrot::reference_orbit`]).
    pub orbit: crate::number::Orbit<'a>,
}

impl<'a, F: Num> Env<'a, F> {
    /// An environment with these time and parameter values and no perturbation reference.
    pub fn new(time: F, params: &'a [F]) -> Env<'a, F> {
        Env { time, params, reference: None, anchor: None }
    }
    /// Time 0 and no parameters.
    pub fn still() -> Env<'static, F> {
        Env::new(F::lit(0.0), &[])
    }
    /// The point `p` relative to the perturbation reference: the reference's offset, or `p` itself around the
    /// reference point 0.
    #[inline]
    pub fn reference_offset(&self, p: V3<F>) -> V3<F> {
        self.reference.map_or(p, |r| r.offset)
    }
    /// The anchor, or the origin (what the native evaluator reads for [`crate::lower::code::FrameField::Anchor`]).
    #[inline]
    pub fn anchor(&self) -> V3<F> {
        self.anchor.unwrap_or(V3::splat(F::lit(0.0)))
    }
    /// The perturbation reference orbit, or the orbit of 0.
    #[inline]
    pub fn reference_orbit(&self) -> crate::number::Orbit<'a> {
        self.reference.map_or(crate::number::ORBIT_AT_ZERO, |r| r.orbit)
    }
}

/// The surface description at a point: distance and the material of the nearest geometry.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample<F> {
    pub distance: F,
    pub albedo: V3<F>,
    pub ambient: F,
    pub diffuse: F,
    pub specular: F,
    pub shininess: F,
}

/// A CPU evaluator of one scene in precision `F`.
pub trait Evaluator<F: Real>: Sync {
    /// Signed distance (a lower bound) from `p` to the scene.
    fn distance(&self, p: V3<F>, env: &Env<F>) -> F;
    /// Distance and material at `p`; never called by the march loop, only where a ray has hit.
    fn sample(&self, p: V3<F>, env: &Env<F>) -> Sample<F>;
    /// The normal at `p` of a scene shaded by its gradient ([`plan::Plan::shaded_by_gradient`]): the gradient's
    /// [`crate::number::math::direction`]. `None` for any other scene: the ray program takes its tetrahedral normal.
    fn normal(&self, _p: V3<F>, _env: &Env<F>) -> Option<V3<F>> {
        None
    }
    /// The same scene eight f32 points at a time, where the evaluator has a packet instance.
    fn packets(&self) -> Option<&dyn PacketEvaluator> {
        None
    }
}

/// An evaluator of eight f32 points at a time ([`crate::number::lanes::F32x8`]), lane for lane the arithmetic of its
/// f32 [`Evaluator`].
pub trait PacketEvaluator: Sync {
    fn distance_x8(
        &self,
        p: V3<crate::number::lanes::F32x8>,
        env: &Env<crate::number::lanes::F32x8>,
    ) -> crate::number::lanes::F32x8;
    /// Normals at eight points: [`Evaluator::normal`].
    fn normal_x8(
        &self,
        _p: V3<crate::number::lanes::F32x8>,
        _env: &Env<crate::number::lanes::F32x8>,
    ) -> Option<V3<crate::number::lanes::F32x8>> {
        None
    }
    /// Distances and materials at eight points.
    fn sample_x8(
        &self,
        p: V3<crate::number::lanes::F32x8>,
        env: &Env<crate::number::lanes::F32x8>,
    ) -> Sample<crate::number::lanes::F32x8>;
}
