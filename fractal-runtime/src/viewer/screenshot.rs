//! PNG files of images: screenshots and the no-display fallback write them (atomically: a temporary file renamed into
//! place, so a reader never sees half a file), tests read them back.

use std::path::{Path, PathBuf};

use fractal_render::image::Image;

/// Writes `image` as an RGBA PNG at `path`.
pub fn write_png(image: &Image, path: &Path) -> Result<(), String> {
    let buffer = image::RgbaImage::from_raw(image.width, image.height, image.to_rgba8())
        .ok_or_else(|| format!("image {}x{} has the wrong number of pixels", image.width, image.height))?;
    let file_name = path.file_name().ok_or_else(|| format!("{} is not a file name", path.display()))?;
    let mut temp_name = std::ffi::OsString::from(".");
    temp_name.push(file_name);
    temp_name.push(format!(".{}.tmp", std::process::id()));
    let temp = path.with_file_name(temp_name);
    let written = buffer.save_with_format(&temp, image::ImageFormat::Png).map_err(|e| e.to_string());
    let renamed = written.and_then(|()| std::fs::rename(&temp, path).map_err(|e| e.to_string()));
    if renamed.is_err() {
        let _ = std::fs::remove_file(&temp);
    }
    renamed
}

/// Reads a PNG (or any format the `image` crate reads with the features built) as an [`Image`].
pub fn read_png(path: &Path) -> Result<Image, String> {
    let rgba = image::open(path).map_err(|e| format!("{}: {e}", path.display()))?.to_rgba8();
    let (width, height) = rgba.dimensions();
    let pixels = rgba.pixels().map(|p| u32::from_le_bytes(p.0)).collect();
    Ok(Image { width, height, pixels })
}

/// The first `<stem>-NNNN.png` in `folder` that does not exist yet.
pub fn next_screenshot_path(folder: &Path, stem: &str) -> PathBuf {
    let stem: String =
        stem.chars().map(|c| if c.is_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect();
    (1..10_000)
        .map(|n| folder.join(format!("{stem}-{n:04}.png")))
        .find(|p| !p.exists())
        .unwrap_or_else(|| folder.join(format!("{stem}-last.png")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pngs_round_trip_and_names_count_up() {
        let dir = std::env::temp_dir().join(format!("fractal-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let image =
            Image { width: 3, height: 2, pixels: vec![0xff00_00ff, 0xff00_ff00, 0xffff_0000, 0, 1, 0x8012_3456] };
        let first = next_screenshot_path(&dir, "my scene");
        assert_eq!(first.file_name().unwrap(), "my_scene-0001.png");
        write_png(&image, &first).unwrap();
        assert_eq!(read_png(&first).unwrap(), image);
        assert_eq!(next_screenshot_path(&dir, "my scene").file_name().unwrap(), "my_scene-0002.png");
        let leftovers: Vec<_> = std::fs::read_dir(&dir).unwrap().filter_map(|e| e.ok()).collect();
        assert_eq!(leftovers.len(), 1, "no temporary file is left behind");
        assert!(write_png(&image, &dir.join("no/such/folder/x.png")).is_err());
        assert!(read_png(&dir.join("missing.png")).is_err());
        let _ = std::fs::remove_dir_all(&dir);
    }
}
