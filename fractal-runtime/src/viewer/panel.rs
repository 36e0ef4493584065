//! The viewer's panel: an overlay in the window's top-left corner with frame time and FPS, the scene time (a slider to
//! scrub it), the quality settings, and a slider for every `param(..)` with its range. Drawn on the host in the 8×8
//! bitmap font as an image with alpha; both presenters blend it over the frame (the wgpu surface in its blit pass,
//! softbuffer on the host), so it looks the same on every backend. Moving a slider changes a uniform: it never
//! recompiles.

use fractal_render::image::{pack_rgba8, unpack_rgba8, Image};

use crate::text::{draw_text, fill, text_width, GLYPH};

/// Pixels between the panel's edge and its text.
const MARGIN: u32 = 6;
/// Height of a slider's bar.
const BAR_HEIGHT: u32 = 6;
/// Width of a slider's bar, in glyph cells.
const BAR_CELLS: u32 = 26;
const BACKDROP: [u8; 4] = [12, 14, 20, 190];
const TEXT: [u8; 4] = [230, 232, 238, 255];
const DIM: [u8; 4] = [150, 156, 170, 255];
const ACCENT: [u8; 4] = [250, 190, 90, 255];
const BAR: [u8; 4] = [70, 76, 92, 255];

/// One parameter as the panel shows it.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamRow {
    pub name: String,
    pub value: f64,
    pub min: f64,
    pub max: f64,
}

/// What the panel shows.
#[derive(Clone, Debug, PartialEq)]
pub struct PanelContent {
    /// Scene name; backend, frame time and render size: the first lines.
    pub status: Vec<String>,
    pub time: f64,
    /// The time slider's range: 0 to this.
    pub time_span: f64,
    pub paused: bool,
    /// Steps, epsilon and effects, a line each.
    pub quality: Vec<String>,
    pub params: Vec<ParamRow>,
    /// The parameter the arrow keys change.
    pub selected: usize,
}

/// What a slider sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SliderTarget {
    Time,
    Param(usize),
}

/// A slider's bar in window pixels, and the range it maps across its width.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slider {
    pub target: SliderTarget,
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
    pub min: f64,
    pub max: f64,
}

impl Slider {
    /// Whether the window pixel (x, y) is on the slider (with a few pixels' slack above and below the thin bar).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let slack = 4.0;
        x >= self.x as f64
            && x < (self.x + self.width) as f64
            && y >= self.y as f64 - slack
            && y < (self.y + self.height) as f64 + slack
    }
    /// The value at window column `x`, clamped to the range.
    pub fn value_at(&self, x: f64) -> f64 {
        let f = ((x - self.x as f64) / self.width.max(1) as f64).clamp(0.0, 1.0);
        self.min + f * (self.max - self.min)
    }
}

/// The drawn panel: an image with alpha placed at `origin` in the window, and its sliders in window pixels.
#[derive(Clone, Debug)]
pub struct Overlay {
    pub image: Image,
    pub origin: (u32, u32),
    pub sliders: Vec<Slider>,
}

impl Overlay {
    /// Whether the window pixel (x, y) is on the panel.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let (ox, oy) = (self.origin.0 as f64, self.origin.1 as f64);
        x >= ox && y >= oy && x < ox + self.image.width as f64 && y < oy + self.image.height as f64
    }
    /// The slider at window pixel (x, y).
    pub fn slider_at(&self, x: f64, y: f64) -> Option<Slider> {
        self.sliders.iter().copied().find(|s| s.contains(x, y))
    }
    /// Blends the panel over a window-sized image whose pixels are `0x00RRGGBB` (softbuffer's layout).
    pub fn blend_over_xrgb(&self, pixels: &mut [u32], window_width: u32) {
        let (ox, oy) = self.origin;
        for y in 0..self.image.height {
            for x in 0..self.image.width.min(window_width.saturating_sub(ox)) {
                let [r, g, b, a] = unpack_rgba8(self.image.pixels[(y * self.image.width + x) as usize]);
                let Some(dst) = pixels.get_mut(((oy + y) * window_width + ox + x) as usize) else {
                    return;
                };
                let under = [(*dst >> 16) & 0xff, (*dst >> 8) & 0xff, *dst & 0xff];
                let mix = |over: u8, under: u32| (over as u32 * a as u32 + under * (255 - a as u32) + 127) / 255;
                *dst = mix(r, under[0]) << 16 | mix(g, under[1]) << 8 | mix(b, under[2]);
            }
        }
    }
}

/// The glyph scale for a window: 2 from 1600 pixels wide (so the text stays readable on large screens), else 1.
pub fn scale_for(window_width: u32) -> u32 {
    if window_width >= 1600 {
        2
    } else {
        1
    }
}

/// Draws the panel for `content` at glyph scale `scale`, placed at the window's top-left corner.
pub fn draw(content: &PanelContent, scale: u32) -> Overlay {
    let line = (GLYPH + 4) * scale;
    let bar_width = BAR_CELLS * GLYPH * scale;
    let mut lines: Vec<(String, [u8; 4])> = content.status.iter().map(|l| (l.clone(), TEXT)).collect();
    lines.push((format!("t = {:.2} s, {}", content.time, if content.paused { "paused" } else { "running" }), TEXT));
    let time_bar_line = lines.len();
    lines.push((String::new(), TEXT));
    lines.extend(content.quality.iter().map(|l| (l.clone(), DIM)));
    let mut param_bar_lines = Vec::new();
    for (i, p) in content.params.iter().enumerate() {
        let marker = if i == content.selected { ">" } else { " " };
        let colour = if i == content.selected { ACCENT } else { TEXT };
        lines.push((format!("{marker}{} {:.4} [{}, {}]", p.name, p.value, p.min, p.max), colour));
        param_bar_lines.push(lines.len());
        lines.push((String::new(), TEXT));
    }
    lines.push(("O hide, H keys, P camera".to_string(), DIM));

    let width = lines.iter().map(|(t, _)| text_width(t, scale)).max().unwrap_or(0).max(bar_width) + 2 * MARGIN;
    let height = lines.len() as u32 * line + 2 * MARGIN;
    let mut image = Image { width, height, pixels: vec![pack_rgba8(BACKDROP); (width * height) as usize] };
    for (i, (text, colour)) in lines.iter().enumerate() {
        draw_text(&mut image, text, MARGIN, MARGIN + i as u32 * line, scale, *colour);
    }
    let mut sliders = Vec::new();
    let mut bar = |image: &mut Image, at_line: usize, target: SliderTarget, value: f64, min: f64, max: f64| {
        let y = MARGIN + at_line as u32 * line + (line - BAR_HEIGHT * scale) / 2;
        let h = BAR_HEIGHT * scale;
        fill(image, MARGIN, y, bar_width, h, pack_rgba8(BAR));
        let f = if max > min { ((value - min) / (max - min)).clamp(0.0, 1.0) } else { 0.0 };
        fill(image, MARGIN, y, (f * bar_width as f64).round() as u32, h, pack_rgba8(ACCENT));
        sliders.push(Slider { target, x: MARGIN, y, width: bar_width, height: h, min, max });
    };
    bar(&mut image, time_bar_line, SliderTarget::Time, content.time, 0.0, content.time_span);
    for (i, (p, &at)) in content.params.iter().zip(&param_bar_lines).enumerate() {
        bar(&mut image, at, SliderTarget::Param(i), p.value, p.min, p.max);
    }
    Overlay { image, origin: (0, 0), sliders }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn content() -> PanelContent {
        PanelContent {
            status: vec!["sphere".into(), "cpu, 16.0 ms, 62 FPS".into()],
            time: 5.0,
            time_span: 20.0,
            paused: false,
            quality: vec!["steps 128, epsilon 0.0005".into()],
            params: vec![ParamRow { name: "radius".into(), value: 0.75, min: 0.5, max: 1.5 }],
            selected: 0,
        }
    }

    #[test]
    fn sliders_map_their_width_onto_the_range_and_show_the_value() {
        let overlay = draw(&content(), 1);
        assert_eq!(overlay.sliders.len(), 2);
        let time = overlay.sliders[0];
        assert_eq!(time.target, SliderTarget::Time);
        assert_eq!(time.value_at(time.x as f64), 0.0);
        assert!((time.value_at((time.x + time.width / 2) as f64) - 10.0).abs() < 0.1);
        assert_eq!(time.value_at(1e9), 20.0, "clamped to the range");
        let radius = overlay.sliders[1];
        assert_eq!(radius.target, SliderTarget::Param(0));
        assert!(overlay.slider_at((radius.x + 3) as f64, radius.y as f64).is_some_and(|s| s == radius));
        // The filled part of the radius bar covers a quarter of it: (0.75 − 0.5) / (1.5 − 0.5).
        let row = radius.y + 1;
        let filled =
            (radius.x..radius.x + radius.width).filter(|&x| overlay.image.rgba(x, row) == Some(ACCENT)).count() as f64;
        assert!((filled / radius.width as f64 - 0.25).abs() < 0.01, "{filled}");
    }

    #[test]
    fn the_panel_blends_over_the_frame_and_stays_inside_the_window() {
        let overlay = draw(&content(), 1);
        let (w, h) = (overlay.image.width + 10, overlay.image.height + 10);
        let mut pixels = vec![0x00ff_ffff; (w * h) as usize];
        overlay.blend_over_xrgb(&mut pixels, w);
        // The backdrop darkens the white frame under it; outside the panel nothing changes.
        assert!(pixels[(5 * w + 2) as usize] & 0xff < 0x80);
        assert_eq!(pixels[(h * w - 1) as usize], 0x00ff_ffff);
        // A window narrower than the panel cuts it.
        let mut narrow = vec![0u32; 20 * 20];
        overlay.blend_over_xrgb(&mut narrow, 20);
        assert!(overlay.contains(1.0, 1.0) && !overlay.contains(w as f64, 1.0));
    }
}
