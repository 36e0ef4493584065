//! `fractal view`: opens the interactive viewer ([`crate::viewer::run`]) on a built-in scene (its build-time kernels
//! and native evaluator) or a `.fractal` file (reloaded whenever it is saved). With no display it fails with a hint to
//! render an image instead. `--headless` runs the viewer's frames with no window ([`crate::viewer::run_headless`])
//! and prints what they cost.

use fractal_render::select::RendererOptions;

use crate::bench::Stats;
use crate::cli::args::ViewArgs;
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary, SceneOrigin};
use crate::viewer::{run, run_headless, FrameKind, HeadlessRun, RenderScale, ViewerError, ViewerOptions, ViewerScene};

/// Scene seconds per frame of a headless run: as at 60 frames/s, whatever the frames cost.
const HEADLESS_TIME_STEP: f64 = 1.0 / 60.0;

pub fn view(args: &ViewArgs, library: &SceneLibrary) -> Result<(), CliError> {
    // Loading first reports an unknown scene or a broken file the same way the other commands do.
    let loaded = LoadedScene::load(&args.scene, library)?;
    // Unknown names and out-of-range values are refused here, as `render` refuses them.
    loaded.params(&args.params)?;
    let scene = match &loaded.origin {
        SceneOrigin::File(path) => ViewerScene::file(path),
        SceneOrigin::BuiltIn => match library.scenes.iter().find(|(name, _)| *name == loaded.name) {
            Some(&(name, compiled)) => ViewerScene::compiled(name, compiled),
            None => ViewerScene::built(loaded.name.clone(), loaded.scene.clone())
                .map_err(|e| CliError::failure(e.to_string()))?,
        },
    };
    let options = ViewerOptions {
        backend: args.device.backend,
        renderer: RendererOptions { precise: args.device.precise },
        window_size: args.size,
        camera_path: args.camera_path.clone(),
        start_time: args.time,
        paused: args.paused,
        move_speed: args.move_speed,
        mouse_sensitivity: args.mouse_sensitivity,
        params: args.params.clone(),
        samples: args.samples,
        accumulate: !args.no_accumulate,
        panel: args.panel.then_some(true),
        precision: args.device.precision,
        render_scale: match (args.scale, args.headless) {
            (Some(scale), _) => RenderScale::Fixed(scale),
            (None, true) => RenderScale::Fixed(1.0),
            (None, false) => RenderScale::default(),
        },
        fixed_time_step: args.headless.then_some(HEADLESS_TIME_STEP),
        print_help: !args.headless,
        present: args.present,
        ..ViewerOptions::default()
    };
    if args.headless {
        let report = run_headless(scene, options, args.frames, args.screenshot.clone())
            .map_err(|e| CliError::failure(e.to_string()))?;
        print!("{}", describe(&report));
        return Ok(());
    }
    match run(scene, options) {
        Ok(summary) => {
            eprintln!("viewed {} frames", summary.frames);
            Ok(())
        }
        Err(ViewerError::NoDisplay(reason)) => Err(CliError::failure(format!(
            "no display ({reason}): render an image instead with `fractal render {} -o {}.png`",
            args.scene, loaded.name
        ))),
        Err(e) => Err(CliError::failure(e.to_string())),
    }
}

/// The frame times of a headless run: per kind of frame the host's time, and the device's time of the kernel and
/// the blit where it has timestamps (min / median / max in milliseconds; the first frame, which compiles the kernels,
/// apart).
pub fn describe(run: &HeadlessRun) -> String {
    let mut out = format!(
        "{} frames at {}x{} (rendered at {}x{}) with {}, presented to {}\n",
        run.frames.len(),
        run.window_size.0,
        run.window_size.1,
        run.render_size.0,
        run.render_size.1,
        run.summary.device.as_ref().map_or("no device".to_string(), |d| d.to_string()),
        run.summary.presenter.unwrap_or("nothing"),
    );
    if let Some((kind, first)) = run.frames.first() {
        out += &format!("  first frame ({kind}; compiles the kernels; left out below): {first:.1} ms\n");
    }
    let line = |label: String, s: Stats| format!("  {label}: {:.2} / {:.2} / {:.2} ms\n", s.min, s.median, s.max);
    let host = |kind: FrameKind| -> Vec<f64> {
        run.frames.iter().skip(1).filter(|(k, _)| *k == kind).map(|(_, ms)| *ms).collect()
    };
    let kinds = [FrameKind::Kernel, FrameKind::Wide, FrameKind::Pass, FrameKind::Rest, FrameKind::Skipped];
    out += "  host time per frame, min / median / max:\n";
    for kind in kinds {
        let ms = host(kind);
        if !ms.is_empty() {
            out += &line(format!("  {} {kind}", ms.len()), Stats::of(&ms));
        }
    }
    let device = &run.device_times[run.device_times.len().min(1)..];
    let kernel: Vec<f64> = device.iter().filter_map(|t| t.kernel_ms).collect();
    let blit: Vec<f64> = device.iter().map(|t| t.blit_ms).collect();
    if blit.is_empty() {
        out += "  device time: none (the device has no timestamps, or no frame went through a wgpu texture)\n";
        return out;
    }
    out += "  device time per frame, min / median / max:\n";
    if !kernel.is_empty() {
        out += &line("  kernel".to_string(), Stats::of(&kernel));
    }
    out += &line("  blit".to_string(), Stats::of(&blit));
    // The host's own share: each frame's time less its wait for the device. A CPU device (lavapipe) does its work
    // inside the submission, on the host's thread, so there the line would read the whole frame.
    let own: Vec<f64> = run.frames.iter().zip(&run.waited_ms).skip(1).map(|((_, ms), waited)| ms - waited).collect();
    let cpu_device = run.summary.device.as_ref().is_some_and(|d| d.device_type == "Cpu");
    if !own.is_empty() && !cpu_device {
        out += &line("host work per frame (less the waits for the device)".to_string(), Stats::of(&own));
    }
    let frames = host(FrameKind::Kernel);
    if !frames.is_empty() && !kernel.is_empty() {
        let over = Stats::of(&frames).median - Stats::of(&kernel).median;
        out += &format!("  kernel frame − kernel (medians): {over:.2} ms\n");
    }
    out
}
