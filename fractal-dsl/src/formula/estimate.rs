//! The fractal families' distance estimators: each returns (distance estimate, orbit trap in [0, 1]).

use super::common::*;
use super::shapes::sd_box;
use crate::number::math::*;
use crate::number::{Mask, Num};

// ---- fractals: each returns (distance estimate, orbit trap in [0, 1]) ---------------------------------------------

/// Escape radius that keeps r^power finite in f32 and below the user's bailout.
#[inline(always)]
pub fn mandelbulb_escape<F: Num>(power: F, bailout: F) -> F {
    min(bailout, exp2(c::<F>(POW_LOG2_MAX) / power))
}

/// Whether an escape-time orbit goes on: neither |z| past the escape radius nor the derivative past [`DR_MAX`].
#[inline(always)]
fn orbit_bounded<F: Num>(r: F, escape: F, dr: F) -> F::Mask {
    !(gt(r, escape) | gt(dr, c(DR_MAX)))
}

/// The escape-time distance estimate 0.5·ln(r)·r/dr (r floored so ln stays finite at an orbit through 0).
#[inline(always)]
fn escape_estimate<F: Num>(r: F, dr: F) -> F {
    c::<F>(0.5) * ln(max(r, c(TINY))) * r / dr
}

/// An escape-time estimate signed by membership: ≤ 0 where the orbit never passed the escape radius (the point is in
/// the drawn set), > 0 where it escaped. Inside the set the estimate is no distance; its sign is what a march that
/// takes hits on the set itself reads (step 3b of [`crate::ray`], `membership_hits`): the `*_signed` leaves.
/// Only there: with few iterations or a large bailout the drawn set reaches past the bound that holds the surface the
/// plain hit test renders (1 iteration at bailout 256), and a plain march would stop on the bound's face.
#[inline(always)]
fn signed_by_membership<F: Num>(estimate: F, bounded: F::Mask) -> F {
    select(bounded, -abs(estimate), estimate)
}

/// The orbit of an escape-time map from z = p: z ← map(z, |z|, dr) + offset with dr ← its derivative, while |z|
/// stays within `escape` and dr below [`DR_MAX`]; returns the distance estimate (if `SIGNED`, signed by membership:
/// [`signed_by_membership`], an orbit stopped by the derivative cap alone staying in) and the orbit trap (closest
/// approach to the origin, at most 1). The offset is p for Mandelbrot-type sets, a constant for Julia-type ones.
#[inline(always)]
fn escape_time<F: Num, const SIGNED: bool>(
    p: V3<F>,
    offset: V3<F>,
    iterations: F::Count,
    escape: F,
    map: impl Fn(V3<F>, F, F) -> (V3<F>, F),
) -> [F; 2] {
    let r0 = length(p);
    let (_, dr, r, trap) = F::iterate(
        iterations,
        (p, c::<F>(1.0), r0, r0),
        #[inline(always)]
        |&(_, dr, r, _)| orbit_bounded(r, escape, dr),
        #[inline(always)]
        |(z, dr, r, trap)| {
            let (z, dr) = map(z, r, dr);
            let z = z + offset;
            let r = length(z);
            (z, dr, r, min(trap, r))
        },
    );
    let estimate = escape_estimate(r, dr);
    [if SIGNED { signed_by_membership(estimate, le(r, escape)) } else { estimate }, min(trap, c(1.0))]
}

/// Mandelbulb of any power by the trigonometric form; the derivative uses the same `power` as the iteration.
#[inline(always)]
pub fn de_mandelbulb<F: Num>(p: V3<F>, power: F, iterations: F::Count, bailout: F) -> [F; 2] {
    mandelbulb_trigonometric::<F, false, false>(p, power, iterations, bailout)
}

/// [`de_mandelbulb`] signed by membership: ≤ 0 where the orbit never escapes (`signed_by_membership`).
#[inline(always)]
pub fn de_mandelbulb_signed<F: Num>(p: V3<F>, power: F, iterations: F::Count, bailout: F) -> [F; 2] {
    mandelbulb_trigonometric::<F, false, true>(p, power, iterations, bailout)
}

/// [`de_mandelbulb`] with the derivative taking the map's azimuthal stretch (`bulb_power`), as the Juliabulb's
/// does: the estimate of the low powers. Below power 4 the plain derivative over-reaches far near the coordinate axes
/// and needs a small step factor everywhere; the stretched estimate is smaller wherever the azimuth stretches more
/// than the radius, steps at the factor 1 and over-reaches on about as few points, near the x axis and the coordinate
/// planes where the stretch is 1 (measured: `docs/settings.md`, “Step factors of the fractal families”).
#[inline(always)]
pub fn de_mandelbulb_stretched<F: Num>(p: V3<F>, power: F, iterations: F::Count, bailout: F) -> [F; 2] {
    mandelbulb_trigonometric::<F, true, false>(p, power, iterations, bailout)
}

/// [`de_mandelbulb_stretched`] signed by membership: ≤ 0 where the orbit never escapes (`signed_by_membership`).
#[inline(always)]
pub fn de_mandelbulb_stretched_signed<F: Num>(p: V3<F>, power: F, iterations: F::Count, bailout: F) -> [F; 2] {
    mandelbulb_trigonometric::<F, true, true>(p, power, iterations, bailout)
}

#[inline(always)]
fn mandelbulb_trigonometric<F: Num, const STRETCHED: bool, const SIGNED: bool>(
    p: V3<F>,
    power: F,
    iterations: F::Count,
    bailout: F,
) -> [F; 2] {
    escape_time::<F, SIGNED>(
        p,
        p,
        iterations,
        mandelbulb_escape(power, bailout),
        #[inline(always)]
        |z, r, dr| {
            let (z, dr) = bulb_power::<F, STRETCHED>(z, r, dr, power);
            (z, dr + c(1.0))
        },
    )
}

/// z ↦ z^power in spherical coordinates (r = |z|), the map of the Mandelbulb and the Juliabulb, with the chain rule's
/// dr ↦ power·r^(power−1)·dr, times k if `STRETCHED`. k = max(1, |sin(power·θ) / sin θ|) (θ from the polar axis) is
/// how much more the map stretches along the azimuth than along the radius: its Jacobian's largest singular value over
/// the radial one, which tends to the power near the polar axis. With it the Juliabulb's estimate stays below the true
/// distance. The Mandelbulb keeps the plain rule from power 4 up, as the correction leaves its outliers near the x and
/// y axes and its smaller estimate stops rays further in front of the power-8 bulb; below it, it takes the stretch
/// (measured: `docs/settings.md`, “Step factors of the fractal families”).
#[inline(always)]
pub(super) fn bulb_power<F: Num, const STRETCHED: bool>(z: V3<F>, r: F, dr: F, power: F) -> (V3<F>, F) {
    // θ from atan2(ρ, z), not acos(z/r): acos is ill-conditioned at ±1, where GPU drivers' approximations lose most
    // (lavapipe's by ~1e-4 rad at the poles, which an orbit then magnifies). On the polar axis the azimuth is
    // undefined and atan2(0, 0) differs between drivers: it is taken as 0 there on every backend.
    let rho = sqrt(z.x * z.x + z.y * z.y);
    let theta = (!STRETCHED).then(|| atan2(rho, z.z) * power);
    let phi = select(gt(rho, c(0.0)), atan2(z.y, z.x), c(0.0)) * power;
    let dr = power * pow(r, power - c(1.0)) * dr;
    let zr = pow(r, power);
    let (st, ct) = match theta {
        Some(theta) => (sin(theta), cos(theta)),
        None => polar_trig_from_the_nearer_pole(rho, z.z, power),
    };
    let (sp, cp) = (sin(phi), cos(phi));
    let dr = if STRETCHED {
        // |sin pθ / sin θ| = |sin pθ|·r/ρ, capped at p: its limit on the axis and its bound for integer powers (a
        // non-integer power tears space along the negative axis, where no derivative bounds it).
        let sin_ratio_r = abs(st) * r;
        dr * select(le(rho * power, sin_ratio_r), power, max(sin_ratio_r / max(rho, c(TINY)), c(1.0)))
    } else {
        dr
    };
    (v3(st * cp, sp * st, ct) * zr, dr)
}

/// sin pθ and cos pθ, θ = atan2(ρ, z), for the stretched map, whose estimate reads |sin pθ| relative to ρ. For a
/// whole power p below the equator pθ = pπ − pθ', θ' the angle from the south pole, so they are ±sin pθ' and
/// ±cos pθ': taken so, they keep their precision near the negative axis, where pθ lies close to a multiple of π and
/// sin pθ would be mostly the rounding of pθ (one ulp of θ on the pole axis moved the estimate by half). The plain map
/// keeps θ: its estimate does not read sin pθ alone, and the selects cost the animated showcase 11 %.
#[inline(always)]
fn polar_trig_from_the_nearer_pole<F: Num>(rho: F, z: F, power: F) -> (F, F) {
    let near = atan2(rho, abs(z));
    let south = lt(z, c(0.0));
    let whole = le(power, floor(power)) & le(floor(power), power);
    let odd = gt(power - c::<F>(2.0) * floor(power * c(0.5)), c(0.5));
    let reflected = south & whole;
    let theta = select(south & !whole, c::<F>(core::f64::consts::PI) - near, near) * power;
    let (s, co) = (sin(theta), cos(theta));
    (select(reflected, select(odd, s, -s), s), select(reflected & odd, -co, co))
}

/// Power-8 Mandelbulb without trigonometry: the same map as [`de_mandelbulb`] at power 8, by
/// (z + iρ)^8 and ((x + iy)/ρ)^8 expanded as polynomials.
#[inline(always)]
pub fn de_mandelbulb8<F: Num>(p: V3<F>, iterations: F::Count, bailout: F) -> [F; 2] {
    mandelbulb8::<F, false>(p, iterations, bailout)
}

/// [`de_mandelbulb8`] signed by membership: ≤ 0 where the orbit never escapes (`signed_by_membership`).
#[inline(always)]
pub fn de_mandelbulb8_signed<F: Num>(p: V3<F>, iterations: F::Count, bailout: F) -> [F; 2] {
    mandelbulb8::<F, true>(p, iterations, bailout)
}

#[inline(always)]
fn mandelbulb8<F: Num, const SIGNED: bool>(p: V3<F>, iterations: F::Count, bailout: F) -> [F; 2] {
    escape_time::<F, SIGNED>(
        p,
        p,
        iterations,
        mandelbulb_escape(c(8.0), bailout),
        #[inline(always)]
        |z, r, dr| mandelbulb8_step(z, r, dr),
    )
}

/// One step of the power-8 Mandelbulb map without trigonometry, z ↦ z^8 (r = |z|), with the derivative
/// dr ↦ 8·r^7·dr + 1.
#[inline(always)]
pub(super) fn mandelbulb8_step<F: Num>(z: V3<F>, r: F, dr: F) -> (V3<F>, F) {
    let x2 = z.x * z.x;
    let y2 = z.y * z.y;
    let a = z.z * z.z;
    let b = x2 + y2;
    let r2 = a + b;
    let dr = c::<F>(8.0) * r2 * r2 * r2 * r * dr + c(1.0);
    let a2 = a * a;
    let b2 = b * b;
    let cos_part = a2 * a2 - c::<F>(28.0) * a2 * a * b + c::<F>(70.0) * a2 * b2 - c::<F>(28.0) * a * b2 * b + b2 * b2;
    let sin_part = c::<F>(8.0) * z.z * (a2 * a - c::<F>(7.0) * a2 * b + c::<F>(7.0) * a * b2 - b2 * b);
    // On the polar axis ρ = 0 and the azimuth is undefined; the map sends x and y to 0 there. The threshold is
    // TINY, not 0: fast-math GPU code flushes subnormal b to 0 inside sqrt, and 1/sqrt(0) would be Inf.
    let inv_rho = select(gt(b, c(TINY)), c::<F>(1.0) / sqrt(max(b, c(TINY))), c(0.0));
    let ux = z.x * inv_rho;
    let uy = z.y * inv_rho;
    let u2x = ux * ux - uy * uy;
    let u2y = c::<F>(2.0) * ux * uy;
    let u4x = u2x * u2x - u2y * u2y;
    let u4y = c::<F>(2.0) * u2x * u2y;
    let u8x = u4x * u4x - u4y * u4y;
    let u8y = c::<F>(2.0) * u4x * u4y;
    let rho_sin = b * inv_rho * sin_part;
    (v3(rho_sin * u8x, rho_sin * u8y, cos_part), dr)
}

/// Menger sponge of `levels` levels in [-1, 1]³ (IQ's formulation).
#[inline(always)]
pub fn de_menger<F: Num>(p: V3<F>, levels: F::Count) -> [F; 2] {
    let (two, three) = (c::<F>(2.0), c::<F>(3.0));
    let (d, _, trap) = repeat(
        levels,
        (sd_box(p, V3::splat(c(1.0))), c::<F>(1.0), c::<F>(1.0)),
        #[inline(always)]
        |(d, s, trap)| {
            let a = (p * s).map(
                #[inline(always)]
                |v| fmod_floor(v, two) - c(1.0),
            );
            let s = s * three;
            let r = a.map(
                #[inline(always)]
                |v| abs(c::<F>(1.0) - three * abs(v)),
            );
            let da = max(r.x, r.y);
            let db = max(r.y, r.z);
            let dc = max(r.z, r.x);
            let cut = (min(min(da, db), dc) - c(1.0)) / s;
            (max(d, cut), s, min(trap, dot(a, a) * c(0.5)))
        },
    );
    [d, trap]
}

/// Sierpinski tetrahedron of `levels` folds (vertices (1,1,1), (-1,-1,1), (1,-1,-1), (-1,1,-1)).
#[inline(always)]
pub fn de_sierpinski<F: Num>(p: V3<F>, levels: F::Count) -> [F; 2] {
    let zero = c::<F>(0.0);
    let (z, scale, trap) = repeat(
        levels,
        (p, c::<F>(1.0), c::<F>(1.0)),
        #[inline(always)]
        |(z, scale, trap)| {
            let z = select3(lt(z.x + z.y, zero), v3(-z.y, -z.x, z.z), z);
            let z = select3(lt(z.x + z.z, zero), v3(-z.z, z.y, -z.x), z);
            let z = select3(lt(z.y + z.z, zero), v3(z.x, -z.z, -z.y), z);
            let z = z * c::<F>(2.0) - V3::splat(c(1.0));
            (z, scale * c(0.5), min(trap, dot(z, z) * c(0.25)))
        },
    );
    let face = max(max(-z.x - z.y - z.z, z.x + z.y - z.z), max(-z.x + z.y + z.z, z.x - z.y + z.z));
    [(face - c(1.0)) * c(INV_SQRT3) * scale, trap]
}

/// Quaternion Julia set z ← z² + c in the slice w = 0, c = (cx, cy, cz, cw); `bailout` is the escape radius of |z|.
#[inline(always)]
pub fn de_julia<F: Num>(p: V3<F>, cx: F, cy: F, cz: F, cw: F, iterations: F::Count, bailout: F) -> [F; 2] {
    julia::<F, false>(p, [cx, cy, cz, cw], iterations, bailout)
}

/// [`de_julia`] signed by membership: ≤ 0 where the orbit never escapes (`signed_by_membership`).
#[inline(always)]
pub fn de_julia_signed<F: Num>(p: V3<F>, cx: F, cy: F, cz: F, cw: F, iterations: F::Count, bailout: F) -> [F; 2] {
    julia::<F, true>(p, [cx, cy, cz, cw], iterations, bailout)
}

/// The quaternion Julia orbit with its constant as `c4`.
#[inline(always)]
fn julia<F: Num, const SIGNED: bool>(p: V3<F>, c4: [F; 4], iterations: F::Count, bailout: F) -> [F; 2] {
    let [cx, cy, cz, cw] = c4;
    let dot4 = |a: [F; 4]| a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3];
    let z0 = [p.x, p.y, p.z, c(0.0)];
    let m0 = dot4(z0);
    let escape2 = bailout * bailout;
    let two = c::<F>(2.0);
    let (_, dz, m, trap) = F::iterate(
        iterations,
        (z0, [c::<F>(1.0), c(0.0), c(0.0), c(0.0)], m0, m0),
        #[inline(always)]
        |&(_, dz, m, _)| !(gt(m, escape2) | gt(dot4(dz), c(DR_MAX))),
        #[inline(always)]
        |(z, dz, _, trap)| {
            // dz ← 2·z·dz (quaternion product), z ← z² + c.
            let dz = [
                two * (z[0] * dz[0] - z[1] * dz[1] - z[2] * dz[2] - z[3] * dz[3]),
                two * (z[0] * dz[1] + z[1] * dz[0] + z[2] * dz[3] - z[3] * dz[2]),
                two * (z[0] * dz[2] + z[2] * dz[0] + z[3] * dz[1] - z[1] * dz[3]),
                two * (z[0] * dz[3] + z[3] * dz[0] + z[1] * dz[2] - z[2] * dz[1]),
            ];
            let z = julia_step(z, [cx, cy, cz, cw]);
            let m = dot4(z);
            (z, dz, m, min(trap, m))
        },
    );
    // At an exactly-zero iterate the derivative vanishes too; the floor keeps the estimate finite.
    let estimate = c::<F>(0.25) * ln(max(m, c(TINY))) * sqrt(m / max(dot4(dz), c(TINY)));
    [if SIGNED { signed_by_membership(estimate, le(m, escape2)) } else { estimate }, min(trap, c(1.0))]
}

/// One step of the quaternion Julia map, z ↦ z² + c.
#[inline(always)]
pub(super) fn julia_step<F: Num>(z: [F; 4], c4: [F; 4]) -> [F; 4] {
    let two = c::<F>(2.0);
    [
        z[0] * z[0] - z[1] * z[1] - z[2] * z[2] - z[3] * z[3] + c4[0],
        two * z[0] * z[1] + c4[1],
        two * z[0] * z[2] + c4[2],
        two * z[0] * z[3] + c4[3],
    ]
}

/// Mandelbox: box fold at `fold_limit`, sphere fold with `min_radius` and fixed radius 1, then z ← scale·z + p.
#[inline(always)]
pub fn de_mandelbox<F: Num>(p: V3<F>, scale: F, iterations: F::Count, min_radius: F, fold_limit: F) -> [F; 2] {
    let min_r2 = min_radius * min_radius;
    let one = c::<F>(1.0);
    let (z, dr, trap) = repeat(
        iterations,
        (p, one, one),
        #[inline(always)]
        |(z, dr, trap)| {
            let (z, f, r2) = mandelbox_step(z, p, scale, min_r2, fold_limit);
            let dr = dr * f * abs(scale) + one;
            (z, dr, min(trap, r2))
        },
    );
    [length(z) / abs(dr), trap]
}

/// One step of the Mandelbox map, z ↦ scale·sphere_fold(box_fold(z)) + p; also gives the sphere fold's factor f (the
/// derivative's) and |box_fold(z)|² (the orbit trap's).
#[inline(always)]
pub(super) fn mandelbox_step<F: Num>(z: V3<F>, p: V3<F>, scale: F, min_r2: F, fold_limit: F) -> (V3<F>, F, F) {
    let one = c::<F>(1.0);
    let z = z.map(
        #[inline(always)]
        |v| clamp(v, -fold_limit, fold_limit) * c(2.0) - v,
    );
    let r2 = dot(z, z);
    // Inside min_radius the fold scales by 1/min_r², between it and 1 by 1/r², outside not at all.
    let f = select(lt(r2, min_r2), one / min_r2, select(lt(r2, one), one / max(r2, c(TINY)), one));
    (z * f * scale + p, f, r2)
}

/// Juliabulb: the Mandelbulb's map of `power` with the constant c = (cx, cy, cz) in place of the point, z ← z^power + c
/// from z = p. The derivative has no + 1: c does not move with p, and takes the map's azimuthal stretch
/// (`bulb_power`).
#[inline(always)]
pub fn de_juliabulb<F: Num>(p: V3<F>, cx: F, cy: F, cz: F, power: F, iterations: F::Count, bailout: F) -> [F; 2] {
    juliabulb::<F, false>(p, [cx, cy, cz, power], iterations, bailout)
}

/// [`de_juliabulb`] signed by membership: ≤ 0 where the orbit never escapes (`signed_by_membership`).
#[inline(always)]
pub fn de_juliabulb_signed<F: Num>(
    p: V3<F>,
    cx: F,
    cy: F,
    cz: F,
    power: F,
    iterations: F::Count,
    bailout: F,
) -> [F; 2] {
    juliabulb::<F, true>(p, [cx, cy, cz, power], iterations, bailout)
}

/// The Juliabulb's orbit with its constant and power as `[cx, cy, cz, power]`.
#[inline(always)]
fn juliabulb<F: Num, const SIGNED: bool>(p: V3<F>, c_power: [F; 4], iterations: F::Count, bailout: F) -> [F; 2] {
    let [cx, cy, cz, power] = c_power;
    // An orbit through 0 (p = 0 itself) has dr = 0 from then on; the floor keeps the estimate finite.
    escape_time::<F, SIGNED>(
        p,
        v3(cx, cy, cz),
        iterations,
        mandelbulb_escape(power, bailout),
        #[inline(always)]
        |z, r, dr| {
            let (z, dr) = bulb_power::<F, true>(z, r, dr, power);
            (z, max(dr, c(TINY)))
        },
    )
}

/// The golden ratio φ, rounded to f32 like every constant below that is not already an f32: the icosahedral fold
/// repeats its mirror at every step of an orbit that magnifies differences by the scale each step, so the f64
/// reference and the f32 kernels must fold with the same mirror, not with roundings of it.
const PHI: f64 = 1.618_033_988_749_895_f64 as f32 as f64;

/// Folds z into the octahedral chamber x ≥ y ≥ z ≥ 0: mirrors in the coordinate planes, then in x = y, x = z, y = z.
#[inline(always)]
pub(super) fn octahedral_fold<F: Num>(z: V3<F>) -> V3<F> {
    let a = abs3(z);
    let a = select3(lt(a.x, a.y), v3(a.y, a.x, a.z), a);
    let a = select3(lt(a.x, a.z), v3(a.z, a.y, a.x), a);
    select3(lt(a.y, a.z), v3(a.x, a.z, a.y), a)
}

/// Folds z towards a chamber of the icosahedron with vertices (0, ±1, ±φ) and their cyclic permutations: three
/// rounds of the mirrors in the coordinate planes and the mirror with normal (−φ, −1, φ − 1)/2.
#[inline(always)]
pub(super) fn icosahedral_fold<F: Num>(z: V3<F>) -> V3<F> {
    let n = v3(c::<F>(-0.5 * PHI), c(-0.5), c(0.5 * (PHI - 1.0)));
    repeat(
        F::count(3),
        z,
        #[inline(always)]
        |z| {
            let a = abs3(z);
            a - n * (c::<F>(2.0) * min(dot(a, n), c(0.0)))
        },
    )
}

/// The unit vertex the octahedral KIFS scales about.
#[inline(always)]
pub(super) fn octahedral_vertex<F: Num>() -> V3<F> {
    v3(c(1.0), c(0.0), c(0.0))
}

/// The unit vertex the icosahedral KIFS scales about: (0, 1, φ) normalised, on the fold's chamber.
#[inline(always)]
pub(super) fn icosahedral_vertex<F: Num>() -> V3<F> {
    let inv = 1.0 / (1.0 + PHI * PHI).sqrt();
    v3(c(0.0), c(inv as f32 as f64), c((PHI * inv) as f32 as f64))
}

/// The orbit of a kaleidoscopic IFS from z = p: fold, turn by `angle` about z, then z ← scale·z − (scale − 1)·vertex,
/// for `iterations` steps or until `going_on(z)` fails; returns the final z, the orbit trap and scaleᵏ for the k
/// steps taken. Every step is
/// `scale`-Lipschitz (folds and turns are isometries) and the set stays within the unit ball (past it |z| − 1 grows by
/// the scale each step), so after all n steps (|z| − 1)/scaleⁿ is a 1-Lipschitz lower bound of the distance to the set:
/// a step factor of 1. (Stopping early where |z| is large would be faster but makes the estimate jump between counts.)
#[inline(always)]
pub(super) fn kifs_orbit<F: Num>(
    p: V3<F>,
    scale: F,
    angle: F,
    iterations: F::Count,
    vertex: V3<F>,
    fold: impl Fn(V3<F>) -> V3<F>,
    going_on: impl Fn(V3<F>) -> F::Mask,
) -> (V3<F>, F, F) {
    let (co, si) = (cos(angle), sin(angle));
    let shift = vertex * (scale - c(1.0));
    F::iterate(
        iterations,
        (p, c::<F>(1.0), c::<F>(1.0)),
        #[inline(always)]
        |&(z, _, _)| going_on(z),
        #[inline(always)]
        |(z, trap, grown)| {
            let z = fold(z);
            let z = v3(co * z.x - si * z.y, si * z.x + co * z.y, z.z);
            let z = z * scale - shift;
            (z, min(trap, dot(z, z)), grown * scale)
        },
    )
}

/// A KIFS estimate from the orbit's full `iterations` steps: (|z| − 1)/scale^iterations, with the orbit trap.
#[inline(always)]
fn kifs_estimate<F: Num>(
    p: V3<F>,
    scale: F,
    angle: F,
    iterations: F::Count,
    vertex: V3<F>,
    fold: impl Fn(V3<F>) -> V3<F>,
) -> [F; 2] {
    let (z, trap, grown) = kifs_orbit(
        p,
        scale,
        angle,
        iterations,
        vertex,
        fold,
        #[inline(always)]
        |_| F::Mask::splat(true),
    );
    [(length(z) - c(1.0)) / grown, min(trap, c(1.0))]
}

/// The octahedral KIFS (at scale 2, the Sierpinski octahedron with vertices (±1, 0, 0), (0, ±1, 0), (0, 0, ±1)).
#[inline(always)]
pub fn de_octahedral_kifs<F: Num>(p: V3<F>, scale: F, angle: F, iterations: F::Count) -> [F; 2] {
    kifs_estimate(p, scale, angle, iterations, octahedral_vertex(), octahedral_fold)
}

/// The icosahedral KIFS (at scale φ² ≈ 2.618, the icosahedron flake).
#[inline(always)]
pub fn de_icosahedral_kifs<F: Num>(p: V3<F>, scale: F, angle: F, iterations: F::Count) -> [F; 2] {
    kifs_estimate(p, scale, angle, iterations, icosahedral_vertex(), icosahedral_fold)
}
