//! A sequence's frames encoded and written on worker threads while the renderer draws the next ones: PNG encoding
//! takes longer than a GPU's frame, so one thread writing after each frame would keep the device waiting. The queue
//! is bounded (two frames a worker), so a disk or encoder slower than the device holds the renderer back instead of
//! filling memory. Each frame is written atomically ([`crate::output::png::write_png`]), as a sequence written
//! frame by frame is.

use std::path::PathBuf;
use std::sync::mpsc::{self, Receiver, SyncSender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Instant;

use fractal_render::image::Image;

use crate::output::png::write_png;
use crate::output::OutputError;

/// A frame on disk: its number, path and the seconds its encoding and writing took.
#[derive(Clone, Debug)]
pub struct Written {
    pub frame: u64,
    pub path: PathBuf,
    pub seconds: f64,
}

type Job = (u64, PathBuf, Image);

/// Worker threads that write the frames pushed to them, in any order.
pub struct FrameWriters {
    queue: Option<SyncSender<Job>>,
    done: Receiver<Result<Written, OutputError>>,
    workers: Vec<JoinHandle<()>>,
}

impl FrameWriters {
    /// `workers` threads (at least one), taking frames from a queue of two frames a worker.
    pub fn new(workers: usize) -> FrameWriters {
        let workers = workers.max(1);
        let (queue, jobs) = mpsc::sync_channel::<Job>(2 * workers);
        let (report, done) = mpsc::channel();
        let jobs = Arc::new(Mutex::new(jobs));
        let workers = (0..workers)
            .map(|_| {
                let (jobs, report) = (Arc::clone(&jobs), report.clone());
                std::thread::spawn(move || loop {
                    // The lock is held only while taking a job; a closed queue ends the worker.
                    let next = jobs.lock().map_err(drop).and_then(|jobs| jobs.recv().map_err(drop));
                    let Ok((frame, path, image)) = next else { return };
                    let started = Instant::now();
                    let written = write_frame(&path, &image).map(|()| Written {
                        frame,
                        path,
                        seconds: started.elapsed().as_secs_f64(),
                    });
                    if report.send(written).is_err() {
                        return;
                    }
                })
            })
            .collect();
        FrameWriters { queue: Some(queue), done, workers }
    }

    /// One worker per core the machine has, up to 8.
    pub fn per_core() -> FrameWriters {
        FrameWriters::new(std::thread::available_parallelism().map_or(1, |n| n.get().min(8)))
    }

    /// Queues `image` to be written as `frame` at `path`; waits while the queue is full.
    pub fn push(&self, frame: u64, path: PathBuf, image: Image) -> Result<(), OutputError> {
        let closed = || OutputError::Write { path: path.clone(), source: std::io::Error::other("the writers stopped") };
        let queue = self.queue.as_ref().ok_or_else(closed)?;
        queue.send((frame, path.clone(), image)).map_err(|_| closed())
    }

    /// The frames written (or failed) since the last call, without waiting.
    pub fn written(&self) -> Vec<Result<Written, OutputError>> {
        self.done.try_iter().collect()
    }

    /// Waits for every queued frame; the frames written (or failed) since the last [`FrameWriters::written`].
    pub fn finish(mut self) -> Vec<Result<Written, OutputError>> {
        self.close();
        self.done.try_iter().collect()
    }

    /// Closes the queue and waits for the workers to write what it held.
    fn close(&mut self) {
        self.queue = None;
        for worker in self.workers.drain(..) {
            let _ = worker.join();
        }
    }
}

impl Drop for FrameWriters {
    fn drop(&mut self) {
        self.close();
    }
}

/// Writes one frame, making its folder first.
fn write_frame(path: &std::path::Path, image: &Image) -> Result<(), OutputError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| OutputError::Write { path: path.to_path_buf(), source })?;
    }
    write_png(path, image)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::png::read_png;

    #[test]
    fn every_frame_pushed_is_written_once_whole() {
        let dir = std::env::temp_dir().join(format!("fractal-writers-{}", std::process::id()));
        let writers = FrameWriters::new(3);
        let images: Vec<Image> = (0..10u32)
            .map(|f| Image { width: 5, height: 3, pixels: (0..15).map(|i| 0xff00_0000 | (f << 8) | i).collect() })
            .collect();
        for (f, image) in images.iter().enumerate() {
            writers.push(f as u64, dir.join(format!("sub/{f:03}.png")), image.clone()).unwrap();
        }
        let mut written: Vec<Written> = writers.finish().into_iter().map(Result::unwrap).collect();
        written.sort_by_key(|w| w.frame);
        assert_eq!(written.iter().map(|w| w.frame).collect::<Vec<_>>(), (0..10).collect::<Vec<_>>());
        for (w, image) in written.iter().zip(&images) {
            assert_eq!(&read_png(&w.path).unwrap(), image);
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_frame_that_cannot_be_written_is_reported() {
        let file = std::env::temp_dir().join(format!("fractal-writers-file-{}", std::process::id()));
        std::fs::write(&file, b"not a folder").unwrap();
        let writers = FrameWriters::new(1);
        writers.push(7, file.join("0007.png"), Image { width: 1, height: 1, pixels: vec![0] }).unwrap();
        let reported = writers.finish();
        let _ = std::fs::remove_file(&file);
        assert!(matches!(reported.as_slice(), [Err(OutputError::Write { .. })]), "{reported:?}");
    }
}
