//! Where the UI's named widgets were last drawn, in window pixels, so a script can press a widget by name (the
//! viewer's tests drive the UI through egui's own input this way, as a person's pointer would).

use std::collections::HashMap;

/// Widget rectangles of the frame being built and of the last frame drawn.
#[derive(Clone, Debug, Default)]
pub struct Widgets {
    building: HashMap<String, egui::Rect>,
    drawn: HashMap<String, egui::Rect>,
    pixels_per_point: f32,
}

impl Widgets {
    /// Starts a frame drawn at `pixels_per_point`.
    pub fn begin(&mut self, pixels_per_point: f32) {
        self.building.clear();
        self.pixels_per_point = pixels_per_point;
    }

    /// Ends the frame: its rectangles are the ones [`Widgets::point`] answers from.
    pub fn end(&mut self) {
        std::mem::swap(&mut self.building, &mut self.drawn);
    }

    pub fn record(&mut self, name: &str, rect: egui::Rect) {
        self.building.insert(name.to_string(), rect * self.pixels_per_point);
    }

    /// A slider's rail (the part a press moves the value to), not its number box or label.
    pub fn record_slider(&mut self, name: &str, response: &egui::Response) {
        let width = response.ctx.global_style().spacing.slider_width;
        let rail = egui::Rect::from_min_size(response.rect.min, egui::vec2(width, response.rect.height()));
        self.record(name, rail);
    }

    /// The window pixel at fraction `at` (0..1 across, 0..1 down) of the widget `name` as last drawn. A slider's
    /// rail keeps a handle's radius free at each end; `at.0` spans what is between.
    pub fn point(&self, name: &str, at: (f32, f32)) -> Option<(f32, f32)> {
        let rect = self.drawn.get(name)?;
        let inset = (rect.height() / 2.5).min(rect.width() / 2.0);
        let x = rect.left() + inset + at.0.clamp(0.0, 1.0) * (rect.width() - 2.0 * inset);
        Some((x, rect.top() + at.1.clamp(0.0, 1.0) * rect.height()))
    }

    /// The names drawn last frame (for an error that names a missing widget).
    pub fn names(&self) -> Vec<&str> {
        let mut names: Vec<&str> = self.drawn.keys().map(String::as_str).collect();
        names.sort_unstable();
        names
    }
}
