//! How steeply an expression can change with the point: an upper bound of |∇ₚ e| over every point, time and parameter
//! value, by the chain rule over the expression with the interval ranges of its parts. A displacement divides its
//! distance by 1 + this bound, so the displaced distance stays a lower bound of the true distance (a step of it never
//! passes the surface) without a hand-tuned step factor.
//!
//! Infinite where no bound follows (a division by a range holding 0, a square root reaching 0, `pow` of a varying
//! exponent): validation refuses such a displacement with that reason.

use super::interval::range;
use crate::formula::noise::{NOISE2_SLOPE, NOISE3_SLOPE};
use crate::ir::{BinOp, Expr, Func};

/// An upper bound of |∇ₚ e| (0 for an expression that does not read the point).
pub fn slope(e: &Expr) -> f64 {
    if !e.uses_point() {
        return 0.0;
    }
    match e {
        Expr::Point(_) => 1.0,
        Expr::Lit(_) | Expr::Time | Expr::Param(_) => 0.0,
        Expr::Neg(a) => slope(a),
        Expr::Bin(op, a, b) => {
            let (sa, sb) = (slope(a), slope(b));
            let (ra, rb) = (range(a), range(b));
            match op {
                BinOp::Add | BinOp::Sub => sa + sb,
                // |∇(ab)| ≤ |a|·|∇b| + |b|·|∇a| (0·∞ is 0 here: a constant factor has no slope to scale).
                BinOp::Mul => product(ra.max_abs(), sb) + product(rb.max_abs(), sa),
                BinOp::Div => {
                    let least = rb.min_abs();
                    if least <= 0.0 || rb.contains(0.0) {
                        return f64::INFINITY;
                    }
                    (product(ra.max_abs(), sb) + product(least, sa)) / (least * least)
                }
            }
        }
        Expr::Call(f, args) => {
            let s = |i: usize| args.get(i).map_or(0.0, slope);
            // The gradient of a function of several arguments, each moving with the point: at most the sum of the
            // partial slopes' bounds times the arguments' slopes.
            match f {
                Func::Sin | Func::Cos | Func::Abs => s(0),
                Func::Sqrt => {
                    let lo = range(&args[0]).lo;
                    if lo > 0.0 {
                        s(0) / (2.0 * lo.sqrt())
                    } else {
                        f64::INFINITY
                    }
                }
                Func::Min | Func::Max => s(0).max(s(1)),
                // clamp(x, lo, hi) moves no faster than its arguments.
                Func::Clamp => s(0).max(s(1)).max(s(2)),
                // a + (b − a)·t: |∇| ≤ |∇a|·(1 + |t|) + |∇b|·|t| + |b − a|·|∇t|.
                Func::Mix => {
                    let t = range(&args[2]).max_abs();
                    let span = (range(&args[1]) - range(&args[0])).max_abs();
                    product(1.0 + t, s(0)) + product(t, s(1)) + product(span, s(2))
                }
                Func::Pow => {
                    let exponent = range(&args[1]);
                    let base = range(&args[0]);
                    if s(1) > 0.0 || !exponent.is_point() {
                        return f64::INFINITY;
                    }
                    // d/dx x^k = k·x^(k−1): bounded over the base's range when it stays away from 0 or k ≥ 1.
                    let k = exponent.lo;
                    let largest = if k >= 1.0 {
                        base.max_abs().powf(k - 1.0)
                    } else if base.min_abs() > 0.0 && !base.contains(0.0) {
                        base.min_abs().powf(k - 1.0)
                    } else {
                        return f64::INFINITY;
                    };
                    product(k.abs() * largest, s(0))
                }
                // Noise bounds |∇n| as a vector, so |∇ₚ n(q(p))| = |Jᵀ∇n| ≤ ‖J‖·|∇n| with ‖J‖ at most the
                // Frobenius norm √Σ|∇qᵢ|²: on noise2(0.3x, 0.3z) that is 0.42, against 0.6 for the sum of the slopes.
                Func::Noise2 => NOISE2_SLOPE * frobenius(&[s(0), s(1)]),
                Func::Noise3 => NOISE3_SLOPE * frobenius(&[s(0), s(1), s(2)]),
                // Octave i contributes ½ⁱ·noise(2ⁱ·q): each octave has the first one's slope.
                Func::Fbm2 => octaves(args) * NOISE2_SLOPE * frobenius(&[s(0), s(1)]),
                Func::Fbm3 => octaves(args) * NOISE3_SLOPE * frobenius(&[s(0), s(1), s(2)]),
                // The escape count jumps at every level set of the fractal boundary: no bound.
                Func::Mandelbrot => f64::INFINITY,
            }
        }
    }
}

/// `a · b` where a constant factor (b = 0) stays 0 even against an unbounded `a`.
fn product(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        0.0
    } else {
        a * b
    }
}

/// √Σ sᵢ²: the Frobenius norm of a Jacobian whose rows have lengths at most `slopes`.
fn frobenius(slopes: &[f64]) -> f64 {
    slopes.iter().map(|s| s * s).sum::<f64>().sqrt()
}

/// The octave count of an fbm call (its last argument).
fn octaves(args: &[Expr]) -> f64 {
    args.last().and_then(Expr::as_lit).unwrap_or(f64::INFINITY)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::builder::*;

    #[test]
    fn slopes_follow_the_chain_rule_with_ranges() {
        assert_eq!(slope(&Expr::Lit(2.0)), 0.0);
        assert_eq!(slope(&(x() * 3.0 + time())), 3.0);
        assert_eq!(slope(&(x() + y() - z())), 3.0);
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12 * b;
        // Noise of scaled coordinates: the noise's slope times the Jacobian's Frobenius norm (4√3 here, 4 along any
        // one axis), not the sum of the coordinates' slopes.
        let noise = slope(&(Expr::from(0.1) * noise3(x() * 4.0, y() * 4.0, z() * 4.0)));
        assert!(close(noise, 0.1 * NOISE3_SLOPE * 48f64.sqrt()), "{noise}");
        let hills = slope(&(Expr::from(0.5) * fbm2(x(), z(), 4)));
        assert!(close(hills, 0.5 * 4.0 * NOISE2_SLOPE * 2f64.sqrt()), "{hills}");
        // sin of a fast coordinate, scaled down.
        assert!((slope(&(Expr::from(0.05) * sin(x() * 10.0))) - 0.5).abs() < 1e-12);
        // Unbounded: a division by the point, and a product of the point with itself (x·x grows without limit).
        assert_eq!(slope(&(Expr::from(1.0) / x())), f64::INFINITY);
        assert_eq!(slope(&(x() * x())), f64::INFINITY);
        // A parameter scales within its range.
        assert_eq!(slope(&(param("a", 0.1, 0.0..0.3) * x())), 0.3);
    }
}
