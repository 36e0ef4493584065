//! `fractal accuracy SCENE --image`: the scene default's image against the truth of the image
//! ([`crate::truth::image`]) — PSNR, SSIM, pixels off by more than 8/255, normals against the pixel-integrated true
//! normal — and flicker along a few frames of a slow camera move, by the metrics of [`crate::accuracy::image`].

use std::fmt::Write as _;
use std::time::Instant;

use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::Scene;
use fractal_render::backend::cpu::{render_scene, trace_scene, PixelTrace};
use fractal_render::device::Backend;
use fractal_render::frame::{Frame, ParamValues};
use fractal_render::image::Image;
use fractal_render::renderer::{KernelSources, RenderJob, Renderer};
use fractal_render::select::RendererOptions;
use fractal_render::Pose;

use crate::accuracy::image::{flicker, image_error, motion, normal_error, ImageBudget};
use crate::cli::args::AccuracyArgs;
use crate::cli::error::CliError;
use crate::cli::scene::LoadedScene;
use crate::output::png::{prepare_output, write_png};
use crate::truth::image::{ImageTruth, ImageTruthError, ImageTruthSettings};
use crate::truth::TruthSettings;

/// Scene time between the frames of a camera path the flicker is measured along: one frame at 30 frames a second.
pub const FLICKER_STEP: f64 = 1.0 / 30.0;
/// Timed renders of the default; the median is reported.
const TIMING_RUNS: usize = 3;

/// The image truth's settings from the command line.
pub fn settings(args: &AccuracyArgs) -> Result<ImageTruthSettings, CliError> {
    let settings = ImageTruthSettings {
        grid: args.truth_grid,
        max_grid: args.truth_max_grid,
        settle: args.truth_settle,
        truth: TruthSettings { step_footprints: args.truth_step, iteration_factor: args.truth_factor.unwrap_or(1) },
    };
    settings.check().map_err(CliError::usage)?;
    Ok(settings)
}

/// Measures one scene's default image (or its image at each of `--samples`' counts, and at one sample for the
/// ratios) against the image truth of each frame of the flight; prints the figures and returns them as Markdown.
pub fn study(loaded: &LoadedScene, args: &AccuracyArgs, backend: Backend) -> Result<String, CliError> {
    let settings = settings(args)?;
    // Glow is a sum along the renderer's march, which the truth does not define: both go without it.
    let mut without_glow = loaded.scene.clone();
    let glow = without_glow.settings.glow.take().is_some();
    let scene = &without_glow;
    let params = loaded.params(&[])?;
    let (w, h) = args.size;
    let poses = flight(scene, &params, args.time, args.flicker_frames, w, h)?;
    let mut renderer = match backend {
        Backend::Cpu => None,
        other => Some(fractal_render::select::open(other, &RendererOptions { precise: args.precise })?),
    };
    let mut md = String::new();
    let at = if args.time == 0.0 { String::new() } else { format!(" at t = {} s", args.time) };
    let say = &mut |line: String| {
        println!("{line}");
        let _ = writeln!(md, "{line}");
    };
    let glow = if glow { ", its glow left out" } else { "" };
    say(format!("image accuracy of {}{at} at {w}x{h} on {backend} (the scene default{glow})", loaded.name));
    let mut frames = Vec::new();
    let mut truths: Vec<Image> = Vec::new();
    let mut first_truth = None;
    for (i, (time, pose)) in poses.iter().enumerate() {
        let frame = Frame::new(scene, pose, *time, w, h, &params).map_err(|e| CliError::failure(e.to_string()))?;
        let start = Instant::now();
        let truth = ImageTruth::compute(scene, &frame, settings).map_err(truth_error)?;
        let took = start.elapsed().as_secs_f64();
        truths.push(truth.image());
        if i == 0 {
            say(format!(
                "  image truth: {g}x{g} sub-rays per pixel up to {m}x{m} until the standard error of the mean display \
                 luma is at most {s} levels; {:.1} sub-rays per pixel on average, {:.2} % of pixels not settled; \
                 {took:.1} s",
                truth.mean_sub_rays(),
                100.0 * truth.unsettled(),
                g = settings.grid,
                m = settings.max_grid,
                s = settings.settle,
            ));
            if args.truth_check {
                let finer = ImageTruthSettings { grid: 2 * settings.grid, max_grid: 2 * settings.max_grid, ..settings };
                finer.check().map_err(CliError::usage)?;
                let start = Instant::now();
                let check = ImageTruth::compute(scene, &frame, finer).map_err(truth_error)?;
                say(format!(
                    "  image truth with lattices doubled ({}x{} up to {}x{}) against it: {} ({:.1} s)",
                    finer.grid,
                    finer.grid,
                    finer.max_grid,
                    finer.max_grid,
                    image_error(&check.image(), &truths[0]).describe(),
                    start.elapsed().as_secs_f64()
                ));
            }
            first_truth = Some(truth);
        } else {
            say(format!("  frame {i} (t = {time:.3} s): image truth {took:.1} s"));
        }
        frames.push(frame);
    }
    let first_truth = first_truth.expect("a flight has a first frame");
    if frames.len() > 1 {
        let moved = if poses.iter().all(|(t, _)| *t == args.time) {
            "an orbit of a pixel's angle per frame".to_string()
        } else {
            format!("the camera path, {FLICKER_STEP:.4} s apart")
        };
        say(format!(
            "  flicker over {} frames of {moved}; the truth moved {:.2} levels RMS",
            frames.len(),
            motion(&truths)
        ));
    }
    // One sample first: the time and flicker ratios are against it.
    let own = scene.settings.samples;
    let mut counts: Vec<u32> = if args.samples.is_empty() { vec![own] } else { args.samples.clone() };
    if !counts.contains(&1) {
        counts.insert(0, 1);
    }
    let mut single: Option<(f64, f64)> = None;
    for n in counts {
        let mut sampled = scene.clone();
        sampled.settings.samples = n;
        let mut images = Vec::new();
        let (mut ms, mut traces) = (0.0, None);
        for (i, frame) in frames.iter().enumerate() {
            let (image, t, took) = render(&sampled, frame, backend, renderer.as_mut(), i == 0)?;
            if i == 0 {
                (ms, traces) = (took, t);
                if let Some(dir) = &args.image_out {
                    let own = if n == scene.settings.samples { String::new() } else { format!(".{n}") };
                    for (what, picture) in [("truth", &truths[0]), ("render", &image)] {
                        let path = dir.join(format!("{}{own}.{what}.png", loaded.name));
                        prepare_output(&path)?;
                        write_png(&path, picture)?;
                    }
                }
            }
            images.push(image);
        }
        let error = image_error(&truths[0], &images[0]);
        let paired: Vec<(Image, Image)> = images.iter().cloned().zip(truths.iter().cloned()).collect();
        let shimmer = (paired.len() > 1).then(|| flicker(&paired));
        let (base_ms, base_flicker) = *single.get_or_insert((ms, shimmer.unwrap_or(f64::NAN)));
        let per_pixel = traces.as_ref().map_or(f64::NAN, |t: &Vec<PixelTrace>| {
            t.iter().map(|p| f64::from(p.samples)).sum::<f64>() / t.len() as f64
        });
        let shimmer =
            shimmer.map_or(String::new(), |f| format!(", flicker {f:.2} levels RMS ({:.2}x)", f / base_flicker));
        say(format!(
            "  samples {n} (threshold {}): {per_pixel:.2} per pixel, {ms:.1} ms ({:.2}x), {}{shimmer}; {}",
            scene.settings.sample_threshold,
            ms / base_ms,
            error.describe(),
            ImageBudget::default().verdict(&error),
        ));
        if n == own {
            match &traces {
                Some(traces) => say(format!("    {}", normal_error(&first_truth, traces).describe())),
                None => say("    normals: not read on this backend".to_string()),
            }
        }
    }
    Ok(md)
}

fn truth_error(e: ImageTruthError) -> CliError {
    match e {
        ImageTruthError::Settings(message) => CliError::usage(message),
        ImageTruthError::Render(e) => e.into(),
    }
}

/// The scene's render on `backend`: its image, its per-pixel traces where the backend keeps them, and the median
/// time of [`TIMING_RUNS`] renders in milliseconds (where `timed`; else one render, untimed, and no traces).
fn render(
    scene: &Scene,
    frame: &Frame,
    backend: Backend,
    renderer: Option<&mut Box<dyn Renderer>>,
    timed: bool,
) -> Result<(Image, Option<Vec<PixelTrace>>, f64), CliError> {
    let runs = if timed { TIMING_RUNS } else { 1 };
    let mut times = Vec::new();
    let (image, traces) = match (backend, renderer) {
        (Backend::Cpu, _) | (_, None) => {
            let interpreter = Interpreter::new(scene).map_err(|e| CliError::failure(e.to_string()))?;
            let mut image = None;
            for _ in 0..runs {
                let start = Instant::now();
                image = Some(render_scene::<f32, _>(&interpreter, scene, frame)?);
                times.push(start.elapsed().as_secs_f64() * 1e3);
            }
            let traces = if timed { Some(trace_scene::<f32, _>(&interpreter, scene, frame)?) } else { None };
            (image.expect("rendered at least once"), traces)
        }
        (_, Some(renderer)) => {
            let kernels = fractal_dsl::compile(scene).map_err(|e| CliError::failure(e.to_string()))?;
            let job = RenderJob::new(KernelSources::compiled(&kernels), frame);
            // The first render builds the kernel; it is not timed.
            let mut image = renderer.render(&job)?;
            for _ in 0..runs {
                let start = Instant::now();
                image = renderer.render(&job)?;
                times.push(start.elapsed().as_secs_f64() * 1e3);
            }
            if !timed {
                return Ok((image, None, f64::NAN));
            }
            let tracing = kernels.tracing();
            let traced = renderer.trace(&RenderJob::new(KernelSources::compiled(&tracing), frame))?;
            (image, Some(traced.pixels))
        }
    };
    times.sort_by(f64::total_cmp);
    Ok((image, traces, times[times.len() / 2]))
}

/// The scene times and poses of `count` frames of a slow camera move from `time`: the camera path's, [`FLICKER_STEP`]
/// apart, where the camera moves then; else an orbit about the vertical through the point as far along the view as
/// the camera is from the origin (at least one unit), turning by one pixel's angle per frame.
fn flight(
    scene: &Scene,
    params: &ParamValues,
    time: f64,
    count: u32,
    width: u32,
    height: u32,
) -> Result<Vec<(f64, Pose)>, CliError> {
    let lookup = |p: &fractal_dsl::ParamDecl| params.lookup(p);
    let pose_at = |t: f64| Pose::from_camera(&scene.camera, t, &lookup).map_err(|e| CliError::failure(e.to_string()));
    let first = pose_at(time)?;
    let next = pose_at(time + FLICKER_STEP)?;
    let moves = (next.position - first.position).length() > 1e-9 || (next.forward - first.forward).length() > 1e-9;
    if moves {
        return (0..count)
            .map(|i| {
                let t = time + i as f64 * FLICKER_STEP;
                Ok((t, pose_at(t)?))
            })
            .collect();
    }
    let frame = Frame::new(scene, &first, time, width, height, params).map_err(|e| CliError::failure(e.to_string()))?;
    let angle = frame.pixel_footprint() as f64;
    let pivot = first.position + first.forward * first.position.length().max(1.0);
    let axis = glam::DVec3::Y;
    Ok((0..count)
        .map(|i| {
            let turn = glam::DQuat::from_axis_angle(axis, i as f64 * angle);
            let pose = Pose {
                position: pivot + turn * (first.position - pivot),
                forward: (turn * first.forward).normalize(),
                ..first
            };
            (time, pose)
        })
        .collect())
}
