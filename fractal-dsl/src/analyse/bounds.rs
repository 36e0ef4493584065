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

use super::interval::{range, Interval};
pub use crate::geom::Aabb;
use crate::ir::prim::ArgRange;
use crate::ir::{ArgValue, Axis, Fractal, Node, Prim, Vec3Expr};

/// Signed distance from `p` to the box, by the same formula as [`crate::sdf::sd_box`] (so a guard computed here and one
/// computed in a kernel agree).
pub fn sd_aabb(p: [f64; 3], b: &Aabb) -> f64 {
    let c = b.center();
    let h = b.half_extents();
    let local = crate::math::v3(p[0] - c[0], p[1] - c[1], p[2] - c[2]);
    crate::sdf::sd_box(local, crate::math::v3(h[0], h[1], h[2]))
}

/// A node's bound and how its distance relates to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bound {
    /// The box the shape lies in; `None` when unbounded.
    pub aabb: Option<Aabb>,
    /// Outside the box, the node's distance is at least `reach` × the distance to the box (0 < reach ≤ 1; 0 when
    /// nothing is known). Growing operations divide by it.
    pub reach: f64,
    /// Whether the node's distance is at least the box's signed distance everywhere, inside the box too: then a union
    /// guard that skips the node never changes the union's value.
    pub exact_guard: bool,
}

impl Bound {
    const UNBOUNDED: Bound = Bound { aabb: None, reach: 0.0, exact_guard: false };
    fn map(self, f: impl FnOnce(Aabb) -> Option<Aabb>) -> Bound {
        match self.aabb.and_then(f) {
            Some(b) if b.is_finite() => Bound { aabb: Some(b), ..self },
            _ => Bound::UNBOUNDED,
        }
    }
    /// The bound of `{d − by ≤ 0}`: the box grown by `by`/reach.
    fn grown(self, by: f64) -> Bound {
        if by <= 0.0 {
            return self;
        }
        if self.reach <= 0.0 {
            return Bound::UNBOUNDED;
        }
        let reach = self.reach;
        self.map(|b| Some(b.grow(by / reach)))
    }
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
        Node::Union(children) => {
            let all: Vec<Bound> = children.iter().map(bound_info).collect();
            hull(&all)
        }
        Node::Intersect(children) | Node::SmoothIntersect(children, _) => {
            // smooth_max(a, b) ≥ max(a, b): a smooth intersection lies inside the plain one.
            let all: Vec<Bound> = children.iter().map(bound_info).collect();
            overlap(&all)
        }
        // max(a, −b) ≥ a, and smooth_max(a, −b) ≥ max(a, −b): the left operand bounds both.
        Node::Subtract(a, _) | Node::SmoothSubtract(a, _, _) => bound_info(a),
        Node::SmoothUnion(children, k) => {
            // Each step of the left fold subtracts at most k/4 from the plain minimum (sdf::smooth_min).
            let all: Vec<Bound> = children.iter().map(bound_info).collect();
            let k = range(k).hi.max(0.0);
            let steps = children.len().saturating_sub(1) as f64;
            let h = hull(&all);
            if k.is_finite() {
                h.grown(steps * k * 0.25)
            } else {
                Bound::UNBOUNDED
            }
        }
        Node::Translate(c, offset) => {
            let r = ranges(offset);
            bound_info(c).map(|b| Some(b.translate(r.map(|i| i.lo), r.map(|i| i.hi))))
        }
        Node::Rotate(c, axis, angle) => {
            let angle = range(angle);
            bound_info(c).map(|b| rotated(&b, *axis, angle))
        }
        Node::Scale(c, s) => {
            let s = range(s);
            if s.lo.is_nan() || s.lo <= 0.0 || !s.is_finite() {
                return Bound::UNBOUNDED;
            }
            // child(p / s)·s: the shape is s × the child's; every factor in between is a convex combination.
            bound_info(c).map(|b| Some(b.scale(s.lo).union(&b.scale(s.hi))))
        }
        Node::Repeat(c, period) => {
            if period.0.iter().all(|e| e.as_lit() == Some(0.0)) {
                bound_info(c)
            } else {
                Bound::UNBOUNDED
            }
        }
        Node::RepeatLimited(c, period, count) => {
            let widen: [Option<f64>; 3] = [0, 1, 2].map(|i| {
                if period.0[i].as_lit() == Some(0.0) {
                    return Some(0.0);
                }
                let p = range(&period.0[i]);
                p.is_finite().then(|| p.max_abs() * count[i] as f64)
            });
            match widen {
                [Some(x), Some(y), Some(z)] => bound_info(c).map(|b| Some(b.grow3([x, y, z]))),
                _ => Bound::UNBOUNDED,
            }
        }
        Node::Twist(c, k) | Node::Bend(c, k) => {
            // Both rotate a plane about an axis through the origin: the radius from that axis and the coordinate
            // along it are kept, so the box is the cylinder of the child's farthest corner. The distance is divided
            // by the stretch, which far away approaches a constant: nothing is known about its reach.
            let (a, b, along) = if matches!(node, Node::Twist(..)) { (0, 2, 1) } else { (0, 1, 2) };
            let inner = bound_info(c);
            let identity = k.as_lit() == Some(0.0);
            let out = inner.map(|bx| {
                let radius = bx.corners().iter().map(|p| p[a].hypot(p[b])).fold(0.0, f64::max);
                let mut min = [-radius; 3];
                let mut max = [radius; 3];
                min[along] = bx.min[along];
                max[along] = bx.max[along];
                Some(Aabb { min, max })
            });
            if identity {
                out
            } else {
                Bound { reach: 0.0, exact_guard: false, ..out }
            }
        }
        Node::Round(c, r) => {
            let r = range(r).hi.max(0.0);
            if !r.is_finite() {
                return Bound::UNBOUNDED;
            }
            let inner = bound_info(c);
            Bound { exact_guard: inner.exact_guard && inner.reach >= 1.0, ..inner.grown(r) }
        }
        Node::Onion(c, th) => {
            // |d| − th ≤ 0 needs d ≤ th.
            let th = range(th).hi.max(0.0);
            if !th.is_finite() {
                return Bound::UNBOUNDED;
            }
            let inner = bound_info(c);
            Bound { exact_guard: inner.exact_guard && inner.reach >= 1.0, ..inner.grown(th) }
        }
        Node::Elongate(c, h) => {
            // child(p − clamp(p, −h, h)): every point of the shape is a child point moved by at most |h| per axis.
            let h = ranges(h);
            if h.iter().any(|i| !i.is_finite()) {
                return Bound::UNBOUNDED;
            }
            bound_info(c).map(|b| Some(b.grow3(h.map(|i| i.max_abs()))))
        }
        Node::Material(c, _) => bound_info(c),
    }
}

fn ranges(v: &Vec3Expr) -> [Interval; 3] {
    [0, 1, 2].map(|i| range(&v.0[i]))
}

fn hull(all: &[Bound]) -> Bound {
    let mut out: Option<Bound> = None;
    for b in all {
        let Some(bx) = b.aabb else { return Bound::UNBOUNDED };
        out = Some(match out {
            None => *b,
            Some(o) => Bound {
                aabb: o.aabb.map(|a| a.union(&bx)),
                reach: o.reach.min(b.reach),
                exact_guard: o.exact_guard && b.exact_guard,
            },
        });
    }
    out.unwrap_or(Bound::UNBOUNDED)
}

fn overlap(all: &[Bound]) -> Bound {
    let bounded: Vec<&Bound> = all.iter().filter(|b| b.aabb.is_some()).collect();
    let Some(first) = bounded.first() else { return Bound::UNBOUNDED };
    let mut aabb = first.aabb.unwrap_or_else(|| unreachable!("filtered to bounded"));
    let mut reach = first.reach;
    for b in &bounded[1..] {
        aabb = aabb.intersection(&b.aabb.unwrap_or_else(|| unreachable!("filtered to bounded")));
        reach = reach.min(b.reach);
    }
    // max(d_i) ≥ reach·max(dist to box_i), and the distance to the overlap of n axis-aligned boxes is at most √n times
    // the largest distance to one of them (per axis it is the largest of the per-axis gaps).
    let n = bounded.len() as f64;
    Bound { aabb: Some(aabb), reach: reach / n.sqrt(), exact_guard: false }
}

/// The box of the shape rotated by any angle in `angle` about `axis`.
fn rotated(b: &Aabb, axis: Axis, angle: Interval) -> Option<Aabb> {
    let k = axis.unit();
    if angle.is_point() && angle.is_finite() {
        let (s, c) = angle.lo.sin_cos();
        return Aabb::of_points(b.corners().map(|p| rodrigues(p, k, s, c)));
    }
    // Any angle: the shape sweeps around the axis. For a coordinate axis the swept set is a cylinder; otherwise a ball.
    let corners = b.corners();
    let along = |p: &[f64; 3]| p[0] * k[0] + p[1] * k[1] + p[2] * k[2];
    match axis {
        Axis::X | Axis::Y | Axis::Z => {
            let i = match axis {
                Axis::X => 0,
                Axis::Y => 1,
                _ => 2,
            };
            let radius = corners
                .iter()
                .map(|p| {
                    let t = along(p);
                    ((0..3).map(|j| (p[j] - t * k[j]).powi(2)).sum::<f64>()).sqrt()
                })
                .fold(0.0, f64::max);
            let mut min = [-radius; 3];
            let mut max = [radius; 3];
            min[i] = b.min[i];
            max[i] = b.max[i];
            Some(Aabb { min, max })
        }
        Axis::Any(_) => {
            let radius = corners.iter().map(|p| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()).fold(0.0, f64::max);
            Some(Aabb::cube(radius))
        }
    }
}

/// `p` rotated by the angle whose sine and cosine are `s`, `c` about the unit axis `k`.
fn rodrigues(p: [f64; 3], k: [f64; 3], s: f64, c: f64) -> [f64; 3] {
    let cross = [k[1] * p[2] - k[2] * p[1], k[2] * p[0] - k[0] * p[2], k[0] * p[1] - k[1] * p[0]];
    let dot = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
    [0, 1, 2].map(|i| p[i] * c + cross[i] * s + k[i] * dot * (1.0 - c))
}

/// A primitive's bound, as its declaration computes it from the arguments' ranges.
fn prim_bound(p: &Prim) -> Bound {
    let ranges: Vec<ArgRange> = p
        .args
        .iter()
        .map(|a| match a {
            ArgValue::Num(e) => ArgRange::Num(range(e)),
            ArgValue::Vec3(v) => ArgRange::Vec3(ranges(v)),
        })
        .collect();
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
