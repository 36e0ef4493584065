//! Scalar and vector arithmetic shared by the interpreter and the generated native evaluator.
//!
//! Both evaluators are generic over [`Real`] (f32 or f64) so the f64 instance is the accuracy reference for the f32
//! one. Names mirror the shading languages (`length`, `dot`, `mix`) so generated Rust reads like the kernels.

use core::ops::{Add, Div, Mul, Neg, Sub};
use num_traits::Float;

/// A floating-point type an evaluator runs in.
pub trait Real: Float + core::fmt::Debug + Send + Sync + 'static {
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

/// Shorthand for [`Real::c`], used by generated code for literals.
#[inline(always)]
pub fn c<F: Real>(v: f64) -> F {
    F::c(v)
}

/// A 3-vector of a [`Real`]; plain data, no SIMD, so f32 and f64 evaluate the same operations in the same order.
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

impl<F: Real> V3<F> {
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
    #[inline(always)]
    pub fn max_element(self) -> F {
        self.x.max(self.y).max(self.z)
    }
    #[inline(always)]
    pub fn min_element(self) -> F {
        self.x.min(self.y).min(self.z)
    }
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
        impl<F: Real> $tr for V3<F> {
            type Output = V3<F>;
            #[inline(always)]
            fn $f(self, o: V3<F>) -> V3<F> { v3(self.x $op o.x, self.y $op o.y, self.z $op o.z) }
        }
        impl<F: Real> $tr<F> for V3<F> {
            type Output = V3<F>;
            #[inline(always)]
            fn $f(self, o: F) -> V3<F> { v3(self.x $op o, self.y $op o, self.z $op o) }
        }
    )*};
}
vec_ops!(Add add +, Sub sub -, Mul mul *, Div div /);

impl<F: Real> Neg for V3<F> {
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
pub fn dot<F: Real>(a: V3<F>, b: V3<F>) -> F {
    a.x * b.x + a.y * b.y + a.z * b.z
}
#[inline(always)]
pub fn length<F: Real>(a: V3<F>) -> F {
    dot(a, a).sqrt()
}
#[inline(always)]
pub fn normalize<F: Real>(a: V3<F>) -> V3<F> {
    a / length(a)
}
#[inline(always)]
pub fn cross<F: Real>(a: V3<F>, b: V3<F>) -> V3<F> {
    v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x)
}
#[inline(always)]
pub fn abs3<F: Real>(a: V3<F>) -> V3<F> {
    a.map(F::abs)
}
#[inline(always)]
pub fn max3<F: Real>(a: V3<F>, b: F) -> V3<F> {
    a.map(|v| v.max(b))
}
#[inline(always)]
pub fn min3<F: Real>(a: V3<F>, b: F) -> V3<F> {
    a.map(|v| v.min(b))
}
#[inline(always)]
pub fn clamp<F: Real>(v: F, lo: F, hi: F) -> F {
    v.max(lo).min(hi)
}
#[inline(always)]
pub fn mix<F: Real>(a: F, b: F, t: F) -> F {
    a + (b - a) * t
}
#[inline(always)]
pub fn mix3<F: Real>(a: V3<F>, b: V3<F>, t: F) -> V3<F> {
    a + (b - a) * t
}
/// Floored modulo as GLSL's `mod` (not Rust's `%`, which truncates): the result has the sign of `m`.
#[inline(always)]
pub fn fmod_floor<F: Real>(x: F, m: F) -> F {
    x - m * (x / m).floor()
}
/// `x` if `cond`, else `y`: the shading languages' `select`, spelled once for the generated code.
#[inline(always)]
pub fn select<T>(cond: bool, x: T, y: T) -> T {
    if cond {
        x
    } else {
        y
    }
}
