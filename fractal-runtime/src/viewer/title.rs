//! The window title as the viewer's overlay: frame time and FPS, render size, device, time and effects, the
//! selected parameter, and the passes while the view stands still. Frame times are averaged over short windows so
//! the numbers are readable.

use std::time::{Duration, Instant};

/// How often the title changes.
const REFRESH: Duration = Duration::from_millis(250);

/// Averages frame times over [`REFRESH`] windows.
#[derive(Clone, Debug)]
pub struct FrameClock {
    window_start: Instant,
    frames: u32,
    total: f64,
    /// The last window's average frame time in seconds.
    average: Option<f64>,
}

impl FrameClock {
    pub fn new(now: Instant) -> FrameClock {
        FrameClock { window_start: now, frames: 0, total: 0.0, average: None }
    }

    /// Records one frame; true when a new average is ready (time to refresh the title).
    pub fn record(&mut self, frame_seconds: f64, now: Instant) -> bool {
        if frame_seconds.is_finite() && frame_seconds >= 0.0 {
            self.frames += 1;
            self.total += frame_seconds;
        }
        if now.duration_since(self.window_start) < REFRESH || self.frames == 0 {
            return false;
        }
        self.average = Some(self.total / self.frames as f64);
        self.window_start = now;
        self.frames = 0;
        self.total = 0.0;
        true
    }

    pub fn average(&self) -> Option<f64> {
        self.average
    }
}

/// What the title shows.
pub struct TitleFacts<'a> {
    pub scene: &'a str,
    pub frame_seconds: Option<f64>,
    pub render_size: (u32, u32),
    pub scale: f64,
    pub backend: &'a str,
    pub time: f64,
    pub paused: bool,
    pub effects: &'a str,
    pub param: Option<&'a str>,
    pub following_path: bool,
    /// The progressive passes while the view stands still (e.g. `37 passes`).
    pub passes: Option<&'a str>,
}

pub fn title(f: &TitleFacts) -> String {
    let timing = match f.frame_seconds {
        Some(s) if s > 0.0 => format!("{:.1} ms ({:.0} FPS)", s * 1e3, 1.0 / s),
        _ => "… ms".to_string(),
    };
    let mut t = format!(
        "{} — {timing} — {}x{} ({:.0}%) — {} — t {:.2}{}{} — {}",
        f.scene,
        f.render_size.0,
        f.render_size.1,
        f.scale * 100.0,
        f.backend,
        f.time,
        if f.paused { " (paused)" } else { "" },
        if f.following_path { "" } else { " — free camera" },
        f.effects
    );
    for part in [f.param, f.passes].into_iter().flatten() {
        t.push_str(" — ");
        t.push_str(part);
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn averages_refresh_every_quarter_second() {
        let start = Instant::now();
        let mut c = FrameClock::new(start);
        assert!(!c.record(0.010, start + Duration::from_millis(10)));
        assert!(c.record(0.030, start + Duration::from_millis(300)));
        assert!((c.average().unwrap() - 0.020).abs() < 1e-12);
        let text = title(&TitleFacts {
            scene: "s",
            frame_seconds: c.average(),
            render_size: (640, 360),
            scale: 0.5,
            backend: "wgpu",
            time: 1.0,
            paused: true,
            effects: "no shadows",
            param: Some("r = 1"),
            following_path: false,
            passes: Some("16 passes"),
        });
        assert_eq!(
            text,
            "s — 20.0 ms (50 FPS) — 640x360 (50%) — wgpu — t 1.00 (paused) — free camera — no shadows — r = 1 — 16 \
             passes"
        );
    }
}
