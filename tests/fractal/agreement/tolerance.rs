//! The agreement tolerances, each with its reason. All are relative to the f32 unit roundoff u = 2^-24 and to the
//! magnitudes involved: a distance is held to |d − d_ref| ≤ abs + rel · s with s = max(1, |p|, |d_ref|) (the
//! intermediate quantities, p − centre, |p|, are as large as p, every rounding is relative to the quantity rounded,
//! and the last one to |d|), a material channel v to |v − v_ref| ≤ abs + rel · max(1, |v_ref|).
//!
//! The reference is the f64 interpreter, whose own error (~2^-53 relative) is negligible against all of these. The
//! points, time and parameter values are f32 numbers given to every evaluator exactly, so the differences are the
//! evaluators' own arithmetic. The values are about 1.5× the largest differences the suite measures (it prints them
//! on every run): no looser than needed, with room for a driver's built-ins to differ by an ulp or so.
//!
//! A material is accepted (harness `compare`) when it is within its tolerance of the reference at p (plus, for a
//! smooth blend, the weight's sensitivity to the distances' rounding, see `Row::blends`); or, for a steep but
//! continuous material (an orbit trap near the set), when each channel lies in the range the reference takes within
//! the distance tolerance of p; or, at a boundary between materials, when it is the whole material the reference
//! gives a point [`MATERIAL_NEIGHBOUR_STEP`] away. The tables count the last two cases ("steep", "bndry").

use super::harness::Family;

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
    #[cfg_attr(not(feature = "opencl"), allow(dead_code))]
    FastMath,
    /// The WGSL (`SHADER_F64`) and OpenCL (`cl_khr_fp64`) kernels in f64, their answers rounded to the probe's f32
    /// outputs.
    GpuF64,
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

/// The distance tolerance of a family of rows for a class of evaluators. Each is about 1.5× the largest difference
/// the suite measures for that family and class (quoted below in units of u·s), so a change that makes any evaluator
/// noticeably less accurate fails here.
pub fn distance_tolerance(family: Family, class: Class) -> Tol {
    use Class::*;
    use Family::*;
    match (class, family) {
        // The native evaluator calls the same `sdf` functions as the interpreter with its operations in the same
        // order (the lowering folds literal-only subexpressions in f64, as the interpreter's folding does, and drops
        // only exact identities such as x + 0 and x · 1), so in f64 the two are bit-identical: measured 0 on every
        // row. Any difference means the generated Rust and the interpreter do different arithmetic somewhere.
        (Twin, _) => Tol { abs: 0.0, rel: 0.0 },
        // The same arithmetic in f64 — with the device's f64 built-ins (OpenCL) or the traced ones of
        // `number::portable`, within 2 f64 ulps (WGSL) — then rounded to the f32 the probe writes: at most 1 u·s
        // (measured ≤ 0.92 on pocl); the built-ins' f64 differences, amplified by an orbit by at most ~1e7
        // (1e-13, see `TWO_FORMS_F64`), are far below it. A kernel that computed in f32 is caught by its text
        // (`tests/fractal/kernels.rs`), not here: on exact rows its error is as small.
        (GpuF64, _) => ulps(1.5),
        // Primitives, CSG, transforms, domain operations and expressions: a handful of roundings of quantities no
        // larger than s. Measured ≤ 3.1 on the CPU (the ellipsoid, a negated translation) and on pocl, fast math
        // included (pocl's sqrt and division stay correctly rounded on a CPU device). Where sin/cos/pow run per
        // point (twist, bend, animated rotations, sin/cos/pow of t) lavapipe's pow is the least accurate built-in:
        // 4.6 against the CPU's 1.7 on the pow row.
        (CpuF32, Exact | Trig | Pattern) => ulps(5.0),
        (Gpu | FastMath, Exact | Trig | Pattern) => ulps(7.0),
        // Menger, Sierpinski and Mandelbox fold space with exact operations (abs, floor, min/max, clamp, scaling by
        // 2, 3 or the Mandelbox scale) and round only in the last few steps: measured ≤ 1.8 everywhere, the 6-level
        // sponge on k/3 planes and 100 units away included.
        (_, Menger | Sierpinski | Mandelbox) => ulps(3.0),
        // KIFS: exact folds, a turn rounded in f32 each step, and the estimate divides the orbit's growth back out.
        // Measured ≤ 3.2 on the CPU, 3.2 on lavapipe, 3.1 on pocl.
        (_, Kifs) => ulps(5.0),
        // Quaternion Julia: each iteration rounds z relative to |z| and the derivative grows with the orbit's
        // amplification, but the estimate ¼·ln m·√(m/|dz|²) takes their ratio, in which the amplification cancels.
        // Measured ≤ 7.4 on the CPU, 11.2 on pocl.
        (CpuF32, Julia) => ulps(12.0),
        (Gpu | FastMath, Julia) => ulps(16.0),
        // Mandelbulb: the same cancellation, except at high powers and bailouts, where r^power spans many binades, and
        // in the trigonometric form (any power but the literal 8, the Juliabulb), which takes θ = atan2(ρ, z):
        // acos(z/r) lost ~1e-4 rad near the poles on lavapipe, which a Juliabulb orbit magnified past any tolerance.
        // Measured ≤ 27.6 on the CPU (power 8 with bailout 256), 9.6 on pocl. lavapipe's atan2 and pow are less
        // accurate than libm's (Vulkan allows several ulps; pow 3 + 2|x·log2 y| ulps): 119.7 on power 7.5 near
        // never-escaping points (CPU 0.5), 89.8 down the pole axis (CPU 15.7). The Juliabulb measures ≤ 13.7 on
        // lavapipe, 1.4 on the CPU (outside the set; inside only the sign is compared, see the harness). pocl's fast
        // math depends on the host it compiles for: ≤ 9.6 on an AMD EPYC, 120.7 on an Intel Xeon (power 8 with bailout
        // 256 at a never-escaping point on x = 0, where the estimate is −0.012), so fast math gets the GPU bound.
        // The Juliabulb's derivative takes the map's azimuthal stretch |sin pθ|·r/ρ (`sdf::de_juliabulb`), so
        // lavapipe's sin at arguments up to 8π reaches its estimate too: measured 203 on lavapipe near the surface
        // (13.7 before the stretch).
        // A hybrid of a power-4 trigonometric bulb map (θ = atan2(ρ, z)·4, sin and cos of up to 4π) and a box fold of
        // scale 1.5, taken in turn: lavapipe's atan2 and sin err as on the Juliabulb, and the escape-time estimate
        // divides by |Jᵀz|/|z|, the Jacobian read along the orbit's direction, which those errors turn a little each
        // step. Measured 663 on lavapipe at one point of 272 (0.446 from the set: a relative error of 1e-4 in the
        // estimate), within the Mandelbulb's bounds on the CPU and on pocl.
        (CpuF32, Hybrid) => ulps(40.0),
        (Gpu | FastMath, Hybrid) => ulps(1000.0),
        (CpuF32, Mandelbulb | Juliabulb) => ulps(40.0),
        (Gpu | FastMath, Mandelbulb) => ulps(180.0),
        (Gpu | FastMath, Juliabulb) => ulps(300.0),
    }
}

/// The tolerance of each material channel v, relative to max(1, |v|).
pub fn material_tolerance(family: Family, class: Class) -> Tol {
    match class {
        // Bit-identical, as the distances.
        Class::Twin => Tol { abs: 0.0, rel: 0.0 },
        // Rounded to f32 once, as the distances.
        Class::GpuF64 => ulps(1.5),
        // A pattern computed at the point rounds a dozen times (noise's fade and blends, the Mandelbrot count's logs):
        // measured ≤ 3.7 on the CPU away from the escape count's steep bands, where the harness's neighbourhood rule
        // takes over.
        _ if family == Family::Pattern => ulps(6.0),
        // Constants rounded to f32 (½ u; measured 0.4 u: 0.95 and 0.1 are not f32 numbers) and one mix
        // a + (b − a)·w of values in [0, 1] (≤ 2 u). Blends and orbit traps add their own terms (see the harness).
        _ => ulps(2.0),
    }
}
