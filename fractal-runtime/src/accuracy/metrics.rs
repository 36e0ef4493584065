//! A render against the truth ([`crate::truth`]): the true error of one image.
//!
//! - **Hit mask**: false hits (the render hit, the truth misses) and false misses, as fractions of all pixels; false
//!   misses whose march ran out of steps are counted apart. False hits are counted thin-ray (the ray through the
//!   pixel's centre misses) and cone-consistent (no ray of the pixel's cone, [`COVER_GRID`]² of them, meets the
//!   scene either, [`Truth::cone_sees_scene`]): a pixel a filament crosses off its centre is partly covered, and a
//!   render that hits there is as right as one that misses. The budget judges the cone-consistent figure.
//! - **Depth** where both hit, in pixel footprints: |t − t_true| / (pixel angle · t_true). *Thin-ray*: against the
//!   crossing of the ray through the pixel's centre. *Cone-consistent*: a render that stopped where some part of the
//!   pixel's cone meets the scene is not wrong by more than the depth gap to that meeting (a ray that stops on a
//!   filament it passes a twentieth of a footprint from has found what the pixel sees); searched at
//!   [`CONE_SAMPLES`] points across the pixel's cone at each depth, every [`CONE_STEP`] within [`CONE_WINDOW`]
//!   footprints of where the render stopped ([`Truth::cone_error`]), for pixels whose thin-ray error is above
//!   [`CONE_CHECK`]. Both over all pixels that hit and over
//!   *interior* pixels (truth hits whose 8 neighbours are truth hits too).
//! - **Overshoot**: the truth hits and the ray ended more than a footprint past the true hit (hit or miss): it passed
//!   through the surface.
//! - **Normals** where both hit the same surface (within [`NORMAL_SAME_SURFACE`] footprints along the ray; a render
//!   that stopped on another surface has a depth error, counted above) and the true surface is smooth at the pixel's
//!   scale (not [`crate::truth::TruthPixel::rough`]): the angle between the render's shading normal and the true
//!   surface's at the pixel's centre, in degrees; *cone-consistent*, the angle to the nearest of the true normals
//!   across the pixel's footprint ([`Truth::cone_normal_error`], for errors above [`NORMAL_CONE_CHECK`]): a smooth
//!   surface still turns by up to [`crate::truth::ROUGH_DEGREES`] within a pixel, which shades one normal for all of
//!   it. The budget judges the latter. Also the share of both-hit pixels measured.
//! - **Depth on smooth surfaces**: the thin-ray depth error over the pixels both hit where the true surface is smooth
//!   at the pixel's scale (it has a normal there and is not rough). The cone explains nothing there, since every ray
//!   of the pixel meets the same plane: a render that stops tens of footprints in front of a smooth surface (an f32
//!   estimate too coarse for a close zoom) is wrong even where, a footprint away, the cone-consistent figures find
//!   some other part of the scene. The budget judges its median.

//! - **Colour**: PSNR of the 8-bit image against the true hit shaded the same way, over all pixels.
//! - **Health**: pixels with NaN or Inf anywhere (colour, depth of a hit, normal); rays that ran out of steps;
//!   distance evaluations per pixel.
//!
//! From an image alone (the GPU backends) only the hit mask (a pixel of the background colour is a miss) and PSNR can
//! be read; where glow tints the misses, the mask comes from a second image ([`TrueError::with_hit_mask`]).

use fractal_dsl::Scene;
use fractal_render::backend::cpu::PixelTrace;
use fractal_render::image::{linear_rgba8, unpack_rgba8, Image};

use crate::truth::{angle_degrees, Truth};

/// Largest thin-ray depth difference, in footprints, at which the render and the truth stand on the same surface and
/// their normals are compared.
pub const NORMAL_SAME_SURFACE: f64 = 1.0;
/// Thin-ray depth errors above this many footprints are checked against the pixel's cone.
pub const CONE_CHECK: f64 = 0.5;
/// How far from where the render stopped, in footprints, the cone check looks for the scene.
pub const CONE_WINDOW: f64 = 2.0;
/// Points across the pixel's cone at each depth of the cone check, a new spread at every depth. Enough that the check
/// has converged where the scene is hair: at the built-in `mandelbulb`'s close-up (t = 25 s, 192×108, against its
/// 64-iteration truth) the default's interior depth p99 reads 1.64 footprints with 25 (a 5×5 lattice's worth), 0.52
/// with 100 and 0.48 with 400; fixed sub-rays on a 5×5 lattice read 3.38.
pub const CONE_SAMPLES: u32 = 100;
/// Sub-rays per side of the pixel, edge to edge, that decide whether its cone meets the scene at all (a false hit's):
/// each marches the whole ray, so fewer than the depth check's; a third of a pixel apart.
pub const COVER_GRID: u32 = 4;
/// Sampling step of the cone check along each sub-ray, in footprints: coarser than the truth's march (a sixty-fourth
/// of a footprint is far below what a pixel resolves, and the check runs for every render of a sweep), and a feature
/// thinner than it only makes the check stricter.
pub const CONE_STEP: f64 = 1.0 / 64.0;
/// Normal errors above this many degrees against the centre's true normal are checked against the normals across
/// the pixel's footprint.
pub const NORMAL_CONE_CHECK: f64 = 2.0;
/// How far past the true hit, in footprints, a ray must end to have passed through the surface.
pub const OVERSHOOT_FOOTPRINTS: f64 = 1.0;

/// Levels per channel within which a pixel still has the miss colour (driver rounding of sqrt and the like).
pub const MISS_TOLERANCE: u8 = 2;

/// Whether `pixel` has the miss colour `miss`: RGB within [`MISS_TOLERANCE`] levels.
pub fn is_miss(pixel: u32, miss: [u8; 4]) -> bool {
    unpack_rgba8(pixel).iter().zip(miss).take(3).all(|(p, c)| p.abs_diff(c) <= MISS_TOLERANCE)
}

/// The hit mask of an image of `scene` read from its pixels: a pixel of the background colour (packed as the
/// renderers pack it) is a miss. `None` when the scene has glow, which tints misses.
pub fn scene_hits(scene: &Scene, image: &Image) -> Option<Vec<bool>> {
    if scene.settings.glow.is_some() {
        return None;
    }
    let background = linear_rgba8(scene.settings.background, scene.settings.gamma);
    Some(image.pixels.iter().map(|&p| !is_miss(p, background)).collect())
}

/// median, 99th percentile and maximum of a set of errors.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Spread {
    pub count: usize,
    pub median: f64,
    pub p99: f64,
    pub max: f64,
}

impl Spread {
    /// The spread of `values` (NaN figures when there are none).
    pub fn of(mut values: Vec<f64>) -> Spread {
        if values.is_empty() {
            return Spread { count: 0, median: f64::NAN, p99: f64::NAN, max: f64::NAN };
        }
        values.sort_by(f64::total_cmp);
        let at = |q: f64| values[((values.len() - 1) as f64 * q).round() as usize];
        Spread { count: values.len(), median: at(0.5), p99: at(0.99), max: values[values.len() - 1] }
    }
}

/// What was rendered: the CPU renderer's per-pixel traces, or an image from any backend.
pub enum Observed<'a> {
    Traced(&'a [PixelTrace]),
    Image(&'a Image),
}

/// The figures measured on the render's depths, normals and march (not readable from an image).
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct TracedError {
    pub depth_thin: Spread,
    pub depth_cone: Spread,
    pub depth_thin_interior: Spread,
    pub depth_cone_interior: Spread,
    /// Thin-ray, over the pixels both hit where the true surface is smooth at the pixel's scale.
    pub depth_smooth: Spread,
    /// Fraction of pixels whose ray passed more than [`OVERSHOOT_FOOTPRINTS`] through the true surface: *thin-ray*.
    pub overshoot: f64,
    /// Of those, the fraction of pixels where every ray of the pixel's cone meets the scene that far in front of
    /// where the render stopped: *cone-consistent* (a ray that passes through a feature narrower than the pixel
    /// draws what the rest of the pixel sees).
    pub overshoot_cone: f64,
    /// Degrees, against the true normal at the pixel's centre.
    pub normal: Spread,
    /// Degrees, against the nearest of the true normals across the pixel's footprint: *cone-consistent* (the
    /// budget's).
    pub normal_cone: Spread,
    /// Fraction of the pixels both hit where the normal was measured (the rest are rough at the pixel's scale).
    pub normal_measured: f64,
    /// Pixels with NaN or Inf.
    pub non_finite: usize,
    /// Fraction of pixels whose march ran out of steps.
    pub out_of_steps: f64,
    /// Fraction of pixels that are false misses out of steps.
    pub false_misses_out_of_steps: f64,
    /// Where the renderer counts them (the CPU's; a kernel does not).
    pub evaluations_per_pixel: Option<f64>,
}

/// A render's true error.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct TrueError {
    pub width: u32,
    pub height: u32,
    /// Fractions of all pixels; NaN when the render is an image whose hit mask cannot be read (glow tints misses).
    /// Thin-ray: the render hits, the ray through the pixel's centre misses.
    pub false_hits: f64,
    /// Cone-consistent: false hits where no ray of the pixel's cone meets the scene either (the budget's).
    pub false_hits_cone: f64,
    pub false_misses: f64,
    /// Colour PSNR in dB (+∞ when identical).
    pub psnr: f64,
    pub traced: Option<TracedError>,
}

impl TrueError {
    /// This error with the hit figures of `hits`, a mask of the same render read another way (an image with glow
    /// has none of its own).
    pub fn with_hit_mask(self, truth: &Truth, hits: &[bool]) -> TrueError {
        let (false_hits, false_hits_cone, false_misses) = mask_error(truth, hits);
        TrueError { false_hits, false_hits_cone, false_misses, ..self }
    }

    /// Cone-consistent false hits and false misses: the budget's hit mismatch.
    pub fn hit_mismatch(&self) -> f64 {
        self.false_hits_cone + self.false_misses
    }

    /// Thin-ray false hits and false misses.
    pub fn hit_mismatch_thin(&self) -> f64 {
        self.false_hits + self.false_misses
    }

    /// One line for reports.
    pub fn describe(&self) -> String {
        let mut s = if self.false_hits.is_nan() {
            format!("hit mask not readable from the image (glow tints misses), colour PSNR {:.1} dB", self.psnr)
        } else {
            format!(
                "false hits {:.3} % thin-ray / {:.3} % cone-consistent, false misses {:.3} %, colour PSNR {:.1} dB",
                100.0 * self.false_hits,
                100.0 * self.false_hits_cone,
                100.0 * self.false_misses,
                self.psnr
            )
        };
        if let Some(t) = &self.traced {
            s += &format!(
                "; depth error (footprints) median {:.2}, p99 {:.2} thin-ray / {:.2} cone-consistent, interior p99 \
                 {:.2} cone-consistent, median {:.2} thin-ray on smooth surfaces; overshoot {:.3} % thin-ray / {:.3} % cone-consistent; normal error median {:.1}°, p99 {:.1}° at the centre / {:.1}° \
                 cone-consistent (on {:.0} % of hits); {:.3} % out of steps; {} NaN/Inf pixels{}",
                t.depth_thin.median,
                t.depth_thin.p99,
                t.depth_cone.p99,
                t.depth_cone_interior.p99,
                t.depth_smooth.median,
                100.0 * t.overshoot,
                100.0 * t.overshoot_cone,
                t.normal.median,
                t.normal.p99,
                t.normal_cone.p99,
                100.0 * t.normal_measured,
                100.0 * t.out_of_steps,
                t.non_finite,
                t.evaluations_per_pixel.map_or(String::new(), |e| format!("; {e:.1} distance evaluations per pixel"))
            );
        }
        s
    }
}

fn psnr(pairs: impl Iterator<Item = ([u8; 4], [u8; 4])>) -> f64 {
    let (mut sum, mut n) = (0.0, 0usize);
    for (a, b) in pairs {
        for i in 0..3 {
            let d = a[i] as f64 - b[i] as f64;
            sum += d * d;
            n += 1;
        }
    }
    let mse = sum / n.max(1) as f64;
    10.0 * (255.0 * 255.0 / mse).log10()
}

/// Measures a render of `scene` against its truth (same frame).
pub fn measure(scene: &Scene, truth: &Truth, observed: Observed) -> TrueError {
    let gamma = scene.settings.gamma;
    let truth_colours = truth.pixels.iter().map(|p| linear_rgba8(p.colour, gamma));
    // Glow tints misses, so an image of a scene with glow has no hit mask (`None`).
    let hits: Option<Vec<bool>> = match &observed {
        Observed::Traced(traces) => Some(traces.iter().map(|p| p.hit).collect()),
        Observed::Image(image) => scene_hits(scene, image),
    };
    let psnr = match &observed {
        Observed::Traced(traces) => psnr(traces.iter().map(|p| linear_rgba8(p.colour, gamma)).zip(truth_colours)),
        Observed::Image(image) => psnr(image.pixels.iter().map(|&p| unpack_rgba8(p)).zip(truth_colours)),
    };
    let (false_hits, false_hits_cone, false_misses) = match &hits {
        Some(hits) => mask_error(truth, hits),
        None => (f64::NAN, f64::NAN, f64::NAN),
    };
    let traced = match observed {
        Observed::Traced(traces) => Some(traced_error(truth, traces)),
        Observed::Image(_) => None,
    };
    TrueError { width: truth.width, height: truth.height, false_hits, false_hits_cone, false_misses, psnr, traced }
}

/// False hits (thin-ray, and those whose pixel cone sees none of the scene) and false misses of a hit mask, as
/// fractions of all pixels.
fn mask_error(truth: &Truth, hits: &[bool]) -> (f64, f64, f64) {
    use rayon::prelude::*;
    let n = truth.pixels.len().max(1) as f64;
    let false_hits: Vec<usize> = (0..hits.len()).filter(|&i| hits[i] && !truth.pixels[i].hit()).collect();
    let uncovered = false_hits
        .par_iter()
        .filter(|&&i| !truth.cone_sees_scene(i as u32 % truth.width, i as u32 / truth.width, COVER_GRID))
        .count();
    let false_misses = hits.iter().zip(&truth.pixels).filter(|(h, t)| !**h && t.hit()).count();
    (false_hits.len() as f64 / n, uncovered as f64 / n, false_misses as f64 / n)
}

/// Whether pixel (x, y) and its 8 neighbours are all truth hits.
fn interior(truth: &Truth, x: u32, y: u32) -> bool {
    let (w, h) = (truth.width as i64, truth.height as i64);
    (-1..=1).all(|dy| {
        (-1..=1).all(|dx| {
            let (nx, ny) = (x as i64 + dx, y as i64 + dy);
            nx >= 0 && ny >= 0 && nx < w && ny < h && truth.at(nx as u32, ny as u32).hit()
        })
    })
}

/// One pixel's (thin, cone, interior, smooth) depth errors where both hit, (centre, cone) normal errors, and whether
/// it overshot (`None`: no; `Some(cone)`: thin-ray, and `cone` when the pixel's cone does not explain it either).
type PixelError = (Option<(f64, f64, bool, bool)>, Option<(f64, f64)>, Option<bool>);

/// The (centre, cone-consistent) normal error of render pixel `r` at (x, y), where both hit the same surface
/// (`thin`: the thin-ray depth error) and the true surface is smooth at the pixel's scale.
fn normal_error(truth: &Truth, (x, y): (u32, u32), r: &PixelTrace, thin: f64) -> Option<(f64, f64)> {
    let t = truth.at(x, y);
    match (r.normal, t.normal) {
        (Some(a), Some(b)) if !t.rough && thin <= NORMAL_SAME_SURFACE => Some(against_truth(truth, (x, y), a, b)),
        _ => None,
    }
}

/// The (centre, cone-consistent) angle of normal `n` at pixel (x, y) to the true normal `b` there.
fn against_truth(truth: &Truth, (x, y): (u32, u32), n: [f64; 3], b: [f64; 3]) -> (f64, f64) {
    let centre = angle_degrees(n, b);
    let cone = if centre > NORMAL_CONE_CHECK {
        truth.cone_normal_error(x, y, n).map_or(centre, |c| c.min(centre))
    } else {
        centre
    };
    (centre, cone)
}

/// One pixel whose normal was measured, with what was compared: for finding where a render's normals go wrong.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalSample {
    pub x: u32,
    pub y: u32,
    /// Degrees, against the true normal at the pixel's centre and cone-consistent.
    pub centre: f64,
    pub cone: f64,
    /// The ray through the pixel's centre (origin, unit direction), relative to the frame's anchor.
    pub ray: ([f64; 3], [f64; 3]),
    /// Ray distances of the render's and the truth's hits, and the footprint at the truth's.
    pub t_render: f64,
    pub t_truth: f64,
    pub footprint: f64,
    pub render_normal: [f64; 3],
    pub true_normal: [f64; 3],
}

/// Every pixel of a traced render whose normal is measured against `truth` (as [`measure`] measures it), row-major.
pub fn normal_samples(truth: &Truth, traces: &[PixelTrace]) -> Vec<NormalSample> {
    use rayon::prelude::*;
    (0..traces.len())
        .into_par_iter()
        .filter_map(|i| {
            let (x, y) = ((i as u32) % truth.width, (i as u32) / truth.width);
            let (r, t) = (&traces[i], truth.pixels[i]);
            if !(r.hit && t.hit()) {
                return None;
            }
            let thin = (r.t - t.t).abs() / truth.footprint_at(t.t);
            let (centre, cone) = normal_error(truth, (x, y), r, thin)?;
            Some(NormalSample {
                x,
                y,
                centre,
                cone,
                ray: truth.centre_ray(x, y),
                t_render: r.t,
                t_truth: t.t,
                footprint: truth.footprint_at(t.t),
                render_normal: r.normal?,
                true_normal: t.normal?,
            })
        })
        .collect()
}

/// Normals from elsewhere (a method tried outside the renderer: (x, y, normal) per pixel) judged as [`measure`]
/// judges a render's: (centre, cone-consistent) spreads over the given pixels where the true surface has a normal
/// at the pixel's scale (the rest are skipped).
pub fn judge_normals(truth: &Truth, normals: &[(u32, u32, [f64; 3])]) -> (Spread, Spread) {
    let judged: Vec<(f64, f64)> = normals
        .iter()
        .filter(|&&(x, y, _)| x < truth.width && y < truth.height)
        .filter_map(|&(x, y, n)| {
            let t = truth.at(x, y);
            Some(against_truth(truth, (x, y), n, t.normal.filter(|_| !t.rough)?))
        })
        .collect();
    (Spread::of(judged.iter().map(|j| j.0).collect()), Spread::of(judged.iter().map(|j| j.1).collect()))
}

/// [`normal_samples`] as CSV, with a header.
pub fn normal_samples_csv(samples: &[NormalSample]) -> String {
    let mut out =
        String::from("x,y,centre_deg,cone_deg,ox,oy,oz,dx,dy,dz,t_render,t_truth,footprint,rnx,rny,rnz,tnx,tny,tnz\n");
    for s in samples {
        let hits = [s.t_render, s.t_truth, s.footprint];
        let fields = [&[s.centre, s.cone][..], &s.ray.0, &s.ray.1, &hits, &s.render_normal, &s.true_normal].concat();
        let fields: Vec<String> = fields.iter().map(f64::to_string).collect();
        out += &format!("{},{},{}\n", s.x, s.y, fields.join(","));
    }
    out
}

fn traced_error(truth: &Truth, traces: &[PixelTrace]) -> TracedError {
    use rayon::prelude::*;
    let n = traces.len().max(1) as f64;
    // Per pixel: (thin, cone, interior) depth errors where both hit, normal error, overshoot.
    let per_pixel: Vec<PixelError> = traces
        .par_iter()
        .enumerate()
        .map(|(i, r)| {
            let (x, y) = ((i as u32) % truth.width, (i as u32) / truth.width);
            let t = truth.pixels[i];
            let margin = OVERSHOOT_FOOTPRINTS * truth.footprint_at(t.t);
            let overshoot = t.hit() && r.t.is_finite() && r.t > t.t + margin;
            let overshoot = overshoot.then(|| !truth.cone_sees_past(x, y, r.t - margin, COVER_GRID));
            if !(r.hit && t.hit()) {
                return (None, None, overshoot);
            }
            let thin = (r.t - t.t).abs() / truth.footprint_at(t.t);
            let cone = if thin > CONE_CHECK && r.t.is_finite() {
                let window = thin.min(CONE_WINDOW);
                truth.cone_error(x, y, r.t, window, CONE_SAMPLES, CONE_STEP).map_or(thin, |c| c.min(thin))
            } else {
                thin
            };
            let normal = normal_error(truth, (x, y), r, thin);
            let smooth = t.normal.is_some() && !t.rough;
            (Some((thin, cone, interior(truth, x, y), smooth)), normal, overshoot)
        })
        .collect();
    let depths = || per_pixel.iter().filter_map(|p| p.0);
    let non_finite = traces
        .iter()
        .filter(|r| {
            r.colour.iter().any(|c| !c.is_finite())
                || (r.hit && !r.t.is_finite())
                || r.normal.is_some_and(|n| n.iter().any(|c| !c.is_finite()))
        })
        .count();
    TracedError {
        depth_thin: Spread::of(depths().map(|d| d.0).collect()),
        depth_cone: Spread::of(depths().map(|d| d.1).collect()),
        depth_thin_interior: Spread::of(depths().filter(|d| d.2).map(|d| d.0).collect()),
        depth_cone_interior: Spread::of(depths().filter(|d| d.2).map(|d| d.1).collect()),
        depth_smooth: Spread::of(depths().filter(|d| d.3).map(|d| d.0).collect()),
        overshoot: per_pixel.iter().filter(|p| p.2.is_some()).count() as f64 / n,
        overshoot_cone: per_pixel.iter().filter(|p| p.2 == Some(true)).count() as f64 / n,
        normal: Spread::of(per_pixel.iter().filter_map(|p| p.1.map(|n| n.0)).collect()),
        normal_cone: Spread::of(per_pixel.iter().filter_map(|p| p.1.map(|n| n.1)).collect()),
        normal_measured: per_pixel.iter().filter(|p| p.1.is_some()).count() as f64
            / per_pixel.iter().filter(|p| p.0.is_some()).count().max(1) as f64,
        non_finite,
        out_of_steps: traces.iter().filter(|r| r.out_of_steps).count() as f64 / n,
        false_misses_out_of_steps: traces
            .iter()
            .zip(&truth.pixels)
            .filter(|(r, t)| !r.hit && r.out_of_steps && t.hit())
            .count() as f64
            / n,
        evaluations_per_pixel: traces
            .iter()
            .map(|r| r.evaluations.map(|e| e as f64))
            .sum::<Option<f64>>()
            .map(|e| e / n),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::truth::TruthSettings;
    use fractal_dsl::builder::*;
    use fractal_dsl::eval::interp::Interpreter;
    use fractal_render::backend::cpu::trace_scene;
    use fractal_render::frame::Frame;

    #[test]
    fn the_normal_samples_are_the_pixels_measure_judges_normals_on() {
        let s = scene(sphere(1.0).translate(vec3(0.2, -0.1, 0.3))).camera(camera([0.0, 0.5, -3.0], [0.0; 3]).fov(50.0));
        let f = Frame::default_view(&s, 0.0, 40, 30).unwrap();
        let truth = Truth::compute(&s, &f, TruthSettings::default()).unwrap();
        let traces = trace_scene::<f32, _>(&Interpreter::new(&s).unwrap(), &s, &f).unwrap();
        let traced = measure(&s, &truth, Observed::Traced(&traces)).traced.unwrap();
        let samples = normal_samples(&truth, &traces);
        let both = traces.iter().zip(&truth.pixels).filter(|(r, t)| r.hit && t.hit()).count();
        assert_eq!(samples.len(), (traced.normal_measured * both as f64).round() as usize);
        assert!(samples.len() > 100, "{} samples", samples.len());
        assert_eq!(Spread::of(samples.iter().map(|s| s.centre).collect()), traced.normal);
        for s in &samples {
            // The truth's hit, from the sample's ray, lies on the sphere.
            let (o, d) = s.ray;
            let p: Vec<f64> = (0..3).map(|i| o[i] + d[i] * s.t_truth).collect();
            let r = ((p[0] - 0.2).powi(2) + (p[1] + 0.1).powi(2) + (p[2] - 0.3).powi(2)).sqrt();
            assert!((r - 1.0).abs() < 1e-9, "pixel ({}, {}): {r}", s.x, s.y);
            assert!((angle_degrees(s.render_normal, s.true_normal) - s.centre).abs() < 1e-9);
        }
        // The render's normals given back are judged as measure judged them, and the truth's own are 0° off.
        let given: Vec<(u32, u32, [f64; 3])> = samples.iter().map(|s| (s.x, s.y, s.render_normal)).collect();
        assert_eq!(judge_normals(&truth, &given), (traced.normal, traced.normal_cone));
        let exact: Vec<(u32, u32, [f64; 3])> = samples.iter().map(|s| (s.x, s.y, s.true_normal)).collect();
        let (centre, cone) = judge_normals(&truth, &exact);
        assert!(centre.count == samples.len() && centre.max < 1e-6 && cone.max < 1e-6, "{centre:?}");
        let csv = normal_samples_csv(&samples);
        assert_eq!(csv.lines().count(), samples.len() + 1);
        assert!(csv.lines().all(|l| l.split(',').count() == 19));
    }
}
