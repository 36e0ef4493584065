//! `fractal bench`: runs [`crate::bench`] on a scene, prints the report on stdout and appends the record to the CSV
//! and JSON Lines files asked for. The record files' directories are checked before the run, so an unwritable path
//! fails at once.

use std::io::IsTerminal;

use fractal_render::select::RendererOptions;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::bench::{append_csv, append_json, run, BenchLength, BenchSpec};
use crate::cli::args::BenchArgs;
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary, SceneOrigin};
use crate::output::png::prepare_output;

/// The built-in scene set up like the hand-written baseline (camera, light, iterations, steps, epsilon), and the
/// scene `fractal bench` times when none is named.
pub const BASELINE_SCENE: &str = "mandelbulb_bench";
/// Timed frames when neither `--frames` nor `--seconds` is given.
pub const DEFAULT_FRAMES: u32 = 10;

pub fn bench(args: &BenchArgs, library: &SceneLibrary) -> Result<(), CliError> {
    let mut loaded = LoadedScene::load(args.scene.as_deref().unwrap_or(BASELINE_SCENE), library)?;
    loaded.set_samples(args.render.samples)?;
    let params = loaded.params(&args.render.params)?;
    for path in args.csv.iter().chain(&args.json) {
        prepare_output(path)?;
    }
    let length = match (args.frames, args.seconds) {
        (Some(n), _) => BenchLength::Frames(n),
        (None, Some(s)) => BenchLength::Seconds(s),
        (None, None) => BenchLength::Frames(DEFAULT_FRAMES),
    };
    let (width, height) = args.render.size;
    let spec = BenchSpec {
        scene_name: &loaded.name,
        scene: &loaded.scene,
        kernels: loaded.sources(),
        params: &params,
        width,
        height,
        length,
        backend: args.render.device.backend,
        options: RendererOptions { precise: args.render.device.precise },
        precision: args.render.device.precision,
        baseline: args.baseline,
        image_error: args.image_error,
        baseline_comparable: loaded.origin == SceneOrigin::BuiltIn && loaded.name == BASELINE_SCENE,
    };
    let bar = if std::io::stderr().is_terminal() {
        let bar = match length {
            BenchLength::Frames(n) => ProgressBar::new(n as u64),
            BenchLength::Seconds(_) => ProgressBar::new_spinner(),
        };
        let style = ProgressStyle::with_template("bench [{bar:30}] {pos} frames, {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar());
        bar.with_style(style)
    } else {
        ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())
    };
    let report = run(&spec, &mut |frames, _| bar.set_position(frames))?;
    bar.finish_and_clear();
    report.print(&mut std::io::stdout().lock()).map_err(|e| CliError::failure(format!("writing the report: {e}")))?;
    let record = report.record(&loaded.scene, &params);
    if let Some(path) = &args.csv {
        append_csv(path, &record).map_err(|e| CliError::failure(format!("cannot write {}: {e}", path.display())))?;
        eprintln!("appended a row to {}", path.display());
    }
    if let Some(path) = &args.json {
        append_json(path, &record).map_err(|e| CliError::failure(format!("cannot write {}: {e}", path.display())))?;
        eprintln!("appended a record to {}", path.display());
    }
    Ok(())
}
