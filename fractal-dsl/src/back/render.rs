//! The render algorithm every renderer follows — the OpenCL and WGSL `render` kernels (spelled by the writers) and
//! the CPU renderer in fractal-runtime — and the constants they share, so the three draw the same image.
//!
//! Per pixel (x, y) of a w×h image, with the [`super::FrameLayout`] uniforms:
//! 1. **Ray.** u = (2(x + 0.5) − w)/h, v = −(2(y + 0.5) − h)/h; ro = origin; rd = normalize(forward + u·right + v·up).
//! 2. **Clip to the scene bound** (only when the scene is bounded): slab test against the scene's AABB, with each rd
//!    component of magnitude below [`MIN_DIRECTION`] replaced by ±MIN_DIRECTION, + for components ≥ 0 including −0
//!    (keeps fast-math free of Inf);
//!    t_near = max(entry, 0), t_far = min(exit, max_distance); a ray that misses (t_near > t_far) is background.
//!    Unbounded scenes march from 0 to max_distance.
//! 3. **March.** t = t_near; for step in 0..max_steps: p = ro + rd·t; d = scene_de(p);
//!    eps = fixed ε, or k·footprint·t for a pixel ε; eps = max(eps, [`T_SPACING`]·t) so a far hit never asks for more
//!    precision than t has; hit if d < eps; otherwise (glow only) glow += 1/(1 + [`GLOW_FALLOFF`]·d²); t += d;
//!    stop when t > t_far. Because d ≥ eps ≥ T_SPACING·t, every step moves t by at least 4 ulps: no stalls far away.
//!    With over-relaxation ω > 1 (the scene's `over_relaxation`; Keinert et al. 2014) the step is a `stride`, with
//!    `previous` = |d| of the last point, both from 0: if ω > 1 and |d| + previous < stride (the unbounding spheres
//!    do not overlap), stride = stride − ω·stride and ω = 1, and no hit test; otherwise the hit test as above, then
//!    stride = d·ω; then previous = |d|, glow as above, t += stride. ω = 1 is the plain march exactly.
//!    Scenes refined by sign (3b) keep each step's point as the last sample (t_last, d_last), first (t_near, 0).
//!    **3b. Sign refinement** ([`crate::analyse::sign_refinement`]): scenes that displace a surface and hold no
//!    fractal, and scenes with `membership_hits`. A displaced distance is divided by the displacement's slope bound
//!    k, so d < eps may be k·eps/sin(grazing angle) short of the surface, or above a crest the ray passes over; its
//!    sign is exact. An escape-time estimate can be far below the distance to its set (a hundredth of it beside the
//!    power-2 Mandelbulb), and its sign is the set's membership. So d < eps is a hit only where d ≤ 0; at
//!    0 < d < eps the step is a sign step. Displacement: eps, or where d_last > d [`PROBE_SHARE`] of the distance to
//!    the zero of the line through the last two samples, d·(t − t_last)/(d_last − d), if that is longer; at most
//!    [`PROBE_REACH`]·eps. Membership: [`MEMBERSHIP_STEP`]·eps. With over-relaxation, ω = 1 from then on. At a
//!    hit with d_last > 0 (d ≤ 0 < d_last brackets the crossing): [`REFINE_STEPS`] steps of the Illinois false
//!    position on (a, f_a) = (t_last, d_last), (b, f_b) = (t, d) — m = a + (b − a)·f_a/(f_a − f_b); where
//!    scene_de(m) ≤ 0, b = m, and f_a halves if b moved last time too; else a = m, and f_b halves if a moved last
//!    time too — then t = the final bracket's false position.
//! 4. **Hit shading.** p = ro + rd·t; n = normalize(Σ k_i·scene_de(p + k_i·h)) over the tetrahedron
//!    k = (1,−1,−1), (−1,−1,1), (−1,1,−1), (1,1,1) (a zero sum gives the normal +y), h = k_n·footprint·t with the
//!    scene's `normal_pixel_epsilon` k_n, else eps, or in a scene refined by sign (3b) [`REFINED_NORMAL_SHARE`]·eps;
//!    m = scene_sample(p).
//!    Ambient occlusion (when enabled, strength s): occ = Σ_{i<5} (h_i − scene_de(p + n·h_i))·0.95^i with
//!    h_i = [`AO_START`] + [`AO_SPAN`]·i/4; ao = clamp(1 − 3·s·occ, 0, 1); otherwise ao = 1.
//!    colour = albedo·ambient·ao; then per light: L and radiance (directional: the slot's unit direction and colour,
//!    distance limit max_distance; point: L = normalize(pos − p), radiance = colour/|pos − p|², limit |pos − p|);
//!    ndl = max(dot(n, L), 0); shadow = 1, or (when shadows are on and ndl > 0) a march from p + n·2·eps towards the
//!    light up to the limit, max_steps steps: hard: t from 0, 0 at the first d < eps; soft(k): res = min(res, k·d/t) with t
//!    starting at 2·eps, 0 at d < eps, then shadow = res²(3 − 2·res); colour += albedo·diffuse·ndl·radiance·shadow;
//!    specular (only if some material has specular ≠ 0): h = normalize(L − rd),
//!    colour += specular·max(dot(n, h), 0)^shininess·radiance·shadow.
//!    Fog (when enabled): colour = mix(colour, fog, 1 − exp(−density·t)).
//! 5. **Miss:** colour = background.
//! 6. **Glow** (when enabled): colour += glow·min(glow/[`GLOW_NORM`], 1), for hits and misses alike.
//! 7. **Output:** colour = clamp(colour, 0, 1)^(1/gamma) (sqrt when gamma = 2, nothing when 1); packed RGBA8 with
//!    each channel u32(c·255 + 0.5), R in the low byte, A = 255.

/// Relative float spacing of t that the hit epsilon never goes below: 4 ulps of an f32 (2⁻²¹ ≈ 4.77e-7).
pub const T_SPACING: f64 = 4.76837158203125e-7;
/// Smallest ray-direction component used by the bound slab test.
pub const MIN_DIRECTION: f64 = 1e-20;
/// Glow accumulation fall-off with distance.
pub const GLOW_FALLOFF: f64 = 256.0;
/// Glow accumulated over this many near misses saturates.
pub const GLOW_NORM: f64 = 32.0;
/// Ambient occlusion: distance of the first sample along the normal.
pub const AO_START: f64 = 0.01;
/// Ambient occlusion: distance from the first to the last sample.
pub const AO_SPAN: f64 = 0.12;
/// Ambient occlusion samples.
pub const AO_SAMPLES: u32 = 5;
/// Sign refinement: share of the extrapolated distance to the crossing a sign step takes (the line through the last
/// two samples is a guess; going half way, a bump the line does not foresee is more likely sampled than passed).
pub const PROBE_SHARE: f64 = 0.5;
/// Sign refinement: the longest sign step, in hit epsilons.
pub const PROBE_REACH: f64 = 16.0;
/// Sign refinement of membership hits: the sign step, in hit epsilons. On `mandelbulb_powers` (192×108, CPU, 32
/// iterations, half-pixel epsilon) a step of the epsilon passed through 0.17 % of the pixels' sets and missed 0.72 %;
/// half of it, 0.03 % and 0.41 % at 1.25× the evaluations (`fractal accuracy`).
pub const MEMBERSHIP_STEP: f64 = 0.5;
/// Sign refinement: Illinois steps on a bracketed crossing.
pub const REFINE_STEPS: u32 = 6;
/// Sign refinement: the normal's tap in hit epsilons. The hit is on the surface, and a tap an epsilon away reaches
/// across a crease onto a surface whose distance has another scale (the exact ocean beside land divided by its slope
/// bound), which turned the planet's coastal normals by up to 29°.
pub const REFINED_NORMAL_SHARE: f64 = 0.125;
