//! The command-line grammar (clap derive) and the parsers of its values: sizes, frame ranges, shards, parameter
//! assignments, backends and export targets. Every value is checked here, so a bad one is a usage error before any
//! work starts (an image size is checked against [`fractal_render::MAX_IMAGE_SIDE`] before anything is allocated).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use fractal_render::frame::check_image_size;
use fractal_render::precision::PrecisionChoice;
use fractal_render::select::BackendChoice;

use crate::export::Target;
use crate::output::{Aov, FrameRange, Shard};
use crate::package::Engine;
use crate::viewer::PresentMode;

/// Most frames `bench --frames` times.
pub const MAX_BENCH_FRAMES: u32 = 100_000;
/// Longest `bench --seconds`, in seconds.
pub const MAX_BENCH_SECONDS: f64 = 3600.0;

const AFTER_HELP: &str = "\
<SCENE> is a built-in scene name (see `fractal list`) or a path to a .fractal file.

Examples:
  fractal render mandelbulb --size 3840x2160 --time 2.5 -o bulb.png
  fractal render sphere_box --frames 0..240 --fps 30 -o frames/%05d.png
  fractal render sphere_box --frames 0..240 --shard 3/8 -o frames/%05d.png
  fractal render my_scene.fractal --frames 0..120 -o clip.mp4
  fractal bench --size 1920x1080 --frames 10 --backend wgpu --baseline --csv bench.csv
  fractal export sierpinski_collection --target glsl -o sierpinski.comp

Exit status: 0 on success, 2 for usage errors, 1 when rendering or writing fails.";

#[derive(Debug, Parser)]
#[command(
    name = "fractal",
    version,
    about = "Render, benchmark and export 3D fractal and signed-distance scenes",
    long_about = "Render, benchmark and export 3D fractal and signed-distance scenes.\n\n\
                  Scenes run as generated WGSL (wgpu), OpenCL C, or natively on the CPU.",
    after_help = AFTER_HELP,
    propagate_version = true
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Debug, Subcommand)]
pub enum Command {
    /// Render a scene to a PNG, a numbered PNG sequence or a video
    Render(RenderArgs),
    /// Time a scene on one backend and record the figures (CSV, JSON Lines)
    Bench(BenchArgs),
    /// Measure quality settings against a ground truth that does not trust the distance estimate
    Accuracy(AccuracyArgs),
    /// Write a scene's render kernel for another engine
    Export(ExportArgs),
    /// Write a scene's surface as a triangle mesh (.glb, .ply, .stl, .obj)
    Mesh(MeshArgs),
    /// List the built-in scenes
    List,
    /// Render every built-in scene into a folder, with a labelled contact sheet of them all
    Gallery(GalleryArgs),
    /// Open a scene in the interactive viewer (needs a display; press H in the window for the controls)
    View(ViewArgs),
}

/// Which device renders: the backend and OpenCL's math mode (render, bench, view, gallery).
#[derive(Clone, Copy, Debug, Args)]
pub struct DeviceArgs {
    /// Backend: auto tries wgpu, then OpenCL, then the CPU
    #[arg(long, value_name = "auto|wgpu|opencl|cpu", default_value = "auto", value_parser = parse_backend)]
    pub backend: BackendChoice,
    /// OpenCL: build without -cl-fast-relaxed-math
    #[arg(long)]
    pub precise: bool,
    /// Number type of each frame: auto picks f32 unless f32's rounding at the frame's hits is too coarse for the
    /// view (a close zoom, a scene far from the origin), then f64, which the backend draws where its device has
    /// f64 (OpenCL cl_khr_fp64, wgpu SHADER_F64) and the CPU renderer otherwise
    #[arg(long, value_name = "auto|f32|f64", default_value = "auto", value_parser = parse_precision)]
    pub precision: PrecisionChoice,
}

/// Options shared by the commands that render.
#[derive(Debug, Args)]
pub struct RenderOptions {
    /// Image size, WIDTHxHEIGHT (each side 1..=16384)
    #[arg(long, value_name = "WxH", default_value = "1920x1080", value_parser = parse_size)]
    pub size: (u32, u32),
    #[command(flatten)]
    pub device: DeviceArgs,
    /// Set a scene parameter (repeatable)
    #[arg(long = "param", value_name = "NAME=VALUE", value_parser = parse_param)]
    pub params: Vec<(String, f64)>,
    /// The most rays a pixel may take, 1..=256 (1: one ray through its centre) [default: the scene's `samples`]
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub samples: Option<u32>,
}

#[derive(Debug, Args)]
#[command(after_help = "\
Sequences: each frame is written atomically (NAME.partial, then renamed), and rerunning the same command renders only
the frames that are missing, so an interrupted render resumes where it stopped.

Shards: --shard I/N renders the frames f with (f - START) mod N = I. N jobs with I = 0..N-1 cover every frame exactly
once and may share one output directory, e.g. as a Slurm job array:
  #SBATCH --array=0-7
  fractal render mandelbulb --frames 0..2400 --fps 60 --shard $SLURM_ARRAY_TASK_ID/8 -o frames/%05d.png

Video (.mp4, .webm, .mkv, .mov) pipes raw RGBA frames to ffmpeg, which must be on PATH; sizes must be even.")]
pub struct RenderArgs {
    /// Built-in scene name or .fractal file
    pub scene: String,
    #[command(flatten)]
    pub render: RenderOptions,
    /// Scene time in seconds (single images)
    #[arg(long, allow_negative_numbers = true, value_name = "SECONDS", default_value_t = 0.0, conflicts_with = "frames", value_parser = parse_time)]
    pub time: f64,
    /// Output: a .png file, a frame pattern such as frames/%05d.png, or a video (.mp4, .webm, .mkv, .mov)
    /// [default: SCENE.png, or SCENE/%05d.png with --frames]
    #[arg(short, long, value_name = "PATH")]
    pub output: Option<PathBuf>,
    /// Refine the still for this many seconds: pass after pass of one ray a pixel at the pixel program's next sample
    /// (and lens point), averaged
    #[arg(long, value_name = "SECONDS", allow_negative_numbers = true, conflicts_with_all = ["frames", "aov", "samples"],
          value_parser = parse_progressive)]
    pub progressive: Option<f64>,
    /// Render an animation: frames START..END (end exclusive) or START..=END; frame f is at time f / fps
    #[arg(long, value_name = "START..END", value_parser = parse_frames)]
    pub frames: Option<FrameRange>,
    /// Frames per second of the animation
    #[arg(long, allow_negative_numbers = true, default_value_t = 30.0, requires = "frames", value_parser = parse_fps)]
    pub fps: f64,
    /// Render only shard I of N of the frames (for job arrays)
    #[arg(long, value_name = "I/N", requires = "frames", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Also write per-pixel depth, normal and/or steps as 32-bit float OpenEXR beside the PNG (NAME.depth.exr, ...);
    /// computed by the CPU renderer
    #[arg(long, value_name = "depth,normal,steps", value_delimiter = ',', conflicts_with = "frames", value_parser = parse_aov)]
    pub aov: Vec<Aov>,
    #[command(flatten)]
    pub camera: CameraOverride,
}

/// A camera that replaces the scene's own (its camera or camera path), so any view can be rendered and compared.
#[derive(Clone, Debug, Default, Args)]
pub struct CameraOverride {
    /// Camera position X,Y,Z (with --camera-target): replaces the scene's camera or camera path
    #[arg(long, value_name = "X,Y,Z", requires = "camera_target", allow_hyphen_values = true, value_parser = parse_point)]
    pub camera_pos: Option<[f64; 3]>,
    /// The point the camera looks at, X,Y,Z (with --camera-pos)
    #[arg(long, value_name = "X,Y,Z", requires = "camera_pos", allow_hyphen_values = true, value_parser = parse_point)]
    pub camera_target: Option<[f64; 3]>,
    /// Vertical field of view in degrees, in (0, 180)
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true, value_parser = parse_fov)]
    pub fov: Option<f64>,
}

impl CameraOverride {
    /// `camera` with what was given replaced.
    pub fn apply(&self, camera: &mut fractal_dsl::Camera) {
        if let (Some(position), Some(target)) = (self.camera_pos, self.camera_target) {
            camera.placement =
                fractal_dsl::CameraPlacement::LookAt { position: position.into(), target: target.into() };
        }
        if let Some(fov) = self.fov {
            camera.fov_degrees = fov;
        }
    }
}

pub fn parse_point(text: &str) -> Result<[f64; 3], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let [x, y, z] = parts[..] else {
        return Err(format!("`{text}` is not a point: write X,Y,Z, e.g. 0,1.5,-4"));
    };
    let coordinate = |c: &str| match c.parse::<f64>() {
        Ok(v) if fractal_dsl::validate::value_problem(v).is_none() => Ok(v),
        _ => Err(format!("`{c}` in `{text}` is not a finite coordinate within ±3.4e38")),
    };
    Ok([coordinate(x)?, coordinate(y)?, coordinate(z)?])
}

pub fn parse_fov(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v > 0.0 && v < 180.0 => Ok(v),
        _ => Err(format!("field of view `{text}` must be a number of degrees in (0, 180)")),
    }
}

pub fn parse_aov(text: &str) -> Result<Aov, String> {
    Aov::parse(text).ok_or_else(|| {
        let names: Vec<&str> = Aov::ALL.iter().map(|a| a.name()).collect();
        format!("unknown output `{text}`: the outputs are {}", names.join(", "))
    })
}

#[derive(Debug, Args)]
#[command(after_help = "\
Camera: the scene's own camera path if it has one (120 frames per pass, scene time = path time); otherwise an orbit
around the camera's target at its distance and height (3 degrees and 1/30 s of scene time per frame). With --baseline,
the scene's static camera at t = 0 for both the scene and the hand-written baseline.

Kernel time is read from the device where it can be (wgpu timestamp queries, OpenCL profiling events); the report
says when wall time is used instead. The error is measured once, untimed, on the first frame at a reduced size (at
most 240 pixels wide): precision against the CPU renderer running the f64 interpreter with the same settings, and the
true error against the ground truth of `fractal accuracy` (depth, normals and steps from the same backend's march).")]
pub struct BenchArgs {
    /// Built-in scene name or .fractal file [default: mandelbulb_bench, the hand-written baseline's scene]
    pub scene: Option<String>,
    #[command(flatten)]
    pub render: RenderOptions,
    /// Number of timed frames [default: 10]
    #[arg(long, allow_negative_numbers = true, value_name = "N", conflicts_with = "seconds", value_parser = clap::value_parser!(u32).range(1..=MAX_BENCH_FRAMES as i64))]
    pub frames: Option<u32>,
    /// Time frames until their frame times add up to this many seconds
    #[arg(long, allow_negative_numbers = true, value_name = "S", value_parser = parse_seconds)]
    pub seconds: Option<f64>,
    /// Append one CSV row to this file (header written when the file is new)
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Append one JSON record (one line, JSON Lines) to this file
    #[arg(long, value_name = "PATH")]
    pub json: Option<PathBuf>,
    /// Also time the hand-written baseline Mandelbulb kernel on the same device and print generated/baseline
    #[arg(long)]
    pub baseline: bool,
    /// Also measure the timed backend's image of the first frame against the truth of the image at the error size
    /// (docs/image-truth.md): PSNR, SSIM, pixels off by more than 8/255. Slow on fractals, whose truth takes many
    /// sub-rays a pixel; not for scenes with glow, which the truth does not define
    #[arg(long)]
    pub image_error: bool,
}

#[derive(Debug, Args)]
#[command(after_help = "\
Renders the scene at --time (default t = 0) with each quality setting (max steps, hit epsilon fixed or per pixel,
iterations of escape-time fractals, over-relaxation, the normal's taps, hits on escape-time sets themselves, fast math
on OpenCL, and on the CPU a factor on the step and the bound on or off), measures each against a ground truth computed
from each fractal's own membership test and exact primitive distances, and prints the table and the fastest setting
within the error budget: hit mismatch <= 0.5 %, overshoot <= 0.1 % (pixel-cone consistent), normal p99 <= 5 degrees
(pixel-cone consistent: against the nearest true normal across the pixel),
no ray out of steps, no NaN/Inf, interior depth p99 <= 1 footprint (pixel-cone consistent), thin-ray depth median
<= 1 footprint where the true surface is smooth at the pixel's scale. A scene with a camera
path is then judged from each of its other keys. --default-only measures the scene's own setting alone.
--report does it for every built-in scene and writes the Markdown report (docs/accuracy.md); with --default-only,
the defaults alone (to judge them at a size the sweep cannot afford). A normal p99 over fewer than 100 measured
normals is not judged, and the verdict says so.
--image measures the scene default's image instead against the truth of the image: per pixel, the box-filtered mean
of the scene's shading over a lattice of sub-rays (docs/image-truth.md): PSNR, SSIM, pixels off by more than 8/255,
normals against the pixel-integrated true normal, and flicker along --flicker-frames frames of the camera path, 1/30 s
apart (or an orbit of a pixel's angle per frame where the camera stands still); each image is judged against the image
budget: PSNR >= 35 dB, at most 2 % of pixels off by more than 8/255. With --samples and --sample-thresholds it
measures each anti-aliasing setting and names the one the rule for defaults chooses (the best image within 3x the
one-sample time, if it buys at least 3 dB over one sample); --plot draws the front; --report
does it for every built-in scene and writes docs/image-accuracy.md with its plots.")]
pub struct AccuracyArgs {
    /// Built-in scene name or .fractal file (every built-in scene with --report)
    #[arg(required_unless_present_any = ["report", "estimators"])]
    pub scene: Option<String>,
    /// Image size, WIDTHxHEIGHT
    #[arg(long, value_name = "WxH", default_value = "192x108", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Backend the settings are rendered on: cpu gives every figure, wgpu and opencl all but the evaluation count
    #[arg(long, value_name = "cpu|wgpu|opencl", default_value = "cpu", value_parser = parse_backend)]
    pub backend: BackendChoice,
    /// OpenCL: build without -cl-fast-relaxed-math
    #[arg(long)]
    pub precise: bool,
    /// Number type of every setting measured: auto takes the one each view asks for (f64 renders on the backend where
    /// its device has f64, else on the CPU)
    #[arg(long, value_name = "auto|f32|f64", default_value = "auto", value_parser = parse_precision)]
    pub precision: PrecisionChoice,
    /// After the sweep, measure the scene's default on these backends too, against the same truth (wgpu,opencl);
    /// one that does not open is reported, not an error
    #[arg(long, value_name = "BACKENDS", value_delimiter = ',', value_parser = parse_one_backend)]
    pub also_on: Vec<fractal_render::device::Backend>,
    /// Measure the scene's own setting only, no sweep (the truths, the default's figures and its verdict)
    #[arg(long)]
    pub default_only: bool,
    /// The most rays a pixel may take, 1..=256 [default: the scene's `samples`]; with --image a list (1,5,16), each
    /// measured against the same truth
    #[arg(long, value_name = "N[,N..]", value_delimiter = ',', value_parser = parse_samples)]
    pub samples: Vec<u32>,
    /// --image: the adaptive thresholds each count above one is measured with (0.004,0.001) [default: the scene's
    /// `sample_threshold`]
    #[arg(long, value_name = "E[,E..]", value_delimiter = ',', requires = "image", value_parser = parse_threshold)]
    pub sample_thresholds: Vec<f64>,

    /// Scene time in seconds the sweep is measured at (the camera path's pose and every animated value then); a
    /// camera path's other keys are checked after it
    #[arg(long, allow_negative_numbers = true, value_name = "SECONDS", default_value_t = 0.0, value_parser = parse_time)]
    pub time: f64,
    /// Truth march step in pixel footprints
    #[arg(long, value_name = "F", default_value_t = crate::truth::DEFAULT_STEP_FOOTPRINTS, value_parser = parse_truth_step)]
    pub truth_step: f64,
    /// Judge against the truth at N times the escape-time fractals' iterations (each family caps the product at its
    /// most) instead of doubling them from 1 until the figures stop moving; and every key of a camera path too
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=64))]
    pub truth_factor: Option<u32>,
    /// Append the table to this CSV file (header written when the file is new)
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Every built-in scene, written as a Markdown report (each from its own camera)
    #[arg(long, conflicts_with_all = ["camera_pos", "fov"])]
    pub report: bool,
    /// Where --report writes (its plots go in the folder of the same name: docs/accuracy/SCENE.svg)
    /// [default: docs/accuracy.md, with --image docs/image-accuracy.md]
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
    /// Write every pixel whose normal the scene default's CPU render is measured on to this CSV file: its ray, both
    /// hits, both normals and the two errors (for finding where normals go wrong)
    #[arg(long, value_name = "PATH", conflicts_with_all = ["report", "estimators", "image"])]
    pub normals_csv: Option<PathBuf>,
    /// Judge these normals against the truth as the budget judges a render's: a CSV file of x,y,nx,ny,nz per pixel
    /// (a way of taking normals tried outside the renderer; `benches/normal_split.py --out` writes one)
    #[arg(long, value_name = "PATH", conflicts_with_all = ["report", "estimators", "image"])]
    pub judge_normals: Option<PathBuf>,
    /// Write a time-against-error plot of each scene, SCENE.svg, into this folder
    #[arg(long, value_name = "DIR")]
    pub plot: Option<PathBuf>,
    /// Measure each fractal family's distance estimate against the true distance instead (also part of --report);
    /// with a scene, its own fractals, recording the step factor each formula written in the scene language measures
    #[arg(long)]
    pub estimators: bool,
    /// Points per family and region for the estimator study
    #[arg(long, value_name = "N", default_value_t = 300, value_parser = clap::value_parser!(u32).range(1..=100_000))]
    pub estimator_samples: u32,
    /// Measure the scene default's image against the truth of the image instead of sweeping: PSNR, SSIM, pixels
    /// off by more than 8/255, normals against the pixel-integrated true normal, and flicker along a slow camera move
    #[arg(long, conflicts_with_all = ["estimators", "default_only", "also_on", "csv"])]
    pub image: bool,
    /// --image: sub-rays per side of each pixel's first lattice
    #[arg(long, value_name = "N", default_value_t = crate::truth::image::DEFAULT_GRID, requires = "image",
          value_parser = clap::value_parser!(u32).range(2..=crate::truth::image::LARGEST_GRID as i64))]
    pub truth_grid: u32,
    /// --image: sub-rays per side of the finest lattice a pixel whose estimate has not settled refines to
    #[arg(long, value_name = "N", default_value_t = crate::truth::image::DEFAULT_MAX_GRID, requires = "image",
          value_parser = clap::value_parser!(u32).range(2..=crate::truth::image::LARGEST_GRID as i64))]
    pub truth_max_grid: u32,
    /// --image: a pixel's estimate has settled when the standard error of its sub-rays' mean display luma is at most
    /// this many 8-bit levels
    #[arg(long, value_name = "LEVELS", default_value_t = crate::truth::image::DEFAULT_SETTLE, requires = "image",
          allow_negative_numbers = true,
          value_parser = parse_settle)]
    pub truth_settle: f64,
    /// --image: frames of the camera move the flicker is measured over (1: no flicker figure)
    #[arg(long, value_name = "N", default_value_t = 3, requires = "image",
          value_parser = clap::value_parser!(u32).range(1..=64))]
    pub flicker_frames: u32,
    /// --image: also compute the image truth with both lattices doubled per side and print how far it moved
    #[arg(long, requires = "image")]
    pub truth_check: bool,
    /// --image: also draw progressive passes of the first frame for this long (as `fractal render --progressive`
    /// and the viewer standing still draw them) and measure their mean against the truth
    #[arg(long, value_name = "SECONDS", requires = "image", value_parser = parse_progressive)]
    pub progressive: Option<f64>,
    /// --image: write the first frame's truth and render here as PNG (SCENE.truth.png, SCENE.render.png)
    #[arg(long, value_name = "DIR", requires = "image")]
    pub image_out: Option<PathBuf>,
    #[command(flatten)]
    pub camera: CameraOverride,
}

fn parse_settle(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!("the settle threshold is a number of 8-bit levels >= 0, got `{text}`")),
    }
}

fn parse_truth_step(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 && v <= 1.0 => Ok(v),
        _ => Err(format!("the truth step is a number of footprints in (0, 1], got `{text}`")),
    }
}

#[derive(Debug, Args)]
#[command(after_help = "\
Engine packages: -o DIR gets the package's files (a library, a ready material, a README); a one-file package
(shadertoy) goes to standard output without -o.
Kernels: text goes to standard output without -o. SPIR-V is binary: it needs -o, or a standard output that is not a
terminal (a pipe or a file).")]
pub struct ExportArgs {
    /// Built-in scene name or .fractal file
    pub scene: String,
    /// An engine package (bevy, godot, unity, unreal, shadertoy, or the glsl, hlsl, wgsl function libraries; -o
    /// names a directory) or a render kernel (opencl, wgsl-kernel, glsl-kernel, hlsl-kernel, msl, spirv)
    #[arg(long, value_name = "TARGET", value_parser = parse_export_target, required_unless_present = "camera_path")]
    pub target: Option<ExportTarget>,
    /// Export the scene's camera as a glTF 2.0 camera animation instead of a kernel (z mirrored: glTF is
    /// right-handed)
    #[arg(long, conflicts_with = "target")]
    pub camera_path: bool,
    /// Camera export: samples per second between the camera path's keys, every key sampled too [default: 30]
    #[arg(long, value_name = "FPS", value_parser = parse_fps)]
    pub fps: Option<f64>,
    /// Camera export: seconds sampled of a look-at camera that moves with `t`; a path runs from its first key to its
    /// last [default: 10]
    #[arg(long, value_name = "SECONDS", value_parser = parse_positive)]
    pub duration: Option<f64>,
    /// Camera export: the image size whose aspect ratio the glTF camera records, WIDTHxHEIGHT [default: 1920x1080]
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Output file
    #[arg(short, long, value_name = "PATH")]
    pub output: Option<PathBuf>,
}

#[derive(Debug, Args)]
#[command(after_help = "\
The surface is extracted by surface nets from the scene's distance function, cut to the meshing box (the scene's
bound, the cube of half-side 4 around the origin for an unbounded scene, or --bounds), so the mesh is closed. The grid
streams through memory a layer at a time. Files are in glTF's right-handed frame: the renderer's with z mirrored,
as `fractal export --camera-path` writes cameras.")]
pub struct MeshArgs {
    /// Built-in scene name or .fractal file
    pub scene: String,
    /// Cells along the longest side of the meshing box
    #[arg(long, value_name = "N", default_value_t = 256, value_parser = clap::value_parser!(u32).range(8..=4096))]
    pub resolution: u32,
    /// Output file: .glb, .ply, .stl or .obj; with --frames a pattern such as meshes/%05d.glb
    #[arg(short, long, value_name = "PATH")]
    pub output: PathBuf,
    /// A mesh sequence: frames START..END (end exclusive) or START..=END; frame f is at time f / fps
    #[arg(long, value_name = "START..END", value_parser = parse_frames, conflicts_with = "time")]
    pub frames: Option<FrameRange>,
    /// Frames per second of the sequence
    #[arg(long, default_value_t = 30.0, value_parser = parse_fps)]
    pub fps: f64,
    /// The box to mesh, X0,Y0,Z0,X1,Y1,Z1 (default: the scene's bound)
    #[arg(long, value_name = "X0,Y0,Z0,X1,Y1,Z1", value_parser = parse_bounds)]
    pub bounds: Option<[f64; 6]>,
    /// Scene time in seconds
    #[arg(long, allow_negative_numbers = true, value_name = "SECONDS", default_value_t = 0.0, value_parser = parse_time)]
    pub time: f64,
    /// Set a scene parameter (repeatable)
    #[arg(long = "param", value_name = "NAME=VALUE", value_parser = parse_param)]
    pub params: Vec<(String, f64)>,
}

#[derive(Debug, Args)]
#[command(after_help = "\
Each scene is drawn from its own camera (the start of its camera path) with its parameters at their defaults, into
DIR/<scene>.png; DIR/gallery.png is the contact sheet, scene names under the images.")]
pub struct GalleryArgs {
    /// Folder for the images and the contact sheet (created if missing)
    #[arg(short, long, value_name = "DIR", default_value = "gallery")]
    pub output: PathBuf,
    /// Size of each scene's image, WIDTHxHEIGHT
    #[arg(long, value_name = "WxH", default_value = "320x180", value_parser = parse_size)]
    pub size: (u32, u32),
    #[command(flatten)]
    pub device: DeviceArgs,
    /// Scene time of every image, in seconds
    #[arg(long, allow_negative_numbers = true, value_name = "SECONDS", default_value_t = 0.0, value_parser = parse_time)]
    pub time: f64,
    /// Images per row of the contact sheet
    #[arg(long, value_name = "N", default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub columns: u32,
    /// The most rays a pixel may take, 1..=256 (1: one ray through its centre) [default: the scene's `samples`]
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub samples: Option<u32>,
}

#[derive(Debug, Args)]
#[command(after_help = "\
Controls: click to capture the mouse (Esc releases it), W A S D to move, Q / E down / up, Shift faster, P prints the
camera pose, 1-4 toggle shadows / ambient occlusion / glow / fog, 0/9 and 8/7 change steps and epsilon, Space pauses
time, Tab and the arrow keys change parameters, O shows or hides the panel (drag its sliders for time and parameters),
F12 or K saves a screenshot, H prints all controls. A .fractal file is reloaded whenever it is saved. While the view
stands still (nothing that changes the picture changes), it refines pass by pass; --no-accumulate turns that off.")]
pub struct ViewArgs {
    /// Built-in scene name or .fractal file
    pub scene: String,
    /// Window size, WIDTHxHEIGHT
    #[arg(long, value_name = "WxH", default_value = "1280x720", value_parser = parse_size)]
    pub size: (u32, u32),
    #[command(flatten)]
    pub device: DeviceArgs,
    /// Scene time at start, in seconds
    #[arg(long, allow_negative_numbers = true, value_name = "SECONDS", default_value_t = 0.0, value_parser = parse_time)]
    pub time: f64,
    /// Start with time paused
    #[arg(long)]
    pub paused: bool,
    /// Start a scene parameter at this value (repeatable; change it live with Tab and the arrow keys)
    #[arg(long = "param", value_name = "NAME=VALUE", value_parser = parse_param)]
    pub params: Vec<(String, f64)>,
    /// Play this TOML camera path instead of the scene's camera
    #[arg(long, value_name = "PATH")]
    pub camera_path: Option<PathBuf>,
    /// Camera speed in scene units per second
    #[arg(long, allow_negative_numbers = true, value_name = "SPEED", default_value_t = 1.0, value_parser = parse_positive)]
    pub move_speed: f64,
    /// Mouse sensitivity in radians per pixel
    #[arg(long, allow_negative_numbers = true, value_name = "RADIANS", default_value_t = 0.003, value_parser = parse_positive)]
    pub mouse_sensitivity: f64,
    /// The most rays a pixel may take, 1..=256 (1: one ray through its centre) [default: the scene's `samples`]
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub samples: Option<u32>,
    /// Do not refine the picture while the view stands still (by default each frame adds a progressive pass, up to
    /// 256, while nothing that changes the picture changes)
    #[arg(long)]
    pub no_accumulate: bool,
    /// Render this fraction of the window, 0.05..=1 [default: adapts to hold 30 frames/s; 1 with --headless]
    #[arg(long, value_name = "FRACTION", value_parser = parse_scale)]
    pub scale: Option<f64>,
    /// Run the viewer with no window: its frames (with the panel only with --panel) go to a target of the window's
    /// size, time advances 1/60 s per frame, and the frame times are printed
    #[arg(long)]
    pub headless: bool,
    /// With --headless: how many frames to draw
    #[arg(long, value_name = "N", default_value_t = 120, requires = "headless", value_parser = clap::value_parser!(u64).range(1..=1_000_000))]
    pub frames: u64,
    /// How wgpu frames reach the window: `gpu` draws them to it on the device, `host` reads them back and shows them
    /// through softbuffer, `auto` is `gpu` on a GPU and `host` on a software rasteriser (lavapipe)
    #[arg(long, value_name = "auto|gpu|host", default_value = "auto", value_parser = parse_present)]
    pub present: PresentMode,
    /// With --headless: save the last frame, as a window would show it, to this PNG
    #[arg(long, value_name = "PATH", requires = "headless")]
    pub screenshot: Option<PathBuf>,
    /// With --headless: draw the panel over every frame too (its layout and drawing count in the frame times)
    #[arg(long, requires = "headless")]
    pub panel: bool,
}

/// A render scale: a fraction of the window in 0.05..=1.
pub fn parse_scale(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if (0.05..=1.0).contains(&v) => Ok(v),
        _ => Err(format!("--scale takes a fraction of the window in 0.05..=1, got `{text}`")),
    }
}

/// `WIDTHxHEIGHT`, each side within the renderers' limits.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let expected = || format!("expected WIDTHxHEIGHT, e.g. 1920x1080, got `{text}`");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(expected)?;
    let side = |s: &str| s.trim().parse::<u32>().map_err(|_| expected());
    let (w, h) = (side(w)?, side(h)?);
    check_image_size(w, h).map_err(|e| e.to_string())?;
    Ok((w, h))
}

/// Seconds of progressive refinement: positive, at most a day.
pub fn parse_progressive(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(v) if v > 0.0 && v <= 86_400.0 => Ok(v),
        _ => Err(format!("--progressive takes seconds in (0, 86400], got `{text}`")),
    }
}

/// A sample count within the scene language's limits.
pub fn parse_samples(text: &str) -> Result<u32, String> {
    let max = fractal_dsl::validate::MAX_SAMPLES;
    match text.parse::<u32>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!("samples per pixel must be a whole number in 1..={max}, got `{text}`")),
    }
}

fn parse_threshold(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(e) if (0.0..=1.0).contains(&e) => Ok(e),
        _ => Err(format!("a sample threshold is a number in 0..=1 (display luma), got `{text}`")),
    }
}

pub fn parse_precision(text: &str) -> Result<PrecisionChoice, String> {
    text.parse::<PrecisionChoice>().map_err(|e| e.to_string())
}

pub fn parse_present(text: &str) -> Result<PresentMode, String> {
    text.parse::<PresentMode>()
}

pub fn parse_backend(text: &str) -> Result<BackendChoice, String> {
    text.parse::<BackendChoice>().map_err(|e| e.to_string())
}

fn parse_one_backend(text: &str) -> Result<fractal_render::device::Backend, String> {
    match parse_backend(text)? {
        BackendChoice::Only(b) => Ok(b),
        BackendChoice::Auto => Err("name a backend: cpu, wgpu or opencl".to_string()),
    }
}

/// What `fractal export --target` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExportTarget {
    /// A render kernel ([`crate::export`]).
    Kernel(Target),
    /// An engine package ([`crate::package`]).
    Package(Engine),
}

pub fn parse_export_target(text: &str) -> Result<ExportTarget, String> {
    if let Ok(engine) = text.parse::<Engine>() {
        return Ok(ExportTarget::Package(engine));
    }
    text.parse::<Target>().map(ExportTarget::Kernel).map_err(|_| {
        format!(
            "unknown export target `{text}`: expected an engine package (bevy, godot, unity, unreal, shadertoy, \
             glsl, hlsl, wgsl) or a kernel (opencl, wgsl-kernel, glsl-kernel, hlsl-kernel, msl, spirv)"
        )
    })
}

pub fn parse_frames(text: &str) -> Result<FrameRange, String> {
    text.parse::<FrameRange>().map_err(|e| e.to_string())
}

pub fn parse_shard(text: &str) -> Result<Shard, String> {
    text.parse::<Shard>().map_err(|e| e.to_string())
}

/// `name=value` with a finite number.
pub fn parse_bounds(text: &str) -> Result<[f64; 6], String> {
    let values: Vec<f64> = text.split(',').map(|v| finite(v.trim(), "bound")).collect::<Result<_, _>>()?;
    let Ok(b) = <[f64; 6]>::try_from(values) else {
        return Err(format!("bounds `{text}`: expected X0,Y0,Z0,X1,Y1,Z1"));
    };
    if (0..3).any(|a| b[a] >= b[a + 3]) {
        return Err(format!("bounds `{text}`: each minimum must be below its maximum"));
    }
    Ok(b)
}

pub fn parse_param(text: &str) -> Result<(String, f64), String> {
    let (name, value) = text.split_once('=').ok_or_else(|| format!("expected NAME=VALUE, got `{text}`"))?;
    let value: f64 = value.trim().parse().map_err(|_| format!("`{value}` is not a number"))?;
    if !value.is_finite() {
        return Err(format!("`{text}`: the value must be finite"));
    }
    Ok((name.trim().to_string(), value))
}

fn finite(text: &str, what: &str) -> Result<f64, String> {
    let value: f64 = text.trim().parse().map_err(|_| format!("{what} `{text}` is not a number"))?;
    if !value.is_finite() {
        return Err(format!("{what} `{text}` is not finite"));
    }
    Ok(value)
}

pub fn parse_time(text: &str) -> Result<f64, String> {
    let t = finite(text, "time")?;
    fractal_render::frame::check_time(t).map_err(|e| e.to_string())?;
    Ok(t)
}

pub fn parse_fps(text: &str) -> Result<f64, String> {
    let fps = finite(text, "frame rate")?;
    if fps <= 0.0 {
        return Err(format!("frame rate `{text}` must be greater than 0"));
    }
    Ok(fps)
}

pub fn parse_positive(text: &str) -> Result<f64, String> {
    let v = finite(text, "value")?;
    if v <= 0.0 {
        return Err(format!("`{text}` must be greater than 0"));
    }
    Ok(v)
}

pub fn parse_seconds(text: &str) -> Result<f64, String> {
    let s = finite(text, "duration")?;
    if s <= 0.0 || s > MAX_BENCH_SECONDS {
        return Err(format!("duration `{text}` must be in (0, {MAX_BENCH_SECONDS}] seconds"));
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    #[test]
    fn the_grammar_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn sizes_are_checked_before_anything_is_allocated() {
        assert_eq!(parse_size("1920x1080"), Ok((1920, 1080)));
        assert_eq!(parse_size("32X16"), Ok((32, 16)));
        assert!(parse_size("0x0").unwrap_err().contains("invalid"));
        assert!(parse_size("100000x100000").unwrap_err().contains("1..=16384"));
        for bad in ["", "1920", "x", "axb", "-1x5", "1920x1080x3"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn params_and_rates_are_numbers() {
        assert_eq!(parse_param("power=8.5"), Ok(("power".to_string(), 8.5)));
        assert!(parse_param("power").is_err());
        assert!(parse_param("power=inf").is_err());
        assert!(parse_fps("0").is_err());
        assert!(parse_fps("NaN").is_err());
        assert_eq!(parse_fps("29.97"), Ok(29.97));
        assert!(parse_seconds("-1").is_err());
    }
}
