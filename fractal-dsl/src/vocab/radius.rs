//! The radii that bound each fractal family's set, from its iteration's escape argument with measured margins: the
//! declarations in [`super::fractals`] build their bounds from them, and the bounds tests re-check them.

use crate::geom::Interval;

/// Radius of a sphere around the origin that bounds the Mandelbulb of any power ≥ `min_power`, at any iteration count
/// and bailout. Points with |p|^(n−1) > 2 escape (|z^n + p| ≥ |z|^n − |p| > |z| keeps growing), so the set lies within
/// 2^(1/(n−1)); the margin covers the rendered surface, where the estimate is below a hit epsilon (measured:
/// `docs/settings.md`, “Bounds of the fractal families”).
pub fn mandelbulb_radius(min_power: f64) -> Option<f64> {
    if min_power.is_nan() || min_power <= 1.0 || min_power.is_infinite() {
        return None;
    }
    Some(2f64.powf(1.0 / (min_power - 1.0)) + 0.05)
}

/// Radius of a sphere that bounds the quaternion Julia set of any constant with |c| ≤ `c_norm`: points beyond
/// R = (1 + √(1 + 4|c|))/2 escape (|z² + c| ≥ |z|² − |c| > |z|). The margin covers the rendered surface (measured well
/// inside R).
pub fn julia_radius(c_norm: f64) -> Option<f64> {
    if !c_norm.is_finite() {
        return None;
    }
    Some(0.5 * (1.0 + (1.0 + 4.0 * c_norm.max(0.0)).sqrt()) + 0.05)
}

/// Radius of a sphere that bounds the Juliabulb (z ← z^n + c) of any power ≥ `min_power` and constant with
/// |c| ≤ `c_norm`: past the root R of R^n = R + |c|, |z^n + c| ≥ |z|^n − |c| > |z| keeps growing. R is approached
/// from above (from 1 + |c|, above the root since (1 + |c|)^n ≥ 1 + n|c|); the margin is the Mandelbulb's.
pub fn juliabulb_radius(min_power: f64, c_norm: f64) -> Option<f64> {
    if !c_norm.is_finite() || min_power.is_nan() || min_power <= 1.0 || min_power.is_infinite() {
        return None;
    }
    let c = c_norm.max(0.0);
    let mut r = 1.0 + c;
    for _ in 0..64 {
        r = (r + c).powf(1.0 / min_power);
    }
    Some(r + 0.05)
}

/// Half extent of the cube that bounds the Mandelbox for every scale in `scale` and fold limits up to `fold_limit`.
/// For scale s > 1 the box fold's fixed point bounds the orbit: 2f(s + 1)/(s − 1) (the known 6 at s = 2, f = 1); for
/// s < −1 the measured extent is 2f. Scales within [−1, 1] never escape: unbounded.
pub fn mandelbox_half_extent(scale: Interval, fold_limit: f64) -> Option<f64> {
    if !scale.is_finite() || !fold_limit.is_finite() {
        return None;
    }
    let extent = if scale.lo > 1.0 {
        2.0 * fold_limit * (scale.lo + 1.0) / (scale.lo - 1.0)
    } else if scale.hi < -1.0 {
        2.0 * fold_limit
    } else {
        return None;
    };
    // The rendered surface (estimate below a hit epsilon) reaches slightly past the set.
    Some(extent * 1.01 + 0.02)
}
