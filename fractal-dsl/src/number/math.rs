//! Vectors over any [`Num`] and the host's float types.
//!
//! [`V3`] is plain data: three numbers, no SIMD inside, so f32 and f64 evaluate the same operations in the same order
//! and a traced vector is three recorded scalars. Names mirror the shading languages (`length`, `dot`, `mix`) so
//! formulas and generated Rust read like the kernels. [`Real`] is the host-side float (f32 or f64) that evaluators,
//! renderers and references run in: a [`Num`] with plain `bool` masks plus `num_traits::Float`.

use core::ops::{Add, Div, Mul, Neg, Sub};
use num_traits::Float;

pub use crate::number::*;

/// A floating-point type an evaluator runs in on the host.
pub trait Real: Float + Num<Mask = bool, Count = u32> + Send + Sync {
    /// Converts an f64 constant (a folded literal) into this type, rounding to nearest.
    fn c(v: f64) -> Self;
    /// Widens to f64 for comparisons and reporting.
    fn f64(self) -> f64;
    /// Machine epsilon of this type, the spacing of floats at 1.0.
    const EPS: Self;
}

impl Real for f32 {
    #[inline(always)]
    fn c(v: f64) -> Self {
        v as f32
    }
    #[inline(always)]
    fn f64(self) -> f64 {
        self as f64
    }
    const EPS: Self = f32::EPSILON;
}

impl Real for f64 {
    #[inline(always)]
    fn c(v: f64) -> Self {
        v
    }
    #[inline(always)]
    fn f64(self) -> f64 {
        self
    }
    const EPS: Self = f64::EPSILON;
}

/// A 3-vector of a [`Num`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct V3<F> {
    pub x: F,
    pub y: F,
    pub z: F,
}

/// Builds a [`V3`].
#[inline(always)]
pub fn v3<F>(x: F, y: F, z: F) -> V3<F> {
    V3 { x, y, z }
}

impl<F: Num> Carry<F> for V3<F> {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        v3(f(self.x), f(self.y), f(self.z))
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        v3(f(self.x, o.x), f(self.y, o.y), f(self.z, o.z))
    }
}

impl<F: Copy> V3<F> {
    #[inline(always)]
    pub fn splat(v: F) -> Self {
        v3(v, v, v)
    }
    #[inline(always)]
    pub fn map(self, f: impl Fn(F) -> F) -> Self {
        v3(f(self.x), f(self.y), f(self.z))
    }
    #[inline(always)]
    pub fn zip(self, o: Self, f: impl Fn(F, F) -> F) -> Self {
        v3(f(self.x, o.x), f(self.y, o.y), f(self.z, o.z))
    }
}

impl<F: Num> V3<F> {
    #[inline(always)]
    pub fn max_element(self) -> F {
        max(max(self.x, self.y), self.z)
    }
    #[inline(always)]
    pub fn min_element(self) -> F {
        min(min(self.x, self.y), self.z)
    }
}

impl<F: Real> V3<F> {
    /// Converts between precisions (f64 reference points into an f32 evaluator).
    #[inline(always)]
    pub fn cast<G: Real>(self) -> V3<G> {
        v3(G::c(self.x.f64()), G::c(self.y.f64()), G::c(self.z.f64()))
    }
}

impl From<glam::Vec3> for V3<f32> {
    fn from(v: glam::Vec3) -> Self {
        v3(v.x, v.y, v.z)
    }
}
impl From<glam::DVec3> for V3<f64> {
    fn from(v: glam::DVec3) -> Self {
        v3(v.x, v.y, v.z)
    }
}
impl From<V3<f32>> for glam::Vec3 {
    fn from(v: V3<f32>) -> Self {
        glam::Vec3::new(v.x, v.y, v.z)
    }
}
impl From<V3<f64>> for glam::DVec3 {
    fn from(v: V3<f64>) -> Self {
        glam::DVec3::new(v.x, v.y, v.z)
    }
}

macro_rules! vec_ops {
    ($($tr:ident $f:ident $op:tt),*) => {$(
        impl<F: Num> $tr for V3<F> {
            type Output = V3<F>;
            #[inline(always)]
            fn $f(self, o: V3<F>) -> V3<F> { v3(self.x $op o.x, self.y $op o.y, self.z $op o.z) }
        }
        impl<F: Num> $tr<F> for V3<F> {
            type Output = V3<F>;
            #[inline(always)]
            fn $f(self, o: F) -> V3<F> { v3(self.x $op o, self.y $op o, self.z $op o) }
        }
    )*};
}
vec_ops!(Add add +, Sub sub -, Mul mul *, Div div /);

impl<F: Num> Neg for V3<F> {
    type Output = V3<F>;
    #[inline(always)]
    fn neg(self) -> V3<F> {
        v3(-self.x, -self.y, -self.z)
    }
}

macro_rules! scalar_lhs {
    ($($t:ty),*) => {$(
        impl Mul<V3<$t>> for $t {
            type Output = V3<$t>;
            #[inline(always)]
            fn mul(self, o: V3<$t>) -> V3<$t> { o * self }
        }
    )*};
}
scalar_lhs!(f32, f64);

#[inline(always)]
pub fn dot<F: Num>(a: V3<F>, b: V3<F>) -> F {
    a.x * b.x + a.y * b.y + a.z * b.z
}
#[inline(always)]
pub fn length<F: Num>(a: V3<F>) -> F {
    sqrt(dot(a, a))
}
#[inline(always)]
pub fn normalize<F: Num>(a: V3<F>) -> V3<F> {
    a / length(a)
}
/// A gradient as a normal: `a` normalised, +y where it has no length.
#[inline(always)]
pub fn direction<F: Num>(a: V3<F>) -> V3<F> {
    let len = length(a);
    let found = lt(F::lit(0.0), len);
    let unit = a / len;
    v3(select(found, unit.x, F::lit(0.0)), select(found, unit.y, F::lit(1.0)), select(found, unit.z, F::lit(0.0)))
}
#[inline(always)]
pub fn cross<F: Num>(a: V3<F>, b: V3<F>) -> V3<F> {
    v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
}
#[inline(always)]
pub fn abs3<F: Num>(a: V3<F>) -> V3<F> {
    a.map(abs)
}
#[inline(always)]
pub fn max3<F: Num>(a: V3<F>, b: F) -> V3<F> {
    a.map(
        #[inline(always)]
        |v| max(v, b),
    )
}
#[inline(always)]
pub fn min3<F: Num>(a: V3<F>, b: F) -> V3<F> {
    a.map(
        #[inline(always)]
        |v| min(v, b),
    )
}
#[inline(always)]
pub fn mix3<F: Num>(a: V3<F>, b: V3<F>, t: F) -> V3<F> {
    v3(mix(a.x, b.x, t), mix(a.y, b.y, t), mix(a.z, b.z, t))
}
