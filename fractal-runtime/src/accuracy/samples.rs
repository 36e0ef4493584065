//! The samples front: each anti-aliasing setting (samples per pixel and the adaptive threshold) of one scene, its
//! image error against the truth of the image ([`super::image`]) beside its time — the table of
//! `docs/image-accuracy.md`, the rule that chooses a scene's default from it, and the points the plot
//! ([`super::plot::image_svg`]) draws.
//!
//! **The rule.** A scene's default is the setting of the best image (highest PSNR) whose time is at most
//! [`TIME_LIMIT`] times the one-sample render's, where it buys at least [`WORTH_DB`] over one sample; else one
//! sample. The time limit is the one the issue that brought anti-aliasing set; 3 dB is a halving of the squared
//! error, the least a user sees side by side. The rule asks for the best image the time allows, not the fastest
//! within the image budget (the geometry sweep's rule): the smooth scenes are within that budget at one sample, and
//! anti-aliasing is what a user of them sees first.

use crate::accuracy::image::{ImageBudget, ImageError};
use crate::accuracy::sweep::pareto;

/// The most time a default's samples may cost, as a factor on the one-sample render's.
pub const TIME_LIMIT: f64 = 3.0;
/// The least PSNR gain over one sample, in dB, that makes more samples worth their time.
pub const WORTH_DB: f64 = 3.0;

/// One anti-aliasing setting measured.
#[derive(Clone, Debug, PartialEq)]
pub struct SamplePoint {
    /// The most rays a pixel may take.
    pub samples: u32,
    /// The adaptive threshold (standard error of the mean display luma a pixel stops at).
    pub threshold: f64,
    /// Rays a pixel took on average (NaN where the backend does not say).
    pub rays_per_pixel: f64,
    /// Median render time, milliseconds.
    pub time_ms: f64,
    /// The first frame against its truth.
    pub error: ImageError,
    /// Flicker along the camera move, 8-bit levels RMS (none with one frame).
    pub flicker: Option<f64>,
    /// The scene's own setting.
    pub default: bool,
}

impl SamplePoint {
    /// The setting in a few words: `samples 16` or `samples 16, threshold 0.001`.
    pub fn label(&self, own_threshold: f64) -> String {
        label(self.samples, self.threshold, own_threshold)
    }
}

/// A setting in a few words: the threshold is named only where it is not the scene's own and matters (more than one
/// sample).
pub fn label(samples: u32, threshold: f64, own_threshold: f64) -> String {
    if samples == 1 || threshold == own_threshold {
        format!("samples {samples}")
    } else {
        format!("samples {samples}, threshold {threshold}")
    }
}

/// The one-sample point, which times and flicker are measured against.
pub fn single(points: &[SamplePoint]) -> Option<&SamplePoint> {
    points.iter().find(|p| p.samples == 1)
}

/// The points no other beats on both time and PSNR, by increasing time.
pub fn front(points: &[SamplePoint]) -> Vec<&SamplePoint> {
    pareto(points, |p| p.time_ms, |p| -p.error.psnr)
}

/// The setting [the rule](self) chooses (one sample where nothing else qualifies; none without a one-sample point).
pub fn chosen(points: &[SamplePoint]) -> Option<&SamplePoint> {
    let one = single(points)?;
    let better = points
        .iter()
        .filter(|p| p.time_ms <= TIME_LIMIT * one.time_ms && p.error.psnr >= one.error.psnr + WORTH_DB)
        .max_by(|a, b| a.error.psnr.total_cmp(&b.error.psnr).then(b.time_ms.total_cmp(&a.time_ms)));
    Some(better.unwrap_or(one))
}

/// The Markdown table of `points`: setting, rays per pixel, time and its ratio to one sample, PSNR, SSIM, pixels
/// off, flicker and its ratio, and the budget's verdict.
pub fn markdown(points: &[SamplePoint], own_threshold: f64, budget: &ImageBudget) -> String {
    let (base_ms, base_flicker) = single(points).map_or((f64::NAN, None), |p| (p.time_ms, p.flicker));
    let mut md = String::from(
        "| setting | rays/px | ms | time × | PSNR dB | SSIM | off % | flicker | flicker × | image budget |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for p in points {
        let mut setting = p.label(own_threshold);
        if p.default {
            setting += " (default)";
        }
        let (flicker, ratio) = match (p.flicker, base_flicker) {
            (Some(f), Some(b)) => (format!("{f:.2}"), format!("{:.2}", f / b)),
            (Some(f), None) => (format!("{f:.2}"), "–".to_string()),
            _ => ("–".to_string(), "–".to_string()),
        };
        let violations = budget.violations(&p.error);
        let verdict = if violations.is_empty() { "within".to_string() } else { violations.join("; ") };
        md += &format!(
            "| {setting} | {} | {:.1} | {:.2} | {:.2} | {:.4} | {:.2} | {flicker} | {ratio} | {verdict} |\n",
            if p.rays_per_pixel.is_finite() { format!("{:.2}", p.rays_per_pixel) } else { "–".to_string() },
            p.time_ms,
            p.time_ms / base_ms,
            p.error.psnr,
            p.error.ssim,
            100.0 * p.error.off,
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(samples: u32, time_ms: f64, psnr: f64) -> SamplePoint {
        SamplePoint {
            samples,
            threshold: 0.004,
            rays_per_pixel: samples as f64,
            time_ms,
            error: ImageError { psnr, ssim: 0.9, off: 0.01 },
            flicker: Some(1.0),
            default: samples == 1,
        }
    }

    #[test]
    fn the_rule_takes_the_best_image_within_the_time_limit() {
        // 5 samples buy 6 dB at 2.5x; 16 buy 9 dB but at 4x: 5 is chosen.
        let points = [point(1, 10.0, 30.0), point(5, 25.0, 36.0), point(16, 40.0, 39.0)];
        assert_eq!(chosen(&points).unwrap().samples, 5);
        // Within the limit 16 wins, though 5 is within the image budget already.
        let points = [point(1, 10.0, 30.0), point(5, 25.0, 36.0), point(16, 29.0, 39.0)];
        assert_eq!(chosen(&points).unwrap().samples, 16);
    }

    #[test]
    fn less_than_three_db_is_not_worth_more_samples() {
        let points = [point(1, 10.0, 30.0), point(5, 12.0, 32.9)];
        assert_eq!(chosen(&points).unwrap().samples, 1);
        assert!(chosen(&points[1..]).is_none(), "no one-sample point, nothing to measure against");
    }

    #[test]
    fn the_front_drops_slower_and_worse_settings() {
        let points = [point(1, 10.0, 30.0), point(5, 25.0, 36.0), point(16, 30.0, 35.0)];
        let front: Vec<u32> = front(&points).iter().map(|p| p.samples).collect();
        assert_eq!(front, [1, 5]);
    }

    #[test]
    fn the_table_states_ratios_against_one_sample_and_the_verdict() {
        let mut slow = point(16, 30.0, 40.0);
        slow.flicker = Some(0.25);
        slow.threshold = 0.001;
        let md = markdown(&[point(1, 10.0, 30.0), slow], 0.004, &ImageBudget::default());
        assert!(md.contains("| samples 1 (default) | 1.00 | 10.0 | 1.00 | 30.00 |"), "{md}");
        assert!(md.contains("| samples 16, threshold 0.001 | 16.00 | 30.0 | 3.00 | 40.00 |"), "{md}");
        assert!(md.contains("| 0.25 | 0.25 | within |"), "{md}");
        assert!(md.contains("PSNR 30.00 dB < 35 dB"), "{md}");
    }
}
