//! The elementary functions in f64 built from what every f64 device computes correctly: `+ − × ÷`, `sqrt`, `floor`,
//! `abs`, `min`, `max`, comparisons and selects — written once, generic over [`Num`], so a kernel traces them like any
//! formula. Vulkan's SPIR-V (GLSL.std.450) defines `sin`, `cos`, `acos`, `atan2`, `exp2`, `log` and `pow` for 16-
//! and 32-bit floats only, and lavapipe returns garbage for them in f64, so an f64 WGSL kernel calls these instead
//! (`crate::back::wgsl`); double-single arithmetic needs the same.
//!
//! The methods are fdlibm's where it has a branch-free form (the π/2 reduction in three parts and the kernel
//! polynomials of `sin` and `cos`, `ln` through atanh with ln 2 in two parts) and series otherwise: `exp2` by Taylor
//! on |f| ≤ ½, `atan` after two half-angle reductions. The exponent is found and applied by halving and doubling in
//! powers of two chosen with selects (no bit access). Their error against libm is stated per function and checked
//! over dense sweeps by this module's tests; they assume f64 (the constants and the number of terms are f64's).

// fdlibm's coefficients, quoted as it publishes them.
#![allow(clippy::excessive_precision)]

use super::Num;

/// The powers of two [`scale_exponent`] multiplies by, largest first; 512 twice so that the subnormal and overflowing
/// ends of f64 (2^−1074, 2^1024) are reached.
const STEPS: [i32; 11] = [512, 512, 256, 128, 64, 32, 16, 8, 4, 2, 1];

fn lit<N: Num>(v: f64) -> N {
    N::lit(v)
}

fn not_nan<N: Num>(x: N) -> N::Mask {
    N::le(x, x)
}

/// `m == b` for numbers that are whole (quadrants, exponents).
fn equals<N: Num>(a: N, b: f64) -> N::Mask {
    N::le(a, lit(b)) & N::le(lit(b), a)
}

/// 2^k · r for a whole k in [−1535, 1535] (f64's range and beyond: the result overflows or underflows as the product
/// does).
fn scale_exponent<N: Num>(r: N, k: N) -> N {
    let (mut r, mut k) = (r, k);
    for b in STEPS {
        let up = N::le(lit(f64::from(b)), k);
        r = N::select(up, r * lit(2f64.powi(b)), r);
        k = N::select(up, k - lit(f64::from(b)), k);
        let down = N::le(k, lit(-f64::from(b)));
        r = N::select(down, r * lit(2f64.powi(-b)), r);
        k = N::select(down, k + lit(f64::from(b)), k);
    }
    r
}

/// `x` = m · 2^e with m in (√½, √2], for positive finite x: (m, e).
fn split_exponent<N: Num>(x: N) -> (N, N) {
    let (mut m, mut e) = (x, lit::<N>(0.0));
    for b in STEPS {
        let big = N::le(lit(2f64.powi(b)), m);
        m = N::select(big, m * lit(2f64.powi(-b)), m);
        e = N::select(big, e + lit(f64::from(b)), e);
        let small = N::lt(m, lit(2f64.powi(1 - b)));
        m = N::select(small, m * lit(2f64.powi(b)), m);
        e = N::select(small, e - lit(f64::from(b)), e);
    }
    // m in [1, 2)
    let high = N::lt(lit(core::f64::consts::SQRT_2), m);
    (N::select(high, m * lit(0.5), m), N::select(high, e + lit(1.0), e))
}

/// Horner's rule: c[0] + z·(c[1] + z·(…)).
fn horner<N: Num>(z: N, c: &[f64]) -> N {
    c.iter().rev().skip(1).fold(lit(c[c.len() - 1]), |acc, &k| lit::<N>(k) + z * acc)
}

const LN2_HI: f64 = 6.93147180369123816490e-01;
const LN2_LO: f64 = 1.90821492927058770002e-10;

/// ln(m) − e·ln 2's low part, for m in (√½, √2], by fdlibm's `log`: with f = m − 1 and s = f/(2 + f),
/// ln(1 + f) = f − f²/2 + s·(f²/2 + R), R the atanh series in s² to s^22 (the next term is below 2^−60 of the sum);
/// `e` adds e·ln 2 in two parts.
fn ln_split<N: Num>(m: N, e: N) -> N {
    let f = m - lit(1.0);
    let hfsq = lit::<N>(0.5) * f * f;
    let s = f / (lit::<N>(2.0) + f);
    let z = s * s;
    let terms: [f64; 11] = std::array::from_fn(|k| 2.0 / (2 * k + 3) as f64);
    let r = z * horner(z, &terms);
    e * lit(LN2_HI) - ((hfsq - (s * (hfsq + r) + e * lit(LN2_LO))) - f)
}

/// Natural logarithm, within 1 ulp of libm (measured); ln(0) = −∞, ln(x < 0) = NaN, ln(∞) = ∞, NaN for NaN.
pub fn ln<N: Num>(x: N) -> N {
    let (m, e) = split_exponent(x);
    let r = ln_split(m, e);
    let zero = equals(x, 0.0);
    // The special values come from x itself, so no infinite constant is written.
    let r = N::select(N::lt(lit(f64::MAX), x), x, r);
    let r = N::select(zero, lit::<N>(-1.0) / x, r);
    N::select(N::lt(x, lit(0.0)), N::sqrt(x), r)
}

/// 2^x, within 1 ulp of libm (measured); 0 below −1075, ∞ from 1024, NaN for NaN.
pub fn exp2<N: Num>(x: N) -> N {
    let c = N::min(N::max(x, lit(-1100.0)), lit(1100.0));
    let k = N::floor(c + lit(0.5));
    // e^t for |t| ≤ ½·ln 2 by Taylor to t^14 (the next term is below 2^−70).
    let t = (c - k) * lit(core::f64::consts::LN_2);
    let terms: [f64; 15] = std::array::from_fn(|n| 1.0 / (1..=n).map(|i| i as f64).product::<f64>());
    let r = scale_exponent(horner(t, &terms), k);
    N::select(not_nan(x), r, x)
}

/// x^y for x ≥ 0 and, where y is whole, x < 0; NaN for x < 0 and y not whole. As 2^w with w = y·log2 |x|, whose
/// rounding costs up to 2|w| ulps of the result: within 2·(2 + |w|) ulps of libm (measured ≤ 1.66·(2 + |w|) on x in
/// [1e-3, 1e3], y in [−16, 16]). A fractal's orbit near its surface keeps |x| near 1, where w is small.
pub fn pow<N: Num>(x: N, y: N) -> N {
    let ax = N::abs(x);
    let (m, e) = split_exponent(ax);
    let log2 = ln_split(m, e) * lit(core::f64::consts::LOG2_E);
    let r = exp2(y * log2);
    // |x| = 0 or ∞ (log2 is ±∞ or NaN there): 0^y is 0, 1 or ∞ by y's sign; ∞^y is ∞, 1 or 0.
    let zero = equals(ax, 0.0);
    let r = N::select(zero & N::lt(lit(0.0), y), lit(0.0), r);
    let r = N::select(zero & N::lt(y, lit(0.0)), lit::<N>(1.0) / ax, r);
    let infinite = N::lt(lit(f64::MAX), ax);
    let r = N::select(infinite & N::lt(lit(0.0), y), ax, r);
    let r = N::select(infinite & N::lt(y, lit(0.0)), lit(0.0), r);
    // x < 0: whole y takes the sign of x^y from its parity; any other y is NaN.
    let whole = equals(y - N::floor(y), 0.0);
    let odd = equals(y - lit::<N>(2.0) * N::floor(y * lit(0.5)), 1.0);
    let negative = N::lt(x, lit(0.0));
    let r = N::select(negative & whole & odd, -r, r);
    let r = N::select(negative & !whole, N::sqrt(x), r);
    N::select(equals(y, 0.0), lit(1.0), r)
}

const PIO2_1: f64 = 1.57079632673412561417e+00;
const PIO2_2: f64 = 6.07710050630396597660e-11;
const PIO2_2T: f64 = 2.02226624879595063154e-21;

/// x − n·π/2 with n the nearest whole number to x·2/π, in three parts (the first two products exact for |n| < 2^20):
/// (n, r), |r| ≤ π/4.
fn reduce_half_pi<N: Num>(x: N) -> (N, N) {
    let n = N::floor(x * lit(core::f64::consts::FRAC_2_PI) + lit(0.5));
    let r = ((x - n * lit(PIO2_1)) - n * lit(PIO2_2)) - n * lit(PIO2_2T);
    (n, r)
}

/// fdlibm's `__kernel_sin` on |r| ≤ π/4.
fn sin_reduced<N: Num>(r: N) -> N {
    const S: [f64; 6] = [
        -1.66666666666666324348e-01,
        8.33333333332248946124e-03,
        -1.98412698298579493134e-04,
        2.75573137070700676789e-06,
        -2.50507602534068634195e-08,
        1.58969099521155010221e-10,
    ];
    let z = r * r;
    r + r * z * horner(z, &S)
}

/// fdlibm's `__kernel_cos` on |r| ≤ π/4.
fn cos_reduced<N: Num>(r: N) -> N {
    const C: [f64; 6] = [
        4.16666666666666019037e-02,
        -1.38888888888741095749e-03,
        2.48015872894767294178e-05,
        -2.75573143513906633035e-07,
        2.08757232129817482790e-09,
        -1.13596475577881948265e-11,
    ];
    let z = r * r;
    let hz = z * lit(0.5);
    let w = lit::<N>(1.0) - hz;
    w + (((lit::<N>(1.0) - w) - hz) + z * z * horner(z, &C))
}

/// The quadrant n mod 4 of a reduction: (odd, in the lower half: 2 or 3).
fn quadrant<N: Num>(n: N) -> (N::Mask, N::Mask) {
    let q = n - lit::<N>(4.0) * N::floor(n * lit(0.25));
    let odd = equals(q - lit::<N>(2.0) * N::floor(q * lit(0.5)), 1.0);
    (odd, N::lt(lit(1.5), q))
}

/// sin x, within 1 ulp of libm for |x| < 2^20·π/2 (measured; beyond, the reduction loses bits).
pub fn sin<N: Num>(x: N) -> N {
    let (n, r) = reduce_half_pi(x);
    let (odd, lower) = quadrant(n);
    let v = N::select(odd, cos_reduced(r), sin_reduced(r));
    // sin ±0 = ±0: its sign reaches an angle taken of it later (atan2 of a zero).
    N::select(equals(x, 0.0), x, N::select(lower, -v, v))
}

/// cos x, within 1 ulp of libm for |x| < 2^20·π/2 (measured).
pub fn cos<N: Num>(x: N) -> N {
    let (n, r) = reduce_half_pi(x);
    let (odd, lower) = quadrant(n);
    let v = N::select(odd, sin_reduced(r), cos_reduced(r));
    // Quadrants 1 and 2 are negative.
    N::select((odd & !lower) | (!odd & lower), -v, v)
}

/// atan t for t ≥ 0 (∞ included), by fdlibm's `atan`: t reduced to |u| < 7/16 around one of atan ½, atan 1,
/// atan 1.5 or π/2 (each in two parts), then its odd polynomial.
fn atan_positive<N: Num>(t: N) -> N {
    const AT: [f64; 11] = [
        3.33333333333329318027e-01,
        -1.99999999998764832476e-01,
        1.42857142725034663711e-01,
        -1.11111104054623557880e-01,
        9.09088713343650656196e-02,
        -7.69187620504482999495e-02,
        6.66107313738753120669e-02,
        -5.83357013379057348645e-02,
        4.97687799461593236017e-02,
        -3.65315727442169155270e-02,
        1.62858201153657823623e-02,
    ];
    const HI: [f64; 4] = [
        4.63647609000806093515e-01,
        core::f64::consts::FRAC_PI_4,
        9.82793723247329054082e-01,
        core::f64::consts::FRAC_PI_2,
    ];
    const LO: [f64; 4] = [
        2.26987774529616870924e-17,
        3.06161699786838301793e-17,
        1.39033110312309984516e-17,
        6.12323399573676603587e-17,
    ];
    let one = lit::<N>(1.0);
    // The reductions, from the largest t down, so the last that applies wins.
    let reductions = [
        (2.4375, -one / t, 3),
        (1.1875, (t - lit(1.5)) / (one + lit::<N>(1.5) * t), 2),
        (0.6875, (t - one) / (t + one), 1),
        (0.4375, (lit::<N>(2.0) * t - one) / (lit::<N>(2.0) + t), 0),
    ];
    let (mut u, mut hi, mut lo) = (t, lit::<N>(0.0), lit::<N>(0.0));
    let mut taken = <N::Mask as super::Mask>::splat(false);
    for (from, reduced, i) in reductions {
        let here = N::le(lit(from), t) & !taken;
        u = N::select(here, reduced, u);
        hi = N::select(here, lit(HI[i]), hi);
        lo = N::select(here, lit(LO[i]), lo);
        taken = taken | here;
    }
    let z = u * u;
    hi - ((u * z * horner(z, &AT) - lo) - u)
}

const PI_LO: f64 = 1.2246467991473531772e-16;

/// Whether x is negative, −0 included (1/−0 = −∞).
fn sign_bit<N: Num>(x: N) -> N::Mask {
    N::lt(x, lit(0.0)) | N::lt(lit::<N>(1.0) / x, lit(0.0))
}

/// The angle of (x, y), as atan2(y, x), within 1 ulp of libm (measured), signed zeros as libm: ±0 for (+0, ±0),
/// ±π for (−0, ±0).
pub fn atan2<N: Num>(y: N, x: N) -> N {
    let (ax, ay) = (N::abs(x), N::abs(y));
    let origin = equals(ax, 0.0) & equals(ay, 0.0);
    let z = atan_positive(ay / N::select(origin, lit(1.0), ax));
    // Reflected for x < 0, and for x = −0 where y is ±0 too (elsewhere on x = ±0 the angle is ±π/2 either way).
    let reflect = N::lt(x, lit(0.0)) | (origin & sign_bit(x));
    let z = N::select(reflect, lit::<N>(core::f64::consts::PI) - (z - lit(PI_LO)), z);
    let z = N::select(sign_bit(y), -z, z);
    N::select(not_nan(x) & not_nan(y), z, x + y)
}

/// acos x = 2·atan2(√(1 − x), √(1 + x)), within 2 ulps of libm (measured); NaN outside [−1, 1].
pub fn acos<N: Num>(x: N) -> N {
    let one = lit::<N>(1.0);
    lit::<N>(2.0) * atan2(N::sqrt(one - x), N::sqrt(one + x))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The error of `got` against `want` in ulps of `want` (0 where both are NaN or equal infinities).
    fn ulps(got: f64, want: f64) -> f64 {
        if got == want || (got.is_nan() && want.is_nan()) {
            return 0.0;
        }
        // The spacing of f64 at `want`: 2^−52 of the power of two at or below |want|.
        let spacing = (want.abs().log2().floor().exp2() * f64::EPSILON).max(f64::from_bits(1));
        (got - want).abs() / spacing
    }

    /// `n` points from `lo` to `hi`, spread evenly and nudged off round numbers.
    fn sweep(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
        (0..=n).map(move |i| lo + (hi - lo) * (i as f64 + 0.123_456_789 * ((i % 7) as f64 / 7.0)) / n as f64)
    }

    fn worst(points: impl Iterator<Item = f64>, f: impl Fn(f64) -> (f64, f64)) -> (f64, f64) {
        points.map(|x| (ulps(f(x).0, f(x).1), x)).fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a })
    }

    #[test]
    fn sin_and_cos_are_within_an_ulp_and_a_half() {
        let (s, at_s) = worst(sweep(-200.0, 200.0, 400_000), |x| (sin(x), x.sin()));
        let (c, at_c) = worst(sweep(-200.0, 200.0, 400_000), |x| (cos(x), x.cos()));
        // An ulp of the result, plus the reduction near a zero of the result, where its ulp is small.
        assert!(s <= 1.5, "sin: {s} ulps at {at_s}");
        assert!(c <= 1.5, "cos: {c} ulps at {at_c}");
        assert!(sin(f64::NAN).is_nan() && cos(f64::INFINITY).is_nan());
        assert!(sin(-0.0f64).is_sign_negative() && sin(0.0f64).is_sign_positive());
    }

    #[test]
    fn ln_and_exp2_are_within_an_ulp() {
        let (l, at) = worst(sweep(1e-3, 1e3, 400_000).chain(sweep(0.5, 2.0, 100_000)), |x| (ln(x), x.ln()));
        assert!(l <= 1.0, "ln: {l} ulps at {at}");
        let (l, at) = worst([1e-300, 1e300, f64::MIN_POSITIVE, 4.9e-324, f64::MAX].into_iter(), |x| (ln(x), x.ln()));
        assert!(l <= 1.0, "ln at the ends: {l} ulps at {at}");
        assert_eq!(ln(0.0), f64::NEG_INFINITY);
        assert_eq!(ln(f64::INFINITY), f64::INFINITY);
        assert!(ln(-1.0f64).is_nan() && ln(f64::NAN).is_nan());
        let (e, at) = worst(sweep(-1070.0, 1023.0, 400_000).chain(sweep(-2.0, 2.0, 100_000)), |x| (exp2(x), x.exp2()));
        assert!(e <= 1.0, "exp2: {e} ulps at {at}");
        assert_eq!(exp2(1024.5), f64::INFINITY);
        assert_eq!(exp2(-1100.0), 0.0);
        assert!(exp2(f64::NAN).is_nan());
    }

    #[test]
    fn pow_is_within_twice_two_plus_its_exponent_in_ulps() {
        let mut worst_seen = (0.0, 0.0, 0.0);
        for x in sweep(1e-3, 1e3, 2_000) {
            for y in sweep(-16.0, 16.0, 200) {
                let w = (y * x.log2()).abs();
                let e = ulps(pow(x, y), x.powf(y)) / (2.0 * (2.0 + w));
                if e > worst_seen.0 {
                    worst_seen = (e, x, y);
                }
            }
        }
        assert!(worst_seen.0 <= 1.0, "pow: {} × 2(2 + |w|) ulps at {}^{}", worst_seen.0, worst_seen.1, worst_seen.2);
        for (x, y) in [(0.0, 2.0), (0.0, 0.0), (0.0, -1.0), (-2.0, 3.0), (-2.0, 2.0), (-2.0, 0.5), (5.0, 0.0)] {
            let (got, want) = (pow(x, y), f64::powf(x, y));
            assert!(got == want || (got.is_nan() && want.is_nan()), "pow({x}, {y}) = {got}, libm {want}");
        }
    }

    #[test]
    fn atan2_is_within_an_ulp_and_acos_two() {
        let mut a = (0.0, 0.0);
        for angle in sweep(-core::f64::consts::PI, core::f64::consts::PI, 200_000) {
            for r in [1e-3, 0.7, 1.0, 5e3] {
                let (y, x) = (r * angle.sin(), r * angle.cos());
                let e = ulps(atan2(y, x), y.atan2(x));
                if e > a.0 {
                    a = (e, angle);
                }
            }
        }
        assert!(a.0 <= 1.0, "atan2: {} ulps at angle {}", a.0, a.1);
        for (y, x) in [(0.0, 0.0), (-0.0, 0.0), (0.0, -0.0), (-0.0, -0.0), (0.0, -1.0), (-0.0, -1.0), (1.0, -0.0)] {
            let (got, want) = (atan2(y, x), f64::atan2(y, x));
            assert!(
                got == want && got.is_sign_negative() == want.is_sign_negative(),
                "atan2({y}, {x}) = {got}, {want}"
            );
        }
        assert!(atan2(f64::NAN, 1.0).is_nan());
        let (c, at) = worst(sweep(-1.0, 1.0, 400_000), |x| (acos(x), x.acos()));
        assert!(c <= 2.0, "acos: {c} ulps at {at}");
        assert!(acos(1.5f64).is_nan());
    }
}
