//! What the formulas share: the guard constants that keep f32 finite (they reach every kernel as traced literals)
//! and small helpers over [`Num`].

use crate::number::math::*;
use crate::number::{Carry, Mask, Num};

/// Smallest divisor used where a formula divides by a user value that may be zero (smooth blend k, capsule length).
pub const TINY: f64 = 1e-30;
/// Derivative cap for escape-time fractals: past it the estimate is 0 to within float precision anyway, and stopping
/// keeps f32 from overflowing to Inf (and Inf/Inf to NaN): power · r^(power−1) · dr stays below 2^128 up to power 64
/// with r ≤ 2^(60/power).
pub const DR_MAX: f64 = 1e17;
/// Largest log2 of |z|^power an iteration may produce: `length` squares |z|, so 2^60 keeps |z|² (2^120) finite in
/// f32 (max ~2^128).
pub const POW_LOG2_MAX: f64 = 60.0;
/// 1/√3: the distance from a point to a plane whose normal has three unit components.
pub(super) const INV_SQRT3: f64 = 0.577_350_269_189_625_8;

/// `a` where `m`, else `b`, per component.
#[inline(always)]
pub(super) fn select3<F: Num>(m: F::Mask, a: V3<F>, b: V3<F>) -> V3<F> {
    v3(select(m, a.x, b.x), select(m, a.y, b.y), select(m, a.z, b.z))
}

/// Runs `step` `n` times (a loop without an early exit).
#[inline(always)]
pub(super) fn repeat<F: Num, S: Carry<F>>(n: F::Count, init: S, step: impl Fn(S) -> S) -> S {
    F::iterate(
        n,
        init,
        #[inline(always)]
        |_| F::Mask::splat(true),
        step,
    )
}
