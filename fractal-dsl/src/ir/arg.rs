//! Arguments of declared vocabulary items (primitives and operators): what type an argument has, the rule its value
//! must keep, and the value itself. Parser signatures, printing, validation, folding and bounds all read arguments
//! through these types, so a rule is stated once in a declaration and checked the same way for every item.

use super::{Expr, Vec3Expr};
use crate::geom::Interval;

/// The type of an argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgShape {
    Number,
    Vec3,
    /// A vector of constants (a rotation axis): no `t`, no `param`.
    ConstVec3,
    /// A vector of non-negative integer literals (repeat counts), stored as whole-number literals.
    Counts,
}

/// The rule an argument's value must keep (checked over the value's whole range when it animates).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// > 0 (each component of a vector).
    Positive,
    /// ≥ 0.
    NonNegative,
    /// Any finite value.
    Finite,
    /// A non-zero direction: finite, not the zero vector; a constant one is normalised when built.
    Direction,
    /// Between 0 and the smallest component of the vector argument at this index (a rounding that cannot turn the
    /// shape inside out).
    RoundingOf(usize),
    /// A repetition period: ≥ 0 per axis (0 leaves the axis alone), and not 0 on every axis.
    Period,
    /// Whole numbers no greater than this.
    AtMost(u32),
    /// A whole-number literal from 1 to this (a count of copies).
    CountUpTo(u32),
    /// A displacement: an expression of the point whose range and slope ([`crate::analyse::slope`]) are bounded.
    Displacement,
}

/// One declared argument.
#[derive(Clone, Copy, Debug)]
pub struct ArgDecl {
    pub name: &'static str,
    /// How messages name it: "sphere radius".
    pub what: &'static str,
    pub shape: ArgShape,
    pub rule: Rule,
}

/// A number argument, for declarations.
pub const fn num(name: &'static str, what: &'static str, rule: Rule) -> ArgDecl {
    ArgDecl { name, what, shape: ArgShape::Number, rule }
}
/// A vector argument, for declarations.
pub const fn vec(name: &'static str, what: &'static str, rule: Rule) -> ArgDecl {
    ArgDecl { name, what, shape: ArgShape::Vec3, rule }
}

/// An argument's value. Constant vectors and counts are vectors of literals.
#[derive(Clone, Debug, PartialEq)]
pub enum ArgValue {
    Num(Expr),
    Vec3(Vec3Expr),
}

impl ArgValue {
    /// The expressions it holds, in order.
    pub fn exprs(&self) -> &[Expr] {
        match self {
            ArgValue::Num(e) => std::slice::from_ref(e),
            ArgValue::Vec3(v) => &v.0,
        }
    }
    pub fn exprs_mut(&mut self) -> &mut [Expr] {
        match self {
            ArgValue::Num(e) => std::slice::from_mut(e),
            ArgValue::Vec3(v) => &mut v.0,
        }
    }
    /// Whether every expression is the literal `v`.
    pub fn is_all(&self, v: f64) -> bool {
        self.exprs().iter().all(|e| e.as_lit() == Some(v))
    }
}

impl From<Expr> for ArgValue {
    fn from(e: Expr) -> Self {
        ArgValue::Num(e)
    }
}
impl From<Vec3Expr> for ArgValue {
    fn from(v: Vec3Expr) -> Self {
        ArgValue::Vec3(v)
    }
}

/// The range an argument takes, for bounds.
#[derive(Clone, Copy, Debug)]
pub enum ArgRange {
    Num(Interval),
    Vec3([Interval; 3]),
}

impl ArgRange {
    /// The number's range (a vector's first component).
    pub fn num(&self) -> Interval {
        match self {
            ArgRange::Num(i) => *i,
            ArgRange::Vec3(v) => v[0],
        }
    }
    /// The vector's ranges (a number's on every axis).
    pub fn vec3(&self) -> [Interval; 3] {
        match self {
            ArgRange::Num(i) => [*i; 3],
            ArgRange::Vec3(v) => *v,
        }
    }
    /// The largest value, at least 0 (the extent a size gives).
    pub fn hi(&self) -> f64 {
        self.num().hi.max(0.0)
    }
    /// The largest magnitude.
    pub fn max_abs(&self) -> f64 {
        self.num().max_abs()
    }
    /// The constant vector a constant argument holds (a rotation axis); `None` while any component varies.
    pub fn point3(&self) -> Option<[f64; 3]> {
        let v = self.vec3();
        v.iter().all(|i| i.is_point()).then(|| v.map(|i| i.lo))
    }
}

/// Normalises the constant directions among `values` (as [`Rule::Direction`] asks), in place.
pub fn normalise_directions(decls: &[ArgDecl], values: &mut [ArgValue]) {
    for (a, value) in decls.iter().zip(values.iter_mut()) {
        if let (Rule::Direction, ArgValue::Vec3(v)) = (a.rule, &mut *value) {
            if let Some(n) = v.lits() {
                *v = normalised(n).into();
            }
        }
    }
}

/// A constant direction as the builder stores it: unit length, or as written when it already is (to the last bit,
/// so a printed scene reads back unchanged) or is zero (validation reports that).
pub fn normalised(n: [f64; 3]) -> [f64; 3] {
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && (len - 1.0).abs() > 4.0 * f64::EPSILON {
        n.map(|c| c / len)
    } else {
        n
    }
}
