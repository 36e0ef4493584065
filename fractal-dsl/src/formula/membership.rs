//! Each fractal's own definition as a membership test, with no estimate: the ground truth that checks the estimators.

use super::common::*;
use super::estimate::*;
use super::shapes::sd_box;
use crate::number::math::*;
use crate::number::Num;

// ---- membership: each fractal's own definition, with no estimate (the ground truth that checks the estimators) ----

/// A membership value: −1 inside the set; outside, `apart` — a lower bound on the distance to the set that follows
/// from the set's definition alone (from a ball or box that must hold it), floored at [`TINY`]. Under min and max
/// (union, intersection, subtraction, transforms) the sign of a scene holding fractals is still its membership. Near
/// the set the positive value says nothing of how far the set is, so a march over it must take small fixed steps;
/// away from it the march may step by `apart`.
#[inline(always)]
fn membership<F: Num>(inside: F::Mask, apart: F) -> F {
    select(inside, c(-1.0), max(apart, c(TINY)))
}

/// A radius holding every point whose orbit z ← z^power + p survives one step within `bailout`: past it
/// |z₁| ≥ |p|^power − |p| > bailout. The root of r^power − r = bailout, approached from above by
/// r ← (bailout + r)^(1/power) from bailout + 1, so every iterate holds the set.
#[inline(always)]
fn first_step_radius<F: Num>(power: F, bailout: F) -> F {
    let r = bailout + c(1.0);
    repeat(
        F::count(6),
        r,
        #[inline(always)]
        |r| pow(bailout + r, c::<F>(1.0) / power),
    )
}

/// Whether the orbit z ← map(z, |z|) + offset from z = p stays within `escape` for `iterations` steps; `radius`
/// holds the set.
#[inline(always)]
fn escape_time_membership<F: Num>(
    p: V3<F>,
    offset: V3<F>,
    iterations: F::Count,
    escape: F,
    radius: F,
    map: impl Fn(V3<F>, F) -> V3<F>,
) -> F {
    let (_, r) = F::iterate(
        iterations,
        (p, length(p)),
        #[inline(always)]
        |&(_, r)| le(r, escape),
        #[inline(always)]
        |(z, r)| {
            let z = map(z, r) + offset;
            (z, length(z))
        },
    );
    membership(le(r, escape), length(p) - radius)
}

/// The Mandelbulb of any power: the orbit stays within `bailout` for `iterations` (at least 1) steps.
#[inline(always)]
pub fn in_mandelbulb<F: Num>(p: V3<F>, power: F, iterations: F::Count, bailout: F) -> F {
    let radius = first_step_radius(power, bailout);
    escape_time_membership(
        p,
        p,
        iterations,
        bailout,
        radius,
        #[inline(always)]
        |z, r| bulb_power::<F, false>(z, r, c(1.0), power).0,
    )
}

/// The power-8 Mandelbulb: the orbit stays within `bailout` for `iterations` (at least 1) steps.
#[inline(always)]
pub fn in_mandelbulb8<F: Num>(p: V3<F>, iterations: F::Count, bailout: F) -> F {
    let radius = first_step_radius(c(8.0), bailout);
    escape_time_membership(
        p,
        p,
        iterations,
        bailout,
        radius,
        #[inline(always)]
        |z, r| mandelbulb8_step(z, r, c(1.0)).0,
    )
}

/// The Menger sponge of `levels` levels in [-1, 1]³: inside the cube, and at no level in the middle third of its cell
/// along two axes or more (the cross each level removes, open, so the sponge is closed).
#[inline(always)]
pub fn in_menger<F: Num>(p: V3<F>, levels: F::Count) -> F {
    let (zero, one, three) = (c::<F>(0.0), c::<F>(1.0), c::<F>(3.0));
    let in_cube = le(abs(p.x), one) & le(abs(p.y), one) & le(abs(p.z), one);
    // The point's position in its cell at the current level, in [0, 1]³, and whether a level has removed it.
    let cell = (p + V3::splat(one)) * c::<F>(0.5);
    let (_, removed) = repeat(
        levels,
        (cell, zero),
        #[inline(always)]
        |(cell, removed)| {
            let s = cell * three;
            let digit = s.map(
                #[inline(always)]
                |v| clamp(floor(v), zero, c(2.0)),
            );
            let middle = s.map(
                #[inline(always)]
                |v| select(gt(v, one) & lt(v, c(2.0)), one, zero),
            );
            let cut = ge(middle.x + middle.y + middle.z, c(2.0));
            (s - digit, select(cut, one, removed))
        },
    );
    membership(in_cube & lt(removed, c(0.5)), sd_box(p, V3::splat(one)))
}

/// The Sierpinski tetrahedron of `levels` levels (vertices (1,1,1), (-1,-1,1), (1,-1,-1), (-1,1,-1)): inside the
/// tetrahedron, and at every level in the half-size copy at one vertex (barycentric coordinate λᵢ = (1 + vᵢ·z)/4 at
/// least ½), which the map z ← 2z − vᵢ blows up to the whole tetrahedron for the next level.
#[inline(always)]
pub fn in_sierpinski<F: Num>(p: V3<F>, levels: F::Count) -> F {
    let (zero, one, half) = (c::<F>(0.0), c::<F>(1.0), c::<F>(0.5));
    let vertices = [[1.0, 1.0, 1.0], [-1.0, -1.0, 1.0], [1.0, -1.0, -1.0], [-1.0, 1.0, -1.0]].map(
        #[inline(always)]
        |[x, y, z]| v3(c::<F>(x), c::<F>(y), c::<F>(z)),
    );
    let barycentric = |z: V3<F>| {
        vertices.map(
            #[inline(always)]
            |v| (one + dot(v, z)) * c(0.25),
        )
    };
    let l = barycentric(p);
    let in_tetrahedron = ge(min(min(l[0], l[1]), min(l[2], l[3])), zero);
    let (_, kept) = repeat(
        levels,
        (p, select(in_tetrahedron, one, zero)),
        #[inline(always)]
        |(z, kept)| {
            let l = barycentric(z);
            let largest = max(max(l[0], l[1]), max(l[2], l[3]));
            let v = select3(
                ge(l[0], largest),
                vertices[0],
                select3(ge(l[1], largest), vertices[1], select3(ge(l[2], largest), vertices[2], vertices[3])),
            );
            (z * c::<F>(2.0) - v, select(ge(largest, half), kept, zero))
        },
    );
    // Outside a face plane vᵢ·p = −1 (λᵢ < 0) the tetrahedron is at least (−1 − vᵢ·p)/√3 = −4λᵢ/√3 away.
    let apart = -c::<F>(4.0 * INV_SQRT3) * min(min(l[0], l[1]), min(l[2], l[3]));
    membership(gt(kept, half), apart)
}

/// The quaternion Julia set in the slice w = 0: the orbit z ← z² + c from (p, 0) stays within `bailout` for
/// `iterations` steps.
#[inline(always)]
pub fn in_julia<F: Num>(p: V3<F>, cx: F, cy: F, cz: F, cw: F, iterations: F::Count, bailout: F) -> F {
    let dot4 = |a: [F; 4]| a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3];
    let z0 = [p.x, p.y, p.z, c(0.0)];
    let escape2 = bailout * bailout;
    let (_, m) = F::iterate(
        iterations,
        (z0, dot4(z0)),
        #[inline(always)]
        |&(_, m)| le(m, escape2),
        #[inline(always)]
        |(z, _)| {
            let z = julia_step(z, [cx, cy, cz, cw]);
            (z, dot4(z))
        },
    );
    // Past √(bailout + |c|), |z₁| ≥ |p|² − |c| > bailout.
    let radius = sqrt(bailout + sqrt(cx * cx + cy * cy + cz * cz + cw * cw));
    membership(le(m, escape2), length(p) - radius)
}

/// 2√3: the most a box fold at limit f can shorten a vector, in units of f (each axis by at most 2f).
const TWO_SQRT3: f64 = 3.464_101_615_137_754_6;

/// The radius past which a Mandelbox orbit from a point `distance` from the origin provably escapes:
/// R = max((2√3·|s|·f + |p|)/(|s| − 1), 1 + 2√3·f). Past it the box fold shortens z by at most 2√3·f, leaving it
/// outside the unit sphere where the sphere fold does nothing, so |s·fold(z) + p| > |z| and the orbit grows without
/// bound.
#[inline(always)]
pub fn mandelbox_escape_radius<F: Num>(distance: F, scale: F, fold_limit: F) -> F {
    let one = c::<F>(1.0);
    let shortening = c::<F>(TWO_SQRT3) * abs(fold_limit);
    let s = abs(scale);
    max((s * shortening + distance) / max(s - one, c(TINY)), one + shortening)
}

/// The Mandelbox: the orbit stays within the radius past which it provably escapes ([`mandelbox_escape_radius`]).
#[inline(always)]
pub fn in_mandelbox<F: Num>(p: V3<F>, scale: F, iterations: F::Count, min_radius: F, fold_limit: F) -> F {
    let min_r2 = min_radius * min_radius;
    let escape = mandelbox_escape_radius(length(p), scale, fold_limit);
    let (_, r) = F::iterate(
        iterations,
        (p, length(p)),
        #[inline(always)]
        |&(_, r)| le(r, escape),
        #[inline(always)]
        |(z, _)| {
            let (z, _, _) = mandelbox_step(z, p, scale, min_r2, fold_limit);
            (z, length(z))
        },
    );
    // No ball is known to hold every Mandelbox from its definition alone: fixed steps everywhere.
    membership(le(r, escape), c(0.0))
}

/// The Juliabulb: the orbit z ← z^power + c from z = p stays within `bailout` for `iterations` (at least 1) steps. Past
/// (bailout + |c|)^(1/power), |z₁| ≥ |p|^power − |c| > bailout; past bailout the orbit has escaped at once.
#[inline(always)]
pub fn in_juliabulb<F: Num>(p: V3<F>, cx: F, cy: F, cz: F, power: F, iterations: F::Count, bailout: F) -> F {
    let offset = v3(cx, cy, cz);
    let radius = min(bailout, pow(bailout + length(offset), c::<F>(1.0) / power));
    escape_time_membership(
        p,
        offset,
        iterations,
        bailout,
        radius,
        #[inline(always)]
        |z, r| bulb_power::<F, false>(z, r, c(1.0), power).0,
    )
}

/// Whether a KIFS orbit stays within the unit ball for `iterations` steps (the set's own test, see [`kifs_orbit`]).
#[inline(always)]
fn kifs_membership<F: Num>(
    p: V3<F>,
    scale: F,
    angle: F,
    iterations: F::Count,
    vertex: V3<F>,
    fold: impl Fn(V3<F>) -> V3<F>,
) -> F {
    let inside = |z: V3<F>| le(dot(z, z), c(1.0));
    let (z, _, _) = kifs_orbit(p, scale, angle, iterations, vertex, fold, inside);
    membership(inside(z), length(p) - c(1.0))
}

/// The octahedral KIFS at `iterations` steps.
#[inline(always)]
pub fn in_octahedral_kifs<F: Num>(p: V3<F>, scale: F, angle: F, iterations: F::Count) -> F {
    kifs_membership(p, scale, angle, iterations, octahedral_vertex(), octahedral_fold)
}

/// The icosahedral KIFS at `iterations` steps.
#[inline(always)]
pub fn in_icosahedral_kifs<F: Num>(p: V3<F>, scale: F, angle: F, iterations: F::Count) -> F {
    kifs_membership(p, scale, angle, iterations, icosahedral_vertex(), icosahedral_fold)
}
