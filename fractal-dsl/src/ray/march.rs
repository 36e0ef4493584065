//! Steps 2–3b of the ray program: the bound clip, the march state and its step (plain or over-relaxed sphere
//! tracing, glow, sign steps and the refined hit). The step is its own function so a renderer that refills packet
//! lanes (the CPU's) runs exactly the steps [`march`] runs.

use super::rules::{Rules, View, GLOW_FALLOFF, MEMBERSHIP_STEP, MIN_DIRECTION, PROBE_REACH, PROBE_SHARE};
use super::rules::{REFINE_STEPS, T_SPACING};
use super::scene::SceneFns;
use crate::analyse::SignRefinement;
use crate::number::lanes::F32x8;
use crate::number::math::V3;
use crate::number::{Carry, Mask, Num};
use crate::HitEpsilon;

/// A march in progress, or its end. Truth values are numbers (0 or 1) so the state is one [`Carry`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct March<N> {
    pub t: N,
    /// Where the clipped ray ends.
    pub t_far: N,
    /// The hit epsilon at the last point.
    pub eps: N,
    /// The distance at the last point.
    pub d: N,
    /// The sample before the last point: (t_last, d_last), for the sign refinement.
    pub last_t: N,
    pub last_d: N,
    /// Distance evaluations of the march itself (not counting the refinement's).
    pub steps: N,
    /// 1 once the march hit.
    pub hit: N,
    pub glow: N,
    /// Over-relaxation: ω, |d| at the last point and the last step.
    pub omega: N,
    pub previous: N,
    pub stride: N,
}

/// The state's numbers, named once: [`Carry`] over them, and lane access in packets.
macro_rules! march_numbers {
    ($($field:ident),*) => {
        impl<N: Num> Carry<N> for March<N> {
            #[inline(always)]
            fn map_nums(self, f: &mut impl FnMut(N) -> N) -> Self {
                March { $($field: f(self.$field)),* }
            }
            #[inline(always)]
            fn zip_nums(self, o: Self, f: &mut impl FnMut(N, N) -> N) -> Self {
                March { $($field: f(self.$field, o.$field)),* }
            }
        }

        impl<N: Num> March<N> {
            /// A state with every number `v`.
            pub fn splat(v: N) -> March<N> {
                March { $($field: v),* }
            }
        }

        impl March<F32x8> {
            /// The march in lane `i`.
            #[inline(always)]
            pub fn lane(&self, i: usize) -> March<f32> {
                March { $($field: self.$field.0[i]),* }
            }
            /// Sets lane `i` to `m`.
            #[inline(always)]
            pub fn set_lane(&mut self, i: usize, m: &March<f32>) {
                $(self.$field.0[i] = m.$field;)*
            }
        }
    };
}

march_numbers!(t, t_far, eps, d, last_t, last_d, steps, hit, glow, omega, previous, stride);

impl<N: Num> March<N> {
    /// Whether the march hit.
    #[inline(always)]
    pub fn hit(&self) -> N::Mask {
        N::lt(N::lit(0.0), self.hit)
    }
    /// Whether the march goes on: no hit yet and t within the clipped ray (a NaN t stops it). The step count is
    /// the caller's loop bound.
    #[inline(always)]
    pub fn running(&self) -> N::Mask {
        !self.hit() & N::le(self.t, self.t_far)
    }
    /// Whether the march used all of `max_steps` without hitting or leaving the ray.
    #[inline(always)]
    pub fn out_of_steps(&self, max_steps: u32) -> N::Mask {
        !self.hit() & N::le(N::lit(f64::from(max_steps)), self.steps) & N::le(self.t, self.t_far)
    }
}

/// Step 2: the part of the ray (ro, rd) to march, inside the bound and before max_distance: (t_near, t_far, whether
/// the ray enters). An unbounded scene marches from 0. `ro` is relative to `anchor` ([`View`]).
#[inline(always)]
pub fn clip<N: Num>(rules: &Rules, anchor: V3<N>, ro: V3<N>, rd: V3<N>) -> (N, N, N::Mask) {
    let (zero, max_distance) = (N::lit(0.0), N::lit(rules.max_distance));
    let Some(b) = rules.bound else {
        return (zero, max_distance, N::Mask::splat(true));
    };
    let min_dir = N::lit(MIN_DIRECTION);
    // Each direction component kept at least MIN_DIRECTION from 0, with its sign (+ for −0).
    let safe = rd.map(|d| {
        let m = N::max(N::abs(d), min_dir);
        N::select(N::le(zero, d), m, -m)
    });
    let t0 = ((super::lit3::<N>(b.min) - anchor) - ro) / safe;
    let t1 = ((super::lit3::<N>(b.max) - anchor) - ro) / safe;
    let entry = t0.zip(t1, N::min).max_element();
    let exit = t0.zip(t1, N::max).min_element();
    let t_near = N::max(entry, zero);
    let t_far = N::min(exit, max_distance);
    (t_near, t_far, N::le(t_near, t_far))
}

/// The march's first state on a ray clipped to [t_near, t_far].
#[inline(always)]
pub fn start<N: Num>(rules: &Rules, t_near: N, t_far: N) -> March<N> {
    let zero = N::lit(0.0);
    March {
        t: t_near,
        t_far,
        eps: zero,
        d: zero,
        last_t: t_near,
        last_d: zero,
        steps: zero,
        hit: zero,
        glow: zero,
        omega: N::lit(rules.over_relaxation),
        previous: zero,
        stride: zero,
    }
}

/// The point the march samples next.
#[inline(always)]
pub fn point<N: Num>(ro: V3<N>, rd: V3<N>, m: &March<N>) -> V3<N> {
    ro + rd * m.t
}

/// The hit epsilon at ray distance `t`.
#[inline(always)]
pub fn hit_epsilon<N: Num>(rules: &Rules, view: &View<N>, t: N) -> N {
    let eps = match rules.epsilon {
        HitEpsilon::Fixed(e) => N::lit(e),
        HitEpsilon::Pixel(k) => N::lit(k) * view.footprint * t,
    };
    N::max(eps, N::lit(T_SPACING) * t)
}

/// Step 3 with `d`, the distance at [`point`]: the hit test, the step (over-relaxed, or a sign step near the surface
/// of a scene refined by sign) and glow. A march that ended is then [`settle`]d.
#[inline(always)]
pub fn advance<N: Num>(rules: &Rules, view: &View<N>, m: March<N>, d: N) -> March<N> {
    let (zero, one) = (N::lit(0.0), N::lit(1.0));
    let t = m.t;
    let eps = hit_epsilon(rules, view, t);
    let near = N::lt(d, eps);
    // Step 3b: near the surface of a scene refined by sign, a hit is a crossing and the step a sign step.
    let (hit_near, near_step) = match rules.refine {
        Some(rule) => (N::le(d, zero), sign_step(rule, d, eps, t, (m.last_t, m.last_d))),
        None => (near, d),
    };
    let mut next = m;
    let (hit, step) = if rules.over_relaxation > 1.0 {
        // The unbounding spheres of this point and the last do not overlap: the relaxed step may have passed the
        // surface, so take back its excess and go on with plain steps (no hit test at this point).
        let abs_d = N::abs(d);
        let overshot = N::lt(one, m.omega) & N::lt(abs_d + m.previous, m.stride);
        let near = !overshot & near;
        let stride = N::select(overshot, m.stride - m.omega * m.stride, N::select(near, near_step, d * m.omega));
        next.omega = N::select(overshot | near, one, m.omega);
        next.previous = abs_d;
        next.stride = stride;
        (near & hit_near, stride)
    } else {
        (near & hit_near, N::select(near, near_step, d))
    };
    if rules.glow.is_some() {
        next.glow = N::select(hit, m.glow, m.glow + one / (one + N::lit(GLOW_FALLOFF) * d * d));
    }
    next.t = N::select(hit, t, t + step);
    next.last_t = N::select(hit, m.last_t, t);
    next.last_d = N::select(hit, m.last_d, d);
    next.d = d;
    next.eps = eps;
    next.steps = m.steps + one;
    next.hit = N::select(hit, one, zero);
    next
}

/// Step 3b's end of a march, in a scene refined by sign: a hit with d ≤ 0 < d_last brackets the crossing, and moves
/// onto it.
#[inline(always)]
pub fn settle<N: Num, S: SceneFns<N>>(rules: &Rules, scene: &S, (ro, rd): (V3<N>, V3<N>), m: March<N>) -> March<N> {
    if rules.refine.is_none() {
        return m;
    }
    let bracketed = m.hit() & N::lt(N::lit(0.0), m.last_d);
    let t = N::when(bracketed, m.t, |t| refined(scene, (ro, rd), (m.last_t, m.last_d), (t, m.d)));
    March { t, ..m }
}

/// Steps 2–3 along the unit ray (ro, rd): the march's end, and whether the ray entered the bound at all.
#[inline(always)]
pub fn march<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    view: &View<N>,
    scene: &S,
    ro: V3<N>,
    rd: V3<N>,
) -> (March<N>, N::Mask) {
    let (t_near, t_far, enters) = clip(rules, view.anchor, ro, rd);
    let end = N::iterate(
        N::count(rules.max_steps),
        start(rules, t_near, t_far),
        |m| m.running(),
        |m| advance(rules, view, m, scene.distance(point(ro, rd, &m))),
    );
    (settle(rules, scene, (ro, rd), end), enters)
}

/// Step 3b's sign step at 0 < d < eps. Displacement: eps, or a share of the distance to the zero of the line through
/// the last sample and this one where the ray nears the surface, up to the reach. Membership: a share of eps.
#[inline(always)]
fn sign_step<N: Num>(rule: SignRefinement, d: N, eps: N, t: N, (last_t, last_d): (N, N)) -> N {
    if rule == SignRefinement::Membership {
        return N::lit(MEMBERSHIP_STEP) * eps;
    }
    let toward = N::lit(PROBE_SHARE) * d * (t - last_t) / (last_d - d);
    let step = N::select(N::lt(d, last_d), N::max(eps, toward), eps);
    N::min(step, N::lit(PROBE_REACH) * eps)
}

/// Step 3b's refinement of a crossing bracketed by (a, f_a) with f_a > 0 and (b, f_b) with f_b ≤ 0:
/// [`REFINE_STEPS`] steps of the Illinois false position (an end kept twice in a row has its value halved, so both
/// ends move), then the final bracket's false position.
#[inline(always)]
fn refined<N: Num, S: SceneFns<N>>(scene: &S, (ro, rd): (V3<N>, V3<N>), a: (N, N), b: (N, N)) -> N {
    let (zero, one, half) = (N::lit(0.0), N::lit(1.0), N::lit(0.5));
    let [a, fa, b, fb, _] = N::iterate(
        N::count(REFINE_STEPS),
        [a.0, a.1, b.0, b.1, zero],
        |_| N::Mask::splat(true),
        |[a, fa, b, fb, side]| {
            let m = a + (b - a) * (fa / (fa - fb));
            let fm = scene.distance(ro + rd * m);
            let inside = N::le(fm, zero);
            [
                N::select(inside, a, m),
                N::select(inside, N::select(N::lt(side, zero), fa * half, fa), fm),
                N::select(inside, m, b),
                N::select(inside, fm, N::select(N::lt(zero, side), fb * half, fb)),
                N::select(inside, -one, one),
            ]
        },
    );
    a + (b - a) * (fa / (fa - fb))
}
