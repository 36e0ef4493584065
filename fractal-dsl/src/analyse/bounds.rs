//! Conservative axis-aligned bounds of every node: the shape (where the distance is ≤ 0) lies inside; `None` means
//! unbounded (planes, infinite repetition, or a value range without a limit).
//!
//! Bounds are used twice: a ray skips empty space up to the scene bound, and a union skips an expensive child while
//! the point is at least as far from the child's bound as the nearest distance so far. The second use is exact (it
//! never changes the union's value) when the child's distance is never below the distance to its bound. This module
//! tracks that per node as a *reach ratio* κ: outside its box, a node's distance is at least κ times the distance to
//! the box. κ = 1 for exact primitives and CSG over them; fractal radii are chosen (from measurements, see the
//! constants below) so that Menger, Mandelbulb and Julia reach κ = 1 too. Operations that grow a shape by a distance
//! (round, onion, smooth union) grow the box by that distance divided by κ, which keeps them conservative over
//! estimators that fall short of the true distance (Sierpinski, Mandelbox, twist, bend).

use super::interval::{arg_range, Interval};
pub use crate::geom::{Aabb, Bound};
use crate::ir::{Fractal, Node, Prim};

/// Signed distance from `p` to the box, by the same formula as [`crate::formula::sd_box`] (so a guard computed here and one
/// computed in a kernel agree).
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

// ---- fractal radii (measured; the bounds tests re-check them) --------------------------------------------------------

/// Radius of a sphere around the origin that bounds the Mandelbulb of any power ≥ `min_power`, at any iteration count
/// and bailout. Points with |p|^(n−1) > 2 escape (|z^n + p| ≥ |z|^n − |p| > |z| keeps growing), so the set lies within
/// 2^(1/(n−1)); the margin covers the rendered surface, where the estimate is below a hit epsilon (measured over powers
/// 2–32 and 1–16 iterations: at most 0.035 beyond the set radius for estimates below 0.02).
pub fn mandelbulb_radius(min_power: f64) -> Option<f64> {
    if min_power.is_nan() || min_power <= 1.0 || min_power.is_infinite() {
        return None;
    }
    Some(2f64.powf(1.0 / (min_power - 1.0)) + 0.05)
}

/// Radius of a sphere that bounds the quaternion Julia set of any constant with |c| ≤ `c_norm`: points beyond
/// R = (1 + √(1 + 4|c|))/2 escape (|z² + c| ≥ |z|² − |c| > |z|). The margin covers the rendered surface (measured well
/// inside R).
pub fn julia_radius(c_norm: f64) -> Option<f64> {
    if !c_norm.is_finite() {
        return None;
    }
    Some(0.5 * (1.0 + (1.0 + 4.0 * c_norm.max(0.0)).sqrt()) + 0.05)
}

/// Radius of a sphere that bounds the Juliabulb (z ← z^n + c) of any power ≥ `min_power` and constant with
/// |c| ≤ `c_norm`: past the root R of R^n = R + |c|, |z^n + c| ≥ |z|^n − |c| > |z| keeps growing. R is approached
/// from above (from 1 + |c|, above the root since (1 + |c|)^n ≥ 1 + n|c|); the margin is the Mandelbulb's.
pub fn juliabulb_radius(min_power: f64, c_norm: f64) -> Option<f64> {
    if !c_norm.is_finite() || min_power.is_nan() || min_power <= 1.0 || min_power.is_infinite() {
        return None;
    }
    let c = c_norm.max(0.0);
    let mut r = 1.0 + c;
    for _ in 0..64 {
        r = (r + c).powf(1.0 / min_power);
    }
    Some(r + 0.05)
}

/// Half extent of the cube that bounds the Mandelbox for every scale in `scale` and fold limits up to `fold_limit`.
/// For scale s > 1 the box fold's fixed point bounds the orbit: 2f(s + 1)/(s − 1) (the known 6 at s = 2, f = 1); for
/// s < −1 the measured extent is 2f. Scales within [−1, 1] never escape: unbounded.
pub fn mandelbox_half_extent(scale: Interval, fold_limit: f64) -> Option<f64> {
    if !scale.is_finite() || !fold_limit.is_finite() {
        return None;
    }
    let extent = if scale.lo > 1.0 {
        2.0 * fold_limit * (scale.lo + 1.0) / (scale.lo - 1.0)
    } else if scale.hi < -1.0 {
        2.0 * fold_limit
    } else {
        return None;
    };
    // The rendered surface (estimate below a hit epsilon) reaches slightly past the set.
    Some(extent * 1.01 + 0.02)
}

/// A fractal's bound, as its family's declaration computes it.
fn fractal_bound(f: &Fractal) -> Bound {
    match (f.decl().bound)(f) {
        Some(b) => Bound { aabb: Some(b.aabb), reach: b.reach, exact_guard: b.reach >= 1.0 }.map(Some),
        None => Bound::UNBOUNDED,
    }
}
