//! Forward-mode automatic differentiation: [`Dual`], a number with its derivatives along the three axes of the point,
//! which implements [`Num`] on top of any [`Num`]. A formula run in `Dual<F>` computes its value and its Jacobian in
//! `F`; so in a kernel the derivative of a formula is traced like the formula itself, and no derivative is written by
//! hand (`crate::formula::user`).
//!
//! Where a derivative is infinite (sqrt, acos and atan2 at their singular points) it is taken at a point [`TINY`]
//! away, so an orbit through a singular point keeps a finite Jacobian; the distance estimate built on it is what the
//! step factor and the estimator study judge.

use core::ops::{Add, Div, Mul, Neg, Sub};

use super::common::TINY;
use crate::number::math::{c, max, select, sqrt};
use crate::number::{Carry, Num};

/// A number with its partial derivatives with respect to the point's x, y and z.
#[derive(Clone, Copy, Debug)]
pub struct Dual<F> {
    pub v: F,
    pub d: [F; 3],
}

impl<F: Num> Dual<F> {
    /// A constant: no derivative.
    #[inline(always)]
    pub fn constant(v: F) -> Dual<F> {
        Dual { v, d: [F::lit(0.0); 3] }
    }
    /// The point's coordinate `axis`: derivative 1 along it.
    #[inline(always)]
    pub fn variable(v: F, axis: usize) -> Dual<F> {
        let mut d = [F::lit(0.0); 3];
        d[axis] = F::lit(1.0);
        Dual { v, d }
    }
    /// The chain rule: f(self) with f'(self) = `slope`.
    #[inline(always)]
    fn chain(self, value: F, slope: F) -> Dual<F> {
        Dual { v: value, d: self.d.map(|d| d * slope) }
    }
}

impl<F: Num> Add for Dual<F> {
    type Output = Dual<F>;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Dual { v: self.v + o.v, d: [0, 1, 2].map(|i| self.d[i] + o.d[i]) }
    }
}
impl<F: Num> Sub for Dual<F> {
    type Output = Dual<F>;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Dual { v: self.v - o.v, d: [0, 1, 2].map(|i| self.d[i] - o.d[i]) }
    }
}
impl<F: Num> Mul for Dual<F> {
    type Output = Dual<F>;
    /// The product rule.
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        Dual { v: self.v * o.v, d: [0, 1, 2].map(|i| self.d[i] * o.v + self.v * o.d[i]) }
    }
}
impl<F: Num> Div for Dual<F> {
    type Output = Dual<F>;
    /// The quotient rule.
    #[allow(clippy::suspicious_arithmetic_impl)]
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        let inv = F::lit(1.0) / o.v;
        let v = self.v * inv;
        Dual { v, d: [0, 1, 2].map(|i| (self.d[i] - v * o.d[i]) * inv) }
    }
}
impl<F: Num> Neg for Dual<F> {
    type Output = Dual<F>;
    #[inline(always)]
    fn neg(self) -> Self {
        Dual { v: -self.v, d: self.d.map(|d| -d) }
    }
}

impl<F: Num> Carry<Dual<F>> for Dual<F> {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(Dual<F>) -> Dual<F>) -> Self {
        f(self)
    }
    #[inline(always)]
    fn zip_nums(self, other: Self, f: &mut impl FnMut(Dual<F>, Dual<F>) -> Dual<F>) -> Self {
        f(self, other)
    }
}

/// A dual number is carried through a loop of `F` as its four numbers.
impl<F: Num> Carry<F> for Dual<F> {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        Dual { v: f(self.v), d: self.d.map(&mut *f) }
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        Dual { v: f(self.v, o.v), d: [0, 1, 2].map(|i| f(self.d[i], o.d[i])) }
    }
}

/// A state of dual numbers seen as a state of `F`, so `F`'s own loops carry it.
#[derive(Clone, Copy)]
struct Lift<S>(S);

impl<F: Num, S: Carry<Dual<F>>> Carry<F> for Lift<S> {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        Lift(self.0.map_nums(&mut |d: Dual<F>| <Dual<F> as Carry<F>>::map_nums(d, f)))
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        // Pair the duals up in order: collect the other's, then zip against them.
        let mut others = Vec::new();
        o.0.map_nums(&mut |d| {
            others.push(d);
            d
        });
        let mut k = 0;
        Lift(self.0.map_nums(&mut |d: Dual<F>| {
            let z = <Dual<F> as Carry<F>>::zip_nums(d, others[k], f);
            k += 1;
            z
        }))
    }
}

impl<F: Num> Num for Dual<F> {
    type Mask = F::Mask;
    type Count = F::Count;

    #[inline(always)]
    fn lit(v: f64) -> Self {
        Dual::constant(F::lit(v))
    }
    #[inline(always)]
    fn count(n: u32) -> F::Count {
        F::count(n)
    }
    #[inline(always)]
    fn abs(x: Self) -> Self {
        let negative = F::lt(x.v, F::lit(0.0));
        x.chain(F::abs(x.v), select(negative, c(-1.0), c(1.0)))
    }
    #[inline(always)]
    fn sqrt(x: Self) -> Self {
        let r = F::sqrt(x.v);
        x.chain(r, c::<F>(0.5) / max(r, c(TINY)))
    }
    #[inline(always)]
    fn floor(x: Self) -> Self {
        x.chain(F::floor(x.v), c(0.0))
    }
    #[inline(always)]
    fn sin(x: Self) -> Self {
        x.chain(F::sin(x.v), F::cos(x.v))
    }
    #[inline(always)]
    fn cos(x: Self) -> Self {
        x.chain(F::cos(x.v), -F::sin(x.v))
    }
    #[inline(always)]
    fn acos(x: Self) -> Self {
        let s = sqrt(max(c::<F>(1.0) - x.v * x.v, c(TINY)));
        x.chain(F::acos(x.v), c::<F>(-1.0) / s)
    }
    #[inline(always)]
    fn atan2(y: Self, x: Self) -> Self {
        let r2 = max(x.v * x.v + y.v * y.v, c(TINY));
        let d = [0, 1, 2].map(|i| (x.v * y.d[i] - y.v * x.d[i]) / r2);
        Dual { v: F::atan2(y.v, x.v), d }
    }
    #[inline(always)]
    fn exp2(x: Self) -> Self {
        let v = F::exp2(x.v);
        x.chain(v, v * c(core::f64::consts::LN_2))
    }
    #[inline(always)]
    fn ln(x: Self) -> Self {
        x.chain(F::ln(x.v), c::<F>(1.0) / max(x.v, c(TINY)))
    }
    #[inline(always)]
    fn pow(x: Self, y: Self) -> Self {
        // d(xʸ) = y·xʸ⁻¹·dx + xʸ·ln x·dy; x^(y−1) rather than xʸ/x keeps x = 0 finite for y ≥ 1.
        let v = F::pow(x.v, y.v);
        let along_x = y.v * F::pow(x.v, y.v - c(1.0));
        let along_y = v * F::ln(max(x.v, c(TINY)));
        Dual { v, d: [0, 1, 2].map(|i| along_x * x.d[i] + along_y * y.d[i]) }
    }
    #[inline(always)]
    fn min(a: Self, b: Self) -> Self {
        Self::select(F::lt(a.v, b.v), a, b)
    }
    #[inline(always)]
    fn max(a: Self, b: Self) -> Self {
        Self::select(F::lt(a.v, b.v), b, a)
    }
    #[inline(always)]
    fn lt(a: Self, b: Self) -> F::Mask {
        F::lt(a.v, b.v)
    }
    #[inline(always)]
    fn le(a: Self, b: Self) -> F::Mask {
        F::le(a.v, b.v)
    }
    #[inline(always)]
    fn select(m: F::Mask, a: Self, b: Self) -> Self {
        Dual { v: F::select(m, a.v, b.v), d: [0, 1, 2].map(|i| F::select(m, a.d[i], b.d[i])) }
    }
    #[inline(always)]
    fn iterate<S: Carry<Self>>(n: F::Count, init: S, active: impl Fn(&S) -> F::Mask, step: impl Fn(S) -> S) -> S {
        F::iterate(n, Lift(init), |s| active(&s.0), |s| Lift(step(s.0))).0
    }
    #[inline(always)]
    fn when<S: Carry<Self>>(cond: F::Mask, state: S, body: impl FnOnce(S) -> S) -> S {
        F::when(cond, Lift(state), |s| Lift(body(s.0))).0
    }
    #[inline(always)]
    fn stand_in(live: F::Mask, x: Self) -> Self {
        Dual { v: F::stand_in(live, x.v), d: x.d.map(|d| F::stand_in(live, d)) }
    }
}
