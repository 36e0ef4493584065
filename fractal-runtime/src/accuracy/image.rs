//! A render's image against the truth of the image ([`crate::truth::image`]): the error a viewer sees.
//!
//! - **PSNR** over the RGB channels of the 8-bit image against the truth packed to 8 bits as a renderer packs it
//!   ([`ImageTruth::image`]), peak 255 (+∞ for identical images).
//! - **SSIM** (Wang, Bovik, Sheikh and Simoncelli 2004) on the 8-bit Rec. 601 luma ([`LUMA`]), with their constants
//!   (K₁ = 0.01, K₂ = 0.03, L = 255) and an 11×11 Gaussian window of σ = 1.5 pixels, centred on every pixel and cut
//!   at the image's edges (its weights renormalised there), averaged over all pixels.
//! - **Off by 8**: the share of pixels with some RGB channel more than [`OFF_LEVELS`] 8-bit levels from the truth.
//! - **Flicker** along frames of a slow camera move: at each pixel, channel and pair of consecutive frames, the
//!   render's change from one frame to the next minus the truth's ([`flicker`]): a true motion moves both alike and is
//!   no flicker. RMS, in 8-bit levels.
//! - **Normals** against the pixel-integrated true normal ([`normal_error`]): judged where the render hit with a
//!   normal and the truth has a pixel normal (at least [`crate::truth::image::COVERED`] of the pixel's sub-rays
//!   hit); the share judged is of the pixels where either hits so.

use fractal_render::backend::cpu::PixelTrace;
use fractal_render::image::{unpack_rgba8, Image};

use crate::truth::angle_degrees;
use crate::truth::image::{ImageTruth, LUMA};

/// A pixel is off when some channel differs from the truth's by more than this many 8-bit levels.
pub const OFF_LEVELS: u8 = 8;
/// Half-width of the SSIM window in pixels (an 11×11 window).
pub const SSIM_RADIUS: i64 = 5;
/// The SSIM window's Gaussian σ in pixels.
pub const SSIM_SIGMA: f64 = 1.5;

/// The error of one image against the truth of the image.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ImageError {
    /// dB over RGB; +∞ for an identical image.
    pub psnr: f64,
    /// Mean SSIM of the luma, 1 for an identical image.
    pub ssim: f64,
    /// Share of pixels with a channel off by more than [`OFF_LEVELS`].
    pub off: f64,
}

impl ImageError {
    /// The figures in one line.
    pub fn describe(&self) -> String {
        format!(
            "PSNR {:.2} dB, SSIM {:.4}, {:.2} % of pixels off by more than {OFF_LEVELS}/255",
            self.psnr,
            self.ssim,
            100.0 * self.off
        )
    }
}

/// The image budget: the least PSNR and the largest share of pixels off by more than [`OFF_LEVELS`] an image may
/// have against the truth of the image. Derived from measurement in `docs/image-truth.md` (“The image budget”): the
/// PSNR lies below what the truth's own lattices settle to on the hardest scene, the share between the smooth
/// scenes' aliased one-ray images and their anti-aliased ones.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageBudget {
    /// dB.
    pub psnr: f64,
    /// Fraction of pixels.
    pub off: f64,
}

impl Default for ImageBudget {
    fn default() -> Self {
        ImageBudget { psnr: 35.0, off: 0.02 }
    }
}

impl ImageBudget {
    /// The ways `e` exceeds the budget (empty: within it).
    pub fn violations(&self, e: &ImageError) -> Vec<String> {
        let mut out = Vec::new();
        if e.psnr.is_nan() || e.psnr < self.psnr {
            out.push(format!("PSNR {:.2} dB < {} dB", e.psnr, self.psnr));
        }
        if e.off.is_nan() || e.off > self.off {
            out.push(format!(
                "{:.2} % of pixels off by more than {OFF_LEVELS}/255 > {} %",
                100.0 * e.off,
                100.0 * self.off
            ));
        }
        out
    }

    /// The verdict on `e` in a few words.
    pub fn verdict(&self, e: &ImageError) -> String {
        let violations = self.violations(e);
        if violations.is_empty() {
            "within the image budget".to_string()
        } else {
            format!("outside the image budget: {}", violations.join(", "))
        }
    }
}

/// `image` against `truth` (same size, which the caller ensures: a size mismatch panics).
pub fn image_error(truth: &Image, image: &Image) -> ImageError {
    assert_eq!((truth.width, truth.height), (image.width, image.height), "image and truth differ in size");
    let pairs = || truth.pixels.iter().zip(&image.pixels).map(|(&a, &b)| (unpack_rgba8(a), unpack_rgba8(b)));
    let (mut sum, mut off) = (0.0, 0usize);
    for (a, b) in pairs() {
        let mut far = false;
        for i in 0..3 {
            let d = a[i] as f64 - b[i] as f64;
            sum += d * d;
            far |= a[i].abs_diff(b[i]) > OFF_LEVELS;
        }
        off += far as usize;
    }
    let count = truth.pixels.len().max(1) as f64;
    let mse = sum / (3.0 * count);
    let psnr = if mse == 0.0 { f64::INFINITY } else { 10.0 * (255.0 * 255.0 / mse).log10() };
    ImageError { psnr, ssim: ssim(truth, image), off: off as f64 / count }
}

/// The 8-bit luma of every pixel.
fn lumas(image: &Image) -> Vec<f64> {
    image
        .pixels
        .iter()
        .map(|&p| {
            let c = unpack_rgba8(p);
            LUMA[0] * c[0] as f64 + LUMA[1] * c[1] as f64 + LUMA[2] * c[2] as f64
        })
        .collect()
}

/// Mean SSIM of the two images' luma (see the module notes).
pub fn ssim(a: &Image, b: &Image) -> f64 {
    let (w, h) = (a.width as i64, a.height as i64);
    let (la, lb) = (lumas(a), lumas(b));
    let (c1, c2) = ((0.01 * 255.0f64).powi(2), (0.03 * 255.0f64).powi(2));
    let weight = |d: i64| (-((d * d) as f64) / (2.0 * SSIM_SIGMA * SSIM_SIGMA)).exp();
    let mut total = 0.0;
    for y in 0..h {
        for x in 0..w {
            let (mut sw, mut ma, mut mb, mut aa, mut bb, mut ab) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
            for j in (y - SSIM_RADIUS).max(0)..=(y + SSIM_RADIUS).min(h - 1) {
                for i in (x - SSIM_RADIUS).max(0)..=(x + SSIM_RADIUS).min(w - 1) {
                    let g = weight(i - x) * weight(j - y);
                    let k = (j * w + i) as usize;
                    let (p, q) = (la[k], lb[k]);
                    sw += g;
                    ma += g * p;
                    mb += g * q;
                    aa += g * p * p;
                    bb += g * q * q;
                    ab += g * p * q;
                }
            }
            let (ma, mb) = (ma / sw, mb / sw);
            let va = (aa / sw - ma * ma).max(0.0);
            let vb = (bb / sw - mb * mb).max(0.0);
            let cov = ab / sw - ma * mb;
            total += ((2.0 * ma * mb + c1) * (2.0 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
        }
    }
    total / (w * h).max(1) as f64
}

/// Flicker along a sequence of frames: the RMS, over pixels, RGB channels and consecutive frame pairs, of the
/// render's frame-to-frame change minus the truth's, in 8-bit levels. 0 for fewer than two frames. `frames` pairs
/// each render with the truth of its frame, all of one size.
pub fn flicker(frames: &[(Image, Image)]) -> f64 {
    rms(frames.windows(2).flat_map(|pair| {
        let [(render_a, truth_a), (render_b, truth_b)] = pair else { unreachable!("windows of two") };
        let all = render_a.pixels.iter().zip(&render_b.pixels).zip(truth_a.pixels.iter().zip(&truth_b.pixels));
        all.flat_map(|((&ra, &rb), (&ta, &tb))| {
            let (ra, rb, ta, tb) = (unpack_rgba8(ra), unpack_rgba8(rb), unpack_rgba8(ta), unpack_rgba8(tb));
            (0..3).map(move |i| (rb[i] as f64 - ra[i] as f64) - (tb[i] as f64 - ta[i] as f64))
        })
    }))
}

/// The RMS frame-to-frame change of a sequence of images, in 8-bit levels: how much the picture moves.
pub fn motion(frames: &[Image]) -> f64 {
    rms(frames.windows(2).flat_map(|pair| {
        pair[0].pixels.iter().zip(&pair[1].pixels).flat_map(|(&a, &b)| {
            let (a, b) = (unpack_rgba8(a), unpack_rgba8(b));
            (0..3).map(move |i| b[i] as f64 - a[i] as f64)
        })
    }))
}

/// The root mean square of `values` (0 for none).
fn rms(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, count) = values.fold((0.0, 0usize), |(sum, count), d| (sum + d * d, count + 1));
    if count == 0 {
        0.0
    } else {
        (sum / count as f64).sqrt()
    }
}

/// A render's normals against the pixel-integrated true normals.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct NormalError {
    /// Pixels where the render hit with a normal or the truth has a pixel normal.
    pub hit_pixels: usize,
    /// Of those, the pixels where both have one: the normals judged.
    pub judged: usize,
    /// Median angle in degrees over the judged pixels (NaN when none).
    pub median: f64,
    /// 90th percentile angle in degrees.
    pub p90: f64,
}

impl NormalError {
    /// Share of the hit pixels whose normal is judged (1 where no pixel hits).
    pub fn judged_share(&self) -> f64 {
        if self.hit_pixels == 0 {
            1.0
        } else {
            self.judged as f64 / self.hit_pixels as f64
        }
    }

    pub fn describe(&self) -> String {
        format!(
            "normals judged on {:.1} % of {} hit pixels, median {:.2}°, p90 {:.2}°",
            100.0 * self.judged_share(),
            self.hit_pixels,
            self.median,
            self.p90
        )
    }
}

/// The render's shading normals (`traces`, row-major over the truth's frame) against `truth`'s pixel normals.
pub fn normal_error(truth: &ImageTruth, traces: &[PixelTrace]) -> NormalError {
    let mut angles = Vec::new();
    let mut hit_pixels = 0;
    for (pixel, trace) in truth.pixels.iter().zip(traces) {
        let seen = trace.normal.filter(|n| trace.hit && n.iter().all(|c| c.is_finite()));
        match (pixel.normal, seen) {
            (Some(a), Some(b)) => {
                hit_pixels += 1;
                angles.push(angle_degrees(a, b));
            }
            (None, None) => {}
            _ => hit_pixels += 1,
        }
    }
    angles.sort_by(f64::total_cmp);
    let at = |q: f64| {
        if angles.is_empty() {
            f64::NAN
        } else {
            angles[((angles.len() - 1) as f64 * q).round() as usize]
        }
    };
    NormalError { hit_pixels, judged: angles.len(), median: at(0.5), p90: at(0.9) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_image_budget_judges_psnr_and_the_share_off() {
        let budget = ImageBudget::default();
        let e = |psnr: f64, off: f64| ImageError { psnr, ssim: 1.0, off };
        assert!(budget.violations(&e(47.6, 0.0065)).is_empty());
        assert_eq!(budget.violations(&e(35.2, 0.0361)).len(), 1, "sphere_box's aliased one-ray image");
        assert_eq!(budget.violations(&e(21.7, 0.18)).len(), 2);
        assert_eq!(budget.violations(&e(f64::NAN, f64::NAN)).len(), 2, "a broken image is never within");
        assert!(budget.verdict(&e(50.0, 0.0)).starts_with("within"));
        assert!(budget.verdict(&e(30.0, 0.0)).contains("PSNR 30.00 dB < 35 dB"), "{}", budget.verdict(&e(30.0, 0.0)));
    }
}
