//! Conservative axis-aligned bounds of every node: the shape (where the distance is ≤ 0) lies inside; `None` means
//! unbounded (planes, infinite repetition, or a value range without a limit).
//!
//! Bounds are used twice: a ray skips empty space up to the scene bound, and a union skips an expensive child while
//! the point is at least as far from the child's bound as the nearest distance so far. The second use is exact (it
//! never changes the union's value) when the child's distance is never below the distance to its bound. This module
//! tracks that per node as a *reach ratio* κ: outside its box, a node's distance is at least κ times the distance to
//! the box. κ = 1 for exact primitives, CSG over them and the Menger sponge; every other fractal family declares the
//! κ its estimate keeps outside its box, with radii from [`crate::vocab::radius`] (both in [`crate::vocab::fractals`];
//! measured: `docs/settings.md`, “Bounds of the fractal families”). Operations that grow a shape by a distance
//! (round, onion, smooth union) grow the box by that distance divided by κ, which keeps them conservative over
//! estimators that fall short of the true distance (Sierpinski, Mandelbox, twist, bend).

use super::interval::arg_range;
pub use crate::geom::{Aabb, Bound};
use crate::ir::{Fractal, Node, Prim};

/// Signed distance from `p` to the box, by the same formula as [`crate::formula::sd_box`] (so a guard computed here and
/// one computed in a kernel agree).
pub fn sd_aabb(p: [f64; 3], b: &Aabb) -> f64 {
    let c = b.center();
    let h = b.half_extents();
    let local = crate::number::math::v3(p[0] - c[0], p[1] - c[1], p[2] - c[2]);
    crate::formula::sd_box(local, crate::number::math::v3(h[0], h[1], h[2]))
}

/// The bound of `node`, or `None` when it is unbounded.
pub fn bound(node: &Node) -> Option<Aabb> {
    bound_info(node).aabb
}

/// The bound of `node` with its reach ratio and whether union guards over it are exact.
pub fn bound_info(node: &Node) -> Bound {
    match node {
        Node::Prim(p) => prim_bound(p),
        Node::Fractal(f) => fractal_bound(f),
        Node::Op(op) => {
            let shapes: Vec<Bound> = op.shapes.iter().map(bound_info).collect();
            let ranges: Vec<_> = op.args.iter().map(arg_range).collect();
            (op.decl().bound)(&shapes, &ranges)
        }
        Node::Material(c, _) => bound_info(c),
    }
}

/// A primitive's bound, as its declaration computes it from the arguments' ranges.
fn prim_bound(p: &Prim) -> Bound {
    let ranges: Vec<_> = p.args.iter().map(arg_range).collect();
    match (p.decl().bound)(&ranges) {
        Some(b) => Bound { aabb: Some(b.aabb), reach: b.reach, exact_guard: b.reach >= 1.0 }.map(Some),
        None => Bound::UNBOUNDED,
    }
}

/// A fractal's bound, as its family's declaration computes it.
fn fractal_bound(f: &Fractal) -> Bound {
    match (f.decl().bound)(f) {
        Some(b) => Bound { aabb: Some(b.aabb), reach: b.reach, exact_guard: b.reach >= 1.0 }.map(Some),
        None => Bound::UNBOUNDED,
    }
}
