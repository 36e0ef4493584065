//! `fractal render`: one PNG, a numbered PNG sequence (atomic writes, resume, shards, progress bar) or a video through
//! ffmpeg. The output is checked (directory created, a file can be written) before the device is opened, so a bad
//! path costs no rendering time.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use fractal_render::camera::Pose;
use fractal_render::error::RenderError;
use fractal_render::frame::{Frame, ParamValues};
use fractal_render::image::Image;
use fractal_render::renderer::{KernelSources, RenderJob, Renderer, Traced};
use fractal_render::select::{select, BackendChoice, RendererOptions};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::cli::args::{RenderArgs, RenderOptions};
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary};
use crate::frame_precision::FramePrecision;
use crate::output::aov::write_aov;
use crate::output::png::{prepare_output, write_png};
use crate::output::sequence::{plan, FramePattern, Shard};
use crate::output::video::{Container, VideoWriter};
use crate::output::writers::{FrameWriters, Written};
use crate::output::OutputError;
use fractal_render::progressive::Progressive;

/// What `-o` and `--frames` ask for.
enum Output {
    Image(PathBuf),
    Sequence(FramePattern),
    Video(PathBuf),
}

fn path_text(path: &Path) -> Result<&str, CliError> {
    path.to_str().ok_or_else(|| CliError::usage(format!("output path {} is not valid UTF-8", path.display())))
}

fn is_png(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("png"))
}

fn unsupported(path: &Path) -> CliError {
    if path.is_dir() {
        return CliError::usage(format!(
            "cannot write {}: it is a directory; give a file name in it, e.g. {}",
            path.display(),
            path.join("image.png").display()
        ));
    }
    // `.png` alone is a hidden file with no extension as far as paths go; say what is missing.
    if path.file_name().is_some_and(|n| n.to_string_lossy().eq_ignore_ascii_case(".png")) {
        return CliError::usage(format!("cannot write {}: the file name before .png is empty", path.display()));
    }
    CliError::usage(format!(
        "cannot write {}: images are written as .png, videos as .mp4, .webm, .mkv or .mov",
        path.display()
    ))
}

fn decide_output(args: &RenderArgs, scene_name: &str) -> Result<Output, CliError> {
    if args.frames.is_none() {
        let path = args.output.clone().unwrap_or_else(|| PathBuf::from(format!("{scene_name}.png")));
        if Container::from_path(&path).is_some() {
            return Err(CliError::usage(format!(
                "{} is a video: give the frames to encode with --frames START..END",
                path.display()
            )));
        }
        if FramePattern::looks_like_pattern(path_text(&path)?) {
            return Err(CliError::usage(format!(
                "{} is a frame pattern: give the frames with --frames START..END",
                path.display()
            )));
        }
        return if is_png(&path) { Ok(Output::Image(path)) } else { Err(unsupported(&path)) };
    }
    let Some(path) = &args.output else {
        let pattern = FramePattern::parse(&format!("{}/%05d.png", scene_name.replace('%', "%%")))
            .map_err(|e| CliError::usage(e.to_string()))?;
        return Ok(Output::Sequence(pattern));
    };
    if Container::from_path(path).is_some() {
        if args.shard.is_some() {
            return Err(CliError::usage(
                "a video cannot be split into shards: render a PNG sequence with --shard and encode it afterwards",
            ));
        }
        let (w, h) = args.render.size;
        if w % 2 != 0 || h % 2 != 0 {
            return Err(CliError::usage(format!("video sizes must be even (yuv420p), got {w}x{h}")));
        }
        return Ok(Output::Video(path.clone()));
    }
    let pattern = FramePattern::parse(path_text(path)?).map_err(|e| CliError::usage(e.to_string()))?;
    if !pattern.suffix().to_ascii_lowercase().ends_with(".png") {
        return Err(unsupported(path));
    }
    Ok(Output::Sequence(pattern))
}

fn note(message: &str) {
    eprintln!("fractal: {message}");
}

pub(super) fn open_renderer(options: &RenderOptions) -> Result<Box<dyn Renderer>, CliError> {
    let mut renderer = select(options.device.backend, &RendererOptions { precise: options.device.precise })?;
    for n in renderer.take_notes() {
        note(&n);
    }
    if options.device.backend != BackendChoice::Auto {
        note(&format!("using {}", renderer.device()));
    }
    Ok(renderer)
}

/// The uniforms of the scene at `time`, seen from its own camera: where a time, camera or moving value is refused.
fn frame_at(
    loaded: &LoadedScene,
    params: &ParamValues,
    time: f64,
    (width, height): (u32, u32),
) -> Result<Frame, CliError> {
    let pose = Pose::from_camera(&loaded.scene.camera, time, &|p| params.lookup(p))
        .map_err(|e| CliError::failure(format!("scene {}: camera at t = {time}: {e}", loaded.name)))?;
    Ok(Frame::new(&loaded.scene, &pose, time, width, height, params).map_err(RenderError::from)?)
}

/// Packs every frame a command will draw before a device is opened or a file written, so a time out of range or a
/// value that goes bad mid-animation is refused up front, not after hours of frames.
fn check_frames(args: &RenderArgs, loaded: &LoadedScene, params: &ParamValues) -> Result<(), CliError> {
    let Some(range) = args.frames else {
        return frame_at(loaded, params, args.time, args.render.size).map(drop);
    };
    for f in range.iter() {
        frame_at(loaded, params, f as f64 / args.fps, args.render.size).map_err(|e| CliError {
            message: format!("frame {f} at {} fps: {e}", fractal_dsl::validate::number_text(args.fps)),
            ..e
        })?;
    }
    Ok(())
}

/// One frame at `time` and every pixel's march, from the trace kernels (the render kernels that also keep depth,
/// normal and steps), so the `--aov` images are of the march that drew the image.
fn trace_frame(
    renderer: &mut dyn Renderer,
    loaded: &LoadedScene,
    params: &ParamValues,
    (time, size): (f64, (u32, u32)),
    precision: &mut FramePrecision,
) -> Result<Traced, CliError> {
    let frame = frame_at(loaded, params, time, size)?;
    let tracing = loaded.tracing()?;
    let sources = KernelSources::compiled(&tracing)
        .with_cpu(loaded.evaluator(), &loaded.scene)
        .with_cpu_wide(loaded.evaluator_wide());
    let job = RenderJob::new(sources, &frame).with_precision(loaded.precision_of(precision, &frame)?);
    let traced = renderer.trace(&job);
    with_notes(renderer, traced)
}

/// A still refined for `seconds` ([`Progressive`]): passes of the scene's one-sample trace kernels, at least one;
/// the image and the passes drawn.
fn progressive(
    renderer: &mut dyn Renderer,
    loaded: &mut LoadedScene,
    params: &ParamValues,
    (time, size): (f64, (u32, u32)),
    seconds: f64,
    precision: &mut FramePrecision,
) -> Result<(Image, u32), CliError> {
    loaded.set_samples(Some(1))?;
    let frame = frame_at(loaded, params, time, size)?;
    let tracing = loaded.tracing()?;
    let sources = KernelSources::compiled(&tracing)
        .with_cpu(loaded.evaluator(), &loaded.scene)
        .with_cpu_wide(loaded.evaluator_wide());
    let job = RenderJob::new(sources, &frame).with_precision(loaded.precision_of(precision, &frame)?);
    let mut passes = Progressive::new(&loaded.scene, &frame);
    let drawn = passes.draw_for(renderer, &job, seconds);
    with_notes(renderer, drawn)?;
    Ok((passes.image(), passes.passes()))
}

/// `drawn`, after printing what the renderer noted while drawing it (a fallback to another backend).
fn with_notes<T>(renderer: &mut dyn Renderer, drawn: Result<T, RenderError>) -> Result<T, CliError> {
    for n in renderer.take_notes() {
        note(&n);
    }
    Ok(drawn?)
}

/// The `--aov` images of `traced` beside the PNG at `png`.
fn write_aovs(args: &RenderArgs, traced: &Traced, png: &Path) -> Result<(), CliError> {
    let (width, height) = (traced.image.width, traced.image.height);
    for &aov in &args.aov {
        let path = aov.path_beside(png);
        write_aov(&path, aov, width, height, &traced.pixels)?;
        eprintln!("wrote {} ({})", path.display(), aov.name());
    }
    Ok(())
}

/// One frame of the scene at `time`, seen from its own camera, in the precision `precision` gives it.
pub(super) fn render_frame(
    renderer: &mut dyn Renderer,
    loaded: &LoadedScene,
    params: &ParamValues,
    (time, size): (f64, (u32, u32)),
    precision: &mut FramePrecision,
) -> Result<Image, CliError> {
    let mut images = render_frames(renderer, loaded, params, (&[time], size), precision)?;
    images.pop().ok_or_else(|| CliError::failure("the renderer drew no frame"))
}

pub fn render(args: &RenderArgs, library: &SceneLibrary) -> Result<(), CliError> {
    let mut loaded = LoadedScene::load(&args.scene, library)?;
    args.camera.apply(&mut loaded.scene.camera);
    loaded.set_samples(args.render.samples)?;
    let params = loaded.params(&args.render.params)?;
    let size = args.render.size;
    check_frames(args, &loaded, &params)?;
    match decide_output(args, &loaded.name)? {
        Output::Image(path) => {
            prepare_output(&path)?;
            let mut renderer = open_renderer(&args.render)?;
            let mut precision =
                FramePrecision::new(args.render.device.precision, format!("fractal: {}: ", loaded.name));
            let start = Instant::now();
            if let Some(seconds) = args.progressive {
                let at = (args.time, size);
                let image = progressive(renderer.as_mut(), &mut loaded, &params, at, seconds, &mut precision)?;
                write_png(&path, &image.0)?;
                let elapsed = start.elapsed().as_secs_f64();
                eprintln!(
                    "wrote {} ({}x{}, t = {}, {} passes, {elapsed:.2} s)",
                    path.display(),
                    size.0,
                    size.1,
                    args.time,
                    image.1
                );
                return Ok(());
            }
            let traced = if args.aov.is_empty() {
                None
            } else {
                Some(trace_frame(renderer.as_mut(), &loaded, &params, (args.time, size), &mut precision)?)
            };
            let image = match &traced {
                Some(traced) => traced.image.clone(),
                None => render_frame(renderer.as_mut(), &loaded, &params, (args.time, size), &mut precision)?,
            };
            let elapsed = start.elapsed().as_secs_f64();
            write_png(&path, &image)?;
            eprintln!("wrote {} ({}x{}, t = {}, {elapsed:.2} s)", path.display(), size.0, size.1, args.time);
            traced.map_or(Ok(()), |traced| write_aovs(args, &traced, &path))
        }
        Output::Sequence(pattern) => render_sequence(args, &loaded, &params, &pattern),
        Output::Video(path) => render_video(args, &loaded, &params, &path),
    }
}

fn progress_bar(len: u64) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
    }
    let style = ProgressStyle::with_template("{elapsed_precise} [{bar:40}] {pos}/{len} frames, {per_sec}, eta {eta}")
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> ");
    ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr()).with_style(style)
}

/// What decides a sequence's pixels, one setting per line: resuming with any of them changed would mix two
/// animations in one sequence.
fn sequence_settings(args: &RenderArgs, loaded: &LoadedScene, params: &ParamValues) -> String {
    let values: Vec<String> = params.values().iter().map(|v| format!("{v:?}")).collect();
    format!(
        "size {}x{}\nfps {:?}\nparams {}\nbackend {}\nprecise {}\nscene {}\n",
        args.render.size.0,
        args.render.size.1,
        args.fps,
        values.join(" "),
        args.render.device.backend,
        args.render.device.precise,
        fractal_dsl::print::to_source(&loaded.scene).replace('\n', " "),
    )
}

fn render_sequence(
    args: &RenderArgs,
    loaded: &LoadedScene,
    params: &ParamValues,
    pattern: &FramePattern,
) -> Result<(), CliError> {
    let Some(range) = args.frames else {
        return Err(CliError::usage("a frame sequence needs --frames START..END"));
    };
    let shard = args.shard.unwrap_or(Shard::ALL);
    let plan = plan(pattern, range, shard);
    // Frames already on disk count as done only if they were drawn with these settings.
    let settings = sequence_settings(args, loaded, params);
    let settings_path = pattern.settings_path();
    if let Ok(recorded) = fractal_dsl::parse::read_source(&settings_path) {
        if !plan.done.is_empty() && recorded != settings {
            let differs = recorded.lines().zip(settings.lines()).find(|(a, b)| a != b);
            let detail = differs.map(|(was, now)| format!(": they have `{was}`, this run `{now}`")).unwrap_or_default();
            return Err(CliError::usage(format!(
                "{} frames of {pattern} were rendered with other settings{detail}; remove them (and {}) or render \
                 to another pattern",
                plan.done.len(),
                settings_path.display()
            )));
        }
    }
    let owned = plan.todo.len() + plan.done.len();
    let of_shard = if shard == Shard::ALL { String::new() } else { format!(" of shard {shard}") };
    if plan.todo.is_empty() {
        eprintln!("nothing to do: all {owned} frames{of_shard} of {range} already exist ({pattern})");
        return Ok(());
    }
    if !plan.done.is_empty() {
        note(&format!("resuming: {} of {owned} frames{of_shard} already complete", plan.done.len()));
    }
    prepare_output(&pattern.path(plan.todo[0]))?;
    let mut renderer = open_renderer(&args.render)?;
    if let Some(dir) = settings_path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|source| crate::output::OutputError::Write { path: settings_path.clone(), source })?;
    }
    std::fs::write(&settings_path, &settings)
        .map_err(|source| crate::output::OutputError::Write { path: settings_path.clone(), source })?;
    let batch_log = !std::io::stderr().is_terminal();
    let bar = progress_bar(plan.todo.len() as u64);
    let started = Instant::now();
    let mut precision = FramePrecision::new(args.render.device.precision, format!("fractal: {}: ", loaded.name));
    // The renderer draws a batch (a GPU keeps its frames in flight) while the writers encode the batch before.
    let writers = FrameWriters::per_core();
    let mut written = 0;
    let mut report = |done: Vec<Result<Written, OutputError>>| -> Result<(), CliError> {
        for w in done {
            let w = w?;
            written += 1;
            bar.inc(1);
            if batch_log {
                // No progress bar without a terminal: one line per frame keeps job-scheduler logs informative.
                let total = plan.todo.len();
                let (frame, path, seconds) = (w.frame, w.path.display(), w.seconds);
                eprintln!("frame {frame} ({written}/{total}) -> {path}, written in {seconds:.2} s");
            }
        }
        Ok(())
    };
    for batch in plan.todo.chunks(SEQUENCE_BATCH) {
        let times: Vec<f64> = batch.iter().map(|&f| f as f64 / args.fps).collect();
        let images = render_frames(renderer.as_mut(), loaded, params, (&times, args.render.size), &mut precision)?;
        for (&f, image) in batch.iter().zip(images) {
            writers.push(f, pattern.path(f), image)?;
        }
        report(writers.written())?;
    }
    report(writers.finish())?;
    bar.finish_and_clear();
    let seconds = started.elapsed().as_secs_f64();
    eprintln!(
        "wrote {} frames{of_shard} to {pattern} in {seconds:.1} s, {:.1} frames/s ({} already complete)",
        plan.todo.len(),
        plan.todo.len() as f64 / seconds,
        plan.done.len()
    );
    Ok(())
}

/// Frames a sequence or video hands the renderer at once ([`Renderer::render_batch`]).
const SEQUENCE_BATCH: usize = 8;

/// Frames of the scene at `times`, seen from its own camera, each in the precision `precision` gives it, drawn as
/// one batch.
fn render_frames(
    renderer: &mut dyn Renderer,
    loaded: &LoadedScene,
    params: &ParamValues,
    (times, size): (&[f64], (u32, u32)),
    precision: &mut FramePrecision,
) -> Result<Vec<Image>, CliError> {
    let frames = times.iter().map(|&t| frame_at(loaded, params, t, size)).collect::<Result<Vec<_>, _>>()?;
    let precisions = frames.iter().map(|f| loaded.precision_of(precision, f)).collect::<Result<Vec<_>, _>>()?;
    let jobs: Vec<RenderJob> =
        frames.iter().zip(precisions).map(|(f, p)| RenderJob::new(loaded.sources(), f).with_precision(p)).collect();
    let drawn = renderer.render_batch(&jobs);
    with_notes(renderer, drawn.into_iter().collect::<Result<Vec<_>, _>>())
}

fn render_video(args: &RenderArgs, loaded: &LoadedScene, params: &ParamValues, path: &Path) -> Result<(), CliError> {
    let Some(range) = args.frames else {
        return Err(CliError::usage("a video needs --frames START..END"));
    };
    prepare_output(path)?;
    let (width, height) = args.render.size;
    // ffmpeg starts first, so a missing ffmpeg is reported before any device time is spent.
    let mut video = VideoWriter::start(path, width, height, args.fps)?;
    let mut renderer = open_renderer(&args.render)?;
    let bar = progress_bar(range.len());
    let started = Instant::now();
    let mut precision = FramePrecision::new(args.render.device.precision, format!("fractal: {}: ", loaded.name));
    let frames: Vec<u64> = range.iter().collect();
    for batch in frames.chunks(SEQUENCE_BATCH) {
        let times: Vec<f64> = batch.iter().map(|&f| f as f64 / args.fps).collect();
        for image in render_frames(renderer.as_mut(), loaded, params, (&times, args.render.size), &mut precision)? {
            video.push(&image)?;
            bar.inc(1);
        }
    }
    bar.finish_and_clear();
    let written = video.finish()?;
    eprintln!(
        "wrote {} ({} frames {range} at {} fps, {width}x{height}) in {:.1} s",
        written.display(),
        range.len(),
        args.fps,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
