//! Text on images in the public-domain 8×8 bitmap font (no font file needed): the gallery contact sheet's labels.
//! (The viewer's UI is egui's, module `viewer::ui`.)

use font8x8::legacy::BASIC_LEGACY;
use fractal_render::image::{pack_rgba8, Image};

/// Side of a glyph cell in font pixels.
pub const GLYPH: u32 = 8;

/// Writes `text` with its top-left corner at (x, y), each font pixel a `scale`-sided square of `rgba`; characters
/// outside ASCII print as `?`, and whatever falls outside the image is cut.
pub fn draw_text(image: &mut Image, text: &str, x: u32, y: u32, scale: u32, rgba: [u8; 4]) {
    let colour = pack_rgba8(rgba);
    for (i, ch) in text.chars().enumerate() {
        let glyph = BASIC_LEGACY[if ch.is_ascii() { ch as usize } else { '?' as usize }];
        let gx = x + i as u32 * GLYPH * scale;
        for (row, bits) in glyph.iter().enumerate() {
            for col in (0..GLYPH).filter(|c| bits >> c & 1 == 1) {
                fill(image, gx + col * scale, y + row as u32 * scale, scale, scale, colour);
            }
        }
    }
}

/// Fills the rectangle at (x, y) of `w`×`h` pixels with the packed colour, cut to the image.
fn fill(image: &mut Image, x: u32, y: u32, w: u32, h: u32, packed: u32) {
    for py in y..(y + h).min(image.height) {
        for px in x..(x + w).min(image.width) {
            image.pixels[(py * image.width + px) as usize] = packed;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glyphs_light_pixels_inside_their_cell_only() {
        let mut image = Image { width: 40, height: 12, pixels: vec![0; 480] };
        draw_text(&mut image, "Hi", 2, 2, 1, [255, 255, 255, 255]);
        let lit: Vec<(u32, u32)> = (0..12)
            .flat_map(|y| (0..40).map(move |x| (x, y)))
            .filter(|&(x, y)| image.pixels[(y * 40 + x) as usize] != 0)
            .collect();
        assert!(lit.len() > 10);
        assert!(lit.iter().all(|&(x, y)| (2..2 + 2 * GLYPH).contains(&x) && (2..10).contains(&y)));
        // Drawing past the edge is cut, not a panic.
        draw_text(&mut image, "far away", 36, 8, 2, [1, 2, 3, 255]);
    }
}
