//! The 2D Mandelbrot set as a pattern expressions can call (`mandelbrot(x, z, iterations)`): its smooth escape count,
//! written once, generic over [`Num`], in two leaf functions — the plain iteration of c, and the same count by
//! perturbation around a reference orbit, which is how the kernels zoom past what f32 can tell apart.
//!
//! **Why perturbation.** Near c ≈ −0.74 an f32 holds numbers 6·10⁻⁸ apart: a view narrower than about 10⁻⁵ turns to
//! noise and then to blocks, whatever the iteration does. Perturbation splits c = C + δc, with C one reference point
//! whose orbit Z₀ = 0, Zₙ₊₁ = Zₙ² + C the host computes in f64 (held by the kernel in f32), and iterates only the
//! difference δₙ = zₙ − Zₙ:  δₙ₊₁ = (2Zₙ + δₙ)·δₙ + δc. δc is small and carried with full relative precision (the
//! kernels pass the hit point relative to the camera, see [`crate::eval::Reference`]), so pixels 10⁻¹⁵ apart stay
//! apart while z = Zₙ + δₙ decides escape.
//!
//! **Rebasing** (Zhuoran, 2021): when |z| < |δ| — the pixel's orbit passed nearer to 0 than to the reference's — or
//! when the reference orbit runs out (it escaped, or its count ended), the iteration goes on from z itself, as δ around
//! the reference's start (Z₀ = 0, index 0). This removes the "glitches" of plain perturbation without a second
//! reference. Around the reference point 0, whose orbit is the single entry [0, 0] ([`crate::number::ORBIT_AT_ZERO`]),
//! the step is exactly the plain iteration's: that is what an evaluator without a frame (a probe,
//! `CompiledScene::sample`) runs.

use crate::number::math::*;
use crate::number::Orbit;

/// Most iterations of the Mandelbrot pattern. The reference orbit of a perturbed pattern lives in the frame uniform,
/// two entries per 16-byte slot; 7500 iterations fill 3751 of the 4096 slots of a 64 KiB uniform buffer (the limit
/// wgpu guarantees), leaving room for 16 lights and over a thousand parameters.
pub const MAX_MANDELBROT_ITERATIONS: u32 = 7_500;
/// Squared escape radius of the Mandelbrot pattern: a large radius makes the smooth count smooth.
const MANDELBROT_ESCAPE2: f64 = 256.0;
/// The least value an escaping Mandelbrot point reads (0 is the set itself).
const TINY_PATTERN: f64 = 1e-6;

/// The `inverse` argument of the pattern's leaf functions for a count: 1/iterations (1 for 0).
pub fn inverse_count(iterations: u32) -> f64 {
    1.0 / f64::from(iterations.max(1))
}

/// The 2D Mandelbrot set at c = (cx, cy): the smooth escape count ν = n + 1 − log₂(log₂|z|) of z ← z² + c over
/// `iterations` (`inverse` = 1/iterations), clamped to (0, 1]; 0 for c whose orbit stays within radius 16 (inside
/// the set, at this count). Material colours read it at the hit only.
#[inline(always)]
pub fn mandelbrot<F: Num>(cx: F, cy: F, iterations: F::Count, inverse: F) -> F {
    let zero = c::<F>(0.0);
    let escape2 = c::<F>(MANDELBROT_ESCAPE2);
    let (zx, zy, steps) = F::iterate(
        iterations,
        (zero, zero, zero),
        #[inline(always)]
        |&(zx, zy, _)| le(zx * zx + zy * zy, escape2),
        #[inline(always)]
        |(zx, zy, steps)| (zx * zx - zy * zy + cx, c::<F>(2.0) * zx * zy + cy, steps + c(1.0)),
    );
    smooth_count(zx, zy, steps, inverse)
}

/// The pattern of [`mandelbrot`] at c = C + (dcx, dcy) by perturbation around `orbit`, the orbit of C (see the
/// module documentation). The loop takes the same steps as the plain one and stops on the same test, |z|² > 256.
#[inline(always)]
pub fn mandelbrot_perturbed<F: Num>(dcx: F, dcy: F, iterations: F::Count, inverse: F, orbit: Orbit<'_>) -> F {
    let zero = c::<F>(0.0);
    let escape2 = c::<F>(MANDELBROT_ESCAPE2);
    let last = F::orbit_last(orbit);
    // (δ, reference index, z, steps)
    let (_, _, [zx, zy], steps) = F::iterate(
        iterations,
        ([zero, zero], zero, [zero, zero], zero),
        #[inline(always)]
        |&(_, _, [zx, zy], _)| le(zx * zx + zy * zy, escape2),
        #[inline(always)]
        |([dx, dy], index, _, steps)| {
            let [rx, ry] = F::orbit_entry(orbit, index);
            let (ax, ay) = (c::<F>(2.0) * rx + dx, c::<F>(2.0) * ry + dy);
            let (nx, ny) = (ax * dx - ay * dy + dcx, ax * dy + ay * dx + dcy);
            let next = index + c(1.0);
            let [sx, sy] = F::orbit_entry(orbit, next);
            let (zx, zy) = (sx + nx, sy + ny);
            // Past `last` the next step would read beyond the orbit, so it rebases before.
            let rebase = lt(zx * zx + zy * zy, nx * nx + ny * ny) | !lt(next, last);
            ([select(rebase, zx, nx), select(rebase, zy, ny)], select(rebase, zero, next), [zx, zy], steps + c(1.0))
        },
    );
    smooth_count(zx, zy, steps, inverse)
}

/// The smooth escape count of an orbit that ended at z after `steps` steps, scaled by `inverse` into (0, 1]; 0 if it
/// never escaped.
#[inline(always)]
fn smooth_count<F: Num>(zx: F, zy: F, steps: F, inverse: F) -> F {
    let escape2 = c::<F>(MANDELBROT_ESCAPE2);
    let m2 = zx * zx + zy * zy;
    let inv_ln2 = c::<F>(std::f64::consts::LOG2_E);
    // log₂|z| = ½·ln|z|²/ln 2, over 2 at the escape radius: its log₂ stays finite.
    let smooth = steps + c(1.0) - ln(c::<F>(0.5) * ln(max(m2, escape2)) * inv_ln2) * inv_ln2;
    select(gt(m2, escape2), clamp(smooth * inverse, c(TINY_PATTERN), c(1.0)), c(0.0))
}

/// The orbit of the reference point (cx, cy) as a perturbed pattern of `iterations` reads it: Z₀ = 0 up to the entry
/// that escaped (|Z|² > 256) or Z_iterations, computed in f64 and rounded to f32.
pub fn reference_orbit(cx: f64, cy: f64, iterations: u32) -> Vec<[f32; 2]> {
    let mut orbit = Vec::with_capacity(iterations as usize + 1);
    let (mut zx, mut zy) = (0.0f64, 0.0f64);
    orbit.push([0.0, 0.0]);
    for _ in 0..iterations {
        (zx, zy) = (zx * zx - zy * zy + cx, 2.0 * zx * zy + cy);
        orbit.push([zx as f32, zy as f32]);
        if zx * zx + zy * zy > MANDELBROT_ESCAPE2 {
            break;
        }
    }
    orbit
}
