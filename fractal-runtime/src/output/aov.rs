//! Arbitrary output variables (AOVs) beside a rendered image: ray depth, shading normal and march steps per pixel as
//! 32-bit float OpenEXR, from the CPU renderer's per-pixel traces, so a view can be composited among other renders
//! or compared with another renderer outside this program.

use std::io::Cursor;
use std::path::{Path, PathBuf};

use exr::prelude::{Image as ExrImage, SpecificChannels, Vec2, WritableImage};
use fractal_render::backend::cpu::PixelTrace;

use crate::output::{write_atomic, OutputError};

/// One per-pixel quantity an image can be accompanied by.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aov {
    /// Ray distance t to the hit (channel `Z`); +inf where the ray misses.
    Depth,
    /// World-space unit shading normal at the hit (channels `R`, `G`, `B` = x, y, z); 0 where the ray misses.
    Normal,
    /// March steps taken (channel `Y`).
    Steps,
}

impl Aov {
    pub const ALL: [Aov; 3] = [Aov::Depth, Aov::Normal, Aov::Steps];

    pub fn name(self) -> &'static str {
        match self {
            Aov::Depth => "depth",
            Aov::Normal => "normal",
            Aov::Steps => "steps",
        }
    }

    /// Reads one name of [`Aov::ALL`].
    pub fn parse(name: &str) -> Option<Aov> {
        Aov::ALL.into_iter().find(|a| a.name() == name)
    }

    /// Where this AOV of the image at `png` goes: `shot.png` → `shot.depth.exr`.
    pub fn path_beside(self, png: &Path) -> PathBuf {
        png.with_extension(format!("{}.exr", self.name()))
    }
}

/// Writes `aov` of `traces` (row-major, `width` × `height`) to `path` as a 32-bit float OpenEXR file, atomically.
pub fn write_aov(path: &Path, aov: Aov, width: u32, height: u32, traces: &[PixelTrace]) -> Result<(), OutputError> {
    assert_eq!(traces.len(), width as usize * height as usize, "one trace per pixel");
    let size = (width as usize, height as usize);
    let at = |p: Vec2<usize>| &traces[p.y() * size.0 + p.x()];
    let mut bytes = Cursor::new(Vec::new());
    let written = match aov {
        Aov::Depth => {
            let depth = |p| {
                let t: &PixelTrace = at(p);
                (if t.hit { t.t as f32 } else { f32::INFINITY },)
            };
            let channels = SpecificChannels::build().with_channel("Z").with_pixel_fn(depth);
            ExrImage::from_channels(size, channels).write().to_buffered(&mut bytes)
        }
        Aov::Normal => {
            let normal = |p| {
                let n = at(p).normal.filter(|_| at(p).hit).unwrap_or([0.0; 3]);
                (n[0] as f32, n[1] as f32, n[2] as f32)
            };
            let channels =
                SpecificChannels::build().with_channel("R").with_channel("G").with_channel("B").with_pixel_fn(normal);
            ExrImage::from_channels(size, channels).write().to_buffered(&mut bytes)
        }
        Aov::Steps => {
            let steps = |p| (at(p).steps as f32,);
            let channels = SpecificChannels::build().with_channel("Y").with_pixel_fn(steps);
            ExrImage::from_channels(size, channels).write().to_buffered(&mut bytes)
        }
    };
    written.map_err(|e| OutputError::Encode { path: path.to_path_buf(), message: e.to_string() })?;
    write_atomic(path, bytes.get_ref())
}
