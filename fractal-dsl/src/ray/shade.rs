//! Steps 4–6 of the ray program: the colour of a marched ray — at a hit its normal, material, ambient occlusion,
//! lights with their shadows and specular terms, and fog; the background on a miss; glow on both.

use super::march::March;
use super::{lit3, Light, Rules, SceneFns, View};
use super::{AO_SAMPLES, AO_SPAN, AO_START, GLOW_NORM, REFINED_NORMAL_SHARE};
use crate::number::math::{dot, length, normalize, v3, V3};
use crate::number::{Mask, Num};
use crate::Shadows;

/// A shaded ray: its linear colour (before display) and, at a hit, its normal (zero on a miss).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shaded<N> {
    pub colour: V3<N>,
    pub normal: V3<N>,
}

/// Steps 4–6 for the ray (ro, rd) after its march `m`.
#[inline(always)]
pub fn shade<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    view: &View<N>,
    scene: &S,
    (ro, rd): (V3<N>, V3<N>),
    m: &March<N>,
) -> Shaded<N> {
    let hit = m.hit();
    let (t, eps) = (N::stand_in(hit, m.t), N::stand_in(hit, m.eps));
    let (colour, normal) = N::when(hit, (lit3(rules.background), V3::splat(N::lit(0.0))), |_| {
        let p = (ro + rd * t).map(|c| N::stand_in(hit, c));
        let n = scene.normal(p, normal_tap(rules, view, t, eps));
        (surface(rules, view, scene, p, n, rd, t, eps, hit), n)
    });
    let colour = match rules.glow {
        Some(g) => colour + lit3::<N>(g) * N::min(m.glow / N::lit(GLOW_NORM), N::lit(1.0)),
        None => colour,
    };
    Shaded { colour, normal }
}

/// Step 4's tap of the normal at a hit at ray distance `t` with epsilon `eps`.
#[inline(always)]
pub fn normal_tap<N: Num>(rules: &Rules, view: &View<N>, t: N, eps: N) -> N {
    match rules.normal_epsilon {
        Some(k) => N::lit(k) * view.footprint * t,
        None if rules.refine.is_some() => eps * N::lit(REFINED_NORMAL_SHARE),
        None => eps,
    }
}

/// The tetrahedron of offsets the normal samples the distance at.
#[inline(always)]
pub fn tetrahedron<N: Num>() -> [V3<N>; 4] {
    let (one, neg) = (N::lit(1.0), N::lit(-1.0));
    [v3(one, neg, neg), v3(neg, neg, one), v3(neg, one, neg), v3(one, one, one)]
}

/// Step 4's normal at `p`: the normalised tetrahedral gradient of the distance, taps `h` apart (a flat gradient has
/// no direction and gives +y).
#[inline(always)]
pub fn normal<N: Num, S: SceneFns<N>>(scene: &S, p: V3<N>, h: N) -> V3<N> {
    let mut gradient = V3::splat(N::lit(0.0));
    for k in tetrahedron::<N>() {
        gradient = gradient + k * scene.distance(p + k * h);
    }
    let len = length(gradient);
    let up = v3(N::lit(0.0), N::lit(1.0), N::lit(0.0));
    let found = N::lt(N::lit(0.0), len);
    let unit = gradient / len;
    v3(N::select(found, unit.x, up.x), N::select(found, unit.y, up.y), N::select(found, unit.z, up.z))
}

/// The colour of the surface at `p` (normal `n`, distance `t` along `rd`, hit epsilon `eps`): ambient light times
/// occlusion, then per light its diffuse and specular terms times its shadow, then fog. `live`: the lanes whose
/// surface this is (shadow rays march only for them).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn surface<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    view: &View<N>,
    scene: &S,
    p: V3<N>,
    n: V3<N>,
    rd: V3<N>,
    t: N,
    eps: N,
    live: N::Mask,
) -> V3<N> {
    let (zero, one) = (N::lit(0.0), N::lit(1.0));
    let ao = if rules.ambient_occlusion.is_some() { scene.occlusion(rules, p, n) } else { one };
    let m = scene.sample(p, rd * t);
    let mut colour = m.albedo * (m.ambient * ao);
    for light in &view.lights {
        let (l, radiance, limit) = light_at(rules, light, p);
        let ndl = N::max(dot(n, l), zero);
        let facing = N::lt(zero, ndl);
        let shadow = if rules.shadows == Shadows::None {
            one
        } else {
            N::when(facing, one, |_| scene.shadow(rules, (p + n * (N::lit(2.0) * eps), l), limit, eps, live & facing))
        };
        colour = colour + m.albedo * (m.diffuse * ndl) * radiance * shadow;
        if rules.specular {
            let h = normalize(l - rd);
            let highlight = N::pow(N::max(dot(n, h), zero), m.shininess);
            colour = colour + radiance * (m.specular * highlight) * shadow;
        }
    }
    if let Some((fog, density)) = rules.fog {
        let f = one - N::exp2(N::lit(-density * std::f64::consts::LOG2_E) * t);
        colour = colour + (lit3::<N>(fog) - colour) * f;
    }
    colour
}

/// A light's direction from `p`, its radiance there and how far a shadow ray goes towards it.
#[inline(always)]
pub fn light_at<N: Num>(rules: &Rules, light: &Light<N>, p: V3<N>) -> (V3<N>, V3<N>, N) {
    match *light {
        Light::Directional { direction, radiance } => (direction, radiance, N::lit(rules.max_distance)),
        Light::Point { position, radiance } => {
            let to_light = position - p;
            let distance = length(to_light);
            (to_light / distance, radiance / (distance * distance), distance)
        }
    }
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

/// Step 7 before packing: the linear colour clamped to [0, 1] and encoded with the scene's gamma.
#[inline(always)]
pub fn display<N: Num>(rules: &Rules, colour: V3<N>) -> V3<N> {
    let (zero, one) = (N::lit(0.0), N::lit(1.0));
    let clamped = colour.map(|c| N::min(N::max(c, zero), one));
    if rules.gamma == 2.0 {
        clamped.map(N::sqrt)
    } else if rules.gamma == 1.0 {
        clamped
    } else {
        let e = N::lit(1.0 / rules.gamma);
        clamped.map(|c| N::pow(c, e))
    }
}
