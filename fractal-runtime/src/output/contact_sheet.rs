//! The gallery's contact sheet: rendered scenes laid out in a grid, each tile labelled with its scene's name in an
//! 8×8 bitmap font (so no font file is needed).

use fractal_render::image::{pack_rgba8, Image};

use crate::text::draw_text;

/// Pixels between tiles and around the sheet.
const GAP: u32 = 6;
/// Each font pixel is drawn as a square of this side, or of side 1 where the label would not fit its tile.
const LABEL_SCALE: u32 = 2;
/// Height of the label band under a tile: the glyphs and a margin above and below.
const LABEL_HEIGHT: u32 = 8 * LABEL_SCALE + 8;
const SHEET_COLOUR: [u8; 4] = [24, 24, 28, 255];
const LABEL_COLOUR: [u8; 4] = [225, 225, 230, 255];

/// The tiles in rows of `columns`, in order, each with its label centred below it (cut to the tile's width). Tiles
/// may differ in size; every cell is as large as the largest.
pub fn contact_sheet(tiles: &[(&str, &Image)], columns: u32) -> Image {
    let columns = columns.clamp(1, tiles.len().max(1) as u32);
    let rows = (tiles.len() as u32).div_ceil(columns);
    let cell_w = tiles.iter().map(|(_, i)| i.width).max().unwrap_or(0);
    let cell_h = tiles.iter().map(|(_, i)| i.height).max().unwrap_or(0) + LABEL_HEIGHT;
    let width = GAP + columns * (cell_w + GAP);
    let height = GAP + rows * (cell_h + GAP);
    let mut sheet = Image { width, height, pixels: vec![pack_rgba8(SHEET_COLOUR); (width * height) as usize] };
    for (i, (label, tile)) in tiles.iter().enumerate() {
        let (col, row) = (i as u32 % columns, i as u32 / columns);
        let x0 = GAP + col * (cell_w + GAP) + (cell_w - tile.width) / 2;
        let y0 = GAP + row * (cell_h + GAP);
        for y in 0..tile.height {
            let src = (y * tile.width) as usize;
            let dst = ((y0 + y) * width + x0) as usize;
            sheet.pixels[dst..dst + tile.width as usize].copy_from_slice(&tile.pixels[src..src + tile.width as usize]);
        }
        let scale = if label.chars().count() as u32 * 8 * LABEL_SCALE <= tile.width { LABEL_SCALE } else { 1 };
        let glyphs = (tile.width / (8 * scale)) as usize;
        let text: String = label.chars().take(glyphs).collect();
        let text_w = text.chars().count() as u32 * 8 * scale;
        let tx = x0 + (tile.width - text_w) / 2;
        let ty = y0 + tile.height + (LABEL_HEIGHT - 8 * scale) / 2;
        draw_text(&mut sheet, &text, tx, ty, scale, LABEL_COLOUR);
    }
    sheet
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(w: u32, h: u32, rgba: [u8; 4]) -> Image {
        Image { width: w, height: h, pixels: vec![pack_rgba8(rgba); (w * h) as usize] }
    }

    #[test]
    fn tiles_land_in_rows_with_labels_below() {
        let (red, blue, green) =
            (solid(64, 32, [255, 0, 0, 255]), solid(64, 32, [0, 0, 255, 255]), solid(48, 20, [0, 255, 0, 255]));
        let sheet = contact_sheet(&[("red", &red), ("blue", &blue), ("green", &green)], 2);
        assert_eq!((sheet.width, sheet.height), (GAP + 2 * (64 + GAP), GAP + 2 * (32 + LABEL_HEIGHT + GAP)));
        assert_eq!(sheet.rgba(GAP, GAP), Some([255, 0, 0, 255]));
        assert_eq!(sheet.rgba(2 * GAP + 64 + 63, GAP + 31), Some([0, 0, 255, 255]));
        // The smaller tile is centred in its cell on the second row.
        let row2 = 2 * GAP + 32 + LABEL_HEIGHT;
        assert_eq!(sheet.rgba(GAP + 8, row2), Some([0, 255, 0, 255]));
        assert_eq!(sheet.rgba(GAP + 7, row2), Some(SHEET_COLOUR));
        // Each label band has lit glyph pixels, and nothing else is drawn there.
        let band = |x0: u32, y0: u32| {
            (y0..y0 + LABEL_HEIGHT)
                .flat_map(|y| (x0..x0 + 64).map(move |x| (x, y)))
                .filter(|&(x, y)| sheet.rgba(x, y) == Some(LABEL_COLOUR))
                .count()
        };
        assert!(band(GAP, GAP + 32) > 20);
        assert!(band(2 * GAP + 64, GAP + 32) > 20);
        assert!(band(GAP, row2 + 20) > 20);
    }

    #[test]
    fn a_label_wider_than_its_tile_is_cut_and_no_tiles_is_an_empty_sheet() {
        let small = solid(20, 10, [9, 9, 9, 255]);
        let sheet = contact_sheet(&[("a very long scene name", &small)], 4);
        assert_eq!(sheet.width, GAP + 20 + GAP);
        let empty = contact_sheet(&[], 4);
        assert_eq!((empty.width, empty.height), (2 * GAP, GAP));
    }
}
