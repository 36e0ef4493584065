//! Interval arithmetic over expressions: the range a value can take for any time t ≥ 0 and any parameter value
//! within its declared range. Bounds use it so an animated radius is bounded by its largest value.
//!
//! Every operation is conservative: the value of the expression lies in the interval for every time and every
//! parameter setting. Where an operation can produce NaN or has no useful limit (division by an interval containing
//! zero, the square root of a possibly negative value, a fractional power of a possibly negative base), the answer is
//! [`Interval::ENTIRE`]. NaN itself is no value: an expression that produces one somewhere (and then perhaps loses it in
//! a `min`, which each shading language treats differently) is outside what a range promises.

use crate::ir::{BinOp, Expr, Func};

/// A closed range of values; infinite ends mean no limit is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

/// Multiplies two interval ends, reading 0 · ∞ as 0: an infinite end is a limit no finite value reaches, and any
/// finite value times 0 is 0.
fn mul_end(a: f64, b: f64) -> f64 {
    if a == 0.0 || b == 0.0 {
        0.0
    } else {
        a * b
    }
}

impl Interval {
    /// Every value (and the answer when nothing better is known).
    pub const ENTIRE: Interval = Interval { lo: f64::NEG_INFINITY, hi: f64::INFINITY };
    /// The range of `t`: scenes start at time 0 and run for as long as they are shown.
    pub const TIME: Interval = Interval { lo: 0.0, hi: f64::INFINITY };

    /// The interval between `a` and `b` in either order; a NaN end gives [`Interval::ENTIRE`].
    pub fn new(a: f64, b: f64) -> Interval {
        if a.is_nan() || b.is_nan() {
            Interval::ENTIRE
        } else {
            Interval { lo: a.min(b), hi: a.max(b) }
        }
    }
    pub fn point(v: f64) -> Interval {
        Interval::new(v, v)
    }
    pub fn is_point(self) -> bool {
        self.lo == self.hi
    }
    /// Both ends finite.
    pub fn is_finite(self) -> bool {
        self.lo.is_finite() && self.hi.is_finite()
    }
    pub fn contains(self, v: f64) -> bool {
        self.lo <= v && v <= self.hi
    }
    pub fn width(self) -> f64 {
        self.hi - self.lo
    }
    /// The largest magnitude of any value in the interval.
    pub fn max_abs(self) -> f64 {
        self.lo.abs().max(self.hi.abs())
    }
    /// The smallest magnitude of any value in the interval (0 when it contains 0).
    pub fn min_abs(self) -> f64 {
        if self.contains(0.0) {
            0.0
        } else {
            self.lo.abs().min(self.hi.abs())
        }
    }
    /// The smallest interval containing both.
    pub fn hull(self, o: Interval) -> Interval {
        Interval::new(self.lo.min(o.lo), self.hi.max(o.hi))
    }

    pub fn abs(self) -> Interval {
        Interval::new(self.min_abs(), self.max_abs())
    }
    pub fn sqrt(self) -> Interval {
        if self.lo < 0.0 {
            // sqrt of a negative value is NaN, which no interval contains.
            return Interval::ENTIRE;
        }
        Interval::new(self.lo.sqrt(), self.hi.sqrt())
    }
    pub fn min(self, o: Interval) -> Interval {
        Interval::new(self.lo.min(o.lo), self.hi.min(o.hi))
    }
    pub fn max(self, o: Interval) -> Interval {
        Interval::new(self.lo.max(o.lo), self.hi.max(o.hi))
    }
    /// `max(x, lo).min(hi)`, as [`Func::Clamp`] evaluates.
    pub fn clamp(self, lo: Interval, hi: Interval) -> Interval {
        self.max(lo).min(hi)
    }
    /// `a + (b − a)·t`, as [`Func::Mix`] evaluates.
    pub fn mix(self, b: Interval, t: Interval) -> Interval {
        self + (b - self) * t
    }
    pub fn sin(self) -> Interval {
        use std::f64::consts::FRAC_PI_2;
        self.periodic(f64::sin, FRAC_PI_2, -FRAC_PI_2)
    }
    pub fn cos(self) -> Interval {
        use std::f64::consts::PI;
        self.periodic(f64::cos, 0.0, PI)
    }
    /// A 2π-periodic function with its peaks at `peak` + 2kπ and troughs at `trough` + 2kπ, monotone in between.
    fn periodic(self, f: fn(f64) -> f64, peak: f64, trough: f64) -> Interval {
        use std::f64::consts::TAU;
        if !self.is_finite() || self.width() >= TAU {
            return Interval::new(-1.0, 1.0);
        }
        let has = |at: f64| at + ((self.lo - at) / TAU).ceil() * TAU <= self.hi;
        let (a, b) = (f(self.lo), f(self.hi));
        let hi = if has(peak) { 1.0 } else { a.max(b) };
        let lo = if has(trough) { -1.0 } else { a.min(b) };
        // The extremum test itself rounds: widen by a few ulps so a value computed at a point near a turn stays inside.
        Interval::new(lo - 4.0 * f64::EPSILON, hi + 4.0 * f64::EPSILON)
            .clamp(Interval::point(-1.0), Interval::point(1.0))
    }
    /// `powf(self, e)`. Exact cases: a constant integer exponent (any base), a constant exponent with a non-negative
    /// base, and a varying exponent with a positive base (through exp(e·ln x)); anything that can be NaN is
    /// [`Interval::ENTIRE`].
    pub fn pow(self, e: Interval) -> Interval {
        if e.is_point() {
            let n = e.lo;
            if n == 0.0 {
                return Interval::point(1.0);
            }
            if n.fract() == 0.0 && n.is_finite() {
                let even = (n / 2.0).fract() == 0.0;
                if n > 0.0 {
                    return if even {
                        Interval::new(self.min_abs().powf(n), self.max_abs().powf(n))
                    } else {
                        Interval::new(self.lo.powf(n), self.hi.powf(n))
                    };
                }
                if self.contains(0.0) {
                    return Interval::ENTIRE;
                }
                return if even {
                    Interval::new(self.max_abs().powf(n), self.min_abs().powf(n))
                } else {
                    Interval::new(self.hi.powf(n), self.lo.powf(n))
                };
            }
            if self.lo < 0.0 {
                return Interval::ENTIRE;
            }
            return Interval::new(self.lo.powf(n), self.hi.powf(n));
        }
        if self.lo < 0.0 {
            return Interval::ENTIRE;
        }
        let log = Interval::new(self.lo.ln(), self.hi.ln());
        let p = e * log;
        // exp(e·ln x) and powf(x, e) round differently: widen by a relative margin far above either's error.
        Interval::new(p.lo.exp() * (1.0 - 1e-12), p.hi.exp() * (1.0 + 1e-12))
    }
}

impl core::ops::Neg for Interval {
    type Output = Interval;
    fn neg(self) -> Interval {
        Interval::new(-self.hi, -self.lo)
    }
}

impl core::ops::Add for Interval {
    type Output = Interval;
    fn add(self, o: Interval) -> Interval {
        Interval::new(self.lo + o.lo, self.hi + o.hi)
    }
}

impl core::ops::Sub for Interval {
    type Output = Interval;
    fn sub(self, o: Interval) -> Interval {
        self + -o
    }
}

impl core::ops::Mul for Interval {
    type Output = Interval;
    fn mul(self, o: Interval) -> Interval {
        let ends = [mul_end(self.lo, o.lo), mul_end(self.lo, o.hi), mul_end(self.hi, o.lo), mul_end(self.hi, o.hi)];
        Interval::new(
            ends.iter().copied().fold(f64::INFINITY, f64::min),
            ends.iter().copied().fold(-f64::INFINITY, f64::max),
        )
    }
}

impl core::ops::Div for Interval {
    type Output = Interval;
    /// Unbounded when the divisor's range contains 0.
    fn div(self, o: Interval) -> Interval {
        if o.contains(0.0) {
            return Interval::ENTIRE;
        }
        // Quotients of the ends directly (not times a reciprocal, which rounds twice): division rounds monotonically.
        let ends = [self.lo / o.lo, self.lo / o.hi, self.hi / o.lo, self.hi / o.hi];
        if ends.iter().any(|v| v.is_nan()) {
            return Interval::ENTIRE;
        }
        Interval::new(
            ends.iter().copied().fold(f64::INFINITY, f64::min),
            ends.iter().copied().fold(-f64::INFINITY, f64::max),
        )
    }
}

/// The range of `e`.
pub fn range(e: &Expr) -> Interval {
    match e {
        Expr::Lit(v) => Interval::point(*v),
        Expr::Time => Interval::TIME,
        // The default is included so a declaration whose default lies outside its range stays covered.
        Expr::Param(p) => Interval::new(p.min, p.max).hull(Interval::point(p.default)),
        Expr::Neg(a) => -range(a),
        Expr::Bin(op, a, b) => {
            let (a, b) = (range(a), range(b));
            match op {
                BinOp::Add => a + b,
                BinOp::Sub => a - b,
                BinOp::Mul => a * b,
                BinOp::Div => a / b,
            }
        }
        Expr::Call(f, args) => {
            let arg = |i: usize| args.get(i).map(range).unwrap_or(Interval::ENTIRE);
            match f {
                Func::Sin => arg(0).sin(),
                Func::Cos => arg(0).cos(),
                Func::Abs => arg(0).abs(),
                Func::Sqrt => arg(0).sqrt(),
                Func::Min => arg(0).min(arg(1)),
                Func::Max => arg(0).max(arg(1)),
                Func::Pow => arg(0).pow(arg(1)),
                Func::Clamp => arg(0).clamp(arg(1), arg(2)),
                Func::Mix => arg(0).mix(arg(1), arg(2)),
            }
        }
    }
}
