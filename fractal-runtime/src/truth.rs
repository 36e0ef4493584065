//! The ground truth renders are measured against, from a reference that never reads a distance estimate.
//!
//! **Membership.** A point is in the scene when the scene walker, run in f64 with every fractal replaced by its
//! family's membership test (the set's own escape-time or IFS iteration, [`member`]), is ≤ 0. Exact primitives keep
//! their exact distances, so scenes of them alone are their exact f64 surfaces.
//!
//! **Depth.** A pixel's true hit is the first outside → inside crossing along the ray through its centre, from the
//! camera to the scene's `max_distance` (the scene bound is not used: a bound that clips is an error to find). The
//! march takes steps of [`TruthSettings::step_footprints`] pixel footprints at the ray's distance (or the exact
//! distance where no fractal is near, or the distance to a ball or box that must hold a fractal) and bisects the
//! crossing to 2⁻⁴⁰ of a step. What it can miss: a feature thinner than one step along the ray
//! ([`DEFAULT_STEP_FOOTPRINTS`]), far below what a pixel resolves.
//!
//! **Normal.** Where the hit lies on an exact distance (a primitive, or CSG of them, away from any fractal), the
//! gradient of that distance at the hit, by f64 central differences: the exact normal. Elsewhere from the true
//! surface: four neighbouring rays half a pixel to each side find their crossings within [`NORMAL_WINDOW`] footprints
//! of the centre's, and the normal is the cross product of the surface's differences across x and y (central where
//! both sides continue the surface, one-sided at a silhouette).
//!
//! **Rough pixels.** A pixel has one normal at its scale only where the surface keeps it across the pixel; elsewhere
//! the pixel is *rough* and no normal error is measured there, since any one normal a renderer picks is as right as
//! another. On an exact surface: the exact gradient half a footprint away along each axis, and at the crossings of the
//! eight rays half a pixel away (axes and diagonals), stays within [`ROUGH_DEGREES`] of the centre's (an edge, the lip
//! of a hole, a silhouette seen nearly edge-on fail it). Elsewhere: the surface bends by more than [`ROUGH_DEGREES`]
//! from one side of the centre to the other (a crease through the pixel), or ends on one side (a silhouette, the lip of
//! a hole), or that normal and the same one from rays a quarter pixel away differ by more than that (a fractal's
//! detail below a pixel), or a ray half a pixel away on a diagonal finds no surface within [`ROUGH_DEGREES`] of the
//! centre's plane (a hole or a rim between the axis neighbours).
//!
//! **Colour.** The true hit shaded by the render algorithm ([`fractal_render::backend::cpu`]) in f64 with the true
//! normal; materials, shadows and occlusion are what the algorithm defines them to be (from the f64 scene distance).
//! Glow is left out: it is a sum along the march.
//!
//! **Iterations.** A finite-iteration membership test draws a fatter set than the limit an escape-time estimator
//! approximates; [`TruthSettings::iteration_factor`] multiplies the iteration count of every fractal whose family
//! approaches a limit ([`fractal_dsl::ir::fractal::Membership::approaches_limit`]). IFS level counts are the shape and
//! stay.

pub mod cone;
pub mod estimate;
pub mod image;
pub mod member;
mod ray;

use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::Env;
use fractal_dsl::number::math::{v3, V3};
use fractal_dsl::Scene;
use rayon::prelude::*;
use std::sync::OnceLock;

use crate::quality::with_iterations_scaled;
use fractal_render::backend::cpu::View;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use member::{Member, SceneMembership};
use ray::TruthRay;

/// Half-width of the depth window, in footprints, in which a neighbouring ray's crossing still belongs to the same
/// surface for the normal.
pub const NORMAL_WINDOW: f64 = 4.0;
/// Offset of the normal's neighbouring rays, in pixels.
pub const NORMAL_OFFSET: f64 = 0.5;
/// Largest angle between the normals from neighbours [`NORMAL_OFFSET`] and half that away for which the true surface
/// still counts as smooth at the pixel's scale.
pub const ROUGH_DEGREES: f64 = 10.0;
/// Directions of a pixel's neighbouring rays, in units of the offset: the axes, then the diagonals.
const NEIGHBOURS: [(f64, f64); 8] =
    [(-1.0, 0.0), (1.0, 0.0), (0.0, -1.0), (0.0, 1.0), (-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)];
/// Below this distance the truth march steps as if it were this far (scene units), so it never crawls at the camera;
/// nearer where the scene is nearer (see [`NEAR_SHARE`]).
pub const NEAR: f64 = 0.1;
/// Below a ray distance of this share of the scene's f64 distance estimate at the camera (where that is under
/// [`NEAR`]) the truth march steps as if it were that far: a camera 1e-9 from a surface is stepped at the surface's
/// footprints. Only the step's fineness reads the estimate, never where a crossing is.
pub const NEAR_SHARE: f64 = 0.25;

/// The truth march's default step in footprints. Halving it from 1/160 to 1/320 on the built-in `mandelbulb` at
/// 192×108 still moves its false hits from 0.26 % to 0.21 % (thin sheets of the 8-iteration set that coarser steps
/// miss); 1/256 is the compromise of time (≈ 20 s there on two cores) against that.
pub const DEFAULT_STEP_FOOTPRINTS: f64 = 1.0 / 256.0;

/// How the truth is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TruthSettings {
    /// March step in pixel footprints at the ray's distance.
    pub step_footprints: f64,
    /// Factor on the iteration count of escape-time fractals (1: the scene's own).
    pub iteration_factor: u32,
}

impl Default for TruthSettings {
    fn default() -> Self {
        TruthSettings { step_footprints: DEFAULT_STEP_FOOTPRINTS, iteration_factor: 1 }
    }
}

/// The truth at one pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TruthPixel {
    /// Ray distance of the first hit; +∞ for a miss.
    pub t: f64,
    /// The true surface's normal at the hit (facing the camera), when the neighbouring rays found the surface.
    pub normal: Option<[f64; 3]>,
    /// The surface has no single normal at this pixel's scale (see the module notes): `normal` shades the truth but
    /// is not a reference to measure a renderer's normal against.
    pub rough: bool,
    /// Linear colour of the true hit (the background for a miss).
    pub colour: [f64; 3],
}

impl TruthPixel {
    pub fn hit(&self) -> bool {
        self.t.is_finite()
    }
}

/// The truth of one frame, and the membership to answer further questions about it (pixel-cone consistency).
pub struct Truth {
    pub width: u32,
    pub height: u32,
    /// Pixel footprint per unit distance (the pixel angle).
    pub footprint: f64,
    pub settings: TruthSettings,
    /// Row-major.
    pub pixels: Vec<TruthPixel>,
    membership: SceneMembership,
    /// The scene holds no fractal: its value is a function whose zero set is the surface (an exact distance, or one
    /// divided by a displacement's slope bound), never a sign only, so its gradient is the surface's normal.
    valued: bool,
    view: View<f64>,
    /// The frame's time and parameter values, as the membership walker reads them.
    time: Member,
    params: Vec<Member>,
    /// Per pixel, once asked: whether some ray of its cone meets the scene ([`Truth::cone_sees_scene`]).
    cone_sees: Vec<OnceLock<bool>>,
    /// Per pixel, once asked: the true normals across its footprint ([`Truth::cone_normal_error`]).
    cone_normals: Vec<OnceLock<Vec<[f64; 3]>>>,
    /// Below this ray distance the march steps as if it were this far: [`NEAR`], or [`NEAR_SHARE`] of the scene's
    /// f64 distance estimate at the camera where that is less, so a camera 1e-9 from a surface is stepped at the
    /// surface's footprints. Only the step's fineness reads the estimate, never where a crossing is.
    near: f64,
}

impl Truth {
    /// Computes the truth of `scene` seen through `frame`.
    pub fn compute(scene: &Scene, frame: &Frame, settings: TruthSettings) -> Result<Truth, RenderError> {
        let scene = with_iterations_scaled(scene, settings.iteration_factor);
        let mut truth = Truth::unfilled(&scene, frame, settings)?;
        let shading = fractal_dsl::lower::tape::interpreter(&scene)?;
        let width = frame.width() as usize;
        let mut pixels = vec![
            TruthPixel { t: f64::INFINITY, normal: None, rough: false, colour: [0.0; 3] };
            width * truth.height as usize
        ];
        pixels.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
            for (x, out) in row.iter_mut().enumerate() {
                *out = truth.pixel(&shading, x as f64 + 0.5, y as f64 + 0.5);
            }
        });
        truth.pixels = pixels;
        Ok(truth)
    }

    /// Only the hit mask of [`Truth::compute`] (row-major), without the normals and colours it would discard.
    pub fn hit_mask(scene: &Scene, frame: &Frame, settings: TruthSettings) -> Result<Vec<bool>, RenderError> {
        let scene = with_iterations_scaled(scene, settings.iteration_factor);
        let truth = Truth::unfilled(&scene, frame, settings)?;
        let width = frame.width();
        Ok((0..width * frame.height())
            .into_par_iter()
            .map(|i| truth.first_hit((i % width) as f64 + 0.5, (i / width) as f64 + 0.5).is_some())
            .collect())
    }

    /// The truth of `scene` (its iterations already scaled) without its pixels.
    fn unfilled(scene: &Scene, frame: &Frame, settings: TruthSettings) -> Result<Truth, RenderError> {
        let view = View::<f64>::in_scene_coordinates(scene, frame, None)?;
        let time = Member(frame.time() as f64);
        let params: Vec<Member> = frame.params().into_iter().map(|p| Member(p as f64)).collect();
        let at_camera = {
            use fractal_dsl::eval::Evaluator;
            let values: Vec<f64> = frame.params().into_iter().map(f64::from).collect();
            let ([x, y, z], a) = (frame.camera_origin(), frame.anchor());
            let (x, y, z) = (x + a[0], y + a[1], z + a[2]);
            Interpreter::new(scene)?.distance(v3(x, y, z), &Env::new(frame.time() as f64, &values)).abs()
        };
        let near = if at_camera > 0.0 { (NEAR_SHARE * at_camera).min(NEAR) } else { NEAR };
        Ok(Truth {
            width: frame.width(),
            height: frame.height(),
            footprint: view.footprint(),
            settings,
            pixels: Vec::new(),
            membership: SceneMembership::new(scene),
            valued: !scene.root.has_fractal(),
            view,
            time,
            params,
            cone_sees: (0..frame.width() as usize * frame.height() as usize).map(|_| OnceLock::new()).collect(),
            cone_normals: (0..frame.width() as usize * frame.height() as usize).map(|_| OnceLock::new()).collect(),
            near,
        })
    }

    pub fn at(&self, x: u32, y: u32) -> &TruthPixel {
        &self.pixels[(y * self.width + x) as usize]
    }

    /// The footprint of a pixel at ray distance `t`.
    pub fn footprint_at(&self, t: f64) -> f64 {
        self.footprint * t
    }

    /// The ray through pixel (x, y)'s centre: origin (relative to the frame's anchor) and unit direction.
    pub fn centre_ray(&self, x: u32, y: u32) -> ([f64; 3], [f64; 3]) {
        let (o, d) = self.view.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
        ([o.x, o.y, o.z], [d.x, d.y, d.z])
    }

    fn with_ray<R>(&self, px: f64, py: f64, f: impl FnOnce(&TruthRay) -> R) -> R {
        let env = self.env();
        let (ro, rd) = self.view.ray(px, py);
        let ray = TruthRay {
            membership: &self.membership,
            env: &env,
            origin: [ro.x, ro.y, ro.z],
            direction: [rd.x, rd.y, rd.z],
        };
        f(&ray)
    }

    /// The first crossing of the ray through (px, py), as the truth marches it.
    fn first_hit(&self, px: f64, py: f64) -> Option<f64> {
        self.with_ray(px, py, |ray| ray.first_crossing(0.0, self.view.max_distance(), |t| self.step(t)))
    }

    /// The frame's time and parameters for the membership walker.
    fn env(&self) -> Env<'_, Member> {
        Env::new(self.time, &self.params)
    }

    /// The march step at ray distance t.
    fn step(&self, t: f64) -> f64 {
        self.settings.step_footprints * self.footprint * t.max(self.near)
    }

    fn pixel(&self, shading: &Interpreter, px: f64, py: f64) -> TruthPixel {
        let background = self.view.background();
        let miss = TruthPixel {
            t: f64::INFINITY,
            normal: None,
            rough: false,
            colour: [background.x, background.y, background.z],
        };
        let Some(t) = self.first_hit(px, py) else {
            return miss;
        };
        let (ro, rd) = self.view.ray(px, py);
        let p = ro + rd * t;
        let (normal, rough) = match self.exact_normal(p, rd, t) {
            Some(n) => (Some(n), !self.exact_smooth(px, py, p, n, t)),
            None => {
                let normal = self.normal(px, py, t, NORMAL_OFFSET);
                let finer = self.normal(px, py, t, 0.5 * NORMAL_OFFSET);
                let smooth = match (normal, finer) {
                    (Some((a, false)), Some((b, false))) => {
                        let cos = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                        cos >= ROUGH_DEGREES.to_radians().cos() && self.continues_to_corners(px, py, t, a)
                    }
                    _ => false,
                };
                (normal.map(|(n, _)| n), !smooth)
            }
        };
        // Without a normal from the surface (a lone sample of it), shade facing the camera.
        let n = normal.map_or(-rd, |n| v3(n[0], n[1], n[2]));
        let colour = self.view.shade_hit(&self.view.on(shading), p, n, rd, t, self.view.hit_epsilon(t));
        TruthPixel { t, normal, rough, colour: [colour.x, colour.y, colour.z] }
    }

    /// Whether the surface the centre ray hit at `t`, with normal `n`, also lies under the pixel's corners: rays
    /// [`NORMAL_OFFSET`] pixels away on both diagonals find it within the window and within [`ROUGH_DEGREES`] of the
    /// plane through the centre's hit. Between the axis neighbours a hole or a rim narrower than the pixel can hide,
    /// and a pixel over one covers more than one surface.
    fn continues_to_corners(&self, px: f64, py: f64, t: f64, n: [f64; 3]) -> bool {
        let (ro, rd) = self.view.ray(px, py);
        let centre = ro + rd * t;
        let n = v3(n[0], n[1], n[2]);
        let d = NORMAL_OFFSET;
        NEIGHBOURS[4..].iter().all(|&(i, j)| {
            self.neighbour(px + i * d, py + j * d, t).is_some_and(|q| {
                let off = q - centre;
                fractal_dsl::number::math::dot(off, n).abs()
                    <= ROUGH_DEGREES.to_radians().sin() * fractal_dsl::number::math::length(off)
            })
        })
    }

    /// The surface point a neighbouring ray at (px, py) finds within the window around depth `t`, if the surface
    /// there is the one the centre ray hit (the neighbour starts the window outside).
    fn neighbour(&self, px: f64, py: f64, t: f64) -> Option<V3<f64>> {
        let window = NORMAL_WINDOW * self.footprint_at(t);
        let fine = |_: f64| 0.5 * self.settings.step_footprints * self.footprint_at(t);
        let start = (t - window).max(0.0);
        let hit = self.with_ray(px, py, |ray| {
            if ray.value(start) <= 0.0 {
                return None;
            }
            ray.first_crossing(start, t + window, fine)
        })?;
        let (ro, rd) = self.view.ray(px, py);
        Some(ro + rd * hit)
    }

    /// The gradient of the scene's value at the hit `p` (ray distance `t`, direction `rd`), facing the camera, when
    /// the value there is an exact distance (see [`Truth::exact_gradient`]).
    fn exact_normal(&self, p: V3<f64>, rd: V3<f64>, t: f64) -> Option<[f64; 3]> {
        let n = self.exact_gradient(p, t)?;
        let n = if fractal_dsl::number::math::dot(n, rd) > 0.0 { -n } else { n };
        Some([n.x, n.y, n.z])
    }

    /// The direction of the gradient of the scene's value at `q` (near ray distance `t`) when the value there is a
    /// smooth function: the same slope on both sides of `q` along each axis (a crease fails it), and in a scene
    /// with a fractal, unit length (the exact distance of a primitive; a fractal's sign-only membership or its bound
    /// nearby fail it).
    fn exact_gradient(&self, q: V3<f64>, t: f64) -> Option<V3<f64>> {
        let h = 1e-3 * self.footprint_at(t.max(self.near));
        let env = self.env();
        let value = |q: V3<f64>| self.membership.value([q.x, q.y, q.z], &env);
        let at = value(q);
        let mut g = [0.0; 3];
        for (axis, slope) in g.iter_mut().enumerate() {
            let e = axis_step(axis, h);
            let (ahead, behind) = ((value(q + e) - at) / h, (at - value(q - e)) / h);
            if (ahead - behind).abs() > 1e-3 {
                return None;
            }
            *slope = 0.5 * (ahead + behind);
        }
        let n = v3(g[0], g[1], g[2]);
        let len = fractal_dsl::number::math::length(n);
        let exact = ((1.0 - 1e-3)..=(1.0 + 1e-3)).contains(&len) || (self.valued && len > 0.0);
        exact.then(|| n / len)
    }

    /// Whether the exact surface with normal `n` at the hit `p` of the ray through (px, py) keeps that normal across
    /// the pixel: within [`ROUGH_DEGREES`] of `n`, the exact gradient [`NORMAL_OFFSET`] footprints away along each
    /// axis on both sides, and the exact normal wherever the eight rays [`NORMAL_OFFSET`] pixels away (axes and
    /// diagonals) meet the surface within the window. An edge or a rim that close (a box's edge, the lip of a hole)
    /// is a crease inside the pixel's footprint, where no one normal is the pixel's; a silhouette of a smooth
    /// surface is not.
    fn exact_smooth(&self, px: f64, py: f64, p: V3<f64>, n: [f64; 3], t: f64) -> bool {
        let n = v3(n[0], n[1], n[2]);
        let r = NORMAL_OFFSET * self.footprint_at(t);
        let cos_rough = ROUGH_DEGREES.to_radians().cos();
        let same = |g: Option<V3<f64>>| g.is_some_and(|g| fractal_dsl::number::math::dot(g, n).abs() >= cos_rough);
        let d = NORMAL_OFFSET;
        (0..6).all(|k| same(self.exact_gradient(p + axis_step(k / 2, if k % 2 == 0 { r } else { -r }), t)))
            && NEIGHBOURS.iter().all(|&(i, j)| {
                self.neighbour(px + i * d, py + j * d, t).is_none_or(|q| same(self.exact_gradient(q, t)))
            })
    }

    /// The true surface's normal at the hit `t` of the ray through (px, py), facing the camera, from neighbouring
    /// rays `offset` pixels away; and whether the surface bends by more than [`ROUGH_DEGREES`] between the two sides
    /// of the centre (a crease through the pixel, on whose either face the centre ray may lie).
    fn normal(&self, px: f64, py: f64, t: f64, offset: f64) -> Option<([f64; 3], bool)> {
        let (ro, rd) = self.view.ray(px, py);
        let centre = ro + rd * t;
        let d = offset;
        let bent = |a: V3<f64>, b: V3<f64>| {
            let cos = fractal_dsl::number::math::dot(a, b)
                / (fractal_dsl::number::math::length(a) * fractal_dsl::number::math::length(b));
            // A NaN (a zero-length difference) counts as bent.
            cos.is_nan() || cos < ROUGH_DEGREES.to_radians().cos()
        };
        let across = |minus: Option<V3<f64>>, plus: Option<V3<f64>>| -> Option<(V3<f64>, bool)> {
            let gap = |q: V3<f64>| fractal_dsl::number::math::length(q - centre);
            match (minus, plus) {
                // Central where both sides continue the surface about equally, else the nearer side.
                (Some(m), Some(p)) if gap(m) < 2.0 * gap(p) && gap(p) < 2.0 * gap(m) => {
                    Some((p - m, bent(centre - m, p - centre)))
                }
                (Some(m), Some(p)) if gap(m) < gap(p) => Some((centre - m, bent(centre - m, p - centre))),
                (Some(m), Some(p)) => Some((p - centre, bent(centre - m, p - centre))),
                // The surface ends within the pixel (a silhouette, the lip of a hole): a normal from the side that
                // goes on, and no single normal for the pixel, which also covers what lies beyond the edge.
                (None, Some(p)) => Some((p - centre, true)),
                (Some(m), None) => Some((centre - m, true)),
                (None, None) => None,
            }
        };
        let (dx, crease_x) = across(self.neighbour(px - d, py, t), self.neighbour(px + d, py, t))?;
        let (dy, crease_y) = across(self.neighbour(px, py - d, t), self.neighbour(px, py + d, t))?;
        let n = fractal_dsl::number::math::cross(dx, dy);
        let len = fractal_dsl::number::math::length(n);
        if len.is_nan() || len <= 0.0 {
            return None;
        }
        let n = n / len;
        let n = if fractal_dsl::number::math::dot(n, rd) > 0.0 { -n } else { n };
        Some(([n.x, n.y, n.z], crease_x || crease_y))
    }
}

/// The angle between two directions, in degrees.
pub fn angle_degrees(a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (dot / (len(a) * len(b))).clamp(-1.0, 1.0).acos().to_degrees()
}

/// A step of `h` along coordinate axis `axis`.
fn axis_step(axis: usize, h: f64) -> V3<f64> {
    let mut e = [0.0; 3];
    e[axis] = h;
    v3(e[0], e[1], e[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accuracy::{measure, Observed};
    use fractal_dsl::analyse::{sign_refinement, SignRefinement};
    use fractal_dsl::builder::*;
    use fractal_render::backend::cpu::trace_scene;

    #[test]
    fn a_sphere_is_hit_where_the_ray_meets_it_analytically() {
        let s = scene(sphere(1.0).translate(vec3(0.2, -0.1, 0.3))).camera(camera([0.0, 0.5, -3.0], [0.0; 3]).fov(50.0));
        let f = Frame::default_view(&s, 0.0, 40, 30).unwrap();
        let truth = Truth::compute(&s, &f, TruthSettings::default()).unwrap();
        let centre = v3(0.2, -0.1, 0.3);
        let (mut hits, mut rough) = (0, 0);
        for y in 0..30 {
            for x in 0..40 {
                let (ro, rd) = truth.view.ray(x as f64 + 0.5, y as f64 + 0.5);
                // |ro + t·rd − c|² = 1 with |rd| = 1: t² + 2bt + (|oc|² − 1) = 0.
                let oc = ro - centre;
                let b = fractal_dsl::number::math::dot(oc, rd);
                let disc = b * b - (fractal_dsl::number::math::dot(oc, oc) - 1.0);
                let pixel = truth.at(x, y);
                if disc.abs() < 1e-3 {
                    continue; // grazing: either answer is right to within the march step
                }
                assert_eq!(pixel.hit(), disc > 0.0, "pixel ({x}, {y})");
                if disc > 0.0 {
                    hits += 1;
                    let t = -b - disc.sqrt();
                    assert!((pixel.t - t).abs() < 1e-9, "pixel ({x}, {y}): {} against {t}", pixel.t);
                    let p = ro + rd * t;
                    let n = (p - centre) / fractal_dsl::number::math::length(p - centre);
                    // The exact distance's own gradient, at the silhouette too.
                    let got = pixel.normal.expect("a normal");
                    let cos = n.x * got[0] + n.y * got[1] + n.z * got[2];
                    assert!(cos > 1.0 - 1e-9, "pixel ({x}, {y}): normal {got:?} against {n:?}");
                    // Only near the silhouette does the normal turn by more than the rough angle within a pixel.
                    let facing = -fractal_dsl::number::math::dot(n, rd);
                    assert!(!pixel.rough || facing < 0.5, "pixel ({x}, {y}) of a sphere is rough, facing {facing}");
                    rough += pixel.rough as usize;
                }
            }
        }
        assert!(hits > 100 && rough < hits / 5, "{hits} hits, {rough} rough");
    }

    /// A render's normal is judged against the nearest true normal across its pixel: on a sphere seen coarsely the
    /// surface turns by degrees within a pixel, and the exact normal where a ray a quarter pixel off the centre meets
    /// it is no error at all, though it is one against the centre's normal.
    #[test]
    fn a_normal_the_surface_takes_within_the_pixel_is_cone_consistent() {
        let centre = v3(0.2, -0.1, 0.3);
        let s = scene(sphere(1.0).translate(vec3(0.2, -0.1, 0.3))).camera(camera([0.0, 0.5, -3.0], [0.0; 3]).fov(50.0));
        let truth =
            Truth::compute(&s, &Frame::default_view(&s, 0.0, 20, 15).unwrap(), TruthSettings::default()).unwrap();
        let mut checked = 0;
        for y in 0..15 {
            for x in 0..20 {
                let pixel = truth.at(x, y);
                let (Some(own), false) = (pixel.normal, pixel.rough) else { continue };
                let (ro, rd) = truth.view.ray(x as f64 + 0.75, y as f64 + 0.5);
                let oc = ro - centre;
                let b = fractal_dsl::number::math::dot(oc, rd);
                let disc = b * b - (fractal_dsl::number::math::dot(oc, oc) - 1.0);
                if disc <= 0.0 {
                    continue;
                }
                let n = ro + rd * (-b - disc.sqrt()) - centre;
                let n = [n.x, n.y, n.z];
                let cone = truth.cone_normal_error(x, y, n).expect("the sub-rays meet the sphere");
                assert!(cone < 1e-3, "pixel ({x}, {y}): {cone}° from its own sub-ray's normal");
                assert!(angle_degrees(n, own) > 0.5, "pixel ({x}, {y}): the surface turns within the pixel");
                checked += 1;
            }
        }
        assert!(checked > 20, "{checked} pixels checked");
    }

    /// An exact surface's normal is the pixel's only where the surface keeps it across the pixel: next to a box's
    /// edge (two faces within the pixel's footprint) the pixel is rough, inside a face it is not.
    #[test]
    fn exact_edges_are_rough_at_the_pixels_scale() {
        let s = scene(box3(vec3(0.6, 0.6, 0.6)).rotate_y(0.5)).camera(camera([1.2, 1.4, -2.6], [0.0; 3]).fov(50.0));
        let (w, h) = (48, 36);
        let truth = Truth::compute(&s, &Frame::default_view(&s, 0.0, w, h).unwrap(), TruthSettings::default()).unwrap();
        let face = |x: i64, y: i64| {
            let p = truth.at(x.clamp(0, w as i64 - 1) as u32, y.clamp(0, h as i64 - 1) as u32);
            p.normal.map(|n| n.map(|c| (c * 1e3).round() as i64))
        };
        let (mut edges, mut faces) = (0, 0);
        for y in 0..h as i64 {
            for x in 0..w as i64 {
                let Some(own) = face(x, y) else { continue };
                let around = |r: i64| (-r..=r).flat_map(move |j| (-r..=r).map(move |i| (i, j)));
                let pixel = truth.at(x as u32, y as u32);
                if around(1).any(|(i, j)| face(x + i, y + j).is_some_and(|n| n != own)) {
                    // Another face in a neighbouring pixel: an edge runs within a pixel and a half of the centre.
                    continue;
                }
                if around(2).all(|(i, j)| face(x + i, y + j) == Some(own)) {
                    assert!(!pixel.rough, "pixel ({x}, {y}) inside a face is rough");
                    faces += 1;
                }
            }
        }
        let on_edge = |x: u32, y: u32| {
            let n = face(x as i64, y as i64);
            n.is_some()
                && [(1, 0), (0, 1)].iter().any(|&(i, j)| {
                    let m = face(x as i64 + i, y as i64 + j);
                    m.is_some() && m != n
                })
        };
        for y in 0..h {
            for x in 0..w {
                if on_edge(x, y) {
                    // The pixel or its right or lower neighbour holds the edge between them.
                    let right_or_below = if face(x as i64 + 1, y as i64) != face(x as i64, y as i64) {
                        truth.at(x + 1, y)
                    } else {
                        truth.at(x, y + 1)
                    };
                    assert!(truth.at(x, y).rough || right_or_below.rough, "edge at ({x}, {y}) is smooth");
                    edges += 1;
                }
            }
        }
        assert!(faces > 50 && edges > 20, "{faces} face pixels, {edges} edge pixels");
    }

    /// On a fractal the membership gives no gradient: normals come from neighbouring rays, and where the set's
    /// detail is finer than a pixel the pixel is rough and left out of the normal error.
    #[test]
    fn fractal_normals_come_from_neighbouring_rays_and_fine_detail_is_rough() {
        let bulb = scene(mandelbulb(8).iterations(4)).camera(camera([1.2, 1.0, -2.2], [0.0; 3]));
        let truth =
            Truth::compute(&bulb, &Frame::default_view(&bulb, 0.0, 48, 27).unwrap(), TruthSettings::default()).unwrap();
        let hits: Vec<&TruthPixel> = truth.pixels.iter().filter(|p| p.hit()).collect();
        let rough = hits.iter().filter(|p| p.rough).count();
        assert!(hits
            .iter()
            .all(|p| p.normal.is_none_or(|n| (n[0] * n[0] + n[1] * n[1] + n[2] * n[2] - 1.0).abs() < 1e-9)));
        assert!(rough > 0 && rough < hits.len(), "{rough} of {} hits rough", hits.len());
    }

    #[test]
    fn too_few_steps_a_blunt_epsilon_and_a_reckless_step_factor_are_reported_and_the_defaults_are_not() {
        let bulb = scene(mandelbulb(8).iterations(6)).camera(camera([1.2, 1.0, -2.2], [0.0; 3]));
        let f = Frame::default_view(&bulb, 0.0, 48, 27).unwrap();
        let settings = TruthSettings { step_footprints: 1.0 / 32.0, iteration_factor: 1 };
        let truth = Truth::compute(&bulb, &f, settings).unwrap();
        let error = |s: &Scene| {
            let traces = trace_scene::<f32, _>(&Interpreter::new(s).unwrap(), s, &f).unwrap();
            measure(s, &truth, Observed::Traced(&traces))
        };
        let good = error(&bulb);
        let starved = error(&bulb.clone().max_steps(8));
        let good_traced = good.traced.as_ref().unwrap();
        let starved_traced = starved.traced.as_ref().unwrap();
        assert!(good.false_misses < 0.01, "{}", good.describe());
        assert!(starved.false_misses > 0.1, "{}", starved.describe());
        assert!(starved_traced.false_misses_out_of_steps > 0.1, "{}", starved.describe());
        assert!(starved_traced.evaluations_per_pixel < good_traced.evaluations_per_pixel);
        // An epsilon of a tenth of the object stops rays well in front of the surface.
        let blunt = error(&bulb.clone().epsilon(0.1));
        assert!(blunt.traced.unwrap().depth_thin.median > 3.0 * good_traced.depth_thin.median.max(0.1));
        assert!(blunt.false_hits > good.false_hits);
        // A scene's step factor past what the estimate allows steps through the surface, where the family's has no
        // overshoot.
        let reckless = error(&scene(mandelbulb(8).iterations(6).step_factor(3.0)).camera(bulb.camera.clone()));
        let reckless_traced = reckless.traced.as_ref().unwrap();
        assert!(good_traced.overshoot == 0.0, "{}", good.describe());
        assert!(reckless_traced.overshoot_cone > 0.01, "{}", reckless.describe());
        assert!(reckless_traced.evaluations_per_pixel < good_traced.evaluations_per_pixel);
    }

    /// A displaced distance is divided by its slope bound (about 7 here), so a hit test on it alone stopped rays up
    /// to that many epsilons short of the ground, more along grazing rays. The march refined by sign stops on it, and
    /// its normal there is the ground's.
    #[test]
    fn displaced_ground_is_hit_where_it_is_not_an_epsilon_times_its_slope_bound_in_front() {
        let source = "scene(plane(vec3(0.0, 1.0, 0.0), 0.0).displace(fbm2(x * 0.5, z * 0.5, 4)))\
                      .camera(camera(vec3(0.0, 1.6, -6.0), vec3(0.0, 0.2, 2.0)).fov(60.0))\
                      .max_steps(384).max_distance(30.0).pixel_epsilon(0.25)";
        let s = fractal_dsl::parse::parse_str(source).unwrap();
        assert_eq!(sign_refinement(&s.root, &s.settings), Some(SignRefinement::Displacement));
        let f = Frame::default_view(&s, 0.0, 64, 36).unwrap();
        let truth = Truth::compute(&s, &f, TruthSettings::default()).unwrap();
        let traces = trace_scene::<f32, _>(&Interpreter::new(&s).unwrap(), &s, &f).unwrap();
        let e = measure(&s, &truth, Observed::Traced(&traces));
        let t = e.traced.as_ref().unwrap();
        assert!(e.false_hits_cone < 0.005 && e.false_misses < 0.005, "{}", e.describe());
        assert!(t.depth_cone_interior.p99 < 1.0 && t.overshoot_cone < 0.005, "{}", e.describe());
        // Its truth takes the normal from the value's gradient, which is not of unit length here.
        assert!(t.normal.count >= 20 && t.normal.p99 < 5.0, "{}", e.describe());
        // A fractal's estimate has no sign to follow: a scene with one keeps the plain hit test.
        let with_bulb = fractal_dsl::parse::parse_str(
            &source.replace("scene(plane", "scene(union(mandelbulb(8), plane").replace("4)))", "4))))"),
        )
        .unwrap();
        assert_eq!(sign_refinement(&with_bulb.root, &with_bulb.settings), None);
    }

    /// The power-2 Mandelbulb's estimate is a tenth of the distance to its set and less around it, so its rays stop
    /// where the estimate passes under a half-pixel epsilon, many footprints in front of the set and on pixels whose
    /// cone holds none of it (measured: 18.8 % of the pixels, interior depth p99 12 footprints). With membership hits
    /// they step on to the set itself (none, 0.44).
    #[test]
    fn membership_hits_stop_on_the_set_where_the_estimate_stops_in_front_of_it() {
        let source = "scene(mandelbulb(2).iterations(32))\
                      .camera(camera(vec3(0.0, 1.6, -3.2), vec3(0.0, 0.0, 0.0)).fov(40.0))\
                      .max_steps(256).max_distance(8.0).pixel_epsilon(0.5)";
        let plain_scene = fractal_dsl::parse::parse_str(source).unwrap();
        let f = Frame::default_view(&plain_scene, 0.0, 64, 36).unwrap();
        // The setting changes the march, not the scene: one truth for both.
        let truth = Truth::compute(&plain_scene, &f, TruthSettings::default()).unwrap();
        let measured = |source: &str| {
            let s = fractal_dsl::parse::parse_str(source).unwrap();
            let traces = trace_scene::<f32, _>(&Interpreter::new(&s).unwrap(), &s, &f).unwrap();
            (sign_refinement(&s.root, &s.settings), measure(&s, &truth, Observed::Traced(&traces)))
        };
        let (refine, plain) = measured(source);
        assert_eq!(refine, None);
        let p = plain.traced.as_ref().unwrap();
        assert!(plain.false_hits_cone > 0.02 && p.depth_cone_interior.p99 > 3.0, "{}", plain.describe());

        let (refine, on_set) = measured(&format!("{source}.membership_hits()"));
        assert_eq!(refine, Some(SignRefinement::Membership));
        let t = on_set.traced.as_ref().unwrap();
        assert!(on_set.false_hits_cone < 0.005 && t.depth_cone_interior.p99 < 1.0, "{}", on_set.describe());
        // What it gives up: sheets of the set thinner than its steps along the ray (measured: 1.6 % of the pixels
        // missed, 0.4 % passed through, at 64×36 so close up; 0.4 % and 0.03 % on `mandelbulb_powers`).
        assert!(on_set.false_misses < 0.03 && t.overshoot_cone < 0.01, "{}", on_set.describe());
    }

    /// A render that stopped on a hair of the scene thinner than any lattice of sub-rays resolves has stopped on
    /// what its pixel's cone holds: a hair running along the cone between the lines of a 5×5 lattice a quarter pixel
    /// apart, a twenty-fifth of a footprint thick, which none of those sub-rays meets, is found by the depth check's
    /// points spread anew at each depth.
    #[test]
    fn a_hair_between_the_sub_rays_is_within_the_pixels_cone() {
        let place = scene(sphere(1.0)).camera(camera([0.0, 0.0, -3.0], [0.0; 3]));
        let f = Frame::default_view(&place, 0.0, 20, 15).unwrap();
        let (x, y, start) = (10, 7, 2.5);
        let view = Truth::compute(&place, &f, TruthSettings::default()).unwrap();
        // Midway between the lattice's sub-rays (at 0, 1/4, … of the pixel), along one of the pixel's own rays.
        let (ro, rd) = view.view.ray(x as f64 + 0.125, y as f64 + 0.125);
        let foot = view.footprint_at(start);
        let (a, b) = (ro + rd * start, ro + rd * (start + 2.0 * foot));
        let hair = scene(capsule([a.x, a.y, a.z], [b.x, b.y, b.z], 0.02 * foot)).camera(place.camera.clone());
        let truth = Truth::compute(&hair, &f, TruthSettings::default()).unwrap();
        for k in 0..25 {
            let (px, py) = cone::sub_pixel(x, y, k, 5);
            assert_eq!(truth.first_hit(px, py), None, "sub-ray {k} meets the hair");
        }
        let found = truth.cone_error(x, y, start, 2.0, 25, 1.0 / 64.0).expect("the cone holds the hair");
        assert!(found < 0.5, "the hair found {found} footprints from where the render stopped");
        assert_eq!(truth.cone_error(2, 2, start, 2.0, 25, 1.0 / 64.0), None, "a pixel whose cone holds no hair");
    }

    /// A false hit is cone-consistent when the pixel's cone meets the scene off its centre: a half-pixel epsilon
    /// fattens a sphere's silhouette by pixels its cone covers in part, and three pixels fatten it beyond any cone.
    #[test]
    fn false_hits_within_the_pixel_cone_are_told_apart() {
        let ball = scene(sphere(1.0)).camera(camera([0.0, 0.3, -3.0], [0.0; 3]));
        let f = Frame::default_view(&ball, 0.0, 40, 30).unwrap();
        let truth = Truth::compute(&ball, &f, TruthSettings::default()).unwrap();
        let error = |s: &Scene| {
            let traces = trace_scene::<f32, _>(&Interpreter::new(s).unwrap(), s, &f).unwrap();
            measure(s, &truth, Observed::Traced(&traces))
        };
        let half = error(&ball.clone().pixel_epsilon(0.5));
        let wide = error(&ball.clone().pixel_epsilon(3.0));
        assert!(half.false_hits > 0.0 && half.false_hits_cone < 0.5 * half.false_hits, "{}", half.describe());
        assert!(wide.false_hits_cone > 0.5 * wide.false_hits, "{}", wide.describe());
        assert!(wide.hit_mismatch() > half.hit_mismatch() && half.hit_mismatch() <= half.hit_mismatch_thin());
    }

    /// An image of a scene with glow has no hit mask (glow tints the misses): its hit figures are not made up.
    #[test]
    fn an_image_with_glow_reports_no_hit_figures() {
        let glowing = scene(sphere(1.0)).camera(camera([0.0, 0.0, -3.0], [0.0; 3])).glow(rgb(0.2, 0.4, 1.0));
        let f = Frame::default_view(&glowing, 0.0, 32, 18).unwrap();
        let truth = Truth::compute(&glowing, &f, TruthSettings::default()).unwrap();
        let image = fractal_render::render_scene::<f32, _>(&Interpreter::new(&glowing).unwrap(), &glowing, &f).unwrap();
        let error = measure(&glowing, &truth, Observed::Image(&image));
        assert!(error.false_hits.is_nan() && error.false_misses.is_nan(), "{}", error.describe());
        assert!(error.describe().starts_with("hit mask not readable"), "{}", error.describe());
        assert!(error.psnr > 20.0, "{}", error.describe());
    }
}
