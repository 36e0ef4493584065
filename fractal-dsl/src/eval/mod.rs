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
//! - smooth union / intersect: materials mixed by [`crate::sdf::blend_weight`];
//! - fractal leaves: estimate × [`crate::Fractal::step_factor`]; an orbit-trap material mixes its two colours by
//!   the trap; other leaves under an orbit-trap material take its first colour;
//! - the innermost `.material(..)` wins; geometry under none gets [`crate::Material::default_surface`].

pub mod interp;
pub mod plan;
pub mod walk;

use crate::math::{Num, Real, V3};

/// What an expression may read besides literals: the time and the parameter values (in [`crate::Scene::params`]
/// order).
#[derive(Clone, Copy, Debug)]
pub struct Env<'a, F> {
    pub time: F,
    pub params: &'a [F],
}

impl<F: Num> Env<'_, F> {
    /// Time 0 and no parameters.
    pub fn still() -> Env<'static, F> {
        Env { time: F::lit(0.0), params: &[] }
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
}
