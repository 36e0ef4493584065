//! The agreement tolerances (provisional: measuring).

use crate::harness::Family;

/// The f32 unit roundoff, 2^-24: the largest relative error of one correctly rounded f32 operation.
pub const UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;
const U: f64 = UNIT_ROUNDOFF;

/// Relative step (times max(1, |p|)) to the neighbours a material may come from when p lies on a material boundary.
pub const MATERIAL_NEIGHBOUR_STEP: f64 = 1e-4;

/// Which evaluator kind a tolerance is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// The native evaluator in f64.
    Twin,
    /// The interpreter and the native evaluator in f32.
    CpuF32,
    /// The WGSL and OpenCL kernels (built without fast math).
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

pub fn distance_tolerance(_family: Family, class: Class) -> Tol {
    match class {
        Class::Twin => Tol { abs: 0.0, rel: 1e-12 },
        _ => Tol { abs: 0.0, rel: 1e6 * U },
    }
}

pub fn material_tolerance(_family: Family, class: Class) -> Tol {
    match class {
        Class::Twin => Tol { abs: 0.0, rel: 1e-12 },
        _ => Tol { abs: 0.0, rel: 1e4 * U },
    }
}
