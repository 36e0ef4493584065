//! Steps 4–6 of the ray program: the colour of a marched ray — at a hit its normal, material, ambient occlusion,
//! lights with their shadows and specular terms, and fog; the background on a miss; glow on both.

use super::march::March;
use super::rules::{lit3, Light, Rules, View, GLOW_NORM, REFINED_NORMAL_SHARE};
use super::scene::SceneFns;
use crate::number::math::{dot, length, normalize, V3};
use crate::number::Num;
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
        (surface(rules, view, scene, p, n, (ro, rd), t, eps, hit), n)
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

/// The colour of the surface at `p` (normal `n`, distance `t` along the ray (ro, rd), hit epsilon `eps`): ambient
/// light times occlusion, then per light its diffuse and specular terms times its shadow, then fog. `live`: the
/// lanes whose surface this is (shadow rays march only for them).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn surface<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    view: &View<N>,
    scene: &S,
    p: V3<N>,
    n: V3<N>,
    (ro, rd): (V3<N>, V3<N>),
    t: N,
    eps: N,
    live: N::Mask,
) -> V3<N> {
    let (zero, one) = (N::lit(0.0), N::lit(1.0));
    let ao = if rules.ambient_occlusion.is_some() { scene.occlusion(rules, p, n) } else { one };
    // The point relative to the camera, to the precision of t: a ray from a lens point starts off the camera.
    let offset = if rules.lens.is_some() { (ro - view.origin) + rd * t } else { rd * t };
    let m = scene.sample(p, offset);
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

/// The linear colour whose sRGB encoding is [`display`]'s: what an engine writes into an sRGB target (or hands its
/// tonemapper) so that the pixel shows as the viewer's does, whatever the scene's gamma.
#[inline(always)]
pub fn display_linear<N: Num>(rules: &Rules, colour: V3<N>) -> V3<N> {
    display(rules, colour).map(|c| {
        let low = c / N::lit(12.92);
        let high = N::pow((c + N::lit(0.055)) / N::lit(1.055), N::lit(2.4));
        N::select(N::le(c, N::lit(0.04045)), low, high)
    })
}
