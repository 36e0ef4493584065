//! The one rule both presenters stretch a frame to the window by: window pixel `d` shows source pixel
//! `((2d + 1)·src) / (2·dst)` in integer arithmetic, the pixel whose area contains the window pixel's centre. The
//! blit shader (module `blit`) writes the same rule in WGSL, so the two presenters show identical pixels.

use fractal_render::image::Image;
use rayon::prelude::*;

/// The source pixel shown at window pixel `d` when `src` pixels are stretched over `dst`.
pub fn source_index(d: u32, dst: u32, src: u32) -> u32 {
    let i = ((2 * d as u64 + 1) * src as u64) / (2 * dst.max(1) as u64);
    (i as u32).min(src.saturating_sub(1))
}

/// `image` stretched to `width`×`height`, each pixel passed through `convert`, written row by row into `out`.
pub fn upscale_into(image: &Image, width: u32, height: u32, out: &mut [u32], convert: impl Fn(u32) -> u32 + Sync) {
    let columns: Vec<usize> = (0..width).map(|x| source_index(x, width, image.width) as usize).collect();
    let src_width = image.width as usize;
    out.par_chunks_mut(width as usize).take(height as usize).enumerate().for_each(|(y, row)| {
        let sy = source_index(y as u32, height, image.height) as usize;
        let src = &image.pixels[sy * src_width..(sy + 1) * src_width];
        for (dst, &sx) in row.iter_mut().zip(&columns) {
            *dst = convert(src[sx]);
        }
    });
}

/// `image` stretched to `width`×`height` (what the window shows for it).
pub fn upscale(image: &Image, width: u32, height: u32) -> Image {
    let mut pixels = vec![0u32; width as usize * height as usize];
    upscale_into(image, width, height, &mut pixels, |p| p);
    Image { width, height, pixels }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn upscaling_picks_the_covering_pixel() {
        assert_eq!((0..4).map(|d| source_index(d, 4, 2)).collect::<Vec<_>>(), vec![0, 0, 1, 1]);
        assert_eq!((0..3).map(|d| source_index(d, 3, 3)).collect::<Vec<_>>(), vec![0, 1, 2], "1:1 is the identity");
        assert_eq!(
            (0..2).map(|d| source_index(d, 2, 4)).collect::<Vec<_>>(),
            vec![1, 3],
            "downscaling samples centres"
        );
        assert_eq!(source_index(16383, 16384, 16384), 16383);
        let image = Image { width: 2, height: 1, pixels: vec![1, 2] };
        assert_eq!(upscale(&image, 4, 2).pixels, vec![1, 1, 2, 2, 1, 1, 2, 2]);
    }
}
