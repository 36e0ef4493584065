//! Video files through `ffmpeg`: raw RGBA frames are piped to its standard input
//! (`-f rawvideo -pix_fmt rgba -s WxH -r FPS -i -`) and encoded with the container's default codec in yuv420p, the
//! pixel format every player reads. ffmpeg writes to a `.partial` file that is renamed into place when it finishes,
//! so a failed or interrupted encode never leaves a truncated video under the final name.

use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::thread::JoinHandle;

use fractal_render::image::Image;

use crate::output::png::partial_path;
use crate::output::OutputError;

/// Video containers recognised by their extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Container {
    Mp4,
    WebM,
    Matroska,
    QuickTime,
}

impl Container {
    /// The container a file name asks for, by extension (case-insensitive); `None` for anything else.
    pub fn from_path(path: &Path) -> Option<Container> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "mp4" => Some(Container::Mp4),
            "webm" => Some(Container::WebM),
            "mkv" => Some(Container::Matroska),
            "mov" => Some(Container::QuickTime),
            _ => None,
        }
    }

    /// ffmpeg's muxer name (given explicitly, because the `.partial` name hides the extension).
    pub fn muxer(self) -> &'static str {
        match self {
            Container::Mp4 => "mp4",
            Container::WebM => "webm",
            Container::Matroska => "matroska",
            Container::QuickTime => "mov",
        }
    }
}

/// An ffmpeg process encoding frames into one file.
pub struct VideoWriter {
    child: Child,
    stdin: Option<ChildStdin>,
    stderr: Option<JoinHandle<String>>,
    partial: PathBuf,
    path: PathBuf,
    width: u32,
    height: u32,
    finished: bool,
}

impl VideoWriter {
    /// Starts ffmpeg writing a `width`×`height` video at `fps` frames per second to `path` (mp4, webm, mkv or mov).
    pub fn start(path: &Path, width: u32, height: u32, fps: f64) -> Result<VideoWriter, OutputError> {
        let container = Container::from_path(path).ok_or_else(|| OutputError::Video {
            path: path.to_path_buf(),
            message: "unknown video container: use .mp4, .webm, .mkv or .mov".into(),
        })?;
        if !width.is_multiple_of(2) || !height.is_multiple_of(2) {
            // yuv420p stores colour at half resolution; encoders refuse odd sizes.
            return Err(OutputError::Video {
                path: path.to_path_buf(),
                message: format!("video sizes must be even in both directions (yuv420p), got {width}x{height}"),
            });
        }
        let partial = partial_path(path);
        let mut child = Command::new("ffmpeg")
            .args(["-hide_banner", "-loglevel", "error", "-y"])
            .args(["-f", "rawvideo", "-pix_fmt", "rgba", "-s", &format!("{width}x{height}")])
            .args(["-r", &fps.to_string(), "-i", "-"])
            .args(["-pix_fmt", "yuv420p", "-f", container.muxer()])
            .arg(&partial)
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| match e.kind() {
                io::ErrorKind::NotFound => OutputError::FfmpegMissing,
                _ => OutputError::Video { path: path.to_path_buf(), message: format!("cannot start ffmpeg: {e}") },
            })?;
        // Drained on a thread: a chatty ffmpeg must never block on a full pipe while we block writing frames.
        let stderr = child.stderr.take().map(|mut pipe| {
            std::thread::spawn(move || {
                let mut text = String::new();
                let _ = pipe.read_to_string(&mut text);
                text
            })
        });
        let stdin = child.stdin.take();
        Ok(VideoWriter { child, stdin, stderr, partial, path: path.to_path_buf(), width, height, finished: false })
    }

    /// Sends one frame; it must have the size the writer was started with.
    pub fn push(&mut self, image: &Image) -> Result<(), OutputError> {
        if (image.width, image.height) != (self.width, self.height) {
            return Err(self.error(format!(
                "frame is {}x{}, the video is {}x{}",
                image.width, image.height, self.width, self.height
            )));
        }
        let Some(stdin) = self.stdin.as_mut() else {
            return Err(self.error("ffmpeg's input is already closed".into()));
        };
        if let Err(e) = stdin.write_all(&image.to_rgba8()) {
            // A broken pipe means ffmpeg exited; its own message says why.
            let log = self.stop();
            return Err(self.error(if log.is_empty() { format!("writing to ffmpeg: {e}") } else { log }));
        }
        Ok(())
    }

    /// Closes the input, waits for ffmpeg and moves the finished file into place.
    pub fn finish(mut self) -> Result<PathBuf, OutputError> {
        drop(self.stdin.take());
        let status = self.child.wait().map_err(|e| self.error(format!("waiting for ffmpeg: {e}")))?;
        let log = self.stderr.take().and_then(|h| h.join().ok()).unwrap_or_default();
        self.finished = true;
        if !status.success() {
            let _ = std::fs::remove_file(&self.partial);
            let detail = if log.trim().is_empty() { status.to_string() } else { log.trim().to_string() };
            return Err(self.error(format!("ffmpeg failed: {detail}")));
        }
        std::fs::rename(&self.partial, &self.path)
            .map_err(|source| OutputError::Write { path: self.path.clone(), source })?;
        Ok(self.path.clone())
    }

    /// Kills ffmpeg and returns what it printed.
    fn stop(&mut self) -> String {
        drop(self.stdin.take());
        let _ = self.child.kill();
        let _ = self.child.wait();
        self.finished = true;
        let _ = std::fs::remove_file(&self.partial);
        self.stderr.take().and_then(|h| h.join().ok()).unwrap_or_default().trim().to_string()
    }

    fn error(&self, message: String) -> OutputError {
        OutputError::Video { path: self.path.clone(), message }
    }
}

impl Drop for VideoWriter {
    /// An unfinished writer (an error or interruption on our side) stops ffmpeg and removes its partial file.
    fn drop(&mut self) {
        if !self.finished {
            self.stop();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn containers_come_from_extensions() {
        assert_eq!(Container::from_path(Path::new("a/b.MP4")), Some(Container::Mp4));
        assert_eq!(Container::from_path(Path::new("b.webm")), Some(Container::WebM));
        assert_eq!(Container::from_path(Path::new("b.mkv")).map(Container::muxer), Some("matroska"));
        assert_eq!(Container::from_path(Path::new("b.mov")), Some(Container::QuickTime));
        assert_eq!(Container::from_path(Path::new("b.png")), None);
        assert_eq!(Container::from_path(Path::new("mp4")), None);
    }

    #[test]
    fn odd_sizes_are_refused_before_ffmpeg_starts() {
        let err = VideoWriter::start(Path::new("never-written.mp4"), 33, 32, 30.0).err().expect("odd width");
        assert!(err.to_string().contains("even"), "{err}");
        assert!(!Path::new("never-written.mp4.partial").exists());
    }
}
