//! Render scale: the fraction of the window's size that is rendered (the image is upscaled to the window). Adaptive
//! scale holds a target frame rate: render time grows with the pixel count, that is with scale², so the scale moves by
//! the square root of the ratio between the target and the measured frame time.

/// How large frames are rendered relative to the window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RenderScale {
    /// Always this fraction of the window (1.0: full resolution).
    Fixed(f64),
    /// Adjusted every few frames to hold `target_fps`, between `min` and `max`.
    Adaptive { target_fps: f64, min: f64, max: f64 },
}

impl Default for RenderScale {
    fn default() -> Self {
        RenderScale::Adaptive { target_fps: 30.0, min: 0.2, max: 1.0 }
    }
}

/// Frames between two adjustments: long enough for the smoothed time to reflect the new scale.
const SETTLE_FRAMES: u32 = 4;
/// Weight of the newest frame in the smoothed frame time.
const SMOOTHING: f64 = 0.3;
/// Below this ratio of target to measured frame time the scale drops without waiting for [`SETTLE_FRAMES`].
const URGENT: f64 = 0.5;
/// No adjustment while the frame time is within this band around the target.
const DEAD_BAND: (f64, f64) = (0.85, 1.15);
/// Largest change of the scale in one adjustment.
const MAX_STEP: (f64, f64) = (0.7, 1.25);
/// Scales are kept on a grid so that small oscillations do not change the render size every frame.
const GRID: f64 = 64.0;

/// Tracks frame times and picks the render scale.
#[derive(Clone, Debug)]
pub struct ScaleController {
    mode: RenderScale,
    scale: f64,
    smoothed: Option<f64>,
    frames_since_change: u32,
}

impl ScaleController {
    pub fn new(mode: RenderScale) -> ScaleController {
        let scale = match mode {
            RenderScale::Fixed(s) => sanitize(s, 1.0),
            // Start in the middle of the range and let the first frames find the level.
            RenderScale::Adaptive { min, max, .. } => {
                let (min, max) = bounds(min, max);
                (0.5f64).clamp(min, max)
            }
        };
        ScaleController { mode, scale, smoothed: None, frames_since_change: 0 }
    }

    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Records the time the last frame took, in seconds.
    pub fn record(&mut self, frame_seconds: f64) {
        let RenderScale::Adaptive { target_fps, min, max } = self.mode else {
            return;
        };
        if !(frame_seconds.is_finite() && frame_seconds > 0.0 && target_fps.is_finite() && target_fps > 0.0) {
            return;
        }
        let smoothed = match self.smoothed {
            Some(s) => s + SMOOTHING * (frame_seconds - s),
            None => frame_seconds,
        };
        self.smoothed = Some(smoothed);
        self.frames_since_change += 1;
        let ratio = (1.0 / target_fps) / smoothed;
        // Far too slow (a CPU backend at a large size): step down every frame rather than wait seconds per step.
        if self.frames_since_change < SETTLE_FRAMES && ratio > URGENT {
            return;
        }
        if ratio > DEAD_BAND.0 && ratio < DEAD_BAND.1 {
            return;
        }
        let (min, max) = bounds(min, max);
        let wanted = self.scale * ratio.sqrt().clamp(MAX_STEP.0, MAX_STEP.1);
        let next = ((wanted * GRID).round() / GRID).clamp(min, max);
        if next != self.scale {
            self.scale = next;
            self.smoothed = None;
            self.frames_since_change = 0;
        }
    }

    /// The render size for a window of `window` pixels: at least 1×1.
    pub fn render_size(&self, window: (u32, u32)) -> (u32, u32) {
        let side = |w: u32| ((w as f64 * self.scale).round() as u32).clamp(1, w.max(1));
        (side(window.0), side(window.1))
    }
}

fn sanitize(scale: f64, fallback: f64) -> f64 {
    if scale.is_finite() && scale > 0.0 {
        scale.min(1.0)
    } else {
        fallback
    }
}

fn bounds(min: f64, max: f64) -> (f64, f64) {
    let min = sanitize(min, 0.2).max(1.0 / GRID);
    let max = sanitize(max, 1.0).max(min);
    (min, max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A renderer whose frame time is proportional to the pixel count.
    fn converge(seconds_at_full: f64, target_fps: f64) -> f64 {
        let mut c = ScaleController::new(RenderScale::Adaptive { target_fps, min: 0.1, max: 1.0 });
        for _ in 0..400 {
            let s = c.scale();
            c.record(seconds_at_full * s * s);
        }
        c.scale()
    }

    #[test]
    fn adaptive_scale_holds_the_target() {
        // 4× too slow at full size: about half the side holds the frame rate.
        let s = converge(4.0 / 30.0, 30.0);
        let fps = 1.0 / (4.0 / 30.0 * s * s);
        assert!((fps / 30.0 - 1.0).abs() < 0.2, "scale {s} gives {fps} FPS");
        assert_eq!(converge(0.001, 30.0), 1.0, "fast scenes render at full size");
        assert_eq!(converge(100.0, 30.0), 0.1, "slow scenes stop at the minimum");
        // A very slow first frame (one second for a 30 FPS target) brings the scale down on the next frame.
        let mut c = ScaleController::new(RenderScale::Adaptive { target_fps: 30.0, min: 0.1, max: 1.0 });
        let first = c.scale();
        c.record(1.0);
        assert!(c.scale() < first, "no wait when far too slow");
    }

    #[test]
    fn sizes_are_never_empty_and_bad_input_is_ignored() {
        let mut c = ScaleController::new(RenderScale::Fixed(0.5));
        assert_eq!(c.render_size((320, 240)), (160, 120));
        c.record(10.0);
        assert_eq!(c.scale(), 0.5, "fixed scales do not adapt");
        assert_eq!(ScaleController::new(RenderScale::Fixed(0.001)).render_size((100, 1)), (1, 1));
        assert_eq!(ScaleController::new(RenderScale::Fixed(f64::NAN)).scale(), 1.0);
        let mut a = ScaleController::new(RenderScale::default());
        let before = a.scale();
        a.record(f64::NAN);
        a.record(-1.0);
        assert_eq!(a.scale(), before);
    }
}
