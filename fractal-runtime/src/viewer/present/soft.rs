//! [`SoftPresenter`]: any image on the host (CPU and OpenCL frames, wgpu frames read back) stretched into a
//! softbuffer surface, or, for a viewer run without a window (`fractal view --headless`), into host memory alone.

use std::num::NonZeroU32;
use std::sync::Arc;

use fractal_render::image::Image;
use winit::window::Window;

use super::stretch::upscale_into;
use crate::viewer::ui::Overlay;

/// Kernel pixels (R in the low byte) to softbuffer pixels (0x00RRGGBB).
fn to_softbuffer(p: u32) -> u32 {
    let [r, g, b, _] = p.to_le_bytes();
    (r as u32) << 16 | (g as u32) << 8 | b as u32
}

fn from_softbuffer(p: u32) -> u32 {
    let [b, g, r, _] = p.to_le_bytes();
    u32::from_le_bytes([r, g, b, 255])
}

/// A window's softbuffer surface.
struct Surface {
    _context: softbuffer::Context<Arc<Window>>,
    surface: softbuffer::Surface<Arc<Window>, Arc<Window>>,
    size: (u32, u32),
}

/// Presents host images through softbuffer.
pub struct SoftPresenter {
    /// `None` without a window: the pixels are stretched into [`SoftPresenter::shown`] only.
    surface: Option<Surface>,
    /// The image last presented, to present again ([`SoftPresenter::redraw`]).
    source: Option<Image>,
    /// The window pixels last presented (softbuffer layout), for screenshots.
    shown: Vec<u32>,
    shown_size: (u32, u32),
}

impl SoftPresenter {
    pub fn new(window: Arc<Window>) -> Result<SoftPresenter, String> {
        let context = softbuffer::Context::new(window.clone()).map_err(|e| format!("softbuffer: {e}"))?;
        let surface = softbuffer::Surface::new(&context, window).map_err(|e| format!("softbuffer: {e}"))?;
        let surface = Surface { _context: context, surface, size: (0, 0) };
        Ok(SoftPresenter { surface: Some(surface), source: None, shown: Vec::new(), shown_size: (0, 0) })
    }

    /// A presenter with no window: each frame is stretched and blended as for a window, into host memory.
    pub fn offscreen() -> SoftPresenter {
        SoftPresenter { surface: None, source: None, shown: Vec::new(), shown_size: (0, 0) }
    }

    /// `"softbuffer"`, or `"host memory"` without a window.
    pub fn name(&self) -> &'static str {
        match self.surface {
            Some(_) => "softbuffer",
            None => "host memory",
        }
    }

    /// Shows `image` stretched over a window of `window` pixels.
    pub fn present(&mut self, image: &Image, window: (u32, u32), overlay: Option<&Overlay>) -> Result<(), String> {
        match &mut self.source {
            Some(source) => source.clone_from(image),
            None => self.source = Some(image.clone()),
        }
        self.redraw(window, overlay)
    }

    /// Shows the image last presented again (with this `overlay`); nothing before the first.
    pub fn redraw(&mut self, window: (u32, u32), overlay: Option<&Overlay>) -> Result<(), String> {
        let (Some(w), Some(h), Some(image)) = (NonZeroU32::new(window.0), NonZeroU32::new(window.1), &self.source)
        else {
            return Ok(());
        };
        let pixels = window.0 as usize * window.1 as usize;
        let Some(surface) = &mut self.surface else {
            self.shown.resize(pixels, 0);
            upscale_into(image, window.0, window.1, &mut self.shown, to_softbuffer);
            if let Some(overlay) = overlay {
                overlay.blend_over_xrgb(&mut self.shown, window.0);
            }
            self.shown_size = window;
            return Ok(());
        };
        if surface.size != window {
            surface.surface.resize(w, h).map_err(|e| format!("softbuffer: {e}"))?;
            surface.size = window;
        }
        let mut buffer = surface.surface.buffer_mut().map_err(|e| format!("softbuffer: {e}"))?;
        upscale_into(image, window.0, window.1, &mut buffer, to_softbuffer);
        if let Some(overlay) = overlay {
            overlay.blend_over_xrgb(&mut buffer, window.0);
        }
        self.shown.clear();
        self.shown.extend_from_slice(&buffer);
        self.shown_size = window;
        buffer.present().map_err(|e| format!("softbuffer: {e}"))
    }

    /// The window as last presented.
    pub fn screenshot(&self) -> Option<Image> {
        if self.shown.is_empty() {
            return None;
        }
        let pixels = self.shown.iter().map(|&p| from_softbuffer(p)).collect();
        Some(Image { width: self.shown_size.0, height: self.shown_size.1, pixels })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn softbuffer_pixels_round_trip() {
        let p = u32::from_le_bytes([10, 20, 30, 255]);
        assert_eq!(to_softbuffer(p), 0x000a_141e);
        assert_eq!(from_softbuffer(to_softbuffer(p)), p);
    }

    #[test]
    fn offscreen_shows_the_stretched_image() {
        let mut soft = SoftPresenter::offscreen();
        let image = Image { width: 2, height: 1, pixels: vec![u32::from_le_bytes([1, 2, 3, 255]), 7 | 255 << 24] };
        soft.present(&image, (4, 2), None).unwrap();
        let shown = soft.screenshot().unwrap();
        assert_eq!((shown.width, shown.height), (4, 2));
        assert_eq!(shown.pixels[0], image.pixels[0]);
        assert_eq!(shown.pixels[7], image.pixels[1]);
    }
}
