//! Bulk evaluation on the calling thread, eight points at a time: an evaluator's packet instance (the native
//! evaluator's, or the interpreter's [`crate::eval::walk::Walk`]er on [`F32x8`]) run over structure-of-arrays inputs.
//! A slice whose length is not a multiple of eight ends with a packet padded by repeating its last point (the
//! padding's results are dropped).

use crate::eval::{Env, Sample};
use crate::number::lanes::{F32x8, LANES};
use crate::number::math::V3;

/// Panics unless the four slices have one length; returns it.
pub fn common_length(x: &[f32], y: &[f32], z: &[f32], out: usize) -> usize {
    assert!(
        x.len() == y.len() && y.len() == z.len() && z.len() == out,
        "slices of unequal length: x {}, y {}, z {}, out {}",
        x.len(),
        y.len(),
        z.len(),
        out
    );
    x.len()
}

/// Eight points from `start` (the last point repeated past the end).
#[inline(always)]
fn packet(x: &[f32], y: &[f32], z: &[f32], start: usize) -> V3<F32x8> {
    let lane = |s: &[f32]| match s.get(start..start + LANES) {
        Some(full) => F32x8(full.try_into().expect("eight lanes")),
        None => {
            let last = s.len() - 1;
            F32x8::from_fn(|i| s[(start + i).min(last)])
        }
    };
    V3 { x: lane(x), y: lane(y), z: lane(z) }
}

/// The time and parameters in every lane.
pub fn splat_params(params: &[f32]) -> Vec<F32x8> {
    params.iter().map(|&v| F32x8::splat(v)).collect()
}

/// `out[i]` = `distance` at `(x[i], y[i], z[i])` at `time` with `params`. Panics if the lengths differ.
#[allow(clippy::too_many_arguments)]
pub fn distance_slice(
    distance: impl Fn(V3<F32x8>, &Env<F32x8>) -> F32x8,
    time: f32,
    params: &[f32],
    x: &[f32],
    y: &[f32],
    z: &[f32],
    out: &mut [f32],
) {
    common_length(x, y, z, out.len());
    let params = splat_params(params);
    let env = Env::new(F32x8::splat(time), &params);
    each_packet(|p| distance(p, &env), x, y, z, out);
}

/// `out[i]` = `distance` at `(x[i], y[i], z[i])`, eight points at a time, for slices of one length. Inlined into its
/// caller, so the native evaluator compiles the whole loop into its AVX2 copy (no call per packet).
#[inline(always)]
pub fn each_packet(distance: impl Fn(V3<F32x8>) -> F32x8, x: &[f32], y: &[f32], z: &[f32], out: &mut [f32]) {
    // Whole packets by exact chunks (no bounds checks, fixed-size copies), then the padded rest.
    let lanes = |s: &[f32]| F32x8(s.try_into().expect("eight lanes"));
    let mut outs = out.chunks_exact_mut(LANES);
    let inputs = x.chunks_exact(LANES).zip(y.chunks_exact(LANES)).zip(z.chunks_exact(LANES));
    for (((xs, ys), zs), o) in inputs.zip(&mut outs) {
        o.copy_from_slice(&distance(V3 { x: lanes(xs), y: lanes(ys), z: lanes(zs) }).0);
    }
    let rest = outs.into_remainder();
    if !rest.is_empty() {
        let d = distance(packet(x, y, z, x.len() - rest.len()));
        rest.copy_from_slice(&d.0[..rest.len()]);
    }
}

/// `out[i]` = `sample` (distance and material) at `(x[i], y[i], z[i])` at `time` with `params`. Panics if the lengths
/// differ.
#[allow(clippy::too_many_arguments)]
pub fn sample_slice(
    sample: impl Fn(V3<F32x8>, &Env<F32x8>) -> Sample<F32x8>,
    time: f32,
    params: &[f32],
    x: &[f32],
    y: &[f32],
    z: &[f32],
    out: &mut [Sample<f32>],
) {
    let n = common_length(x, y, z, out.len());
    let params = splat_params(params);
    let env = Env::new(F32x8::splat(time), &params);
    for (chunk, start) in out.chunks_mut(LANES).zip((0..n).step_by(LANES)) {
        let s = sample(packet(x, y, z, start), &env);
        for (i, sample) in chunk.iter_mut().enumerate() {
            *sample = sample_lane(&s, i);
        }
    }
}

/// Lane `i` of a packet's samples.
pub fn sample_lane(s: &Sample<F32x8>, i: usize) -> Sample<f32> {
    Sample {
        distance: s.distance.0[i],
        albedo: V3 { x: s.albedo.x.0[i], y: s.albedo.y.0[i], z: s.albedo.z.0[i] },
        ambient: s.ambient.0[i],
        diffuse: s.diffuse.0[i],
        specular: s.specular.0[i],
        shininess: s.shininess.0[i],
    }
}
