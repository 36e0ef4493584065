//! Offline output of rendered images: PNG files written atomically ([`png`]), numbered frame sequences that resume
//! after an interruption and split into shards across machines ([`sequence`]), video through ffmpeg ([`video`]),
//! a sequence's frames encoded and written on worker threads while the next ones render ([`writers`]),
//! per-pixel depth, normals and steps as OpenEXR beside an image ([`aov`]), the gallery's contact sheet
//! ([`mod@contact_sheet`]), and a scene's camera as a glTF 2.0 animation for other tools ([`gltf_camera`]).

pub mod aov;
pub mod contact_sheet;
pub mod gltf_camera;
pub mod png;
pub mod sequence;
pub mod video;
pub mod writers;

use std::io;
use std::path::PathBuf;

pub use aov::{write_aov, Aov};
pub use contact_sheet::contact_sheet;
pub use png::{partial_path, read_png, write_atomic, write_atomic_with, write_png};
pub use sequence::{plan, FramePattern, FrameRange, SequencePlan, Shard};
pub use video::{Container, VideoWriter};

/// Why an output file could not be written (or read back).
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot write {}: {source}", .path.display())]
    Write { path: PathBuf, source: io::Error },
    #[error("cannot read {}: {source}", .path.display())]
    Read { path: PathBuf, source: io::Error },
    #[error("cannot encode {}: {message}", .path.display())]
    Encode { path: PathBuf, message: String },
    #[error("{} is not a readable PNG: {message}", .path.display())]
    Decode { path: PathBuf, message: String },
    #[error(
        "ffmpeg was not found on PATH: install ffmpeg to write video, or render a PNG sequence \
         (-o frames/%05d.png) and encode it later"
    )]
    FfmpegMissing,
    #[error("video {}: {message}", .path.display())]
    Video { path: PathBuf, message: String },
}
