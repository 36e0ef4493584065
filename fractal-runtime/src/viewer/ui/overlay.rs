//! The viewer's UI as the host presenter takes it: an image with straight alpha placed at a window pixel, rasterised
//! from egui's meshes (module `raster`) and blended over the frame on the host. The wgpu surface draws the same meshes
//! with egui-wgpu instead; `present::ui_agreement` checks the two drawings agree.

use fractal_render::image::{unpack_rgba8, Image};

/// The UI's pixels (RGBA8, straight alpha) and where their top-left corner sits in the window.
#[derive(Clone, Debug, PartialEq)]
pub struct Overlay {
    pub image: Image,
    pub origin: (u32, u32),
}

impl Overlay {
    /// Blends the overlay over a window-sized image whose pixels are `0x00RRGGBB` (softbuffer's layout); what lies
    /// outside the window is cut.
    pub fn blend_over_xrgb(&self, pixels: &mut [u32], window_width: u32) {
        let (ox, oy) = self.origin;
        for y in 0..self.image.height {
            for x in 0..self.image.width.min(window_width.saturating_sub(ox)) {
                let [r, g, b, a] = unpack_rgba8(self.image.pixels[(y * self.image.width + x) as usize]);
                if a == 0 {
                    continue;
                }
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

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_render::image::pack_rgba8;

    #[test]
    fn the_overlay_blends_over_the_frame_and_stays_inside_the_window() {
        let image = Image { width: 8, height: 4, pixels: vec![pack_rgba8([0, 0, 0, 192]); 32] };
        let overlay = Overlay { image, origin: (2, 1) };
        let (w, h) = (12, 8);
        let mut pixels = vec![0x00ff_ffff; (w * h) as usize];
        overlay.blend_over_xrgb(&mut pixels, w);
        // Three quarters black over white: about 0x40; outside the overlay nothing changes.
        assert_eq!(pixels[(w + 2) as usize] & 0xff, 0x3f);
        assert_eq!(pixels[(w + 1) as usize], 0x00ff_ffff);
        assert_eq!(pixels[(h * w - 1) as usize], 0x00ff_ffff);
        // A window narrower than the overlay cuts it.
        let mut narrow = vec![0x00ff_ffffu32; 4 * 8];
        overlay.blend_over_xrgb(&mut narrow, 4);
        assert!(narrow.iter().filter(|&&p| p != 0x00ff_ffff).count() == 2 * 4);
    }
}
