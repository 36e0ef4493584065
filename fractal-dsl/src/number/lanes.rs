//! A packet of eight f32 lanes, [`F32x8`]: the formulas and the scene walker run on it unchanged (they follow
//! [`Num`]'s rules: choices are selects, loops carry a mask of running lanes), so the CPU evaluates eight points at
//! the cost of a little more than one where the scene's code is arithmetic.
//!
//! The lanes are plain arrays operated on lane by lane in `#[inline(always)]` loops that LLVM turns into vector
//! instructions of whatever the build targets (two 4-wide SSE2 operations per packet on a baseline x86-64 build, one
//! 8-wide AVX operation where AVX is enabled, NEON pairs on aarch64). The elementary functions are the branch-free
//! ones of [`crate::number::elementary`], which f32 runs too, so they vectorise the same way and agree with the scalar
//! results bit for bit. Masks are lanes of 0 / −1 (all bits set), as vector compares produce.

use core::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use crate::number::elementary;
use crate::number::{AnyLane, Carry, Mask, Num, Orbit};

/// Lanes in a packet.
pub const LANES: usize = 8;

/// Whether the CPU runs AVX2, for which the native evaluator's packet instance is also compiled (x86-64; the answer
/// is detected once and cached).
#[cfg(target_arch = "x86_64")]
pub fn has_avx2() -> bool {
    std::is_x86_feature_detected!("avx2")
}

/// The instruction set packets run in on this CPU: what `fractal bench --backend cpu` reports.
pub fn instruction_set() -> &'static str {
    #[cfg(target_arch = "x86_64")]
    {
        if has_avx2() {
            return "AVX2 (8 lanes per instruction)";
        }
        "SSE2 (4 lanes per instruction, 2 per packet)"
    }
    #[cfg(target_arch = "aarch64")]
    {
        "NEON (4 lanes per instruction, 2 per packet)"
    }
    #[cfg(not(any(target_arch = "x86_64", target_arch = "aarch64")))]
    {
        "the target's baseline"
    }
}

/// Eight f32 lanes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(32))]
pub struct F32x8(pub [f32; LANES]);

/// A truth value per lane of an [`F32x8`]: 0 false, −1 (all bits set) true.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C, align(32))]
pub struct M32x8(pub [i32; LANES]);

impl F32x8 {
    /// The same value in every lane.
    #[inline(always)]
    pub fn splat(v: f32) -> F32x8 {
        F32x8([v; LANES])
    }
    /// Lanes from `f(lane index)`.
    #[inline(always)]
    pub fn from_fn(f: impl FnMut(usize) -> f32) -> F32x8 {
        F32x8(core::array::from_fn(f))
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f32) -> f32) -> F32x8 {
        let mut out = self.0;
        for lane in &mut out {
            *lane = f(*lane);
        }
        F32x8(out)
    }
    #[inline(always)]
    fn zip(self, other: F32x8, f: impl Fn(f32, f32) -> f32) -> F32x8 {
        let mut out = self.0;
        for (lane, o) in out.iter_mut().zip(other.0) {
            *lane = f(*lane, o);
        }
        F32x8(out)
    }
    /// `reduced` on every lane where all are within the trigonometric reduction's range (one vector loop), else
    /// `any` lane by lane: the same per-lane results as the scalar functions, which make the same choice per value.
    #[inline(always)]
    fn map_trig(self, reduced: impl Fn(f32) -> f32, any: impl Fn(f32) -> f32) -> F32x8 {
        if self.0.iter().all(|v| v.abs() <= elementary::TRIG_REDUCTION_LIMIT) {
            self.map(reduced)
        } else {
            self.map(any)
        }
    }
    #[inline(always)]
    fn compare(self, other: F32x8, f: impl Fn(f32, f32) -> bool) -> M32x8 {
        let mut out = [0i32; LANES];
        for ((m, a), b) in out.iter_mut().zip(self.0).zip(other.0) {
            *m = -i32::from(f(a, b));
        }
        M32x8(out)
    }
}

impl AnyLane for M32x8 {
    #[inline(always)]
    fn any(self) -> bool {
        self.0.iter().fold(0, |acc, &m| acc | m) != 0
    }
}

impl M32x8 {
    #[inline(always)]
    fn zip(self, other: M32x8, f: impl Fn(i32, i32) -> i32) -> M32x8 {
        let mut out = self.0;
        for (lane, o) in out.iter_mut().zip(other.0) {
            *lane = f(*lane, o);
        }
        M32x8(out)
    }
}

impl Mask for M32x8 {
    #[inline(always)]
    fn splat(v: bool) -> Self {
        M32x8([-i32::from(v); LANES])
    }
}

impl BitAnd for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn bitand(self, o: M32x8) -> M32x8 {
        self.zip(
            o,
            #[inline(always)]
            |a, b| a & b,
        )
    }
}
impl BitOr for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn bitor(self, o: M32x8) -> M32x8 {
        self.zip(
            o,
            #[inline(always)]
            |a, b| a | b,
        )
    }
}
impl Not for M32x8 {
    type Output = M32x8;
    #[inline(always)]
    fn not(self) -> M32x8 {
        let mut out = self.0;
        for lane in &mut out {
            *lane = !*lane;
        }
        M32x8(out)
    }
}

macro_rules! arithmetic {
    ($trait:ident, $method:ident, $op:tt) => {
        impl $trait for F32x8 {
            type Output = F32x8;
            #[inline(always)]
            fn $method(self, o: F32x8) -> F32x8 {
                self.zip(o, #[inline(always)] |a, b| a $op b)
            }
        }
    };
}
arithmetic!(Add, add, +);
arithmetic!(Sub, sub, -);
arithmetic!(Mul, mul, *);
arithmetic!(Div, div, /);

impl Neg for F32x8 {
    type Output = F32x8;
    #[inline(always)]
    fn neg(self) -> F32x8 {
        self.map(
            #[inline(always)]
            |a| -a,
        )
    }
}

impl Carry<F32x8> for F32x8 {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F32x8) -> F32x8) -> Self {
        f(self)
    }
    #[inline(always)]
    fn zip_nums(self, other: Self, f: &mut impl FnMut(F32x8, F32x8) -> F32x8) -> Self {
        f(self, other)
    }
}

/// `a` where `m`, else `b`, lane by lane, by the bits (a blend).
#[inline(always)]
fn blend(m: M32x8, a: F32x8, b: F32x8) -> F32x8 {
    let mut out = a.0;
    for ((lane, other), mask) in out.iter_mut().zip(b.0).zip(m.0) {
        let bits = (lane.to_bits() & mask as u32) | (other.to_bits() & !(mask as u32));
        *lane = f32::from_bits(bits);
    }
    F32x8(out)
}

// The elementary functions are passed as closures marked `#[inline(always)]`, not as function items: a function item
// is called through a shim LLVM may leave out of line, and out of line it is compiled for the baseline, not for the
// AVX2 copy of the packet instance.
#[allow(clippy::redundant_closure)]
impl Num for F32x8 {
    type Mask = M32x8;
    type Count = u32;

    #[inline(always)]
    fn lit(v: f64) -> Self {
        F32x8::splat(v as f32)
    }
    #[inline(always)]
    fn count(n: u32) -> u32 {
        n
    }
    #[inline(always)]
    fn abs(x: Self) -> Self {
        x.map(
            #[inline(always)]
            |v| v.abs(),
        )
    }
    #[inline(always)]
    fn sqrt(x: Self) -> Self {
        x.map(
            #[inline(always)]
            |v| v.sqrt(),
        )
    }
    #[inline(always)]
    fn floor(x: Self) -> Self {
        x.map(
            #[inline(always)]
            |v| elementary::floor(v),
        )
    }
    #[inline(always)]
    fn sin(x: Self) -> Self {
        x.map_trig(
            #[inline(always)]
            |v| elementary::sin_reduced(v),
            #[inline(always)]
            |v| elementary::sin(v),
        )
    }
    #[inline(always)]
    fn cos(x: Self) -> Self {
        x.map_trig(
            #[inline(always)]
            |v| elementary::cos_reduced(v),
            #[inline(always)]
            |v| elementary::cos(v),
        )
    }
    #[inline(always)]
    fn acos(x: Self) -> Self {
        x.map(
            #[inline(always)]
            |v| elementary::acos(v),
        )
    }
    #[inline(always)]
    fn atan2(y: Self, x: Self) -> Self {
        y.zip(
            x,
            #[inline(always)]
            |y, x| elementary::atan2(y, x),
        )
    }
    #[inline(always)]
    fn exp2(x: Self) -> Self {
        x.map(
            #[inline(always)]
            |v| elementary::exp2(v),
        )
    }
    #[inline(always)]
    fn ln(x: Self) -> Self {
        x.map(
            #[inline(always)]
            |v| elementary::ln(v),
        )
    }
    #[inline(always)]
    fn pow(x: Self, y: Self) -> Self {
        x.zip(
            y,
            #[inline(always)]
            |x, y| elementary::pow(x, y),
        )
    }
    #[inline(always)]
    fn min(a: Self, b: Self) -> Self {
        a.zip(
            b,
            #[inline(always)]
            |a, b| a.min(b),
        )
    }
    #[inline(always)]
    fn max(a: Self, b: Self) -> Self {
        a.zip(
            b,
            #[inline(always)]
            |a, b| a.max(b),
        )
    }
    #[inline(always)]
    fn lt(a: Self, b: Self) -> M32x8 {
        a.compare(
            b,
            #[inline(always)]
            |a, b| a < b,
        )
    }
    #[inline(always)]
    fn le(a: Self, b: Self) -> M32x8 {
        a.compare(
            b,
            #[inline(always)]
            |a, b| a <= b,
        )
    }
    #[inline(always)]
    fn select(m: M32x8, a: Self, b: Self) -> Self {
        blend(m, a, b)
    }
    #[inline(always)]
    fn iterate<S: Carry<Self>>(n: u32, init: S, active: impl Fn(&S) -> M32x8, step: impl Fn(S) -> S) -> S {
        let mut s = init;
        for _ in 0..n {
            let running = active(&s);
            if !running.any() {
                break;
            }
            // Lanes that stopped keep their state: the step runs for all, and is discarded where not running.
            s = step(s).zip_nums(s, &mut |new, old| blend(running, new, old));
        }
        s
    }
    #[inline(always)]
    fn stand_in(live: M32x8, x: Self) -> Self {
        match live.0.iter().position(|&m| m != 0) {
            Some(first) => blend(live, x, F32x8::splat(x.0[first])),
            None => x,
        }
    }
    #[inline(always)]
    fn when<S: Carry<Self>>(cond: M32x8, state: S, body: impl FnOnce(S) -> S) -> S {
        if cond.any() {
            body(state).zip_nums(state, &mut |new, old| blend(cond, new, old))
        } else {
            state
        }
    }
    #[inline(always)]
    fn orbit_entry(orbit: Orbit<'_>, index: Self) -> [Self; 2] {
        // Lane by lane, as the scalars index (a select per entry would cost the orbit's length).
        let last = orbit.len().saturating_sub(1);
        let mut entry = [F32x8::splat(0.0); 2];
        for (lane, i) in index.0.iter().enumerate() {
            let e = orbit.get((*i as usize).min(last)).unwrap_or(&[0.0, 0.0]);
            entry[0].0[lane] = e[0];
            entry[1].0[lane] = e[1];
        }
        entry
    }
}
