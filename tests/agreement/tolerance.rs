//! The agreement tolerances, each with its reason. All are relative to the f32 unit roundoff u = 2^-24 and to the
//! magnitudes involved: a distance is held to |d − d_ref| ≤ abs + rel · s with s = max(1, |p|, |d_ref|) (a point
//! rounded to f32 already moves by up to u·|p|, and every result is rounded relative to its own size), a material
//! channel v to |v − v_ref| ≤ abs + rel · max(1, |v_ref|).
//!
//! The reference is the f64 interpreter, whose own error (~2^-53 relative) is negligible against all of these.
//! The values were set a little above the largest differences the suite measures (printed by every run), rounded up
//! to a power of two: no looser than needed, with room for a driver's built-ins to differ by an ulp or two.

use crate::harness::Family;

/// The f32 unit roundoff, 2^-24: the largest relative error of one correctly rounded f32 operation.
pub const UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;
const U: f64 = UNIT_ROUNDOFF;

/// Relative step (times max(1, |p|)) to the neighbours a material may come from when p lies on a boundary between
/// materials: a union's children within an f32 distance error of each other pick either material, and that happens
/// within ~|δd| / |∇(d_a − d_b)| of the boundary, which 1e-4 covers for every row here with room to spare.
pub const MATERIAL_NEIGHBOUR_STEP: f64 = 1e-4;

/// Which kind of evaluator a tolerance is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// The native evaluator in f64.
    Twin,
    /// The interpreter and the native evaluator in f32.
    CpuF32,
    /// The WGSL and OpenCL kernels, OpenCL built without fast math.
    Gpu,
    /// The OpenCL kernel built with `-cl-fast-relaxed-math`.
    FastMath,
}

/// `abs + rel · scale`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tol {
    pub abs: f64,
    pub rel: f64,
}

impl Tol {
    pub fn of(self, scale: f64) -> f64 {
        self.abs + self.rel * scale
    }
}

const fn ulps(n: f64) -> Tol {
    Tol { abs: 0.0, rel: n * U }
}

/// The distance tolerance of a family of rows for a class of evaluators.
pub fn distance_tolerance(family: Family, class: Class) -> Tol {
    use Class::*;
    use Family::*;
    match (class, family) {
        // The native evaluator calls the same `sdf` functions as the interpreter with its operations in the same
        // order (the lowering folds only literal subexpressions, in f64 like the interpreter's folding, and drops
        // only exact identities such as x + 0 and x · 1), so in f64 the two are bit-identical.
        (Twin, _) => Tol { abs: 0.0, rel: 0.0 },
        // Primitives, CSG, transforms, domain operations: a handful of roundings of quantities no larger than s
        // (measured ≤ 3.1 u·s on every evaluator). The same where sin/cos/pow run per point (twist, bend, animated
        // rotations, expressions): Rust's libm and pocl are correctly rounded or nearly, lavapipe's pow measures 4.6.
        (CpuF32 | Gpu | FastMath, Exact | Trig) => ulps(8.0),
        // Menger, Sierpinski and Mandelbox fold space with exact operations (abs, floor, min/max, clamp, scaling by
        // a power of two or 3) and measure ≤ 1.8 u·s.
        (CpuF32 | Gpu | FastMath, Menger | Sierpinski | Mandelbox) => ulps(4.0),
        // Escape-time estimators: each iteration rounds z relative to |z| and the derivative grows with the
        // amplification, so the estimate 0.5·ln r·r/dr carries the iterates' rounding; it stays a small multiple of
        // u·s because the amplification of z and of dr cancel in the ratio, except where the orbit passes near the
        // pole (θ = acos(z/r) is ill-conditioned as z/r → ±1, 1/√(1 − x²)). Measured ≤ 20 u·s on the CPU (the trig
        // path near the pole), ≤ 12 for the trig-free power 8.
        (CpuF32, Mandelbulb) => ulps(32.0),
        // lavapipe's acos/atan2/pow are less accurate than libm's (Vulkan allows several ulps, pow 3 + 2|x·log2 y|):
        // the trig path near the pole measures up to 71 u·s on lavapipe; pocl stays at the CPU's 20.
        (Gpu | FastMath, Mandelbulb) => ulps(128.0),
        // Quaternion Julia: the same escape-time cancellation; no trig. Measured ≤ 11.2 u·s.
        (CpuF32 | Gpu | FastMath, Julia) => ulps(16.0),
    }
}

/// The tolerance of each material channel.
pub fn material_tolerance(_family: Family, class: Class) -> Tol {
    match class {
        Class::Twin => Tol { abs: 0.0, rel: 0.0 },
        // Constants rounded to f32 (½ u) and one mix a + (b − a)·w (2 u of the larger operand).
        _ => ulps(2.0),
    }
}
