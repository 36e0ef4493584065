//! What the ray program reads of a scene ([`SceneFns`]) and the probes it makes of it: the normal, ambient occlusion
//! and shadow rays. A traced scene overrides the provided functions with calls of named kernel functions.

use super::rules::{Rules, AO_SAMPLES, AO_SPAN, AO_START};
use crate::eval::Sample;
use crate::number::math::{direction, v3, V3};
use crate::number::{Mask, Num};
use crate::Shadows;

/// What the ray program reads of a scene, from whichever evaluator runs it. The provided functions are the program's
/// own (below); a traced scene calls them as named kernel functions instead of inlining them.
pub trait SceneFns<N: Num>: Sized {
    /// The scene's distance estimate at `p`.
    fn distance(&self, p: V3<N>) -> N;
    /// Distance and material at `p`; `offset` is `p` relative to the camera (rd·t along a camera ray), which a
    /// perturbed Mandelbrot pattern reads.
    fn sample(&self, p: V3<N>, offset: V3<N>) -> Sample<N>;
    /// [`normal`].
    #[inline(always)]
    fn normal(&self, p: V3<N>, h: N) -> V3<N> {
        normal(self, p, h)
    }
    /// [`occlusion`].
    #[inline(always)]
    fn occlusion(&self, rules: &Rules, p: V3<N>, n: V3<N>) -> N {
        occlusion(rules, self, p, n)
    }
    /// [`shadow`].
    #[inline(always)]
    fn shadow(&self, rules: &Rules, ray: (V3<N>, V3<N>), limit: N, eps: N, live: N::Mask) -> N {
        shadow(rules, self, ray, limit, eps, live)
    }
}

/// The tetrahedron of offsets the normal samples the distance at.
#[inline(always)]
pub fn tetrahedron<N: Num>() -> [V3<N>; 4] {
    let (one, neg) = (N::lit(1.0), N::lit(-1.0));
    [v3(one, neg, neg), v3(neg, neg, one), v3(neg, one, neg), v3(one, one, one)]
}

/// Step 4's normal at `p`: the normalised tetrahedral gradient of the distance, taps `h` apart. A scene shaded by
/// its gradient ([`crate::eval::plan::Plan::shaded_by_gradient`]) overrides it with the [`direction`] of that.
#[inline(always)]
pub fn normal<N: Num, S: SceneFns<N>>(scene: &S, p: V3<N>, h: N) -> V3<N> {
    let mut gradient = V3::splat(N::lit(0.0));
    for k in tetrahedron::<N>() {
        gradient = gradient + k * scene.distance(p + k * h);
    }
    direction(gradient)
}

/// Ambient occlusion at `p` along the normal `n`: 1 − 3·strength·Σ (h_i − d(p + n·h_i))·0.95^i, clamped to [0, 1]
/// (1 where the scene has none).
#[inline(always)]
pub fn occlusion<N: Num, S: SceneFns<N>>(rules: &Rules, scene: &S, p: V3<N>, n: V3<N>) -> N {
    let (zero, one) = (N::lit(0.0), N::lit(1.0));
    let Some(strength) = rules.ambient_occlusion else { return one };
    let [occ, _, _] = N::iterate(
        N::count(AO_SAMPLES),
        [zero, one, zero],
        |_| N::Mask::splat(true),
        |[occ, w, i]| {
            let h = N::lit(AO_START) + N::lit(AO_SPAN) * i / N::lit(f64::from(AO_SAMPLES - 1));
            [occ + (h - scene.distance(p + n * h)) * w, w * N::lit(0.95), i + one]
        },
    );
    N::min(N::max(one - N::lit(3.0 * strength) * occ, zero), one)
}

/// Light reaching `origin` from direction `l` within `limit`: 1 lit, 0 blocked, soft shadows in between. Soft
/// shadows divide by t, so they start one step out; the origin is already off the surface. Lanes outside `live`
/// take no steps.
#[inline(always)]
pub fn shadow<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    scene: &S,
    (origin, l): (V3<N>, V3<N>),
    limit: N,
    eps: N,
    live: N::Mask,
) -> N {
    let (zero, one) = (N::lit(0.0), N::lit(1.0));
    let soft = match rules.shadows {
        Shadows::Soft(k) => Some(k),
        _ => None,
    };
    let t0 = if soft.is_some() { N::lit(2.0) * eps } else { zero };
    let [_, res, _] = N::iterate(
        N::count(rules.max_steps),
        [t0, one, zero],
        |[t, _, blocked]| live & !N::lt(zero, *blocked) & N::lt(*t, limit),
        |[t, res, blocked]| {
            let running = live & !N::lt(zero, blocked) & N::lt(t, limit);
            let d = scene.distance((origin + l * t).map(|c| N::stand_in(running, c)));
            let blocked = N::lt(d, eps);
            let res = match soft {
                Some(k) => N::min(res, N::lit(k) * d / t),
                None => res,
            };
            [N::select(blocked, t, t + d), N::select(blocked, zero, res), N::select(blocked, one, zero)]
        },
    );
    match soft {
        Some(_) => res * res * (N::lit(3.0) - N::lit(2.0) * res),
        None => res,
    }
}
