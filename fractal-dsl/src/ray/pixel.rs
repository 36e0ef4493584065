//! Step 1 over a pixel's area, and step 7's mean: where a pixel's samples go in the pixel and on the lens, how
//! their colours add up, when an adaptive pixel takes more, and the pixel's value. Every renderer draws a pixel
//! with [`first_pass`] and [`refine`] (or, scheduling its rays otherwise, with these same steps in the same order),
//! so the CPU and the kernels take the same samples and stop at the same count.
//!
//! **Value.** A pixel's value is the box-filtered mean over its square of the linear colour clamped to [0, 1], then
//! displayed (step 7). Sample 0 is the ray through the pixel's centre (and the lens's): with one sample a render is
//! the one-ray render, and the march of sample 0 is the pixel's trace (depth, normal, steps).
//!
//! **Positions.** Sample 0 is the centre; samples 1–4 the rotated grid (one in each quarter of the pixel, no two in
//! a row or column of a 4×4 grid), so the first batch sees a feature in any quarter; then the points of Roberts'
//! R2 sequence, fract(½ + j·α) for j = 1, 2, … (R4 with a lens: two more dimensions for the lens, fract(k·α₃,₄) for
//! every sample). Every prefix of it is spread evenly, so a pixel that stops early has still sampled its whole
//! square. The lens point is mapped to the disc by r = a·√u, θ = 2πv.
//!
//! **Two passes.** The first pass draws every pixel's centre ray ([`first_pass`]); with one sample that is the
//! image. Where the scene takes more, a second pass ([`refine`]) reads the first pass's displayed colours of the pixel
//! and its eight neighbours: a pixel whose display luma differs from a neighbour's by more than [`CONTRAST`] times the
//! scene's threshold takes a first batch of [`FIRST`] samples (counting the centre), then batches of [`BATCH`] while
//! the standard error of its mean display luma (√ of the clamped colour's luma) is above the threshold, up to its
//! most samples. The others keep their one ray: a region the centres see as flat costs one ray a pixel. With a lens
//! every pixel refines, since the first pass is the pinhole's sharp image and cannot show where the blur spreads. The
//! centre's sample in the mean is the first pass's displayed colour decoded ([`undisplay`]), 8 bits deep, which is
//! what every renderer keeps of it between the passes.

use super::march;
use super::rules::{Lens, Rules, View};
use super::scene::SceneFns;
use super::shade::{self, Shaded};
use crate::number::math::{length, normalize, v3, V3};
use crate::number::{Mask, Num};

/// Samples in a pixel's first batch: the centre and the rotated grid (one in each quarter of the pixel).
pub const FIRST: u32 = 5;
/// Samples between a pixel's later decisions to take more.
pub const BATCH: u32 = 4;
/// The rotated grid's points in the pixel, samples 1–4.
const ROTATED_GRID: [[f64; 2]; 4] = [[0.375, 0.125], [0.875, 0.375], [0.625, 0.875], [0.125, 0.625]];
/// The plastic number, R2's generator: the real root of x³ = x + 1.
const PLASTIC: f64 = 1.324_717_957_244_746;
/// R4's generator: the real root of x⁵ = x + 1.
const R4_ROOT: f64 = 1.167_303_978_261_418_7;
/// Rec. 709 luma weights, for the adaptive tests.
const LUMA: [f64; 3] = [0.2126, 0.7152, 0.0722];
/// A pixel refines where its display luma and a neighbour's differ by more than this many times the scene's sample
/// threshold (the difference a pixel straddling the two would show across its samples).
pub const CONTRAST: f64 = 4.0;

/// Sample `k`'s point in the pixel (from its top left corner, in [0, 1)²) and on the lens (in [0, 1)², (0, 0) at
/// sample 0: the lens's centre). Samples 1–4 are the rotated grid, each in its own quarter of the pixel; later ones
/// follow the R2 sequence (R4 with a lens) from its first point on.
#[inline(always)]
pub fn sample_point<N: Num>(k: N, lens: bool) -> ([N; 2], [N; 2]) {
    let fract = |x: N| x - N::floor(x);
    let half = N::lit(0.5);
    // The rotated grid: (−1/8, −3/8) from the centre, turned by a quarter turn per sample.
    let grid = |i: usize| {
        let pick = |v: [f64; 4]| {
            let at = |j: usize| N::lit(v[j]);
            N::select(
                N::lt(k, N::lit(1.5)),
                at(0),
                N::select(N::lt(k, N::lit(2.5)), at(1), N::select(N::lt(k, N::lit(3.5)), at(2), at(3))),
            )
        };
        pick(ROTATED_GRID.map(|p| p[i]))
    };
    let in_grid = N::lt(k, N::lit(f64::from(FIRST) - 0.5));
    let after = k - N::lit(f64::from(FIRST - 1));
    let (sequence, on_lens) = if lens {
        let a = |i: i32| N::lit(R4_ROOT.powi(-i));
        ([fract(half + after * a(1)), fract(half + after * a(2))], [fract(k * a(3)), fract(k * a(4))])
    } else {
        let a = [1.0 / PLASTIC, 1.0 / (PLASTIC * PLASTIC)].map(N::lit);
        ([fract(half + after * a[0]), fract(half + after * a[1])], [N::lit(0.0); 2])
    };
    let centre = N::lt(k, half);
    let at = |i: usize| N::select(centre, half, N::select(in_grid, grid(i), sequence[i]));
    ([at(0), at(1)], on_lens)
}

/// Step 1 for a sample: the ray through the image point (px, py) and, with a lens, from the lens point `on_lens` (in
/// [0, 1)²) through the point the pinhole ray meets the plane of focus.
#[inline(always)]
pub fn camera_ray<N: Num>(rules: &Rules, view: &View<N>, px: N, py: N, on_lens: [N; 2]) -> (V3<N>, V3<N>) {
    let Some(lens) = rules.lens else { return view.ray(px, py) };
    let two = N::lit(2.0);
    let u = (two * px - view.width) / view.height;
    let v = -(two * py - view.height) / view.height;
    // The direction with unit forward component reaches the plane of focus at t = focus along it.
    let through = view.forward + view.right * u + view.up * v;
    let focal = view.origin + through * N::lit(lens.focus);
    let [x, y] = lens_point(&lens, on_lens);
    let (right, up) = (view.right / length(view.right), view.up / length(view.up));
    let origin = view.origin + right * x + up * y;
    (origin, normalize(focal - origin))
}

/// The point of the lens for `on_lens` in [0, 1)²: its offset from the camera along the image's right and up axes, in
/// scene units (r = aperture·√u, θ = 2πv).
#[inline(always)]
pub fn lens_point<N: Num>(lens: &Lens, on_lens: [N; 2]) -> [N; 2] {
    let r = N::lit(lens.aperture) * N::sqrt(on_lens[0]);
    let angle = N::lit(std::f64::consts::TAU) * on_lens[1];
    [r * N::cos(angle), r * N::sin(angle)]
}

/// A pixel's samples so far: the sums of their clamped colours, of their display luma and its square, and their
/// count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Accumulated<N> {
    pub colour: V3<N>,
    pub luma: N,
    pub luma_squared: N,
    pub count: N,
}

impl<N: Num> Accumulated<N> {
    /// No samples.
    pub fn empty() -> Accumulated<N> {
        let zero = N::lit(0.0);
        Accumulated { colour: V3::splat(zero), luma: zero, luma_squared: zero, count: zero }
    }

    /// With one more sample of linear colour `colour` (clamped to [0, 1]; a NaN stays NaN, so a broken sample shows).
    #[inline(always)]
    pub fn with(self, colour: V3<N>) -> Accumulated<N> {
        let c = clamped(colour);
        let y = luma(c);
        Accumulated {
            colour: self.colour + c,
            luma: self.luma + y,
            luma_squared: self.luma_squared + y * y,
            count: self.count + N::lit(1.0),
        }
    }

    /// The pixel's value before display: the mean of its samples.
    #[inline(always)]
    pub fn mean(&self) -> V3<N> {
        self.colour / self.count
    }

    /// Whether a pixel with these samples (at least one) takes another: within a batch always (the first is
    /// [`FIRST`] samples, then [`BATCH`]), at a batch's end while the standard error of the mean luma is above the
    /// threshold (var/n > threshold², with the unbiased variance). The caller bounds the count.
    #[inline(always)]
    pub fn wants_more(&self, rules: &Rules) -> N::Mask {
        let n = self.count;
        let (first, batch) = (N::lit(f64::from(FIRST)), N::lit(f64::from(BATCH)));
        let later = n - first;
        let within_batch = N::lt(n, first) | N::lt(N::lit(0.0), later - batch * N::floor(later / batch));
        let mean = self.luma / n;
        let variance = (self.luma_squared - self.luma * mean) / (n - N::lit(1.0));
        let limit = N::lit(rules.sampling.threshold * rules.sampling.threshold) * n;
        within_batch | N::lt(limit, variance)
    }
}

impl<N: Num> crate::number::Carry<N> for Accumulated<N> {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(N) -> N) -> Self {
        Accumulated {
            colour: v3(f(self.colour.x), f(self.colour.y), f(self.colour.z)),
            luma: f(self.luma),
            luma_squared: f(self.luma_squared),
            count: f(self.count),
        }
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(N, N) -> N) -> Self {
        Accumulated {
            colour: v3(f(self.colour.x, o.colour.x), f(self.colour.y, o.colour.y), f(self.colour.z, o.colour.z)),
            luma: f(self.luma, o.luma),
            luma_squared: f(self.luma_squared, o.luma_squared),
            count: f(self.count, o.count),
        }
    }
}

/// A pixel's first pass: its centre ray's march and shading (the pixel's trace, and with one sample its value).
#[derive(Clone, Copy, Debug)]
pub struct Drawn<N: Num> {
    pub centre: march::March<N>,
    /// Whether the centre ray entered the scene's bound.
    pub enters: N::Mask,
    pub shaded: Shaded<N>,
}

/// A linear colour clamped to [0, 1] (a NaN stays NaN, so a broken sample shows).
#[inline(always)]
fn clamped<N: Num>(colour: V3<N>) -> V3<N> {
    let (zero, one) = (N::lit(0.0), N::lit(1.0));
    colour.map(|c| N::select(N::lt(c, zero), zero, N::select(N::lt(one, c), one, c)))
}

/// The display luma of a clamped linear colour: √ of its Rec. 709 luma.
#[inline(always)]
pub fn luma<N: Num>(c: V3<N>) -> N {
    N::sqrt(c.x * N::lit(LUMA[0]) + c.y * N::lit(LUMA[1]) + c.z * N::lit(LUMA[2]))
}

/// A displayed colour (channels in [0, 1], as the first pass packed them) back in linear light: the inverse of
/// [`shade::display`] on colours it has clamped.
#[inline(always)]
pub fn undisplay<N: Num>(rules: &Rules, shown: V3<N>) -> V3<N> {
    if rules.gamma == 2.0 {
        shown * shown
    } else if rules.gamma == 1.0 {
        shown
    } else {
        let e = N::lit(rules.gamma);
        shown.map(|c| N::pow(c, e))
    }
}

/// The display luma of a first pass's displayed colour (channels in [0, 1]): [`luma`] of its [`undisplay`].
#[inline(always)]
pub fn shown_luma<N: Num>(rules: &Rules, shown: V3<N>) -> N {
    luma(undisplay(rules, shown))
}

/// Whether a pixel takes more samples in the second pass, from the display lumas ([`shown_luma`]) of the first
/// pass's colours of the pixel and of its eight neighbours (a neighbour outside the image is the nearest pixel
/// inside it).
#[inline(always)]
pub fn refines<N: Num>(rules: &Rules, centre: N, neighbours: [N; 8]) -> N::Mask {
    if rules.lens.is_some() {
        return N::Mask::splat(true);
    }
    let limit = N::lit(CONTRAST * rules.sampling.threshold);
    neighbours.into_iter().fold(N::Mask::splat(false), |m, n| m | N::lt(limit, N::abs(n - centre)))
}

/// Steps 1–6 for sample `k` of the pixel whose top left corner is (x, y): its ray, march and shading.
#[inline(always)]
pub fn sample<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    view: &View<N>,
    scene: &S,
    (x, y): (N, N),
    k: N,
) -> (march::March<N>, N::Mask, Shaded<N>) {
    let ([dx, dy], on_lens) = sample_point(k, rules.lens.is_some());
    trace_ray(rules, view, scene, camera_ray(rules, view, x + dx, y + dy, on_lens))
}

/// Steps 2–6 along the unit ray (ro, rd): the march, whether the ray entered the bound, and the shading (which a
/// ray outside the bound, taking no step, shades as the background).
#[inline(always)]
fn trace_ray<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    view: &View<N>,
    scene: &S,
    (ro, rd): (V3<N>, V3<N>),
) -> (march::March<N>, N::Mask, Shaded<N>) {
    let (m, enters) = march::march(rules, view, scene, ro, rd);
    (m, enters, shade::shade(rules, view, scene, (ro, rd), &m))
}

/// The first pass of the pixel whose top left corner is (x, y): sample 0, the ray through its centre (and the
/// lens's: the pinhole's ray).
#[inline(always)]
pub fn first_pass<N: Num, S: SceneFns<N>>(rules: &Rules, view: &View<N>, scene: &S, x: N, y: N) -> Drawn<N> {
    let half = N::lit(0.5);
    let (centre, enters, shaded) = trace_ray(rules, view, scene, view.ray(x + half, y + half));
    Drawn { centre, enters, shaded }
}

/// The second pass of the pixel whose top left corner is (x, y), for a scene that takes more than one sample: from
/// its first pass's linear colour `first` ([`undisplay`]), the samples after the centre while the pixel
/// [`refines`] and [`Accumulated::wants_more`] them, up to its most. Its value is the result's mean.
#[inline(always)]
pub fn refine<N: Num, S: SceneFns<N>>(
    rules: &Rules,
    view: &View<N>,
    scene: &S,
    (x, y): (N, N),
    first: V3<N>,
    refines: N::Mask,
) -> Accumulated<N> {
    N::iterate(
        N::count(rules.sampling.samples.max(1) - 1),
        Accumulated::empty().with(first),
        |acc| refines & acc.wants_more(rules),
        |acc| acc.with(sample(rules, view, scene, (x, y), acc.count).2.colour),
    )
}

/// The rounds of sample indices after sample 0 for a renderer that schedules the second pass's samples itself: the
/// rest of the first batch ([`FIRST`]), then whole batches ([`BATCH`]), up to `samples`. After each round a pixel
/// goes on only while it wants more (the check [`refine`] makes before each sample is true within a batch).
pub fn rounds(samples: u32) -> impl Iterator<Item = std::ops::Range<u32>> {
    let mut start = 1;
    std::iter::from_fn(move || {
        if start >= samples {
            return None;
        }
        let end = if start < FIRST { FIRST } else { start + BATCH }.min(samples);
        let round = start..end;
        start = end;
        Some(round)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::rules::Sampling;

    #[test]
    fn sample_zero_is_the_centre_and_the_first_batch_spreads_over_the_pixel() {
        let ([x, y], lens) = sample_point::<f64>(0.0, true);
        assert_eq!((x, y, lens), (0.5, 0.5, [0.0, 0.0]));
        let points: Vec<[f64; 2]> = (1..5).map(|k| sample_point::<f64>(k as f64, false).0).collect();
        // One sample in each quarter of the pixel, and no two on one row or column of a 4×4 grid.
        let mut quadrants: Vec<(bool, bool)> = points.iter().map(|p| (p[0] < 0.5, p[1] < 0.5)).collect();
        quadrants.sort();
        quadrants.dedup();
        assert_eq!(quadrants.len(), 4, "{points:?}");
        let mut columns: Vec<i64> = points.iter().map(|p| (p[0] * 4.0) as i64).collect();
        columns.sort();
        columns.dedup();
        assert_eq!(columns.len(), 4, "{points:?}");
        // Later samples fill the pixel: every cell of a 4×4 grid holds one of the first 32.
        let cells: std::collections::BTreeSet<(i64, i64)> = (0..32)
            .map(|k| sample_point::<f64>(k as f64, false).0)
            .map(|p| ((p[0] * 4.0) as i64, (p[1] * 4.0) as i64))
            .collect();
        assert_eq!(cells.len(), 16);
    }

    #[test]
    fn rounds_follow_the_batches() {
        let r: Vec<_> = rounds(10).collect();
        assert_eq!(r, vec![1..5, 5..9, 9..10]);
        assert_eq!(rounds(1).count(), 0);
    }

    #[test]
    fn a_pixel_whose_samples_agree_stops_after_the_first_batch() {
        let rules = Rules { sampling: Sampling { samples: 16, threshold: 0.004 }, ..test_rules() };
        let mut acc = Accumulated::<f64>::empty();
        for _ in 0..FIRST {
            acc = acc.with(v3(0.3, 0.4, 0.5));
        }
        assert!(!acc.wants_more(&rules));
        let mut edge = Accumulated::<f64>::empty();
        for k in 0..FIRST {
            edge = edge.with(V3::splat(if k % 2 == 0 { 0.9 } else { 0.1 }));
        }
        assert!(edge.wants_more(&rules));
        assert!(acc.with(V3::splat(0.3)).wants_more(&rules), "within the second batch");
        assert!(Accumulated::<f64>::empty().with(V3::splat(0.5)).wants_more(&rules), "within the first batch");
    }

    #[test]
    fn a_pixel_refines_where_a_neighbour_differs_or_a_lens_blurs() {
        let rules = Rules { sampling: Sampling { samples: 16, threshold: 0.004 }, ..test_rules() };
        let shown = |v: f64| shown_luma(&rules, V3::splat(v));
        let flat = [shown(0.5); 8];
        assert!(!refines(&rules, shown(0.5), flat));
        let mut edge = flat;
        edge[5] = shown(0.52);
        assert!(refines(&rules, shown(0.5), edge), "a step of 0.02 in display luma");
        edge[5] = shown(0.51);
        assert!(!refines(&rules, shown(0.5), edge), "a step under the contrast");
        let lens = Rules { lens: Some(Lens { aperture: 0.1, focus: 3.0 }), ..rules };
        assert!(refines(&lens, shown(0.5), flat));
        for shown in [0.0f64, 0.2, 0.5, 1.0] {
            let c = undisplay(&rules, V3::splat(shown));
            assert!((crate::ray::shade::display(&rules, c).x - shown).abs() < 1e-12);
        }
    }

    fn test_rules() -> Rules {
        Rules::of(&crate::builder::scene(crate::builder::sphere(1.0)))
    }
}
