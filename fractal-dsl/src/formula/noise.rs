//! Gradient noise (Perlin's improved noise) in 2D and 3D and its fractal sums (fbm), patterns expressions can call —
//! written once, generic over [`Num`], and reached through the leaf table (`noise2`, `noise3`, `fbm2`, `fbm3` in every
//! kernel that uses them). The other pattern, the Mandelbrot set, is
//! [`crate::formula::mandelbrot`](mod@crate::formula::mandelbrot).
//!
//! The lattice hash is the permutation polynomial (34x² + x) mod 289 (Gustavson and McEwan's table-free noise), on
//! whole numbers below 2^23, so every product is exact in f32 and every backend picks the same gradients: there is no
//! permutation table to copy into a kernel. Each remainder is taken as x − 289·floor((x + ½)/289): the half keeps the
//! quotient away from whole numbers, so a division rounded differently by a driver (fast math, lavapipe) cannot tip
//! the floor. Lattice coordinates are reduced mod 289 first, so the noise repeats every 289 units.
//!
//! Values lie in [−1, 1] (clamped there; the sums of octaves in [−2, 2]); the slopes |∇| stay below
//! [`NOISE2_SLOPE`] and [`NOISE3_SLOPE`] (measured in `fractal-dsl/tests/dsl/noise.rs`), which the displacement's
//! Lipschitz bound reads ([`crate::analyse::slope`]).

use crate::number::math::*;

/// Largest |∇ noise2|: measured 2.75 over 400 000 points (`fractal-dsl/tests/dsl/noise.rs`), with a third more for what
/// sampling misses.
pub const NOISE2_SLOPE: f64 = 3.6;
/// Largest |∇ noise3|: measured 3.09 over 400 000 points, with a third more for what sampling misses.
pub const NOISE3_SLOPE: f64 = 4.1;
/// Largest |fbm| of any number of octaves: Σ ½ⁱ < 2.
pub const FBM_RANGE: f64 = 2.0;
/// Most octaves an fbm takes.
pub const MAX_OCTAVES: u32 = 12;

/// x mod 289 for whole numbers 0 ≤ |x| < 2^23 (see the module comment).
#[inline(always)]
fn mod289<F: Num>(x: F) -> F {
    let m = c::<F>(289.0);
    x - m * floor((x + c(0.5)) / m)
}

/// The permutation polynomial (34x + 1)·x mod 289 of a whole number in [0, 289).
#[inline(always)]
fn permute<F: Num>(x: F) -> F {
    mod289((x * c(34.0) + c(1.0)) * x)
}

/// x mod n for whole numbers in [0, 289) and small whole n.
#[inline(always)]
fn low<F: Num>(x: F, n: f64) -> F {
    x - c::<F>(n) * floor((x + c(0.5)) * c(1.0 / n))
}

/// The quintic fade 6t⁵ − 15t⁴ + 10t³.
#[inline(always)]
fn fade<F: Num>(t: F) -> F {
    t * t * t * (t * (t * c(6.0) - c(15.0)) + c(10.0))
}

/// The 2D gradient of a lattice hash h — (±1, ±1) for h mod 8 below 4, else (±1, 0) or (0, ±1) — dotted with
/// (x, y).
#[inline(always)]
fn grad2<F: Num>(h: F, x: F, y: F) -> F {
    let h = low(h, 8.0);
    let one = c::<F>(1.0);
    let sx = select(lt(low(h, 2.0), c(0.5)), one, -one);
    let sy = select(lt(low(h, 4.0), c(2.0)), one, -one);
    select(lt(h, c(4.0)), sx * x + sy * y, select(lt(h, c(6.0)), sx * x, sx * y))
}

/// Perlin's 3D gradient of a lattice hash h (its low four bits: the twelve cube edge directions and four repeats),
/// dotted with (x, y, z).
#[inline(always)]
fn grad3<F: Num>(h: F, x: F, y: F, z: F) -> F {
    let h = low(h, 16.0);
    let u = select(lt(h, c(8.0)), x, y);
    let twelve_or_fourteen = lt(abs(h - c(12.0)), c(0.5)) | lt(abs(h - c(14.0)), c(0.5));
    let v = select(lt(h, c(4.0)), y, select(twelve_or_fourteen, x, z));
    let bit0 = lt(low(h, 2.0), c(0.5));
    let bit1 = lt(low(h, 4.0), c(2.0));
    select(bit0, u, -u) + select(bit1, v, -v)
}

/// 2D gradient noise at (x, y), in [−1, 1].
#[inline(always)]
pub fn noise2<F: Num>(x: F, y: F) -> F {
    let (ix, iy) = (floor(x), floor(y));
    let (fx, fy) = (x - ix, y - iy);
    let (ix, iy) = (mod289(ix), mod289(iy));
    let one = c::<F>(1.0);
    let (ix1, iy1) = (mod289(ix + one), mod289(iy + one));
    let (px0, px1) = (permute(ix), permute(ix1));
    let h00 = permute(mod289(px0 + iy));
    let h10 = permute(mod289(px1 + iy));
    let h01 = permute(mod289(px0 + iy1));
    let h11 = permute(mod289(px1 + iy1));
    let (u, v) = (fade(fx), fade(fy));
    let a = mix(grad2(h00, fx, fy), grad2(h10, fx - one, fy), u);
    let b = mix(grad2(h01, fx, fy - one), grad2(h11, fx - one, fy - one), u);
    clamp(mix(a, b, v), c(-1.0), c(1.0))
}

/// 3D gradient noise at p, in [−1, 1].
#[inline(always)]
pub fn noise3<F: Num>(p: V3<F>) -> F {
    let i = p.map(floor);
    let f = p - i;
    let one = c::<F>(1.0);
    let i0 = i.map(mod289);
    let i1 = i.map(
        #[inline(always)]
        |v| mod289(v + one),
    );
    let (px0, px1) = (permute(i0.x), permute(i1.x));
    let (p00, p10) = (permute(mod289(px0 + i0.y)), permute(mod289(px1 + i0.y)));
    let (p01, p11) = (permute(mod289(px0 + i1.y)), permute(mod289(px1 + i1.y)));
    let h = |pxy: F, iz: F| permute(mod289(pxy + iz));
    let (gx, gy, gz) = (f.x - one, f.y - one, f.z - one);
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let z0 = mix(
        mix(grad3(h(p00, i0.z), f.x, f.y, f.z), grad3(h(p10, i0.z), gx, f.y, f.z), u),
        mix(grad3(h(p01, i0.z), f.x, gy, f.z), grad3(h(p11, i0.z), gx, gy, f.z), u),
        v,
    );
    let z1 = mix(
        mix(grad3(h(p00, i1.z), f.x, f.y, gz), grad3(h(p10, i1.z), gx, f.y, gz), u),
        mix(grad3(h(p01, i1.z), f.x, gy, gz), grad3(h(p11, i1.z), gx, gy, gz), u),
        v,
    );
    clamp(mix(z0, z1, w), c(-1.0), c(1.0))
}

/// `octaves` octaves of 2D noise: Σ ½ⁱ·noise2(2ⁱ·(x, y)), each octave shifted so the lattices do not line up (by
/// binary fractions, exact in f32, so every backend shifts by the same amount).
#[inline(always)]
pub fn fbm2<F: Num>(x: F, y: F, octaves: F::Count) -> F {
    let one = c::<F>(1.0);
    let (_, _, sum, _) = F::iterate(
        octaves,
        (x, y, c::<F>(0.0), one),
        #[inline(always)]
        |_| F::Mask::splat(true),
        #[inline(always)]
        |(x, y, sum, amp)| {
            let sum = sum + amp * noise2(x, y);
            (x * c(2.0) + c(17.25), y * c(2.0) + c(-9.125), sum, amp * c(0.5))
        },
    );
    sum
}

/// `octaves` octaves of 3D noise: Σ ½ⁱ·noise3(2ⁱ·p), each octave shifted so the lattices do not line up.
#[inline(always)]
pub fn fbm3<F: Num>(p: V3<F>, octaves: F::Count) -> F {
    let shift = v3(c::<F>(17.25), c(-9.125), c(5.75));
    let (_, sum, _) = F::iterate(
        octaves,
        (p, c::<F>(0.0), c::<F>(1.0)),
        #[inline(always)]
        |_| F::Mask::splat(true),
        #[inline(always)]
        |(p, sum, amp)| (p * c::<F>(2.0) + shift, sum + amp * noise3(p), amp * c(0.5)),
    );
    sum
}
