//! PNG files: encoding rendered images with the `image` crate, reading them back, and writing any output file
//! atomically (a `.partial` file in the same directory, synced, then renamed over the final name), so a reader never
//! sees half a file and an interrupted write leaves only a `.partial` file that the next run replaces.

use std::ffi::OsString;
use std::fs::{self, File};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use fractal_render::image::{pack_rgba8, Image};
use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder, ImageFormat};

use crate::output::OutputError;

/// Suffix of the temporary file an atomic write goes through.
pub const PARTIAL_SUFFIX: &str = ".partial";

/// The temporary name `path` is written under before it is renamed into place: `<name>.partial` in the same
/// directory (a rename is only atomic within one file system).
pub fn partial_path(path: &Path) -> PathBuf {
    let mut name: OsString = path.file_name().map(OsString::from).unwrap_or_default();
    name.push(PARTIAL_SUFFIX);
    path.with_file_name(name)
}

/// Encodes `image` as an 8-bit RGBA PNG.
pub fn encode_png(image: &Image) -> Result<Vec<u8>, image::ImageError> {
    let mut bytes = Vec::new();
    PngEncoder::new(&mut bytes).write_image(&image.to_rgba8(), image.width, image.height, ExtendedColorType::Rgba8)?;
    Ok(bytes)
}

/// Writes `image` to `path` as PNG, atomically.
pub fn write_png(path: &Path, image: &Image) -> Result<(), OutputError> {
    let bytes =
        encode_png(image).map_err(|e| OutputError::Encode { path: path.to_path_buf(), message: e.to_string() })?;
    write_atomic(path, &bytes)
}

/// Reads a PNG file into an [`Image`] (any colour type, converted to RGBA8).
pub fn read_png(path: &Path) -> Result<Image, OutputError> {
    let bytes = fs::read(path).map_err(|source| OutputError::Read { path: path.to_path_buf(), source })?;
    let decoded = image::load_from_memory_with_format(&bytes, ImageFormat::Png)
        .map_err(|e| OutputError::Decode { path: path.to_path_buf(), message: e.to_string() })?
        .to_rgba8();
    let (width, height) = decoded.dimensions();
    let pixels = decoded.pixels().map(|p| pack_rgba8(p.0)).collect();
    Ok(Image { width, height, pixels })
}

/// Writes `bytes` to `path` through its [`partial_path`]: create (or truncate) the partial file, write, sync, rename.
/// On failure the partial file is removed.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Writes to `path` atomically what `write` streams into a buffered writer (large files never held in memory).
pub fn write_atomic_with(path: &Path, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> Result<(), OutputError> {
    let partial = partial_path(path);
    let written = (|| -> io::Result<()> {
        let mut file = io::BufWriter::new(File::create(&partial)?);
        write(&mut file)?;
        let file = file.into_inner().map_err(|e| e.into_error())?;
        // The rename must not reach the disk before the data does, or a crash could leave an empty final file.
        file.sync_all()?;
        fs::rename(&partial, path)
    })();
    written.map_err(|source| {
        let _ = fs::remove_file(&partial);
        OutputError::Write { path: path.to_path_buf(), source }
    })
}

/// Creates the directory `path` will be written in and checks that a file can be created there, so a bad output path
/// is reported before any rendering time is spent.
pub fn prepare_output(path: &Path) -> Result<(), OutputError> {
    let fail = |source| OutputError::Write { path: path.to_path_buf(), source };
    if path.is_dir() {
        return Err(fail(io::Error::new(io::ErrorKind::IsADirectory, "it is a directory")));
    }
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        // create_dir_all says only "File exists" when a file stands where a directory should be; name it.
        if let Some(file) = dir.ancestors().find(|a| a.is_file()) {
            let message = format!("{} is a file, not a directory", file.display());
            return Err(fail(io::Error::new(io::ErrorKind::NotADirectory, message)));
        }
        fs::create_dir_all(dir).map_err(fail)?;
    }
    let probe = partial_path(path);
    File::create(&probe).map_err(fail)?;
    fs::remove_file(&probe).map_err(fail)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("fractal-png-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn png_round_trips_exactly() {
        let dir = scratch("round-trip");
        let image =
            Image { width: 3, height: 2, pixels: vec![0xff00_00ff, 0xff00_ff00, 0xffff_0000, 0, 0x8012_3456, 1] };
        let path = dir.join("a.png");
        write_png(&path, &image).unwrap();
        assert_eq!(read_png(&path).unwrap(), image);
        assert!(!partial_path(&path).exists());
        fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn partial_names_stay_in_the_directory() {
        assert_eq!(partial_path(Path::new("out/00001.png")), PathBuf::from("out/00001.png.partial"));
        assert_eq!(partial_path(Path::new("x.png")), PathBuf::from("x.png.partial"));
    }

    #[test]
    fn unwritable_paths_are_errors() {
        let dir = scratch("unwritable");
        let file = dir.join("plain-file");
        fs::write(&file, b"x").unwrap();
        let under_file = file.join("out.png");
        assert!(matches!(prepare_output(&under_file), Err(OutputError::Write { .. })));
        assert!(matches!(prepare_output(&dir), Err(OutputError::Write { .. })));
        let image = Image { width: 1, height: 1, pixels: vec![0] };
        let err = write_png(&under_file, &image).unwrap_err();
        assert!(err.to_string().starts_with("cannot write"), "{err}");
        prepare_output(&dir.join("new/sub/out.png")).unwrap();
        assert!(dir.join("new/sub").is_dir());
        fs::remove_dir_all(dir).unwrap();
    }
}
