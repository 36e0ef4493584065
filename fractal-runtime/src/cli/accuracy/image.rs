//! `fractal accuracy SCENE --image`: the scene default's image, and its image at each anti-aliasing setting asked
//! for, against the truth of the image ([`crate::truth::image`]) — PSNR, SSIM, pixels off by more than 8/255, normals
//! against the pixel-integrated true normal — and flicker along a few frames of a slow camera move, by the metrics of
//! [`crate::accuracy::image`]; the settings' front and the setting the rule for defaults chooses
//! ([`crate::accuracy::samples`]); with `--report`, every built-in scene written as `docs/image-accuracy.md`.

use std::fmt::Write as _;
use std::time::Instant;

use fractal_dsl::eval::Evaluator;
use fractal_dsl::{Kernels, Scene};
use fractal_render::backend::cpu::PixelTrace;
use fractal_render::device::Backend;
use fractal_render::frame::{Frame, ParamValues};
use fractal_render::image::Image;
use fractal_render::progressive::Progressive;
use fractal_render::renderer::{KernelSources, RenderJob, Renderer};
use fractal_render::select::RendererOptions;
use fractal_render::Pose;

use super::files::{plot_dir, report_path, write_plot};
use crate::accuracy::image::{flicker, image_error, motion, normal_error, ImageBudget, OFF_LEVELS};
use crate::accuracy::plot;
use crate::accuracy::samples::{self, single, SamplePoint};
use crate::cli::args::AccuracyArgs;
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary};
use crate::output::png::{prepare_output, write_png};
use crate::truth::image::{ImageTruth, ImageTruthError, ImageTruthSettings};
use crate::truth::TruthSettings;

/// Scene time between the frames of a camera path the flicker is measured along: one frame at 30 frames a second.
pub const FLICKER_STEP: f64 = 1.0 / 30.0;
/// Timed renders of the default; the median is reported.
const TIMING_RUNS: usize = 3;
/// Renders faster than this many seconds in all are timed again, up to [`MOST_TIMING_RUNS`]: a render of a few
/// milliseconds varies by more than the ratios the table compares.
const TIMING_SECONDS: f64 = 0.5;
/// The most timed renders of one setting.
const MOST_TIMING_RUNS: usize = 25;

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

/// `fractal accuracy --image`: one scene's study, or with `--report` every built-in scene's and the report.
pub fn run(args: &AccuracyArgs, library: &SceneLibrary, backend: Backend) -> Result<(), CliError> {
    let names: Vec<String> = match (&args.scene, args.report) {
        (Some(name), false) => vec![name.clone()],
        (Some(_), true) => return Err(CliError::usage("--report studies every built-in scene: give no scene with it")),
        (None, true) => library.scenes.iter().map(|(n, _)| n.to_string()).collect(),
        (None, false) => return Err(CliError::usage("--image measures one scene: name it, or give --report")),
    };
    let out = report_path(args);
    if args.report {
        prepare_output(&out)?;
    }
    let (mut sections, mut summary) = (String::new(), String::new());
    for name in &names {
        let mut loaded = LoadedScene::load(name, library)?;
        args.camera.apply(&mut loaded.scene.camera);
        let study = study(&loaded, args, backend)?;
        sections += &study.markdown;
        summary += &summary_row(name, &study.points);
        if let Some(dir) = plot_dir(args) {
            let path = dir.join(format!("{name}.svg"));
            write_plot(&path, plot::image_svg(name, &study.points, &ImageBudget::default()))?;
            println!("  wrote {}", path.display());
            if args.report {
                let folder = dir.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
                sections += &format!("![{name}: time against image error]({folder}/{name}.svg)\n\n");
            }
        }
    }
    if args.report {
        let text = report_text(args, backend, &summary, &sections);
        std::fs::write(&out, text).map_err(|e| CliError::failure(format!("cannot write {}: {e}", out.display())))?;
        eprintln!("wrote {}", out.display());
    }
    Ok(())
}

/// A scene's line in the report's summary: its default against one sample, and the rule's choice.
fn summary_row(name: &str, points: &[SamplePoint]) -> String {
    let (Some(one), Some(own)) = (single(points), points.iter().find(|p| p.default)) else {
        return String::new();
    };
    let chosen = samples::chosen(points).map_or("–".to_string(), |c| c.label(own.threshold));
    let violations = ImageBudget::default().violations(&own.error);
    format!(
        "| {name} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {chosen} | {} |\n",
        own.samples,
        one.error.psnr,
        own.error.psnr,
        100.0 * own.error.off,
        own.time_ms / one.time_ms,
        if violations.is_empty() { "within".to_string() } else { violations.join("; ") },
    )
}

/// The report: how it was made, what its columns mean, the summary and every scene's section.
fn report_text(args: &AccuracyArgs, backend: Backend, summary: &str, sections: &str) -> String {
    let (w, h) = args.size;
    let mut command = format!("fractal accuracy --image --report --size {w}x{h} --backend {backend}");
    let list = |v: Vec<String>| v.join(",");
    if !args.samples.is_empty() {
        command += &format!(" --samples {}", list(args.samples.iter().map(u32::to_string).collect()));
    }
    if !args.sample_thresholds.is_empty() {
        command +=
            &format!(" --sample-thresholds {}", list(args.sample_thresholds.iter().map(f64::to_string).collect()));
    }
    command += &format!(" --flicker-frames {} --truth-step {}", args.flicker_frames, args.truth_step);
    let defaults = ImageTruthSettings::default();
    if (args.truth_grid, args.truth_max_grid, args.truth_settle) != (defaults.grid, defaults.max_grid, defaults.settle)
    {
        command += &format!(
            " --truth-grid {} --truth-max-grid {} --truth-settle {}",
            args.truth_grid, args.truth_max_grid, args.truth_settle
        );
    }
    let budget = ImageBudget::default();
    let flicker = match args.flicker_frames {
        1 => "flicker is not measured (one frame; `--flicker-frames 2` or more measures it)".to_string(),
        n => format!(
            "flicker along {n} frames of the camera move (8-bit levels RMS of the render's change between frames \
             less the truth's) and its ratio to one sample"
        ),
    };
    format!(
        "# Image accuracy: samples per pixel against the truth of the image\n\n\
         Written by `{command}`. Every built-in scene is rendered from its own camera at t = 0 (its glow left out, \
         which the truth does not define) with one sample per pixel and each anti-aliasing setting, and measured \
         against the truth of the image: per pixel, the box-filtered mean of the scene's shading over a lattice of \
         true sub-rays (`docs/image-truth.md`, where every figure is defined). The geometry of the same renders is \
         judged in `docs/accuracy.md`.\n\n\
         Columns: rays a pixel took on average; render time (median of {TIMING_RUNS} renders, or of as many as \
         fill {TIMING_SECONDS} s up to {MOST_TIMING_RUNS}; on the CPU in packets as \
         `fractal render` draws) and its ratio to one sample; PSNR and SSIM against the truth; pixels with a channel \
         off by more than {OFF_LEVELS}/255; {flicker}; the image budget's verdict (PSNR ≥ {} dB, at most {} % of \
         pixels off).\n\n\
         **The rule for a scene's default**: the setting of the best image within {}x the one-sample time, where it \
         buys at least {} dB over one sample; else one sample (`fractal-runtime/src/accuracy/samples.rs`). Each \
         scene's line says what it chooses; `docs/settings.md` (“Samples per pixel”) says where a default departs \
         from it and why.\n\n\
         | scene | default samples | PSNR 1 sample | PSNR default | off % default | time × default | rule's choice | \
         image budget (default) |\n|---|---|---|---|---|---|---|---|\n{summary}\n{sections}",
        budget.psnr,
        100.0 * budget.off,
        samples::TIME_LIMIT,
        samples::WORTH_DB,
    )
}

/// One scene's image study: its section of the report and its points.
pub struct ImageStudy {
    /// `## scene`, the truth's figures as a list, the table and the rule's choice.
    pub markdown: String,
    /// Every anti-aliasing setting measured, one sample first.
    pub points: Vec<SamplePoint>,
}

/// Prints `line` and adds it to `md` as an item of a list.
fn say(md: &mut String, line: String) {
    println!("{line}");
    let _ = writeln!(md, "- {}", line.trim_start());
}

/// Measures one scene's default image (or its image at each of `--samples`' counts with each of
/// `--sample-thresholds`, and at one sample for the ratios) against the image truth of each frame of the flight;
/// prints the figures and returns them, with the scene's section of the report.
pub fn study(loaded: &LoadedScene, args: &AccuracyArgs, backend: Backend) -> Result<ImageStudy, CliError> {
    let settings = settings(args)?;
    // Glow is a sum along the renderer's march, which the truth does not define: both go without it.
    let mut without_glow = loaded.scene.clone();
    let glow = without_glow.settings.glow.take().is_some();
    let scene = &without_glow;
    let params = loaded.params(&[])?;
    let (w, h) = args.size;
    let poses = flight(scene, &params, args.time, args.flicker_frames, w, h)?;
    let mut renderer = fractal_render::select::open(backend, &RendererOptions { precise: args.precise })?;
    let mut md = format!("## {}\n\n", loaded.name);
    let at = if args.time == 0.0 { String::new() } else { format!(" at t = {} s", args.time) };
    let glow = if glow { ", its glow left out" } else { "" };
    println!("image accuracy of {}{at} at {w}x{h} on {backend} (the scene's settings{glow})", loaded.name);
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
            say(
                &mut md,
                format!(
                "  image truth: {g}x{g} sub-rays per pixel up to {m}x{m} until the standard error of the mean display \
                 luma is at most {s} levels; {:.1} sub-rays per pixel on average, {:.2} % of pixels not settled; \
                 {took:.1} s",
                truth.mean_sub_rays(),
                100.0 * truth.unsettled(),
                g = settings.grid,
                m = settings.max_grid,
                s = settings.settle,
            ),
            );
            if args.truth_check {
                let finer = ImageTruthSettings { grid: 2 * settings.grid, max_grid: 2 * settings.max_grid, ..settings };
                finer.check().map_err(CliError::usage)?;
                let start = Instant::now();
                let check = ImageTruth::compute(scene, &frame, finer).map_err(truth_error)?;
                say(
                    &mut md,
                    format!(
                        "  image truth with lattices doubled ({}x{} up to {}x{}) against it: {} ({:.1} s)",
                        finer.grid,
                        finer.grid,
                        finer.max_grid,
                        finer.max_grid,
                        image_error(&check.image(), &truths[0]).describe(),
                        start.elapsed().as_secs_f64()
                    ),
                );
            }
            first_truth = Some(truth);
        } else {
            say(&mut md, format!("  frame {i} (t = {time:.3} s): image truth {took:.1} s"));
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
        say(
            &mut md,
            format!(
                "  flicker over {} frames of {moved}; the truth moved {:.2} levels RMS",
                frames.len(),
                motion(&truths)
            ),
        );
    }
    // One sample first: the time and flicker ratios are against it. Then each count with each threshold (one
    // sample has no threshold to vary), and the scene's own setting among them.
    let own = (scene.settings.samples, scene.settings.sample_threshold);
    let mut counts: Vec<u32> = if args.samples.is_empty() { vec![own.0] } else { args.samples.clone() };
    if !counts.contains(&1) {
        counts.insert(0, 1);
    }
    let thresholds = if args.sample_thresholds.is_empty() { vec![own.1] } else { args.sample_thresholds.clone() };
    let mut settings: Vec<(u32, f64)> = counts
        .iter()
        .flat_map(|&n| {
            let list = if n == 1 { vec![own.1] } else { thresholds.clone() };
            list.into_iter().map(move |e| (n, e))
        })
        .collect();
    // The scene's own setting is always judged.
    if !settings.contains(&own) {
        let at = settings.iter().position(|&(n, _)| n > own.0).unwrap_or(settings.len());
        settings.insert(at, own);
    }
    let mut points: Vec<SamplePoint> = Vec::new();
    for (n, threshold) in settings {
        let mut sampled = scene.clone();
        sampled.settings.samples = n;
        sampled.settings.sample_threshold = threshold;
        let kernels = fractal_dsl::compile(&sampled).map_err(|e| CliError::failure(e.to_string()))?;
        let mut images = Vec::new();
        let (mut ms, mut traces) = (0.0, None);
        for (i, frame) in frames.iter().enumerate() {
            let (image, t, took) = render(&sampled, &kernels, loaded.evaluator(), frame, renderer.as_mut(), i == 0)?;
            if i == 0 {
                (ms, traces) = (took, t);
                if let Some(dir) = &args.image_out {
                    let suffix = if (n, threshold) == own { String::new() } else { format!(".{n}") };
                    for (what, picture) in [("truth", &truths[0]), ("render", &image)] {
                        let path = dir.join(format!("{}{suffix}.{what}.png", loaded.name));
                        prepare_output(&path)?;
                        write_png(&path, picture)?;
                    }
                }
            }
            images.push(image);
        }
        let paired: Vec<(Image, Image)> = images.iter().cloned().zip(truths.iter().cloned()).collect();
        let point = SamplePoint {
            samples: n,
            threshold,
            rays_per_pixel: traces.as_ref().map_or(f64::NAN, |t: &Vec<PixelTrace>| {
                t.iter().map(|p| f64::from(p.samples)).sum::<f64>() / t.len() as f64
            }),
            time_ms: ms,
            error: image_error(&truths[0], &images[0]),
            flicker: (paired.len() > 1).then(|| flicker(&paired)),
            default: (n, threshold) == own,
        };
        let base = single(&points).unwrap_or(&point);
        let shimmer = point.flicker.map_or(String::new(), |f| {
            format!(", flicker {f:.2} levels RMS ({:.2}x)", f / base.flicker.unwrap_or(f64::NAN))
        });
        println!(
            "  {}{}: {:.2} rays per pixel, {ms:.1} ms ({:.2}x), {}{shimmer}; {}",
            point.label(own.1),
            if point.default { " (default)" } else { "" },
            point.rays_per_pixel,
            ms / base.time_ms,
            point.error.describe(),
            ImageBudget::default().verdict(&point.error),
        );
        if point.default {
            let normals = match &traces {
                Some(traces) => normal_error(&first_truth, traces).describe(),
                None => "normals: not read on this backend".to_string(),
            };
            say(&mut md, format!("    scene default: {normals}"));
        }
        points.push(point);
    }
    if let Some(seconds) = args.progressive {
        let (image, passes) = progressive(scene, loaded.evaluator(), &frames[0], renderer.as_mut(), seconds)?;
        let error = image_error(&truths[0], &image);
        say(
            &mut md,
            format!(
                "  progressive passes for {seconds} s, as the viewer draws them while the view stands still: {passes} \
                 passes, {}; {}",
                error.describe(),
                ImageBudget::default().verdict(&error)
            ),
        );
    }
    let table = samples::markdown(&points, own.1, &ImageBudget::default());
    println!("{table}");
    let _ = writeln!(md, "\n{table}");
    if let Some(choice) = samples::chosen(&points) {
        let verdict = if choice.default {
            "the scene's default".to_string()
        } else {
            format!("the scene's default is {}", samples::label(own.0, own.1, own.1))
        };
        let line = format!(
            "The rule (the best image within {}x the one-sample time, if it buys at least {} dB over one sample) \
             chooses {}: {verdict}.",
            samples::TIME_LIMIT,
            samples::WORTH_DB,
            choice.label(own.1),
        );
        println!("{line}");
        let _ = writeln!(md, "{line}\n");
    }
    Ok(ImageStudy { markdown: md, points })
}

fn truth_error(e: ImageTruthError) -> CliError {
    match e {
        ImageTruthError::Settings(message) => CliError::usage(message),
        ImageTruthError::Render(e) => e.into(),
    }
}

/// The scene's render by `renderer`: its image, its per-pixel traces, and the median time of [`TIMING_RUNS`]
/// renders or more (to [`TIMING_SECONDS`]) in milliseconds (where `timed`; else one render, untimed, and no traces). The CPU draws with `evaluator`
/// (a built-in's native one, else the interpreter), in packets where it has them, as `fractal render` does.
fn render(
    scene: &Scene,
    kernels: &Kernels,
    evaluator: &dyn Evaluator<f32>,
    frame: &Frame,
    renderer: &mut dyn Renderer,
    timed: bool,
) -> Result<(Image, Option<Vec<PixelTrace>>, f64), CliError> {
    let job = RenderJob::new(KernelSources::compiled(kernels).with_cpu(evaluator, scene), frame);
    // The first render builds the kernel; it is not timed.
    let mut image = renderer.render(&job)?;
    if !timed {
        return Ok((image, None, f64::NAN));
    }
    let mut times = Vec::new();
    while times.len() < TIMING_RUNS
        || (times.len() < MOST_TIMING_RUNS && times.iter().sum::<f64>() < TIMING_SECONDS * 1e3)
    {
        let start = Instant::now();
        image = renderer.render(&job)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    let tracing = kernels.tracing();
    let traced =
        renderer.trace(&RenderJob::new(KernelSources::compiled(&tracing).with_cpu(evaluator, scene), frame))?;
    times.sort_by(f64::total_cmp);
    Ok((image, Some(traced.pixels), times[times.len() / 2]))
}

/// Passes of the scene's one-sample trace kernels drawn for `seconds` ([`Progressive`], as `fractal render
/// --progressive` and the viewer draw them), after one untimed pass that builds the kernels: the image and the passes
/// drawn in the time.
fn progressive(
    scene: &Scene,
    evaluator: &dyn Evaluator<f32>,
    frame: &Frame,
    renderer: &mut dyn Renderer,
    seconds: f64,
) -> Result<(Image, u32), CliError> {
    let mut one = scene.clone();
    one.settings.samples = 1;
    let tracing = fractal_dsl::compile(&one).map_err(|e| CliError::failure(e.to_string()))?.tracing();
    let job = RenderJob::new(KernelSources::compiled(&tracing).with_cpu(evaluator, &one), frame);
    Progressive::new(&one, frame).draw(renderer, &job)?;
    let mut passes = Progressive::new(&one, frame);
    passes.draw_for(renderer, &job, seconds)?;
    Ok((passes.image(), passes.passes()))
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
