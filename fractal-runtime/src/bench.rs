//! The benchmark behind `fractal bench`: renders a fixed camera path for N frames (or S seconds) on one backend, times
//! the kernel and the whole frame separately, measures the error the speed was bought with, and optionally runs the
//! hand-written baseline kernels on the same device in the same run.
//!
//! **Camera.** A scene with a camera path is rendered along its own path: 120 frames per traversal of its keys, the
//! scene time equal to the path time. A scene with a look-at camera is rendered from an orbit: the camera circles the
//! vertical axis through its target, at its own distance and height, one turn per 120 frames (3° per frame), while the
//! scene time advances 1/30 s per frame. With `--baseline` both the scene and the baseline use the scene's own static
//! camera at time 0, since the baseline kernels have their camera built in.
//!
//! **Timing.** Frames are timed by the bench's own dispatchers (module `timer`), which do per frame what the renderers
//! do (upload the frame uniforms, dispatch, wait, read the pixels back) and also read the device's clock:
//! - wgpu: timestamp queries around the compute pass where the adapter supports them, otherwise the wall time from
//!   submit to the end of the wait (the report says which);
//! - OpenCL: the kernel's profiling event (start to end);
//! - CPU: there is no device and no read-back, so the kernel time is the whole frame.
//!
//! The frame time is the wall time of the whole frame, read-back included. A first, untimed frame builds the kernel.
//!
//! **Error.** Once, untimed, the first frame of the path is rendered again by the same backend at a reduced size
//! (at most [`ERROR_WIDTH`] pixels wide, same aspect) and compared with the CPU renderer running the f64 interpreter
//! on the same frame uniforms and the same settings: the fraction of pixels whose hit/miss differs (a pixel is a miss
//! when it has the background colour; not available when the scene has glow, which tints misses) and the mean
//! absolute colour difference in 8-bit levels over all pixels and RGB channels. That is the *precision* (f32 rounding
//! alone). The same image is also measured against the ground truth ([`crate::truth`], which trusts no distance
//! estimate): the *true error* of the setting timed, from the same backend's trace kernel (the render kernel that
//! also keeps each pixel's depth, normal and steps), or from the image alone where no trace kernel runs. Asked for, the
//! image is measured against the truth of the image too ([`crate::truth::image`]): the error of the pixel's value.

mod baseline;
pub mod precision;
mod record;
mod report;
mod timer;

use std::f64::consts::TAU;
use std::io::{self, Write};
use std::path::Path;
use std::time::Instant;

use fractal_dsl::{CameraPlacement, Scene};
use fractal_render::camera::{CameraPath, Pose};
use fractal_render::choose_precision::decide;
use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::frame::{Frame, ParamValues};
use fractal_render::precision::{Chosen, Precision, PrecisionChoice};
use fractal_render::renderer::{KernelSources, RenderJob};
use fractal_render::select::{BackendChoice, RendererOptions};
use glam::{DQuat, DVec3};

use crate::accuracy::image::{image_error, ImageBudget, ImageError};
use crate::accuracy::{measure, Observed, TrueError};
use crate::truth::image::{ImageTruth, ImageTruthError, ImageTruthSettings};
use crate::truth::{Truth, TruthSettings};

pub use baseline::{BASELINE_OPENCL, BASELINE_WGSL};
pub use precision::Deviation;
pub use record::BenchRecord;
pub use report::{BaselineFigures, BenchReport, CameraMotion, Stats, Timings};
pub use timer::KernelClock;

/// Frames per traversal of the bench camera path (one orbit turn, or one pass over a scene's path keys).
pub const PATH_FRAMES: u64 = 120;
/// Scene time per frame of an orbit: a nominal 30 frames per second.
pub const ORBIT_FRAME_TIME: f64 = 1.0 / 30.0;
/// Largest width of the accuracy comparison (the f64 interpreter is slow; 240×135 at 16:9).
pub const ERROR_WIDTH: u32 = 240;
/// The ground truth's march step in footprints for the bench's true error: coarser than `fractal accuracy`'s, so the
/// bench stays quick (it reads a few more false hits on thin sheets of a fractal than a finer truth would).
pub const TRUTH_STEP: f64 = 1.0 / 64.0;

/// How long to run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BenchLength {
    /// This many timed frames.
    Frames(u32),
    /// Timed frames until their frame times add up to this many seconds (at least one).
    Seconds(f64),
}

/// What to benchmark.
#[derive(Clone, Copy)]
pub struct BenchSpec<'a> {
    /// Name for the report (a built-in name or a file name).
    pub scene_name: &'a str,
    pub scene: &'a Scene,
    /// The scene's kernels and CPU evaluator.
    pub kernels: KernelSources<'a>,
    pub params: &'a ParamValues,
    pub width: u32,
    pub height: u32,
    pub length: BenchLength,
    pub backend: BackendChoice,
    pub options: RendererOptions,
    /// The number type of each frame: given, or chosen per frame by the view. The CPU, and a GPU backend whose device
    /// has f64, draw f64 frames; elsewhere they are timed in f32 and the report says how many frames wanted more.
    pub precision: PrecisionChoice,
    /// Also run the hand-written baseline.
    pub baseline: bool,
    /// Also measure the first frame's image against the truth of the image ([`crate::truth::image`]).
    pub image_error: bool,
    /// Whether the scene draws what the baseline draws (the built-in `mandelbulb`), so the baseline's hit mask can be
    /// checked against the scene's f64 reference.
    pub baseline_comparable: bool,
}

/// The camera pose and scene time of bench frame `index`.
pub fn bench_pose(
    scene: &Scene,
    params: &ParamValues,
    motion: CameraMotion,
    index: u64,
) -> Result<(Pose, f64), fractal_render::error::CameraError> {
    let lookup = |p: &fractal_dsl::ParamDecl| params.lookup(p);
    let fraction = (index % PATH_FRAMES) as f64 / PATH_FRAMES as f64;
    match (motion, &scene.camera.placement) {
        (CameraMotion::ScenePath, CameraPlacement::Path { keys, interpolation, looped }) => {
            let (first, last) = CameraPath::new(keys, *interpolation, *looped)?.span();
            let time = first + (last - first) * fraction;
            Ok((Pose::from_camera(&scene.camera, time, &lookup)?, time))
        }
        (CameraMotion::Orbit, CameraPlacement::LookAt { position, target }) => {
            let time = index as f64 * ORBIT_FRAME_TIME;
            let position = DVec3::from_array(position.eval(time, &lookup));
            let target = DVec3::from_array(target.eval(time, &lookup));
            let offset = DQuat::from_rotation_y(TAU * fraction) * (position - target);
            Ok((Pose::look_at(target + offset, target, scene.camera.fov_degrees)?, time))
        }
        _ => Ok((Pose::from_camera(&scene.camera, 0.0, &lookup)?, 0.0)),
    }
}

/// The camera motion a spec gets.
pub fn motion_for(spec: &BenchSpec) -> CameraMotion {
    match (&spec.scene.camera.placement, spec.baseline) {
        (_, true) => CameraMotion::Static,
        (CameraPlacement::Path { .. }, false) => CameraMotion::ScenePath,
        (CameraPlacement::LookAt { .. }, false) => CameraMotion::Orbit,
    }
}

/// The size of the accuracy comparison for a `width`×`height` bench.
pub fn error_size(width: u32, height: u32) -> (u32, u32) {
    if width <= ERROR_WIDTH {
        return (width, height);
    }
    let h = (height as f64 * ERROR_WIDTH as f64 / width as f64).round().max(1.0) as u32;
    (ERROR_WIDTH, h)
}

fn frame_at(spec: &BenchSpec, motion: CameraMotion, index: u64, size: (u32, u32)) -> Result<Frame, RenderError> {
    let (pose, time) =
        bench_pose(spec.scene, spec.params, motion, index).map_err(fractal_render::error::FrameError::from)?;
    Ok(Frame::new(spec.scene, &pose, time, size.0, size.1, spec.params)?)
}

/// Opens the backend (for `auto`: the first of wgpu, OpenCL, CPU that opens and builds the kernel) and renders the
/// untimed first frame.
fn open_timer(
    spec: &BenchSpec,
    first: &Frame,
    notes: &mut Vec<String>,
) -> Result<(Box<dyn timer::Timer>, f64), RenderError> {
    let candidates: Vec<Backend> = match spec.backend {
        BackendChoice::Auto => Backend::ALL.to_vec(),
        BackendChoice::Only(b) => vec![b],
    };
    let mut failures = Vec::new();
    for backend in candidates {
        let attempt = timer::open(backend, &spec.options).and_then(|mut t| {
            let start = Instant::now();
            t.run(&timer::Work::Generated(RenderJob::new(spec.kernels, first)))?;
            Ok((t, start.elapsed().as_secs_f64() * 1e3))
        });
        match attempt {
            Ok(found) => return Ok(found),
            Err(e) if spec.backend == BackendChoice::Auto && e.is_backend_specific() => {
                notes.push(format!("skipping {backend}: {e}"));
                failures.push(format!("{backend}: {e}"));
            }
            Err(e) => return Err(e),
        }
    }
    Err(RenderError::AllBackendsFailed(failures))
}

/// The true error of the timed march at `frame`: the same backend runs the scene's trace kernel, which keeps each
/// pixel's depth, normal and steps beside the image.
fn traced_error(
    spec: &BenchSpec,
    (backend, precision): (Backend, Precision),
    frame: &Frame,
    truth: &Truth,
) -> Result<TrueError, RenderError> {
    let mut renderer = fractal_render::select::open(backend, &spec.options)?;
    let tracing = fractal_dsl::compile(spec.scene)?.tracing();
    let sources = KernelSources { cpu: spec.kernels.cpu, ..KernelSources::compiled(&tracing) };
    let traced = renderer.trace(&RenderJob::new(sources, frame).with_precision(precision))?;
    Ok(measure(spec.scene, truth, Observed::Traced(&traced.pixels)))
}

/// The first frame's `image` at the error size against the truth of the image, at the bench's truth step; `None`
/// with a note where the truth does not define the image (glow).
fn image_error_of(
    spec: &BenchSpec,
    small: &Frame,
    image: &fractal_render::image::Image,
    notes: &mut Vec<String>,
) -> Result<Option<ImageError>, RenderError> {
    if spec.scene.settings.glow.is_some() {
        notes.push("no image error: the truth of the image does not define glow".to_string());
        return Ok(None);
    }
    let truth = TruthSettings { step_footprints: TRUTH_STEP, iteration_factor: 1 };
    match ImageTruth::compute(spec.scene, small, ImageTruthSettings { truth, ..ImageTruthSettings::default() }) {
        Ok(truth) => Ok(Some(image_error(&truth.image(), image))),
        Err(ImageTruthError::Render(e)) => Err(e),
        Err(ImageTruthError::Settings(why)) => {
            notes.push(format!("no image error: {why}"));
            Ok(None)
        }
    }
}

/// The precision of each timed frame: how many were drawn in each, how many wanted more than the backend has, and why
/// the first was drawn as it was.
#[derive(Default)]
struct PrecisionTally {
    drawn: std::collections::BTreeMap<Precision, usize>,
    wanted_more: usize,
    first: Option<String>,
}

impl PrecisionTally {
    /// The precision `frame` is drawn in (the one it asks for where the timer `computes_f64`, else f32).
    fn of(&mut self, spec: &BenchSpec, frame: &Frame, computes_f64: bool) -> Result<Precision, RenderError> {
        let chosen = match spec.kernels.cpu {
            Some(cpu) => match cpu.wide {
                Some(wide) => decide(spec.precision, spec.scene, frame, cpu.evaluator, wide)?,
                None => Chosen { precision: Precision::F32, probe: None, reason: "no f64 evaluator".into() },
            },
            None => Chosen { precision: Precision::F32, probe: None, reason: "no CPU evaluator to probe".into() },
        };
        let drawn = if computes_f64 { chosen.precision } else { Precision::F32 };
        self.wanted_more += usize::from(drawn != chosen.precision);
        *self.drawn.entry(drawn).or_default() += 1;
        self.first.get_or_insert_with(|| chosen.to_string());
        Ok(drawn)
    }

    fn describe(&self, backend: Backend) -> String {
        let total: usize = self.drawn.values().sum();
        let each: Vec<String> = self.drawn.iter().map(|(p, n)| format!("{p} on {n} of {total} frames")).collect();
        let mut line =
            format!("precision: {} (the first frame: {})", each.join(", "), self.first.as_deref().unwrap_or("-"));
        if self.wanted_more > 0 {
            line += &format!(
                "; {} frames wanted f64, which this {backend} device lacks: timed in f32 (--backend cpu draws them in f64)",
                self.wanted_more
            );
        }
        line
    }
}

/// Runs the benchmark. `progress` is called after every timed frame with (frames done, elapsed seconds).
pub fn run(spec: &BenchSpec, progress: &mut dyn FnMut(u64, f64)) -> Result<BenchReport, RenderError> {
    let motion = motion_for(spec);
    let size = (spec.width, spec.height);
    let mut notes = Vec::new();
    let first = frame_at(spec, motion, 0, size)?;
    let (mut timer, first_frame_ms) = open_timer(spec, &first, &mut notes)?;
    let baseline_first_ms = if spec.baseline {
        let start = Instant::now();
        timer.run(&timer::Work::Baseline { width: spec.width, height: spec.height })?;
        Some(start.elapsed().as_secs_f64() * 1e3)
    } else {
        None
    };

    let mut generated = Timings { kernel_ms: Vec::new(), frame_ms: Vec::new(), first_frame_ms };
    let mut baseline =
        baseline_first_ms.map(|first_frame_ms| Timings { kernel_ms: Vec::new(), frame_ms: Vec::new(), first_frame_ms });
    let started = Instant::now();
    let mut index = 0u64;
    let (backend, wide) = (timer.device().backend, timer.computes_f64());
    let mut precisions = PrecisionTally::default();
    loop {
        let done = match spec.length {
            BenchLength::Frames(n) => index >= n as u64,
            BenchLength::Seconds(s) => index > 0 && generated.frame_ms.iter().sum::<f64>() >= s * 1e3,
        };
        if done {
            break;
        }
        let frame = frame_at(spec, motion, index, size)?;
        let precision = precisions.of(spec, &frame, wide)?;
        let timed =
            timer.run(&timer::Work::Generated(RenderJob::new(spec.kernels, &frame).with_precision(precision)))?;
        generated.kernel_ms.push(timed.kernel_ms);
        generated.frame_ms.push(timed.frame_ms);
        // Interleaved, so a device that warms up or throttles during the run affects both kernels alike.
        if let Some(b) = baseline.as_mut() {
            let timed = timer.run(&timer::Work::Baseline { width: spec.width, height: spec.height })?;
            b.kernel_ms.push(timed.kernel_ms);
            b.frame_ms.push(timed.frame_ms);
        }
        index += 1;
        progress(index, started.elapsed().as_secs_f64());
    }

    notes.push(precisions.describe(backend));
    let error_size = error_size(spec.width, spec.height);
    let small = frame_at(spec, motion, 0, error_size)?;
    let precision = precisions.of(spec, &small, wide)?;
    let image =
        timer.run(&timer::Work::Generated(RenderJob::new(spec.kernels, &small).with_precision(precision)))?.image;
    let reference = precision::reference(spec.scene, &small)?;
    let accuracy = precision::compare_scene(spec.scene, &image, &reference);
    let truth = Truth::compute(spec.scene, &small, TruthSettings { step_footprints: TRUTH_STEP, iteration_factor: 1 })?;
    let true_error = match traced_error(spec, (backend, precision), &small, &truth) {
        Ok(error) => error,
        Err(e) => {
            notes.push(format!("no trace kernel ran ({e}): the true error is what the image holds"));
            measure(spec.scene, &truth, Observed::Image(&image))
        }
    };
    let image_error = if spec.image_error { image_error_of(spec, &small, &image, &mut notes)? } else { None };
    let baseline = match baseline {
        Some(timings) => {
            let accuracy = if spec.baseline_comparable {
                let work = timer::Work::Baseline { width: error_size.0, height: error_size.1 };
                let image = timer.run(&work)?.image;
                Some(precision::compare_baseline(spec.scene, &image, &reference))
            } else {
                notes.push(format!(
                    "the baseline draws the Mandelbulb, not {}: the ratio compares against a fixed anchor",
                    spec.scene_name
                ));
                None
            };
            Some(BaselineFigures { timings, accuracy })
        }
        None => None,
    };
    Ok(BenchReport {
        scene_name: spec.scene_name.to_string(),
        width: spec.width,
        height: spec.height,
        device: timer.device(),
        camera: motion,
        clock: timer.clock(),
        options: spec.options,
        generated,
        accuracy,
        true_error,
        image_error,
        baseline,
        notes,
    })
}

fn stats_row(out: &mut dyn Write, label: &str, s: Stats, tail: &str) -> io::Result<()> {
    writeln!(out, "  {label:<18} {:>10.2} {:>10.2} {:>10.2} {:>10.2}  {tail}", s.min, s.median, s.mean, s.max)
}

impl BenchReport {
    /// The human-readable report.
    pub fn print(&self, out: &mut dyn Write) -> io::Result<()> {
        let frames = self.generated.frame_ms.len();
        writeln!(out, "bench {} at {}x{}, {frames} timed frames", self.scene_name, self.width, self.height)?;
        writeln!(out, "  device:  {}", self.device)?;
        writeln!(out, "  camera:  {}", self.camera.describe())?;
        writeln!(out, "  kernel:  {}", self.clock.describe())?;
        writeln!(out, "  build:   {}", record::BuildRecord::current(&self.options).describe())?;
        writeln!(out, "  {:<18} {:>10} {:>10} {:>10} {:>10}  (ms)", "", "min", "median", "mean", "max")?;
        let g = &self.generated;
        stats_row(out, "kernel", g.kernel(), "")?;
        stats_row(out, "frame", g.frame(), &format!("{:.2} FPS", g.fps()))?;
        writeln!(out, "  first frame (incl. kernel build): {:.1} ms", g.first_frame_ms)?;
        writeln!(out, "  precision (vs f64 interpreter, same settings): {}", self.accuracy.describe())?;
        writeln!(
            out,
            "  true error (vs ground truth at {}x{}, truth step 1/{} footprint, escape-time sets at the scene's own \
             iterations; `fractal accuracy` judges against converged ones): {}",
            self.true_error.width,
            self.true_error.height,
            (1.0 / TRUTH_STEP).round(),
            self.true_error.describe()
        )?;
        if let Some(e) = &self.image_error {
            writeln!(
                out,
                "  image error (vs the truth of the image at {}x{}, the box-filtered pixel: docs/image-truth.md): {}; {}",
                self.true_error.width,
                self.true_error.height,
                e.describe(),
                ImageBudget::default().verdict(e)
            )?;
        }
        if let Some(b) = &self.baseline {
            stats_row(out, "baseline kernel", b.timings.kernel(), "")?;
            stats_row(out, "baseline frame", b.timings.frame(), &format!("{:.2} FPS", b.timings.fps()))?;
            if let Some((kernel, frame)) = self.ratios() {
                writeln!(
                    out,
                    "  generated/baseline (median): kernel {kernel:.3}, frame {frame:.3} (below 1: generated is faster)"
                )?;
            }
            match &b.accuracy {
                Some(a) => writeln!(out, "  baseline error vs f64 interpreter: {}", a.describe())?,
                None => writeln!(out, "  baseline error: not compared (it draws another scene)")?,
            }
        }
        for note in &self.notes {
            writeln!(out, "  note: {note}")?;
        }
        Ok(())
    }

    /// The record written to the CSV and JSON Lines files.
    pub fn record(&self, scene: &Scene, params: &ParamValues) -> BenchRecord {
        BenchRecord::new(self, scene, params)
    }
}

/// Appends `record` as one CSV row to `path`, writing the header first when the file is new or empty.
pub fn append_csv(path: &Path, record: &BenchRecord) -> io::Result<()> {
    record::append_csv(path, record)
}

/// Appends `record` as one JSON object on its own line (JSON Lines) to `path`.
pub fn append_json(path: &Path, record: &BenchRecord) -> io::Result<()> {
    record::append_json(path, record)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::{camera, camera_path, key, scene, sphere};

    #[test]
    fn stats_have_the_usual_meaning() {
        let s = Stats::of(&[4.0, 1.0, 3.0, 2.0]);
        assert_eq!(s, Stats { min: 1.0, median: 2.5, mean: 2.5, max: 4.0 });
        assert_eq!(Stats::of(&[5.0, 1.0, 9.0]).median, 5.0);
        assert!(Stats::of(&[]).mean.is_nan());
    }

    #[test]
    fn error_sizes_keep_the_aspect() {
        assert_eq!(error_size(1920, 1080), (240, 135));
        assert_eq!(error_size(3840, 1000), (240, 63));
        assert_eq!(error_size(64, 48), (64, 48));
        assert_eq!(error_size(100_000, 1), (240, 1));
    }

    #[test]
    fn orbits_keep_distance_and_height_and_return() {
        let s = scene(sphere(1.0)).camera(camera([0.0, 1.0, -4.0], [0.0, 0.5, 0.0]));
        let params = ParamValues::defaults(&s);
        let (start, t0) = bench_pose(&s, &params, CameraMotion::Orbit, 0).unwrap();
        assert_eq!(t0, 0.0);
        let target = DVec3::new(0.0, 0.5, 0.0);
        for i in 1..PATH_FRAMES {
            let (pose, t) = bench_pose(&s, &params, CameraMotion::Orbit, i).unwrap();
            assert!((t - i as f64 / 30.0).abs() < 1e-12);
            assert!((pose.position.distance(target) - start.position.distance(target)).abs() < 1e-9);
            assert!((pose.position.y - 1.0).abs() < 1e-9);
            assert!(pose.position.distance(start.position) > 1e-3, "frame {i} is back at the start");
            assert!(pose.forward.distance((target - pose.position).normalize()) < 1e-9);
        }
        let (back, _) = bench_pose(&s, &params, CameraMotion::Orbit, PATH_FRAMES).unwrap();
        assert!(back.position.distance(start.position) < 1e-9);
        let (fixed, t) = bench_pose(&s, &params, CameraMotion::Static, 7).unwrap();
        assert_eq!((fixed.position, t), (start.position, 0.0));
    }

    #[test]
    fn paths_are_followed_over_their_span() {
        let keys = vec![key(1.0, [0.0, 0.0, -4.0], [0.0, 0.0, 0.0]), key(3.0, [4.0, 0.0, 0.0], [0.0, 0.0, 0.0])];
        let s = scene(sphere(1.0)).camera(camera_path(keys));
        let params = ParamValues::defaults(&s);
        let (p0, t0) = bench_pose(&s, &params, CameraMotion::ScenePath, 0).unwrap();
        assert_eq!((p0.position, t0), (DVec3::new(0.0, 0.0, -4.0), 1.0));
        let (_, half) = bench_pose(&s, &params, CameraMotion::ScenePath, PATH_FRAMES / 2).unwrap();
        assert!((half - 2.0).abs() < 1e-12);
    }
}
