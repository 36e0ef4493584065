//! Fractals in the IR: a [`Fractal`] is a [`FractalDecl`] (the family: name, constructor argument, iteration rule,
//! which settings apply, the leaf call, step factor and bound) with its values. Families are declared once
//! (`crate::vocab::fractals`); every reader works from the declaration.

use super::formula::Formula;
use super::prim::PrimBound;
use super::{Expr, Vec3Expr, Vec4Expr};
use crate::formula::Leaf;

/// The constructor argument of a family: `mandelbulb(power)`, `juliabulb(c)`, `julia(c)`, `menger(levels)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FractalArgShape {
    Number,
    Vec3,
    Vec4,
    /// The iteration count itself (stored in [`Fractal::iterations`]).
    Levels,
    /// A map written in the scene language (`escape_time(|z, c| ..)`, [`crate::ir::formula`]).
    Formula,
}

/// The rule the constructor argument keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FractalRule {
    /// lo ≤ value ≤ hi.
    Between(f64, f64),
    /// lo ≤ |value| ≤ hi.
    AbsBetween(f64, f64),
    Finite,
    /// An iteration count, checked by the family's [`Iterations`].
    Count,
}

#[derive(Clone, Copy, Debug)]
pub struct FractalArg {
    pub name: &'static str,
    /// How messages name it: "mandelbulb power".
    pub what: &'static str,
    pub shape: FractalArgShape,
    pub rule: FractalRule,
}

/// A setting chained onto a fractal (`.bailout(b)`); each family declares which apply and their defaults.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Setting {
    Bailout,
    MinRadius,
    FoldLimit,
    Power,
    Angle,
}

impl Setting {
    pub const ALL: [Setting; Setting::COUNT] =
        [Setting::Bailout, Setting::MinRadius, Setting::FoldLimit, Setting::Power, Setting::Angle];
    pub const COUNT: usize = 5;
    /// The method's name.
    pub const fn name(self) -> &'static str {
        match self {
            Setting::Bailout => "bailout",
            Setting::MinRadius => "min_radius",
            Setting::FoldLimit => "fold_limit",
            Setting::Power => "power",
            Setting::Angle => "angle",
        }
    }
    /// The position of the setting in [`Setting::ALL`] and in [`Fractal::settings`].
    pub const fn index(self) -> usize {
        self as usize
    }
}

/// The iteration counts a family takes.
#[derive(Clone, Copy, Debug)]
pub struct Iterations {
    pub default: u32,
    pub min: u32,
    pub max: u32,
}

/// An argument of the leaf call a fractal becomes (after the point).
#[derive(Clone, Debug, PartialEq)]
pub enum CallArg {
    Num(Expr),
    Count(u32),
}

/// A fractal's leaf function with its arguments after the point.
pub type LeafCallOf = (Leaf, Vec<CallArg>);

/// What a fractal family is, declared once.
pub struct FractalDecl {
    pub name: &'static str,
    /// One line for the documentation.
    pub doc: &'static str,
    pub arg: FractalArg,
    pub iterations: Iterations,
    /// The settings that apply, with their defaults.
    pub settings: &'static [(Setting, f64)],
    /// The leaf function and its arguments after the point; `None` for a formula written in the scene language,
    /// which runs as [`crate::formula::user`] runs it.
    pub call: fn(&Fractal) -> Option<LeafCallOf>,
    /// Factor on the estimate so a step never overshoots the surface (measured; see `crate::vocab::fractals`).
    pub step_factor: fn(&Fractal) -> f64,
    /// A conservative bound; `None` when no bound is known for the values' ranges.
    pub bound: fn(&Fractal) -> Option<PrimBound>,
    /// The set's own membership test, which never reads the estimate (the ground truth renders are checked against).
    pub membership: Membership,
}

/// How a family decides membership of its set: by its own iteration, with no distance estimate.
#[derive(Clone, Copy, Debug)]
pub struct Membership {
    /// For each leaf [`FractalDecl::call`] can give, the leaf that is −1 inside the set and positive outside, called
    /// with the same arguments ([`crate::formula`], `in_*`).
    pub leaves: &'static [(Leaf, Leaf)],
    /// Whether the estimate approximates the limit of the iteration — escape-time sets, where more iterations shrink
    /// the set towards the limit — rather than the set at the drawn count (IFS levels, where the count is the shape).
    pub approaches_limit: bool,
    /// For each estimator leaf, the same estimate signed by membership: ≤ 0 exactly where the family's orbit stays
    /// bounded (`signed_by_membership` in `formula/estimate.rs`), which a scene with `membership_hits` calls instead,
    /// to take its hits on the drawn set itself. Empty where the estimate has no such sign (IFS folds, the Mandelbox).
    pub signed: &'static [(Leaf, Leaf)],
}

impl Membership {
    /// The membership leaf for an estimator leaf of this family.
    pub fn leaf_for(&self, estimator: Leaf) -> Option<Leaf> {
        let plain = self.signed.iter().find(|(_, s)| *s == estimator).map_or(estimator, |&(e, _)| e);
        self.leaves.iter().find(|(e, _)| *e == plain).map(|&(_, m)| m)
    }

    /// The estimator leaf signed by membership for an estimator leaf of this family, if it has one.
    pub fn signed_for(&self, estimator: Leaf) -> Option<Leaf> {
        self.signed.iter().find(|(e, _)| *e == estimator).map(|&(_, s)| s)
    }

    /// Whether the family's estimates have a membership sign (see [`Membership::signed`]).
    pub fn has_sign(&self) -> bool {
        !self.signed.is_empty()
    }
}

/// A reference to a family's declaration; equal when the names are.
#[derive(Clone, Copy)]
pub struct FractalKind(pub &'static FractalDecl);

super::named_by_declaration!(FractalKind);

/// The constructor argument's value.
#[derive(Clone, Debug, PartialEq)]
pub enum FractalArgValue {
    Num(Expr),
    Vec3(Vec3Expr),
    Vec4(Vec4Expr),
    /// The count is [`Fractal::iterations`].
    Levels,
    Formula(Box<Formula>),
}

/// A fractal leaf with its settings. `None` means the family's default.
#[derive(Clone, Debug, PartialEq)]
pub struct Fractal {
    pub kind: FractalKind,
    pub arg: FractalArgValue,
    pub iterations: Option<u32>,
    /// The chained settings by [`Setting::index`]; `None` for the family's default (or a setting it lacks).
    pub settings: [Option<Expr>; Setting::COUNT],
    /// The factor on the estimate chosen for this scene (`.step_factor(k)`), in place of the family's measured one:
    /// a constant, as the bound's reach and the kernels' steps take it.
    pub step_factor: Option<f64>,
}

/// The range a chained step factor must lie in, open below (a march must advance) and closed above: the largest
/// measured family factor is 1.4 (the Juliabulb's), and past a few estimates a step is no longer a distance.
pub const STEP_FACTOR_RANGE: (f64, f64) = (0.0, 4.0);

/// The cap on fractal iterations (validation refuses more).
pub const MAX_ITERATIONS: u32 = 64;

impl Fractal {
    pub fn new(decl: &'static FractalDecl, arg: FractalArgValue) -> Fractal {
        Fractal { kind: FractalKind(decl), arg, iterations: None, settings: Default::default(), step_factor: None }
    }
    pub fn decl(&self) -> &'static FractalDecl {
        self.kind.0
    }
    pub fn name(&self) -> &'static str {
        self.kind.0.name
    }
    /// The constructor argument's expressions.
    pub fn arg_exprs(&self) -> &[Expr] {
        match &self.arg {
            FractalArgValue::Num(e) => std::slice::from_ref(e),
            FractalArgValue::Vec3(v) => &v.0,
            FractalArgValue::Vec4(v) => &v.0,
            FractalArgValue::Levels | FractalArgValue::Formula(_) => &[],
        }
    }
    /// The formula of a fractal written in the scene language.
    pub fn formula(&self) -> Option<&Formula> {
        match &self.arg {
            FractalArgValue::Formula(f) => Some(f),
            _ => None,
        }
    }
    pub fn arg_exprs_mut(&mut self) -> &mut [Expr] {
        match &mut self.arg {
            FractalArgValue::Num(e) => std::slice::from_mut(e),
            FractalArgValue::Vec3(v) => &mut v.0,
            FractalArgValue::Vec4(v) => &mut v.0,
            FractalArgValue::Levels | FractalArgValue::Formula(_) => &mut [],
        }
    }
    /// The number argument (the power, the scale); `None` for other shapes.
    pub fn number(&self) -> Option<&Expr> {
        match &self.arg {
            FractalArgValue::Num(e) => Some(e),
            _ => None,
        }
    }
    pub fn iterations_or_default(&self) -> u32 {
        self.iterations.unwrap_or(self.kind.0.iterations.default)
    }
    /// The setting's value as written.
    pub fn setting(&self, s: Setting) -> Option<&Expr> {
        self.settings[s.index()].as_ref()
    }
    pub fn setting_mut(&mut self, s: Setting) -> &mut Option<Expr> {
        &mut self.settings[s.index()]
    }
    /// The fractal with the setting chained on.
    pub fn with(mut self, s: Setting, value: impl Into<Expr>) -> Fractal {
        self.settings[s.index()] = Some(value.into());
        self
    }
    /// Whether the family has the setting.
    pub fn applies(&self, s: Setting) -> bool {
        self.kind.0.settings.iter().any(|(t, _)| *t == s)
    }
    /// The setting's value, or the family's default (NaN for a setting the family does not have).
    pub fn setting_or_default(&self, s: Setting) -> Expr {
        self.setting(s).cloned().unwrap_or_else(|| {
            Expr::Lit(self.kind.0.settings.iter().find(|(t, _)| *t == s).map_or(f64::NAN, |(_, d)| *d))
        })
    }
    pub fn bailout_or_default(&self) -> Expr {
        self.setting_or_default(Setting::Bailout)
    }
    pub fn min_radius_or_default(&self) -> Expr {
        self.setting_or_default(Setting::MinRadius)
    }
    pub fn fold_limit_or_default(&self) -> Expr {
        self.setting_or_default(Setting::FoldLimit)
    }
    /// Factor applied to the estimate so a step never overshoots the surface: the scene's choice, else the family's
    /// measured one for this fractal's arguments (see `crate::vocab::fractals`).
    pub fn step_factor_or_default(&self) -> f64 {
        self.step_factor.unwrap_or_else(|| (self.kind.0.step_factor)(self))
    }
    /// The leaf function and its arguments after the point; `None` for a formula.
    pub fn call(&self) -> Option<LeafCallOf> {
        (self.kind.0.call)(self)
    }
}
