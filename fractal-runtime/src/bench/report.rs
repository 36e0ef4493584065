//! What one bench run measured, as data: the timings of each kernel with their statistics, the errors, the device
//! and the camera motion. Printing it and recording it are the bench's and the record's business.

use fractal_render::device::DeviceInfo;
use fractal_render::select::RendererOptions;

use super::precision::Deviation;
use super::timer::KernelClock;
use crate::accuracy::image::ImageError;
use crate::accuracy::TrueError;

/// Where the camera goes during the bench.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraMotion {
    /// The scene's own camera path.
    ScenePath,
    /// An orbit around the look-at target of the scene's camera.
    Orbit,
    /// The scene's camera at time 0, every frame (`--baseline`).
    Static,
}

impl CameraMotion {
    pub fn describe(self) -> &'static str {
        match self {
            CameraMotion::ScenePath => "the scene's camera path, 120 frames per pass",
            CameraMotion::Orbit => "orbit around the camera's target, 3 degrees and 1/30 s per frame",
            CameraMotion::Static => "the scene's static camera at t = 0 (as the baseline)",
        }
    }
    pub fn name(self) -> &'static str {
        match self {
            CameraMotion::ScenePath => "scene-path",
            CameraMotion::Orbit => "orbit",
            CameraMotion::Static => "static",
        }
    }
}

/// min / median / mean / max of a set of times in milliseconds.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Stats {
    pub min: f64,
    pub median: f64,
    pub mean: f64,
    pub max: f64,
}

impl Stats {
    /// Statistics of `samples` (which must not be empty; an empty set gives NaN).
    pub fn of(samples: &[f64]) -> Stats {
        let mut sorted = samples.to_vec();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        if n == 0 {
            return Stats { min: f64::NAN, median: f64::NAN, mean: f64::NAN, max: f64::NAN };
        }
        let median = if n % 2 == 1 { sorted[n / 2] } else { 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]) };
        Stats { min: sorted[0], median, mean: sorted.iter().sum::<f64>() / n as f64, max: sorted[n - 1] }
    }
}

/// The timings of one kernel.
#[derive(Clone, Debug, PartialEq)]
pub struct Timings {
    pub kernel_ms: Vec<f64>,
    pub frame_ms: Vec<f64>,
    /// The untimed first frame, including the kernel build.
    pub first_frame_ms: f64,
}

impl Timings {
    pub fn kernel(&self) -> Stats {
        Stats::of(&self.kernel_ms)
    }
    pub fn frame(&self) -> Stats {
        Stats::of(&self.frame_ms)
    }
    /// Frames per second from the mean frame time.
    pub fn fps(&self) -> f64 {
        1000.0 / self.frame().mean
    }
}

/// The baseline's figures and how the scene compares.
#[derive(Clone, Debug, PartialEq)]
pub struct BaselineFigures {
    pub timings: Timings,
    /// Hit/miss disagreement of the baseline with the scene's f64 reference (only for the baseline's own scene).
    pub accuracy: Option<Deviation>,
}

/// Everything one bench run measured.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchReport {
    pub scene_name: String,
    pub width: u32,
    pub height: u32,
    pub device: DeviceInfo,
    pub camera: CameraMotion,
    pub clock: KernelClock,
    pub options: RendererOptions,
    pub generated: Timings,
    /// Against the f64 interpreter with the same settings: f32 rounding alone.
    pub accuracy: Deviation,
    /// Against the ground truth ([`crate::truth`]) at the scene's iteration count.
    pub true_error: TrueError,
    /// Against the truth of the image ([`crate::truth::image`]), where asked for.
    pub image_error: Option<ImageError>,
    pub baseline: Option<BaselineFigures>,
    /// Backends skipped by `auto`, and other remarks.
    pub notes: Vec<String>,
}

impl BenchReport {
    /// generated / baseline of the median kernel and median frame times (< 1: the generated kernel is faster).
    pub fn ratios(&self) -> Option<(f64, f64)> {
        self.baseline.as_ref().map(|b| {
            (
                self.generated.kernel().median / b.timings.kernel().median,
                self.generated.frame().median / b.timings.frame().median,
            )
        })
    }
}
