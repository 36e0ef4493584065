//! The numeric trait every formula is written against, once: [`Num`].
//!
//! A leaf function (a primitive's distance, a blend, a fractal estimator) and the scene walker are generic over
//! [`Num`]. `f32` and `f64` run them directly (interpreter, native evaluator, f64 reference); the symbolic type of
//! [`crate::lower::trace`] records them into lowered code that the OpenCL and WGSL writers print; a lane type runs
//! them a packet at a time. So the trait assumes no scalar control flow:
//! - a data-dependent choice is [`select`] on a [`Num::Mask`], never an `if` on a value;
//! - a loop with an early exit is [`Num::iterate`]: a fixed count and a mask of lanes still running;
//! - work worth skipping when no lane needs it (a union child behind its bound) is [`Num::when`].
//!
//! How a leaf function is called (directly, or as a named kernel function) is [`crate::formula::CallLeaf`].
//!
//! The math is spelled as free functions (`sqrt(x)`, `max(a, b)`, `lt(a, b)`) so formulas read like the kernels they
//! become, and so `f32`'s own methods (and `num_traits::Float`'s) never clash with the trait's.

pub mod elementary;
pub mod lanes;
pub mod math;
pub mod portable;

use core::fmt::Debug;
use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

/// A truth value per lane: `bool` for scalars, a recorded condition when tracing.
pub trait Mask: Copy + Debug + BitAnd<Output = Self> + BitOr<Output = Self> + Not<Output = Self> {
    /// The same truth in every lane.
    fn splat(v: bool) -> Self;
}

impl Mask for bool {
    #[inline(always)]
    fn splat(v: bool) -> Self {
        v
    }
}

/// A mask whose lanes the host can inspect (not a traced one): code that runs on the host skips work no lane needs.
pub trait AnyLane: Mask {
    /// Whether any lane is true.
    fn any(self) -> bool;
}

impl AnyLane for bool {
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
}

/// Whether any lane of `m` is true.
#[inline(always)]
pub fn any<M: AnyLane>(m: M) -> bool {
    m.any()
}

/// Values a [`Num::iterate`] loop or a [`Num::when`] block carries from one step to the next: a number, a vector, or
/// tuples and arrays of them. Tracing turns each number into a variable; lanes select each number by the mask.
pub trait Carry<F>: Copy {
    /// Every number replaced by `f(number)`, in a fixed order.
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self;
    /// Every pair of corresponding numbers replaced by `f(mine, other)`, in the order of [`Carry::map_nums`].
    fn zip_nums(self, other: Self, f: &mut impl FnMut(F, F) -> F) -> Self;
}

/// A number type the formulas run in. See the module documentation for the rules formulas follow.
///
/// The math functions take no `self` (call them through the free functions of this module), so they never shadow
/// the methods of `f32`, `f64` or `num_traits::Float`.
pub trait Num:
    Copy
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Carry<Self>
    + 'static
{
    /// A truth value per lane.
    type Mask: Mask;
    /// A loop count (iterations, levels): the same for every lane; a parameter of the function when tracing.
    type Count: Copy + Debug;

    /// A constant, rounded to this type.
    fn lit(v: f64) -> Self;
    /// A constant loop count.
    fn count(n: u32) -> Self::Count;

    fn abs(x: Self) -> Self;
    fn sqrt(x: Self) -> Self;
    fn floor(x: Self) -> Self;
    fn sin(x: Self) -> Self;
    fn cos(x: Self) -> Self;
    fn acos(x: Self) -> Self;
    /// The angle of (x, y), as `atan2(y, x)`.
    fn atan2(y: Self, x: Self) -> Self;
    fn exp2(x: Self) -> Self;
    /// Natural logarithm.
    fn ln(x: Self) -> Self;
    fn pow(x: Self, y: Self) -> Self;
    fn min(a: Self, b: Self) -> Self;
    fn max(a: Self, b: Self) -> Self;
    fn lt(a: Self, b: Self) -> Self::Mask;
    fn le(a: Self, b: Self) -> Self::Mask;
    /// `a` where `m`, else `b`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// Linear interpolation from `a` (t = 0) to `b` (t = 1), as `a + (b − a)·t`.
    #[inline(always)]
    fn mix(a: Self, b: Self, t: Self) -> Self {
        a + (b - a) * t
    }

    /// Runs `step` up to `n` times, stopping (per lane) before the first step at which `active` is false; returns the
    /// state after the last step each lane took.
    fn iterate<S: Carry<Self>>(n: Self::Count, init: S, active: impl Fn(&S) -> Self::Mask, step: impl Fn(S) -> S) -> S;
    /// `body(state)` where `cond` holds, else `state`; the body runs only if some lane needs it.
    fn when<S: Carry<Self>>(cond: Self::Mask, state: S, body: impl FnOnce(S) -> S) -> S;
    /// `x` where `live` holds; in a lane where it does not, the value of a lane where it does (the value there is
    /// not used). A packet's lanes run in step, so work done for lanes that do not count then costs what a counting
    /// lane's costs, not what an arbitrary value's would (a point at a fractal's surface runs every iteration). A
    /// scalar is its own lane.
    #[inline(always)]
    fn stand_in(live: Self::Mask, x: Self) -> Self {
        let _ = live;
        x
    }

    /// Entry `index` of a perturbation reference orbit, the last entry for an index past it (see [`Orbit`]).
    ///
    /// The default picks the entry with one select per entry, which any lane type can run; the scalar types index
    /// the slice, and the tracer reads the kernel's frame.
    fn orbit_entry(orbit: Orbit<'_>, index: Self) -> [Self; 2] {
        let mut entry = [Self::lit(0.0); 2];
        for (i, e) in orbit.iter().enumerate() {
            let reached = Self::le(Self::lit(i as f64), index);
            entry = [0, 1].map(|k| Self::select(reached, Self::lit(f64::from(e[k])), entry[k]));
        }
        entry
    }
    /// The index of a reference orbit's last entry.
    fn orbit_last(orbit: Orbit<'_>) -> Self {
        Self::lit(orbit.len().saturating_sub(1) as f64)
    }
}

/// A perturbation reference orbit: Z₀, Z₁, … of z ← z² + C at one reference point C, in f32 as the kernels hold it
/// (see [`crate::formula::mandelbrot::mandelbrot_perturbed`]). Where a kernel computes, the orbit is the frame's, and
/// the slice a traced formula is handed is empty.
pub type Orbit<'a> = &'a [[f32; 2]];

/// The orbit of the reference point 0 (which never moves): perturbation around it is the plain iteration.
pub const ORBIT_AT_ZERO: Orbit<'static> = &[[0.0, 0.0]];

macro_rules! scalar_num {
    ($t:ty, $math:ident) => {
        impl Carry<$t> for $t {
            #[inline(always)]
            fn map_nums(self, f: &mut impl FnMut($t) -> $t) -> Self {
                f(self)
            }
            #[inline(always)]
            fn zip_nums(self, other: Self, f: &mut impl FnMut($t, $t) -> $t) -> Self {
                f(self, other)
            }
        }

        impl Num for $t {
            type Mask = bool;
            type Count = u32;
            #[inline(always)]
            fn lit(v: f64) -> Self {
                v as $t
            }
            #[inline(always)]
            fn count(n: u32) -> u32 {
                n
            }
            #[inline(always)]
            fn abs(x: Self) -> Self {
                x.abs()
            }
            #[inline(always)]
            fn sqrt(x: Self) -> Self {
                x.sqrt()
            }
            #[inline(always)]
            fn floor(x: Self) -> Self {
                $math::floor(x)
            }
            #[inline(always)]
            fn sin(x: Self) -> Self {
                $math::sin(x)
            }
            #[inline(always)]
            fn cos(x: Self) -> Self {
                $math::cos(x)
            }
            #[inline(always)]
            fn acos(x: Self) -> Self {
                $math::acos(x)
            }
            #[inline(always)]
            fn atan2(y: Self, x: Self) -> Self {
                $math::atan2(y, x)
            }
            #[inline(always)]
            fn exp2(x: Self) -> Self {
                $math::exp2(x)
            }
            #[inline(always)]
            fn ln(x: Self) -> Self {
                $math::ln(x)
            }
            #[inline(always)]
            fn pow(x: Self, y: Self) -> Self {
                $math::pow(x, y)
            }
            #[inline(always)]
            fn min(a: Self, b: Self) -> Self {
                a.min(b)
            }
            #[inline(always)]
            fn max(a: Self, b: Self) -> Self {
                a.max(b)
            }
            #[inline(always)]
            fn lt(a: Self, b: Self) -> bool {
                a < b
            }
            #[inline(always)]
            fn le(a: Self, b: Self) -> bool {
                a <= b
            }
            #[inline(always)]
            fn select(m: bool, a: Self, b: Self) -> Self {
                if m {
                    a
                } else {
                    b
                }
            }
            #[inline(always)]
            fn iterate<S: Carry<Self>>(n: u32, init: S, active: impl Fn(&S) -> bool, step: impl Fn(S) -> S) -> S {
                let mut s = init;
                for _ in 0..n {
                    if !active(&s) {
                        break;
                    }
                    s = step(s);
                }
                s
            }
            #[inline(always)]
            fn when<S: Carry<Self>>(cond: bool, state: S, body: impl FnOnce(S) -> S) -> S {
                if cond {
                    body(state)
                } else {
                    state
                }
            }
            #[inline(always)]
            fn orbit_entry(orbit: Orbit<'_>, index: Self) -> [Self; 2] {
                // `as usize` saturates (NaN reads 0); an empty orbit reads the orbit at 0.
                let e = orbit.get((index as usize).min(orbit.len().saturating_sub(1))).unwrap_or(&[0.0, 0.0]);
                [e[0] as $t, e[1] as $t]
            }
        }
    };
}
// f32 computes its elementary functions without branches, as the packet type does lane by lane (so the two agree
// bit for bit); f64, the reference, keeps the platform's libm.
use crate::number::elementary as f32_math;
scalar_num!(f32, f32_math);
scalar_num!(f64, f64_math);

/// The f64 elementary functions: the platform's libm.
mod f64_math {
    #[inline(always)]
    pub fn floor(x: f64) -> f64 {
        x.floor()
    }
    #[inline(always)]
    pub fn sin(x: f64) -> f64 {
        x.sin()
    }
    #[inline(always)]
    pub fn cos(x: f64) -> f64 {
        x.cos()
    }
    #[inline(always)]
    pub fn acos(x: f64) -> f64 {
        x.acos()
    }
    #[inline(always)]
    pub fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
    #[inline(always)]
    pub fn exp2(x: f64) -> f64 {
        x.exp2()
    }
    #[inline(always)]
    pub fn ln(x: f64) -> f64 {
        x.ln()
    }
    #[inline(always)]
    pub fn pow(x: f64, y: f64) -> f64 {
        x.powf(y)
    }
}

impl<F, A: Carry<F>, B: Carry<F>> Carry<F> for (A, B) {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        (self.0.map_nums(f), self.1.map_nums(f))
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        (self.0.zip_nums(o.0, f), self.1.zip_nums(o.1, f))
    }
}

impl<F, A: Carry<F>, B: Carry<F>, C: Carry<F>> Carry<F> for (A, B, C) {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        (self.0.map_nums(f), self.1.map_nums(f), self.2.map_nums(f))
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        (self.0.zip_nums(o.0, f), self.1.zip_nums(o.1, f), self.2.zip_nums(o.2, f))
    }
}

impl<F, A: Carry<F>, B: Carry<F>, C: Carry<F>, D: Carry<F>> Carry<F> for (A, B, C, D) {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        (self.0.map_nums(f), self.1.map_nums(f), self.2.map_nums(f), self.3.map_nums(f))
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        (self.0.zip_nums(o.0, f), self.1.zip_nums(o.1, f), self.2.zip_nums(o.2, f), self.3.zip_nums(o.3, f))
    }
}

impl<F, A: Carry<F>, const N: usize> Carry<F> for [A; N] {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        self.map(|a| a.map_nums(f))
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        let mut o = o.into_iter();
        self.map(|a| match o.next() {
            Some(b) => a.zip_nums(b, f),
            None => a,
        })
    }
}

// ---- the math as free functions -----------------------------------------------------------------------------------

/// Shorthand for [`Num::lit`]: a constant of the formula's type.
#[inline(always)]
pub fn c<F: Num>(v: f64) -> F {
    F::lit(v)
}

macro_rules! unary {
    ($($(#[$m:meta])* $name:ident),*) => {$(
        $(#[$m])*
        #[inline(always)]
        pub fn $name<F: Num>(x: F) -> F {
            F::$name(x)
        }
    )*};
}
unary!(abs, sqrt, floor, sin, cos, acos, exp2, ln);

#[inline(always)]
pub fn atan2<F: Num>(y: F, x: F) -> F {
    F::atan2(y, x)
}
#[inline(always)]
pub fn pow<F: Num>(x: F, y: F) -> F {
    F::pow(x, y)
}
#[inline(always)]
pub fn min<F: Num>(a: F, b: F) -> F {
    F::min(a, b)
}
#[inline(always)]
pub fn max<F: Num>(a: F, b: F) -> F {
    F::max(a, b)
}
/// `a < b` per lane.
#[inline(always)]
pub fn lt<F: Num>(a: F, b: F) -> F::Mask {
    F::lt(a, b)
}
/// `a <= b` per lane.
#[inline(always)]
pub fn le<F: Num>(a: F, b: F) -> F::Mask {
    F::le(a, b)
}
/// `a > b` per lane.
#[inline(always)]
pub fn gt<F: Num>(a: F, b: F) -> F::Mask {
    F::lt(b, a)
}
/// `a >= b` per lane.
#[inline(always)]
pub fn ge<F: Num>(a: F, b: F) -> F::Mask {
    F::le(b, a)
}
/// `a` where `m`, else `b`.
#[inline(always)]
pub fn select<F: Num>(m: F::Mask, a: F, b: F) -> F {
    F::select(m, a, b)
}
/// `x` limited to `lo..=hi` (as `min(max(x, lo), hi)`).
#[inline(always)]
pub fn clamp<F: Num>(x: F, lo: F, hi: F) -> F {
    min(max(x, lo), hi)
}
/// Linear interpolation from `a` (t = 0) to `b` (t = 1).
#[inline(always)]
pub fn mix<F: Num>(a: F, b: F, t: F) -> F {
    F::mix(a, b, t)
}
/// Floored modulo as GLSL's `mod` (not Rust's `%`, which truncates): the result has the sign of `m`.
#[inline(always)]
pub fn fmod_floor<F: Num>(x: F, m: F) -> F {
    x - m * floor(x / m)
}
