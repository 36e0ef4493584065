//! Primitives in the IR: a [`Prim`] is a [`PrimDecl`] (what the primitive is: name, typed arguments with their rules,
//! leaf function, bound) and the argument values. Every reader — parser, printer, validation, folding, bounds, the
//! evaluators and the kernels — works from the declaration, so a primitive is declared once (`crate::vocab::prims`) and
//! means the same everywhere.

use super::arg::{normalise_directions, ArgDecl, ArgRange, ArgValue};
use crate::formula::Leaf;
use crate::geom::Aabb;

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
    pub args: &'static [ArgDecl],
    /// The distance function; it takes the point, then the arguments in order.
    pub leaf: Leaf,
    /// A conservative bound from the arguments' ranges; `None` for an unbounded shape.
    pub bound: fn(&[ArgRange]) -> Option<PrimBound>,
    /// Arguments that may not all be 0 at once, and the message when they are.
    pub not_all_zero: Option<(&'static [usize], &'static str)>,
}

impl PrimDecl {
    /// The primitive with these arguments, in canonical form (constant directions normalised).
    pub fn node(&'static self, mut args: Vec<ArgValue>) -> super::Node {
        normalise_directions(self.args, &mut args);
        super::Node::Prim(Prim { kind: PrimKind(self), args })
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

super::declared_item!(Prim, PrimDecl);
