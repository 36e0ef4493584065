//! What the ray program reads besides the scene: its constants, the scene's settings as [`Rules`] and a frame's camera
//! and lights as a [`View`] (with step 1, the camera ray).

use crate::analyse::{self, fold::fold_node, Aabb, SignRefinement};
use crate::ir::{Camera, CameraPlacement};
use crate::number::math::{normalize, V3};
use crate::number::Num;
use crate::{HitEpsilon, RenderSettings, Scene, Shadows};

/// Relative float spacing of t that the hit epsilon never goes below: 4 ulps of an f32 (2⁻²¹ ≈ 4.77e-7), so every
/// step moves t and a far hit never asks for more precision than t has.
pub const T_SPACING: f64 = 4.76837158203125e-7;
/// Smallest ray-direction component used by the bound slab test (keeps fast-math free of Inf).
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
/// Sign refinement of membership hits: the sign step, in hit epsilons. Half, not a whole one: whole steps passed
/// through more of the sets and missed more of them (measured: `docs/settings.md`, “The sign step of membership hits”).
pub const MEMBERSHIP_STEP: f64 = 0.5;
/// Sign refinement: Illinois steps on a bracketed crossing.
pub const REFINE_STEPS: u32 = 6;
/// Sign refinement: the normal's tap in hit epsilons. The hit is on the surface, and a tap an epsilon away reaches
/// across a crease onto a surface whose distance has another scale (an exact ocean beside land divided by its slope
/// bound).
pub const REFINED_NORMAL_SHARE: f64 = 0.125;

/// A scene's settings as the ray program reads them: fixed for a compiled scene, so a disabled effect is code the
/// program does not run (and a traced kernel does not contain).
#[derive(Clone, Debug, PartialEq)]
pub struct Rules {
    pub max_steps: u32,
    pub max_distance: f64,
    pub epsilon: HitEpsilon,
    /// Over-relaxation ω (1: plain sphere tracing).
    pub over_relaxation: f64,
    /// Whether hits are refined by the distance's sign, and why.
    pub refine: Option<SignRefinement>,
    /// The normal's taps in pixel footprints at the hit, where the scene sets them apart from the hit epsilon.
    pub normal_epsilon: Option<f64>,
    pub shadows: Shadows,
    /// Ambient occlusion strength.
    pub ambient_occlusion: Option<f64>,
    pub glow: Option<[f64; 3]>,
    /// Fog colour and density.
    pub fog: Option<([f64; 3], f64)>,
    pub background: [f64; 3],
    pub gamma: f64,
    /// Whether some material can have a specular term.
    pub specular: bool,
    /// The box rays are clipped to (`None`: march from 0 to max_distance).
    pub bound: Option<Aabb>,
    /// How many samples a pixel takes.
    pub sampling: Sampling,
    /// The camera's thin lens, if it has one.
    pub lens: Option<Lens>,
}

impl Rules {
    /// The rules of `scene`, with its bound.
    pub fn of(scene: &Scene) -> Rules {
        let folded = fold_node(&scene.root);
        Rules::with_bound(scene, analyse::bound(&folded))
    }

    /// The rules of `scene` with rays clipped to `bound` instead of the scene's own.
    pub fn with_bound(scene: &Scene, bound: Option<Aabb>) -> Rules {
        let folded = fold_node(&scene.root);
        let s = &scene.settings;
        let analysed = (analyse::sign_refinement(&folded, s), analyse::has_specular(&folded));
        Rules::from_settings(s, analysed, bound, Lens::of(&scene.camera))
    }

    /// The rules of a scene's `settings`, with the analyses of its tree (how its hits are refined by sign, whether a
    /// material can have a specular term), the box rays are clipped to and its camera's lens.
    pub fn from_settings(
        s: &RenderSettings,
        (refine, specular): (Option<SignRefinement>, bool),
        bound: Option<Aabb>,
        lens: Option<Lens>,
    ) -> Rules {
        Rules {
            max_steps: s.max_steps,
            max_distance: s.max_distance,
            epsilon: s.epsilon,
            over_relaxation: s.over_relaxation,
            refine,
            normal_epsilon: s.normal_epsilon,
            shadows: s.shadows,
            ambient_occlusion: s.ambient_occlusion,
            glow: s.glow,
            fog: s.fog.as_ref().map(|f| (f.color, f.density)),
            background: s.background,
            gamma: s.gamma,
            specular,
            bound,
            sampling: Sampling { samples: s.samples, threshold: s.sample_threshold },
            lens,
        }
    }
}

/// A light as a frame holds it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light<N> {
    /// `direction`: the unit vector towards the light.
    Directional {
        direction: V3<N>,
        radiance: V3<N>,
    },
    Point {
        position: V3<N>,
        radiance: V3<N>,
    },
}

/// A frame's camera and lights: the camera's position and its right, up and forward axes (scaled by the field of
/// view), the image size, the pixel footprint per unit distance along a ray, and the lights. Positions (the camera's,
/// point lights', every point the program computes) are relative to `anchor`, which the scene functions add back
/// ([`crate::eval::Env::anchor`]): a scene far from the origin seen from nearby keeps the precision it has at the
/// origin.
#[derive(Clone, Debug, PartialEq)]
pub struct View<N> {
    pub anchor: V3<N>,
    pub origin: V3<N>,
    pub right: V3<N>,
    pub up: V3<N>,
    pub forward: V3<N>,
    pub width: N,
    pub height: N,
    pub footprint: N,
    pub lights: Vec<Light<N>>,
}

impl<N: Num> View<N> {
    /// Step 1: the ray through the point (px, py) of the image, in pixels from the top left corner (a pixel's centre
    /// is at (x + 0.5, y + 0.5)).
    #[inline(always)]
    pub fn ray(&self, px: N, py: N) -> (V3<N>, V3<N>) {
        let two = N::lit(2.0);
        let u = (two * px - self.width) / self.height;
        let v = -(two * py - self.height) / self.height;
        (self.origin, normalize(self.forward + self.right * u + self.up * v))
    }
}

/// A constant 3-vector in `N`.
#[inline(always)]
pub(crate) fn lit3<N: Num>(c: [f64; 3]) -> V3<N> {
    V3 { x: N::lit(c[0]), y: N::lit(c[1]), z: N::lit(c[2]) }
}

/// How many samples a pixel may take and when it stops: the scene's `samples` and `sample_threshold`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sampling {
    /// The most samples (1: the centre ray alone).
    pub samples: u32,
    /// The standard error of the mean display luma under which a pixel stops.
    pub threshold: f64,
}

/// A thin lens: its radius and the distance along the view direction it holds in focus.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    pub aperture: f64,
    pub focus: f64,
}

impl Lens {
    /// The lens of `camera`, if it has an aperture. Its default focus is the distance from the camera to its target at
    /// time 0 (the first key's, on a path), with every parameter at its default.
    pub fn of(camera: &Camera) -> Option<Lens> {
        if camera.aperture <= 0.0 {
            return None;
        }
        let focus = camera.focus.unwrap_or_else(|| {
            let (from, to) = match &camera.placement {
                CameraPlacement::LookAt { position, target } => {
                    let at = |v: &crate::ir::Vec3Expr| v.eval(0.0, &|p| p.default);
                    (at(position), at(target))
                }
                CameraPlacement::Path { keys, .. } => {
                    keys.first().map_or(([0.0; 3], [1.0; 3]), |k| (k.position, k.target))
                }
            };
            (0..3).map(|i| (to[i] - from[i]) * (to[i] - from[i])).sum::<f64>().sqrt()
        });
        Some(Lens { aperture: camera.aperture, focus })
    }
}
