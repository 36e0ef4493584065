//! The truth's answers about a pixel's cone rather than its centre ray: whether any ray of the pixel meets the scene,
//! whether any passes a depth unobstructed, how far a render's stop lies from what the pixel sees, and how far its
//! normal lies from the normals the surface takes across the pixel. The metrics ([`crate::accuracy::metrics`]) judge
//! false hits, overshoot, depth and normals with them, so a render is not called wrong for an answer some part of the
//! pixel supports.

use super::{angle_degrees, Truth};

/// Spacing of the sub-rays whose normals make a pixel's normal cone, in pixels: a 3×3 lattice a quarter pixel apart
/// reaches half a pixel from the centre with the normals' own rays that far around each.
pub const CONE_NORMAL_SPACING: f64 = 0.25;

impl Truth {
    /// Pixel-cone consistency of a render's normal `n` at pixel (x, y), a truth hit: the smallest angle, in degrees,
    /// between `n` and the true surface's normals across the pixel's footprint — the centre's, and those of the
    /// surface where the sub-rays [`CONE_NORMAL_SPACING`] pixels apart on a 3×3 lattice around the centre meet it,
    /// each from rays that far around it. A pixel shades one normal for all it covers, and the surface under it turns
    /// by up to [`ROUGH_DEGREES`](super::ROUGH_DEGREES) where it counts as smooth, so any normal the surface takes
    /// within the pixel is as right as the centre's; `None` when no sub-ray finds a normal. Computed once per pixel and
    /// kept.
    pub fn cone_normal_error(&self, x: u32, y: u32, n: [f64; 3]) -> Option<f64> {
        let index = (y * self.width + x) as usize;
        let normals = self.cone_normals[index].get_or_init(|| self.normals_across(x, y));
        normals.iter().map(|&m| angle_degrees(n, m)).min_by(f64::total_cmp)
    }

    /// The true normals across pixel (x, y)'s footprint (see [`Truth::cone_normal_error`]).
    fn normals_across(&self, x: u32, y: u32) -> Vec<[f64; 3]> {
        let centre = self.at(x, y);
        let (cx, cy) = (x as f64 + 0.5, y as f64 + 0.5);
        let d = CONE_NORMAL_SPACING;
        let mut normals: Vec<[f64; 3]> = centre.normal.into_iter().collect();
        for j in -1..=1 {
            for i in -1..=1 {
                let (px, py) = (cx + i as f64 * d, cy + j as f64 * d);
                let Some(q) = self.neighbour(px, py, centre.t) else { continue };
                let (ro, rd) = self.view.ray(px, py);
                let t = fractal_dsl::number::math::dot(q - ro, rd);
                let normal = self.exact_normal(q, rd, t).or_else(|| self.normal(px, py, t, d).map(|(n, _)| n));
                normals.extend(normal);
            }
        }
        normals
    }

    /// Whether some ray of pixel (x, y)'s cone meets the scene (sub-rays on a `grid`×`grid` lattice across the pixel,
    /// each marched as the truth marches): a render that hits where the centre ray misses has then found part of what
    /// the pixel covers, as a ray that stops on a filament it passes a tenth of a footprint from. Computed once per
    /// pixel and kept, as every render of a sweep asks about the same silhouette pixels.
    pub fn cone_sees_scene(&self, x: u32, y: u32, grid: u32) -> bool {
        let index = (y * self.width + x) as usize;
        *self.cone_sees[index].get_or_init(|| {
            (0..grid * grid).any(|k| {
                let (px, py) = sub_pixel(x, y, k, grid);
                self.first_hit(px, py).is_some()
            })
        })
    }

    /// Whether some ray of pixel (x, y)'s cone (sub-rays on a `grid`×`grid` lattice across the pixel, each marched as
    /// the truth marches) meets none of the scene before `t`: a render that went on to `t` past the centre ray's hit
    /// has then passed through a feature narrower than the pixel, and drawn what the rest of the pixel sees.
    pub fn cone_sees_past(&self, x: u32, y: u32, t: f64, grid: u32) -> bool {
        (0..grid * grid).any(|k| {
            let (px, py) = sub_pixel(x, y, k, grid);
            self.with_ray(px, py, |ray| ray.first_crossing(0.0, t, |t| self.step(t)).is_none())
        })
    }

    /// Pixel-cone consistency of a render that stopped at depth `t` in pixel (x, y): the smallest depth difference,
    /// in footprints, between `t` and a point of the scene inside the pixel's cone within `window` footprints of `t`
    /// (sampled every `step_footprints` along the cone, never finer than the truth's own step, at `samples` points
    /// across the pixel at each depth); `None` when the cone holds none of the scene there.
    ///
    /// The points across the pixel move on with every depth (a low-discrepancy sequence), so together they fill the
    /// cone's volume: points on fixed sub-rays would sample it on a few lines only, and a filament thinner than their
    /// spacing that runs between them — the hair of an escape-time set, which the render's estimate sees — would be
    /// called missing however finely each line is sampled. Depths are taken outward from `t` on both sides, so the
    /// first point found is the nearest and ends the search: a render that stopped on the scene costs a few samples,
    /// and only one the pixel's cone does not explain pays for the whole window.
    pub fn cone_error(&self, x: u32, y: u32, t: f64, window: f64, samples: u32, step_footprints: f64) -> Option<f64> {
        let foot = self.footprint_at(t);
        let step = step_footprints.max(self.settings.step_footprints) * foot;
        let depths = (window * foot / step).ceil() as u64;
        let env = self.env();
        let inside = |n: u64, s: f64| {
            let (u, v) = cone_point(n);
            let (ro, rd) = self.view.ray(x as f64 + u, y as f64 + v);
            let p = ro + rd * s;
            self.membership.value([p.x, p.y, p.z], &env) <= 0.0
        };
        let per_depth = samples as u64;
        (0..=depths).find_map(|k| {
            let seen = [t - k as f64 * step, t + k as f64 * step].iter().enumerate().any(|(side, &s)| {
                let first = (2 * k + side as u64) * per_depth;
                s >= 0.0 && (first..first + per_depth).any(|n| inside(n, s))
            });
            seen.then_some(k as f64 * step / foot)
        })
    }
}

/// Point `n` of a low-discrepancy sequence over the pixel, edge to edge (the R2 sequence, Roberts 2018: any run of
/// consecutive points spreads evenly over the square), as an offset from the pixel's corner.
fn cone_point(n: u64) -> (f64, f64) {
    // 1/φ₂ and 1/φ₂², φ₂ the plastic number.
    const A: (f64, f64) = (0.754_877_666_246_692_7, 0.569_840_290_998_053_2);
    ((0.5 + n as f64 * A.0).fract(), (0.5 + n as f64 * A.1).fract())
}

/// The image position of sub-ray `k` of pixel (x, y) on a `grid`×`grid` lattice across the pixel, edge to edge: the
/// pixel's cone reaches half a pixel from its centre, as far as a half-pixel hit epsilon finds the surface (a lattice
/// of cell centres, a third of a pixel out at 3×3, would call that surface outside the pixel).
pub(super) fn sub_pixel(x: u32, y: u32, k: u32, grid: u32) -> (f64, f64) {
    let at = |i: u32| if grid > 1 { i as f64 / (grid - 1) as f64 } else { 0.5 };
    (x as f64 + at(k % grid), y as f64 + at(k / grid))
}
