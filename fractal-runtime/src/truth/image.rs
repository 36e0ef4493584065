//! The truth of an image: the colour each pixel should have, not the geometry at its centre.
//!
//! A pixel's displayed value is the scene's display encoding ([`fractal_dsl::ray::shade::display`]) of the
//! box-filtered mean, over the pixel's square [x, x+1) × [y, y+1), of the linear colour clamped to [0, 1] per sample.
//! This module estimates that integral with the truth's own rays ([`Truth`]): an n×n lattice of sub-rays through the
//! centres of an n×n grid of cells in the pixel (stratified), each sub-ray's first crossing by the truth's march, its
//! normal from the exact gradient where the surface is exact and else from the crossings of its lattice neighbours
//! (the truth depth's gradient at the sub-pixel scale), shaded by the renderer's own shading in f64 with the scene's
//! lights, shadows, occlusion and fog, at the point along the sub-ray where the renderer would stop on that crossing
//! (the reasons are at `shading_depth`). Glow is left out, as in [`Truth`].
//!
//! **Settled.** A pixel's estimate has settled when the standard error of the mean of its sub-rays' display luma
//! (Rec. 601 weights, in 8-bit levels; the spread of the samples over √count, which overstates a stratified
//! estimate's error) is at most [`ImageTruthSettings::settle`]; until then the lattice doubles per side, a fresh
//! lattice each time, up to [`ImageTruthSettings::max_grid`]. Pixels an edge crosses end at the largest lattice.
//!
//! **Pixel normal.** The normalised mean of the hit sub-rays' unit normals where at least [`COVERED`] of the pixel's
//! sub-rays hit; none elsewhere (a pixel mostly of background has no one surface to judge a normal against).

use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::number::math::{cross, dot, length, v3, V3};
use fractal_dsl::ray::rules::Rules;
use fractal_dsl::ray::scene::SceneFns;
use fractal_dsl::ray::shade::display;
use fractal_dsl::Scene;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::{pack_linear, Image};
use rayon::prelude::*;

use super::{Truth, TruthSettings, NORMAL_OFFSET, NORMAL_WINDOW};
use crate::quality::with_iterations_scaled;

/// Sub-rays per side of the first lattice.
pub const DEFAULT_GRID: u32 = 4;
/// Sub-rays per side of the finest lattice a pixel refines to.
pub const DEFAULT_MAX_GRID: u32 = 8;
/// Largest standard error of a pixel's mean display luma, in 8-bit levels, at which its estimate has settled.
pub const DEFAULT_SETTLE: f64 = 1.0;
/// Share of a pixel's sub-rays that must hit for the pixel to have an integrated normal.
pub const COVERED: f64 = 0.5;
/// The largest lattice a setting may ask for, per side.
pub const LARGEST_GRID: u32 = 64;

/// Rec. 601 luma weights, on display values: what [`DEFAULT_SETTLE`] and the image metrics' SSIM read.
pub const LUMA: [f64; 3] = [0.299, 0.587, 0.114];

/// How the image truth is computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageTruthSettings {
    /// Sub-rays per side of the first lattice (at least 2: a sub-ray's normal takes a lattice neighbour).
    pub grid: u32,
    /// Sub-rays per side of the finest lattice; the lattice doubles per side from `grid` while it fits.
    pub max_grid: u32,
    /// Largest standard error of the mean display luma, in 8-bit levels, of a settled pixel.
    pub settle: f64,
    /// The march of each sub-ray.
    pub truth: TruthSettings,
}

impl Default for ImageTruthSettings {
    fn default() -> Self {
        ImageTruthSettings {
            grid: DEFAULT_GRID,
            max_grid: DEFAULT_MAX_GRID,
            settle: DEFAULT_SETTLE,
            truth: TruthSettings::default(),
        }
    }
}

impl ImageTruthSettings {
    /// Why these settings cannot make an image truth, if they cannot.
    pub fn check(&self) -> Result<(), String> {
        if !(2..=LARGEST_GRID).contains(&self.grid) {
            return Err(format!("the image truth's grid is 2 to {LARGEST_GRID} sub-rays per side, got {}", self.grid));
        }
        if !(self.grid..=LARGEST_GRID).contains(&self.max_grid) {
            return Err(format!(
                "the image truth's largest grid is {} (its first) to {LARGEST_GRID} sub-rays per side, got {}",
                self.grid, self.max_grid
            ));
        }
        if !(self.settle.is_finite() && self.settle >= 0.0) {
            return Err(format!("the settle threshold is a number of 8-bit levels ≥ 0, got {}", self.settle));
        }
        Ok(())
    }
}

/// Why an image truth could not be computed.
#[derive(Debug, thiserror::Error)]
pub enum ImageTruthError {
    /// The settings ask for what cannot be computed ([`ImageTruthSettings::check`]).
    #[error("{0}")]
    Settings(String),
    #[error(transparent)]
    Render(#[from] RenderError),
}

/// The truth of one pixel's value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageTruthPixel {
    /// Box-filtered mean of the sub-rays' linear colours, each clamped to [0, 1].
    pub linear: [f64; 3],
    /// `linear` in the scene's display encoding, in [0, 1].
    pub display: [f64; 3],
    /// Share of the sub-rays that hit the scene.
    pub coverage: f64,
    /// The pixel-integrated true normal (facing the camera) where `coverage` ≥ [`COVERED`].
    pub normal: Option<[f64; 3]>,
    /// Sub-rays per side of the lattice the estimate comes from.
    pub grid: u32,
    /// Whether the estimate met the settle threshold (else it stopped at the largest lattice).
    pub settled: bool,
}

/// The truth of every pixel's value of one frame.
pub struct ImageTruth {
    pub width: u32,
    pub height: u32,
    pub settings: ImageTruthSettings,
    /// The scene's display gamma.
    pub gamma: f64,
    /// Row-major.
    pub pixels: Vec<ImageTruthPixel>,
}

/// One sub-ray of a lattice: where it starts and goes, and its first crossing.
struct SubRay {
    px: f64,
    py: f64,
    origin: V3<f64>,
    direction: V3<f64>,
    t: Option<f64>,
}

impl SubRay {
    fn point(&self) -> Option<V3<f64>> {
        self.t.map(|t| self.origin + self.direction * t)
    }
}

impl ImageTruth {
    /// Computes the truth of the image of `scene` seen through `frame`.
    pub fn compute(scene: &Scene, frame: &Frame, settings: ImageTruthSettings) -> Result<ImageTruth, ImageTruthError> {
        settings.check().map_err(ImageTruthError::Settings)?;
        let scene = with_iterations_scaled(scene, settings.truth.iteration_factor);
        let truth = Truth::unfilled(&scene, frame, settings.truth)?;
        let shading = fractal_dsl::lower::tape::interpreter(&scene).map_err(RenderError::from)?;
        let rules = Rules::with_bound(&scene, None);
        let width = frame.width();
        let pixels = (0..width * frame.height())
            .into_par_iter()
            .map(|i| truth.image_pixel(&shading, &rules, &settings, i % width, i / width))
            .collect();
        Ok(ImageTruth { width, height: frame.height(), settings, gamma: scene.settings.gamma, pixels })
    }

    pub fn at(&self, x: u32, y: u32) -> &ImageTruthPixel {
        &self.pixels[(y * self.width + x) as usize]
    }

    /// The truth as an 8-bit image, each pixel's linear value packed as the renderers pack theirs (clamp, the
    /// scene's gamma, round): what a perfect render of the scene would write.
    pub fn image(&self) -> Image {
        let pixels = self.pixels.iter().map(|p| pack_linear(v3(p.linear[0], p.linear[1], p.linear[2]), self.gamma));
        Image { width: self.width, height: self.height, pixels: pixels.collect() }
    }

    /// Mean sub-rays per pixel.
    pub fn mean_sub_rays(&self) -> f64 {
        let total: f64 = self.pixels.iter().map(|p| (p.grid * p.grid) as f64).sum();
        total / self.pixels.len().max(1) as f64
    }

    /// Share of the pixels whose estimate did not settle within the largest lattice.
    pub fn unsettled(&self) -> f64 {
        self.pixels.iter().filter(|p| !p.settled).count() as f64 / self.pixels.len().max(1) as f64
    }
}

/// The luma of a display colour, in [0, 1].
pub fn luma(c: [f64; 3]) -> f64 {
    LUMA[0] * c[0] + LUMA[1] * c[1] + LUMA[2] * c[2]
}

/// A linear colour clamped to [0, 1] per channel, NaN to 0 (as [`pack_linear`] clamps).
fn clamp01(c: V3<f64>) -> [f64; 3] {
    [c.x, c.y, c.z].map(|v| if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) })
}

impl Truth {
    /// The image truth of pixel (x, y): lattices from `settings.grid` up until the estimate settles.
    fn image_pixel(
        &self,
        shading: &Interpreter,
        rules: &Rules,
        settings: &ImageTruthSettings,
        x: u32,
        y: u32,
    ) -> ImageTruthPixel {
        let mut grid = settings.grid;
        loop {
            let (pixel, error) = self.lattice_pixel(shading, rules, x, y, grid);
            let settled = error <= settings.settle;
            if settled || grid * 2 > settings.max_grid {
                return ImageTruthPixel { settled, ..pixel };
            }
            grid *= 2;
        }
    }

    /// Pixel (x, y) from a `grid`×`grid` lattice of sub-rays, and the standard error of its mean display luma in
    /// 8-bit levels.
    fn lattice_pixel(&self, shading: &Interpreter, rules: &Rules, x: u32, y: u32, grid: u32) -> (ImageTruthPixel, f64) {
        let n = grid as usize;
        let spacing = 1.0 / grid as f64;
        let rays: Vec<SubRay> = (0..n * n)
            .map(|k| {
                let px = x as f64 + ((k % n) as f64 + 0.5) * spacing;
                let py = y as f64 + ((k / n) as f64 + 0.5) * spacing;
                let (origin, direction) = self.view.ray(px, py);
                SubRay { px, py, origin, direction, t: self.first_hit(px, py) }
            })
            .collect();
        let on = self.view.on(shading);
        let background = self.view.background();
        let (mut sum, mut normal_sum, mut hits) = ([0.0; 3], v3(0.0, 0.0, 0.0), 0usize);
        let mut lumas = Vec::with_capacity(n * n);
        for (k, ray) in rays.iter().enumerate() {
            let colour = match ray.t {
                Some(t) => {
                    let nrm = self.sub_ray_normal(&rays, n, k, spacing).unwrap_or(-ray.direction);
                    normal_sum = normal_sum + nrm;
                    hits += 1;
                    let s = self.shading_depth(&on, ray, t);
                    let q = ray.origin + ray.direction * s;
                    self.view.shade_hit(&on, q, nrm, ray.direction, s, self.view.hit_epsilon(s))
                }
                _ => background,
            };
            let c = clamp01(colour);
            for (s, v) in sum.iter_mut().zip(c) {
                *s += v;
            }
            let shown = display(rules, v3(c[0], c[1], c[2]));
            lumas.push(255.0 * luma([shown.x, shown.y, shown.z]));
        }
        let count = (n * n) as f64;
        let linear = sum.map(|s| s / count);
        let shown = display(rules, v3(linear[0], linear[1], linear[2]));
        let coverage = hits as f64 / count;
        let len = length(normal_sum);
        let normal = (coverage >= COVERED && len > 0.0).then(|| {
            let m = normal_sum / len;
            [m.x, m.y, m.z]
        });
        let pixel =
            ImageTruthPixel { linear, display: [shown.x, shown.y, shown.z], coverage, normal, grid, settled: true };
        (pixel, standard_error(&lumas))
    }

    /// Where along `ray` the hit at its true crossing `t` is shaded: the renderer shades a hit where the scene's
    /// estimate has fallen to its hit epsilon, and its shadow rays and occlusion read the estimate from there; at the
    /// true crossing of a fractal the estimate is 0 (every escape-time estimate is, on the set), which would shade
    /// every such hit as fully shadowed and occluded. So the hit is shaded where the ray, backed off from `t`
    /// towards the camera, first meets the f64 estimate at the hit epsilon (bisected); where that lies more than
    /// [`NORMAL_WINDOW`] footprints in front, at `t` itself.
    fn shading_depth<S: SceneFns<f64>>(&self, on: &S, ray: &SubRay, t: f64) -> f64 {
        let eps = self.view.hit_epsilon(t);
        let estimate = |back: f64| on.distance(ray.origin + ray.direction * (t - back));
        if estimate(0.0) >= eps {
            return t;
        }
        let limit = (NORMAL_WINDOW * self.footprint_at(t)).min(t);
        let (mut inside, mut outside) = (0.0, eps);
        while estimate(outside) < eps {
            inside = outside;
            outside *= 2.0;
            if outside > limit {
                return t;
            }
        }
        for _ in 0..40 {
            let mid = 0.5 * (inside + outside);
            if estimate(mid) >= eps {
                outside = mid;
            } else {
                inside = mid;
            }
        }
        t - outside
    }

    /// The unit normal, facing the camera, of lattice sub-ray `k` (a hit) of an `n`×`n` lattice `spacing` pixels
    /// apart: the exact gradient where the surface is exact; else the cross product of the surface's differences to
    /// its lattice neighbours across x and y (central where both sides continue the surface about equally, else the
    /// nearer side; a neighbour continues it when its crossing lies within the window the truth's normal allows,
    /// scaled to the spacing); else from rays `spacing` away searched within that window ([`Truth::normal`]).
    fn sub_ray_normal(&self, rays: &[SubRay], n: usize, k: usize, spacing: f64) -> Option<V3<f64>> {
        let ray = &rays[k];
        let (t, centre) = (ray.t?, ray.point()?);
        if let Some(g) = self.exact_normal(centre, ray.direction, t) {
            return Some(v3(g[0], g[1], g[2]));
        }
        let window = NORMAL_WINDOW * spacing / NORMAL_OFFSET * self.footprint_at(t);
        let (i, j) = ((k % n) as isize, (k / n) as isize);
        let at = |di: isize, dj: isize| -> Option<V3<f64>> {
            let (a, b) = (i + di, j + dj);
            if a < 0 || b < 0 || a >= n as isize || b >= n as isize {
                return None;
            }
            let other = &rays[b as usize * n + a as usize];
            other.t.filter(|&u| (u - t).abs() <= window)?;
            other.point()
        };
        let across = |minus: Option<V3<f64>>, plus: Option<V3<f64>>| -> Option<V3<f64>> {
            let gap = |q: V3<f64>| length(q - centre);
            match (minus, plus) {
                (Some(m), Some(p)) if gap(m) < 2.0 * gap(p) && gap(p) < 2.0 * gap(m) => Some(p - m),
                (Some(m), Some(p)) if gap(m) < gap(p) => Some(centre - m),
                (Some(_), Some(p)) | (None, Some(p)) => Some(p - centre),
                (Some(m), None) => Some(centre - m),
                (None, None) => None,
            }
        };
        let lattice = across(at(-1, 0), at(1, 0)).zip(across(at(0, -1), at(0, 1))).and_then(|(dx, dy)| {
            let m = cross(dx, dy);
            let len = length(m);
            (len.is_finite() && len > 0.0).then(|| m / len)
        });
        let m = match lattice {
            Some(m) => m,
            None => {
                let (m, _) = self.normal(ray.px, ray.py, t, spacing)?;
                v3(m[0], m[1], m[2])
            }
        };
        Some(if dot(m, ray.direction) > 0.0 { -m } else { m })
    }
}

/// The standard error of the mean of `values`: their sample standard deviation over √count (0 for fewer than two).
fn standard_error(values: &[f64]) -> f64 {
    let n = values.len() as f64;
    if values.len() < 2 {
        return 0.0;
    }
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (n - 1.0);
    (var / n).sqrt()
}
