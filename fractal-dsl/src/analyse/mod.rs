//! Analyses over the IR: constant folding, conservative bounds, value ranges of expressions, and evaluation order.

pub mod bounds;
pub mod fold;
pub mod interval;
pub mod reference;
pub mod slope;

pub use bounds::{bound, Aabb};
pub use reference::{reference, scene_reference, ReferenceSpec};

use crate::ir::op::Meaning;
use crate::ir::{Node, RenderSettings};

/// Why a march refines its hits by the distance's sign ([`crate::ray`], step 3b), which sets its sign step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SignRefinement {
    /// The tree displaces a surface (its distance is divided by the displacement's slope bound, so a hit test on it
    /// can stop that many times the hit epsilon short of the surface) and holds no fractal (an estimate's sign is
    /// not exact; every primitive's is): sign steps follow the line through the last two samples.
    Displacement,
    /// The scene asks for `membership_hits`: its fractals' estimates are signed by membership of the drawn set
    /// ([`crate::ir::fractal::Membership::signed`]), and sign steps are a fixed share of the epsilon, since near a
    /// fractal the estimate does not extrapolate.
    Membership,
}

/// How a march's hits are refined by the distance's sign, if they are (see [`SignRefinement`]).
pub fn sign_refinement(node: &Node, settings: &RenderSettings) -> Option<SignRefinement> {
    fn displaces(node: &Node) -> bool {
        node.op().is_some_and(|op| op.decl().meaning == Meaning::Displace) || node.children().iter().any(displaces)
    }
    if settings.membership_hits {
        Some(SignRefinement::Membership)
    } else if displaces(node) && !node.has_fractal() {
        Some(SignRefinement::Displacement)
    } else {
        None
    }
}

/// Whether some material of the tree may have a specular term (a literal 0 is the only certain "no"): the kernels
/// and the CPU renderer both leave the specular term out when not.
pub fn has_specular(node: &Node) -> bool {
    let own = matches!(node, Node::Material(_, m) if m.specular.as_lit() != Some(0.0));
    own || node.children().iter().any(has_specular)
}

/// The order a union evaluates its children in: everything without a fractal first, then the fractal subtrees, each
/// group in source order. Cheap children first make the nearest-so-far distance small before an expensive child's
/// bound is tested against it.
pub fn union_order(children: &[Node]) -> Vec<usize> {
    let (mut cheap, expensive): (Vec<usize>, Vec<usize>) =
        (0..children.len()).partition(|&i| !children[i].has_fractal());
    cheap.extend(expensive);
    cheap
}

/// Whether a union child is evaluated behind a bound test: it contains a fractal, has a finite bound, and is not the
/// first child evaluated (the first has no nearest-so-far distance to compare with).
pub fn guarded_bound(children: &[Node], order_pos: usize) -> Option<Aabb> {
    let child = &children[union_order(children)[order_pos]];
    if order_pos == 0 || !child.has_fractal() {
        return None;
    }
    bound(child)
}
