//! Analyses over the IR: constant folding, conservative bounds, value ranges of expressions, and evaluation order.

pub mod bounds;
pub mod fold;
pub mod interval;
pub mod reference;
pub mod slope;

pub use bounds::{bound, Aabb};
pub use reference::{reference, scene_reference, ReferenceSpec};

use crate::ir::op::Meaning;
use crate::ir::Node;

/// Whether a march's hits are refined by the distance's sign ([`crate::back::render`], step 3b): the tree displaces
/// a surface (its distance is divided by the displacement's slope bound, so a hit test on it can stop that many times
/// the hit epsilon short of the surface) and holds no fractal (a distance estimate has no sign to bracket with; every
/// primitive's does).
pub fn refines_by_sign(node: &Node) -> bool {
    fn displaces(node: &Node) -> bool {
        node.op().is_some_and(|op| op.decl().meaning == Meaning::Displace) || node.children().iter().any(displaces)
    }
    displaces(node) && !node.has_fractal()
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
