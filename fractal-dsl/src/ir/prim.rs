//! Primitives in the IR: a [`Prim`] is a [`PrimDecl`] (what the primitive is: name, typed arguments with their rules,
//! leaf function, bound) and the argument values. Every reader — parser, printer, validation, folding, bounds, the
//! evaluators and the kernels — works from the declaration, so a primitive is declared once (`crate::prims`) and
//! means the same everywhere.

use super::{Expr, Vec3Expr};
use crate::geom::{Aabb, Interval};
use crate::sdf::Leaf;

/// The type of a primitive's argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgShape {
    Number,
    Vec3,
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
}

/// One argument of a primitive.
#[derive(Clone, Copy, Debug)]
pub struct PrimArg {
    pub name: &'static str,
    /// How messages name it: "sphere radius".
    pub what: &'static str,
    pub shape: ArgShape,
    pub rule: Rule,
}

/// An argument's value.
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
}

/// A primitive's bound: the box the shape lies in, and how its distance relates to the box outside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimBound {
    pub aabb: Aabb,
    /// Outside the box the distance is at least `reach` × the distance to the box (1 for an exact distance).
    pub reach: f64,
}

impl PrimBound {
    /// The bound of an exact distance.
    pub fn exact(aabb: Aabb) -> Option<PrimBound> {
        Some(PrimBound { aabb, reach: 1.0 })
    }
}

/// What a primitive is, declared once.
pub struct PrimDecl {
    /// The function that makes it in scene source and in the builder API.
    pub name: &'static str,
    /// One line for the documentation.
    pub doc: &'static str,
    pub args: &'static [PrimArg],
    /// The distance function; it takes the point, then the arguments in order.
    pub leaf: Leaf,
    /// A conservative bound from the arguments' ranges; `None` for an unbounded shape.
    pub bound: fn(&[ArgRange]) -> Option<PrimBound>,
    /// Arguments that may not all be 0 at once, and the message when they are.
    pub not_all_zero: Option<(&'static [usize], &'static str)>,
}

impl PrimDecl {
    /// The primitive with these arguments, in canonical form (constant directions normalised).
    pub fn node(&'static self, args: Vec<ArgValue>) -> super::Node {
        let mut args = args;
        for (a, value) in self.args.iter().zip(args.iter_mut()) {
            if let (Rule::Direction, ArgValue::Vec3(v)) = (a.rule, &mut *value) {
                if let Some(n) = v.lits() {
                    *v = normalised(n).into();
                }
            }
        }
        super::Node::Prim(Prim { kind: PrimKind(self), args })
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

/// A reference to a primitive's declaration; equal when the names are.
#[derive(Clone, Copy)]
pub struct PrimKind(pub &'static PrimDecl);

super::named_by_declaration!(PrimKind);

/// An exact signed-distance primitive (1-Lipschitz; the exact Euclidean distance unless its bound says otherwise).
#[derive(Clone, Debug, PartialEq)]
pub struct Prim {
    pub kind: PrimKind,
    /// One value per declared argument, in order.
    pub args: Vec<ArgValue>,
}

impl Prim {
    pub fn decl(&self) -> &'static PrimDecl {
        self.kind.0
    }
    pub fn name(&self) -> &'static str {
        self.kind.0.name
    }
    /// Every expression of every argument, in order.
    pub fn exprs(&self) -> impl Iterator<Item = &Expr> {
        self.args.iter().flat_map(ArgValue::exprs)
    }
    /// The declared arguments with their values.
    pub fn declared_args(&self) -> impl Iterator<Item = (&'static PrimArg, &ArgValue)> {
        self.kind.0.args.iter().zip(&self.args)
    }
}
