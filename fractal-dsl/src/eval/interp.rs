//! The interpreter: runs a scene's [`Plan`] with the [`Walk`]er in f32 or f64. The f64 instance is the accuracy
//! reference. The plan settles everything that does not depend on the point ahead, so evaluation allocates nothing;
//! the walker is the same code the lowering traces into the kernels, so the two agree to the last bit wherever the
//! math functions do.

use crate::eval::plan::Plan;
use crate::eval::walk::Walk;
use crate::eval::{Env, Evaluator, PacketEvaluator, Sample};
use crate::formula::CallLeaf;
use crate::ir::*;
use crate::number::lanes::F32x8;
use crate::number::math::{direction, Real, V3};

/// Evaluates a scene by walking its plan; see [`crate::eval`] for the rules.
#[derive(Clone, Debug)]
pub struct Interpreter {
    plan: Plan,
    guards: bool,
    /// [`Plan::shaded_by_gradient`].
    gradient: bool,
}

impl Interpreter {
    /// Validates, folds and prepares `scene`. [`Env::params`] slot i holds the value of `scene.params()[i]`.
    pub fn new(scene: &Scene) -> Result<Interpreter, crate::validate::InvalidScene> {
        crate::validate::checked(scene)?;
        let plan = Plan::new(scene);
        Ok(Interpreter { gradient: plan.shaded_by_gradient(), plan, guards: true })
    }

    /// The same scene with every union child evaluated, guard boxes ignored: the reference the guards are tested
    /// against.
    pub fn without_bound_guards(mut self) -> Interpreter {
        self.guards = false;
        self
    }

    /// The same scene with `f` applied to each fractal written in the scene language (to attach its host code:
    /// [`crate::lower::tape::attach`]).
    pub fn with_formula_calls(mut self, f: &mut impl FnMut(&mut crate::eval::plan::FormulaCall)) -> Interpreter {
        self.plan.formula_calls_mut(f);
        self
    }

    /// The parameters in slot order.
    pub fn params(&self) -> &[ParamDecl] {
        &self.plan.params
    }

    /// Parameter defaults in slot order, for building an [`Env`].
    pub fn default_params<F: Real>(&self) -> Vec<F> {
        self.plan.params.iter().map(|p| F::c(p.default)).collect()
    }

    fn walk(&self) -> Walk<'_> {
        Walk { plan: &self.plan, guards: self.guards }
    }

    /// Signed distance in precision `F`.
    pub fn distance_in<F: Real + CallLeaf>(&self, p: V3<F>, env: &Env<F>) -> F {
        self.walk().distance(p, env)
    }

    /// The normal in precision `F` where the scene is shaded by its gradient ([`Evaluator::normal`]).
    pub fn normal_in<F: CallLeaf>(&self, p: V3<F>, env: &Env<F>) -> Option<V3<F>> {
        self.gradient.then(|| direction(self.walk().gradient(p, env)))
    }

    /// Distance and material in precision `F`.
    pub fn sample_in<F: Real + CallLeaf>(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        self.walk().sample(p, env)
    }

    /// Distances at many points, eight at a time ([`crate::eval::packet`]): `out[i]` is the distance at
    /// `(x[i], y[i], z[i])` at `time` with parameter values `params` (slot order). Panics if the lengths differ.
    pub fn distance_slice(&self, time: f32, params: &[f32], x: &[f32], y: &[f32], z: &[f32], out: &mut [f32]) {
        let walk = self.walk();
        crate::eval::packet::distance_slice(|p, env| walk.distance(p, env), time, params, x, y, z, out)
    }

    /// Distances and materials at many points, eight at a time; see [`Interpreter::distance_slice`].
    pub fn sample_slice(&self, time: f32, params: &[f32], x: &[f32], y: &[f32], z: &[f32], out: &mut [Sample<f32>]) {
        let walk = self.walk();
        crate::eval::packet::sample_slice(|p, env| walk.sample(p, env), time, params, x, y, z, out)
    }
}

impl<F: Real + CallLeaf> Evaluator<F> for Interpreter {
    fn distance(&self, p: V3<F>, env: &Env<F>) -> F {
        self.distance_in(p, env)
    }
    fn sample(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        self.sample_in(p, env)
    }
    fn normal(&self, p: V3<F>, env: &Env<F>) -> Option<V3<F>> {
        self.normal_in(p, env)
    }
    fn packets(&self) -> Option<&dyn PacketEvaluator> {
        Some(self)
    }
}

impl PacketEvaluator for Interpreter {
    fn distance_x8(&self, p: V3<F32x8>, env: &Env<F32x8>) -> F32x8 {
        self.walk().distance(p, env)
    }
    fn sample_x8(&self, p: V3<F32x8>, env: &Env<F32x8>) -> Sample<F32x8> {
        self.walk().sample(p, env)
    }
    fn normal_x8(&self, p: V3<F32x8>, env: &Env<F32x8>) -> Option<V3<F32x8>> {
        self.normal_in(p, env)
    }
}
