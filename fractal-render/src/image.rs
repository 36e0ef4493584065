//! Rendered images: RGBA8 pixels packed into u32 exactly as the kernels write them (R in the low byte, A high), and
//! the one spelling on the host of how a linear colour becomes such a pixel (clamp, gamma, round), which the CPU
//! renderer writes with and the tools compare against.

use fractal_dsl::number::math::{v3, Real, V3};

/// A rendered image, row-major from the top-left pixel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// `pixels[y·width + x]`, R | G << 8 | B << 16 | A << 24.
    pub pixels: Vec<u32>,
}

/// Packs an RGBA8 colour the way the kernels do.
pub fn pack_rgba8(rgba: [u8; 4]) -> u32 {
    u32::from_le_bytes(rgba)
}

/// Unpacks a kernel pixel into RGBA8.
pub fn unpack_rgba8(pixel: u32) -> [u8; 4] {
    pixel.to_le_bytes()
}

/// A linear colour as the kernels write a pixel (the ray program's last step): each channel clamped to [0, 1] (NaN to
/// 0), raised to 1/`gamma`, rounded to 8 bits; alpha opaque; packed as [`pack_rgba8`] packs. In the colour's own
/// precision, so the f32 CPU renderer rounds as an f32 kernel does.
pub fn pack_linear<F: Real>(colour: V3<F>, gamma: f64) -> u32 {
    let channel = |v: F| {
        // Rust's max/min drop NaN, so a NaN channel becomes 0 rather than poisoning the pixel.
        let v = v.max(F::zero()).min(F::one());
        let v = if gamma == 2.0 {
            v.sqrt()
        } else if gamma == 1.0 {
            v
        } else {
            v.powf(F::c(1.0 / gamma))
        };
        ((v * F::c(255.0) + F::c(0.5)).f64() as u32).min(255)
    };
    channel(colour.x) | (channel(colour.y) << 8) | (channel(colour.z) << 16) | (255 << 24)
}

/// The RGBA8 pixel of an f64 linear colour ([`pack_linear`]).
pub fn linear_rgba8(colour: [f64; 3], gamma: f64) -> [u8; 4] {
    unpack_rgba8(pack_linear(v3(colour[0], colour[1], colour[2]), gamma))
}

impl Image {
    /// The RGBA8 colour at (x, y); `None` outside the image.
    pub fn rgba(&self, x: u32, y: u32) -> Option<[u8; 4]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        self.pixels.get(y as usize * self.width as usize + x as usize).map(|&p| unpack_rgba8(p))
    }

    /// The pixels as RGBA8 bytes, row-major (what PNG encoders and softbuffer-style blitters take).
    pub fn to_rgba8(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.to_le_bytes()).collect()
    }

    /// Whether every pixel has the same colour (a render that drew nothing).
    pub fn is_uniform(&self) -> bool {
        self.pixels.windows(2).all(|w| w[0] == w[1])
    }

    /// Number of pixels that differ from `colour` by more than `tolerance` in some channel (e.g. pixels that are not
    /// background).
    pub fn count_unlike(&self, colour: [u8; 4], tolerance: u8) -> usize {
        self.pixels
            .iter()
            .filter(|&&p| unpack_rgba8(p).iter().zip(&colour).any(|(a, b)| a.abs_diff(*b) > tolerance))
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packing_puts_red_in_the_low_byte() {
        assert_eq!(pack_rgba8([1, 2, 3, 255]), 0xff03_0201);
        let img = Image { width: 2, height: 1, pixels: vec![0xff03_0201, 0xff00_0000] };
        assert_eq!(img.rgba(0, 0), Some([1, 2, 3, 255]));
        assert_eq!(img.rgba(2, 0), None);
        assert_eq!(img.to_rgba8(), vec![1, 2, 3, 255, 0, 0, 0, 255]);
        assert!(!img.is_uniform());
        assert_eq!(img.count_unlike([0, 0, 0, 255], 2), 1);
        assert_eq!(img.count_unlike([0, 0, 0, 255], 3), 0);
    }

    #[test]
    fn packing_rounds_and_applies_gamma() {
        assert_eq!(pack_linear(v3(1.0f32, 0.0, 0.25), 2.0), 0xff80_00ff);
        assert_eq!(pack_linear(v3(0.5f32, 2.0, -1.0), 1.0), 0xff00_ff80);
        assert_eq!(pack_linear(v3(f32::NAN, 0.0, 0.0), 2.0), 0xff00_0000);
        assert_eq!(linear_rgba8([1.0, 0.0, 0.25], 2.0), [255, 0, 128, 255]);
    }
}
