//! The leaf functions: distance to each primitive, each fractal estimator, and the smooth CSG blends, generic over
//! [`Real`]. The interpreter and the generated native evaluator both call these; the kernel writers spell the same
//! formulas in OpenCL C and WGSL (`back/*/library.rs`), and the agreement tests hold all of them together.

use crate::math::*;

/// Smallest divisor used where a formula divides by a user value that may be zero (smooth blend k, capsule length).
pub const TINY: f64 = 1e-30;
/// Derivative cap for escape-time fractals: past it the estimate is 0 to within float precision anyway, and stopping
/// keeps f32 from overflowing to Inf (and Inf/Inf to NaN): power · r^(power−1) · dr stays below 2^128 up to power 64
/// with r ≤ 2^(60/power).
pub const DR_MAX: f64 = 1e17;
/// Largest log2 of |z|^power an iteration may produce: `length` squares |z|, so 2^60 keeps |z|² (2^120) finite in
/// f32 (max ~2^128).
pub const POW_LOG2_MAX: f64 = 60.0;

#[inline(always)]
pub fn sd_sphere<F: Real>(p: V3<F>, r: F) -> F {
    length(p) - r
}

#[inline(always)]
pub fn sd_box<F: Real>(p: V3<F>, b: V3<F>) -> F {
    let q = abs3(p) - b;
    length(max3(q, F::zero())) + q.max_element().min(F::zero())
}

#[inline(always)]
pub fn sd_round_box<F: Real>(p: V3<F>, b: V3<F>, r: F) -> F {
    sd_box(p, b - V3::splat(r)) - r
}

#[inline(always)]
pub fn sd_torus<F: Real>(p: V3<F>, major: F, minor: F) -> F {
    let qx = (p.x * p.x + p.z * p.z).sqrt() - major;
    (qx * qx + p.y * p.y).sqrt() - minor
}

#[inline(always)]
pub fn sd_capsule<F: Real>(p: V3<F>, a: V3<F>, b: V3<F>, r: F) -> F {
    let pa = p - a;
    let ba = b - a;
    let h = clamp(dot(pa, ba) / dot(ba, ba).max(c(TINY)), F::zero(), F::one());
    length(pa - ba * h) - r
}

#[inline(always)]
pub fn sd_cylinder<F: Real>(p: V3<F>, r: F, h: F) -> F {
    let dx = (p.x * p.x + p.z * p.z).sqrt() - r;
    let dy = p.y.abs() - h;
    let ox = dx.max(F::zero());
    let oy = dy.max(F::zero());
    dx.max(dy).min(F::zero()) + (ox * ox + oy * oy).sqrt()
}

/// IQ's exact capped cone.
#[inline(always)]
pub fn sd_cone<F: Real>(p: V3<F>, h: F, r1: F, r2: F) -> F {
    let qx = (p.x * p.x + p.z * p.z).sqrt();
    let qy = p.y;
    let k2x = r2 - r1;
    let k2y = h + h;
    let cax = qx - qx.min(if qy < F::zero() { r1 } else { r2 });
    let cay = qy.abs() - h;
    let t = clamp(((r2 - qx) * k2x + (h - qy) * k2y) / (k2x * k2x + k2y * k2y), F::zero(), F::one());
    let cbx = qx - r2 + k2x * t;
    let cby = qy - h + k2y * t;
    let s = if cbx < F::zero() && cay < F::zero() { -F::one() } else { F::one() };
    s * (cax * cax + cay * cay).min(cbx * cbx + cby * cby).sqrt()
}

#[inline(always)]
pub fn sd_plane<F: Real>(p: V3<F>, n: V3<F>, offset: F) -> F {
    dot(p, n) + offset
}

/// IQ's exact octahedron.
#[inline(always)]
pub fn sd_octahedron<F: Real>(p: V3<F>, s: F) -> F {
    let p = abs3(p);
    let m = p.x + p.y + p.z - s;
    let three = c::<F>(3.0);
    let q = if three * p.x < m {
        p
    } else if three * p.y < m {
        v3(p.y, p.z, p.x)
    } else if three * p.z < m {
        v3(p.z, p.x, p.y)
    } else {
        return m * c(0.577_350_269_189_625_8);
    };
    let k = clamp(c::<F>(0.5) * (q.z - q.y + s), F::zero(), s);
    length(v3(q.x, q.y - s + k, q.z - k))
}

/// IQ's ellipsoid bound; at the centre, minus the smallest radius.
#[inline(always)]
pub fn sd_ellipsoid<F: Real>(p: V3<F>, r: V3<F>) -> F {
    let k0 = length(v3(p.x / r.x, p.y / r.y, p.z / r.z));
    let k1 = length(v3(p.x / (r.x * r.x), p.y / (r.y * r.y), p.z / (r.z * r.z)));
    if k1 > F::zero() {
        k0 * (k0 - F::one()) / k1
    } else {
        -r.min_element()
    }
}

// ---- smooth CSG -----------------------------------------------------------------------------------------------------

/// Polynomial smooth minimum (IQ) with blend radius k; k = 0 is the plain minimum (no division by zero).
#[inline(always)]
pub fn smooth_min<F: Real>(a: F, b: F, k: F) -> F {
    let h = (k - (a - b).abs()).max(F::zero()) / k.max(c(TINY));
    a.min(b) - h * h * k * c(0.25)
}

#[inline(always)]
pub fn smooth_max<F: Real>(a: F, b: F, k: F) -> F {
    -smooth_min(-a, -b, k)
}

/// How far a smooth blend of `a` and `b` leans towards `b` (0 = all `a`, 1 = all `b`): mixes materials.
#[inline(always)]
pub fn blend_weight<F: Real>(a: F, b: F, k: F) -> F {
    clamp(c::<F>(0.5) + c::<F>(0.5) * (a - b) / k.max(c(TINY)), F::zero(), F::one())
}

// ---- fractals: each returns (distance estimate, orbit trap in [0, 1]) --------------------------------------------------

/// Escape radius that keeps r^power finite in f32 and below the user's bailout.
#[inline(always)]
pub fn mandelbulb_escape<F: Real>(power: F, bailout: F) -> F {
    bailout.min((c::<F>(POW_LOG2_MAX) / power).exp2())
}

/// Mandelbulb of any power by the trigonometric form; the derivative uses the same `power` as the iteration.
#[inline(always)]
pub fn de_mandelbulb<F: Real>(p: V3<F>, power: F, iterations: u32, bailout: F) -> [F; 2] {
    let escape = mandelbulb_escape(power, bailout);
    let mut z = p;
    let mut dr = F::one();
    let mut r = length(z);
    let mut trap = r;
    for _ in 0..iterations {
        if r > escape || dr > c(DR_MAX) {
            break;
        }
        let theta = clamp(z.z / r.max(c(TINY)), -F::one(), F::one()).acos() * power;
        let phi = z.y.atan2(z.x) * power;
        dr = power * r.powf(power - F::one()) * dr + F::one();
        let zr = r.powf(power);
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        z = v3(st * cp, sp * st, ct) * zr + p;
        r = length(z);
        trap = trap.min(r);
    }
    [c::<F>(0.5) * r.max(c(TINY)).ln() * r / dr, trap.min(F::one())]
}

/// Power-8 Mandelbulb without trigonometry: the same map as [`de_mandelbulb`] at power 8, by
/// (z + iρ)^8 and ((x + iy)/ρ)^8 expanded as polynomials.
#[inline(always)]
pub fn de_mandelbulb8<F: Real>(p: V3<F>, iterations: u32, bailout: F) -> [F; 2] {
    let escape = mandelbulb_escape(c(8.0), bailout);
    let mut z = p;
    let mut dr = F::one();
    let mut r = length(z);
    let mut trap = r;
    for _ in 0..iterations {
        if r > escape || dr > c(DR_MAX) {
            break;
        }
        let x2 = z.x * z.x;
        let y2 = z.y * z.y;
        let a = z.z * z.z;
        let b = x2 + y2;
        let r2 = a + b;
        dr = c::<F>(8.0) * r2 * r2 * r2 * r * dr + F::one();
        let a2 = a * a;
        let b2 = b * b;
        let cos_part =
            a2 * a2 - c::<F>(28.0) * a2 * a * b + c::<F>(70.0) * a2 * b2 - c::<F>(28.0) * a * b2 * b + b2 * b2;
        let sin_part = c::<F>(8.0) * z.z * (a2 * a - c::<F>(7.0) * a2 * b + c::<F>(7.0) * a * b2 - b2 * b);
        // On the polar axis ρ = 0 and the azimuth is undefined; the map sends x and y to 0 there. The threshold is
        // TINY, not 0: fast-math GPU code flushes subnormal b to 0 inside sqrt, and 1/sqrt(0) would be Inf.
        let inv_rho = if b > c(TINY) { F::one() / b.sqrt() } else { F::zero() };
        let ux = z.x * inv_rho;
        let uy = z.y * inv_rho;
        let u2x = ux * ux - uy * uy;
        let u2y = c::<F>(2.0) * ux * uy;
        let u4x = u2x * u2x - u2y * u2y;
        let u4y = c::<F>(2.0) * u2x * u2y;
        let u8x = u4x * u4x - u4y * u4y;
        let u8y = c::<F>(2.0) * u4x * u4y;
        let rho_sin = b * inv_rho * sin_part;
        z = v3(rho_sin * u8x, rho_sin * u8y, cos_part) + p;
        r = length(z);
        trap = trap.min(r);
    }
    [c::<F>(0.5) * r.max(c(TINY)).ln() * r / dr, trap.min(F::one())]
}

/// Menger sponge of `levels` levels in [-1, 1]³ (IQ's formulation).
#[inline(always)]
pub fn de_menger<F: Real>(p: V3<F>, levels: u32) -> [F; 2] {
    let mut d = sd_box(p, V3::splat(F::one()));
    let mut s = F::one();
    let mut trap = F::one();
    let two = c::<F>(2.0);
    let three = c::<F>(3.0);
    for _ in 0..levels {
        let a = (p * s).map(|v| fmod_floor(v, two) - F::one());
        s = s * three;
        let r = a.map(|v| (F::one() - three * v.abs()).abs());
        let da = r.x.max(r.y);
        let db = r.y.max(r.z);
        let dc = r.z.max(r.x);
        let cut = (da.min(db).min(dc) - F::one()) / s;
        d = d.max(cut);
        trap = trap.min(dot(a, a) * c(0.5));
    }
    [d, trap]
}

/// Sierpinski tetrahedron of `levels` folds (vertices (1,1,1), (-1,-1,1), (1,-1,-1), (-1,1,-1)).
#[inline(always)]
pub fn de_sierpinski<F: Real>(p: V3<F>, levels: u32) -> [F; 2] {
    let mut z = p;
    let mut trap = F::one();
    for _ in 0..levels {
        if z.x + z.y < F::zero() {
            z = v3(-z.y, -z.x, z.z);
        }
        if z.x + z.z < F::zero() {
            z = v3(-z.z, z.y, -z.x);
        }
        if z.y + z.z < F::zero() {
            z = v3(z.x, -z.z, -z.y);
        }
        z = z * c::<F>(2.0) - V3::splat(F::one());
        trap = trap.min(dot(z, z) * c(0.25));
    }
    let face = (-z.x - z.y - z.z).max(z.x + z.y - z.z).max((-z.x + z.y + z.z).max(z.x - z.y + z.z));
    [(face - F::one()) * c(0.577_350_269_189_625_8) * c::<F>(0.5).powi(levels as i32), trap]
}

/// Quaternion Julia set z ← z² + c in the slice w = 0; `bailout` is the escape radius of |z|.
#[inline(always)]
pub fn de_julia<F: Real>(p: V3<F>, cq: [F; 4], iterations: u32, bailout: F) -> [F; 2] {
    let mut z = [p.x, p.y, p.z, F::zero()];
    let mut dz = [F::one(), F::zero(), F::zero(), F::zero()];
    let dot4 = |a: [F; 4]| a[0] * a[0] + a[1] * a[1] + a[2] * a[2] + a[3] * a[3];
    let mut m = dot4(z);
    let mut trap = m;
    let escape2 = bailout * bailout;
    for _ in 0..iterations {
        if m > escape2 || dot4(dz) > c(DR_MAX) {
            break;
        }
        // dz ← 2·z·dz (quaternion product), z ← z² + c.
        let two = c::<F>(2.0);
        dz = [
            two * (z[0] * dz[0] - z[1] * dz[1] - z[2] * dz[2] - z[3] * dz[3]),
            two * (z[0] * dz[1] + z[1] * dz[0] + z[2] * dz[3] - z[3] * dz[2]),
            two * (z[0] * dz[2] + z[2] * dz[0] + z[3] * dz[1] - z[1] * dz[3]),
            two * (z[0] * dz[3] + z[3] * dz[0] + z[1] * dz[2] - z[2] * dz[1]),
        ];
        z = [
            z[0] * z[0] - z[1] * z[1] - z[2] * z[2] - z[3] * z[3] + cq[0],
            two * z[0] * z[1] + cq[1],
            two * z[0] * z[2] + cq[2],
            two * z[0] * z[3] + cq[3],
        ];
        m = dot4(z);
        trap = trap.min(m);
    }
    // At an exactly-zero iterate the derivative vanishes too; the floor keeps the estimate finite.
    [c::<F>(0.25) * m.max(c(TINY)).ln() * (m / dot4(dz).max(c(TINY))).sqrt(), trap.min(F::one())]
}

/// Mandelbox: box fold at `fold_limit`, sphere fold with `min_radius` and fixed radius 1, then z ← scale·z + p.
#[inline(always)]
pub fn de_mandelbox<F: Real>(p: V3<F>, scale: F, iterations: u32, min_radius: F, fold_limit: F) -> [F; 2] {
    let mut z = p;
    let mut dr = F::one();
    let min_r2 = min_radius * min_radius;
    let mut trap = F::one();
    for _ in 0..iterations {
        z = z.map(|v| clamp(v, -fold_limit, fold_limit) * c(2.0) - v);
        let r2 = dot(z, z);
        if r2 < min_r2 {
            let f = F::one() / min_r2;
            z = z * f;
            dr = dr * f;
        } else if r2 < F::one() {
            let f = F::one() / r2;
            z = z * f;
            dr = dr * f;
        }
        z = z * scale + p;
        dr = dr * scale.abs() + F::one();
        trap = trap.min(r2);
    }
    [length(z) / dr.abs(), trap]
}
