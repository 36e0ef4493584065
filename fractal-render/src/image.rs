//! Rendered images: RGBA8 pixels packed into u32 exactly as the kernels write them (R in the low byte, A high).

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
}
