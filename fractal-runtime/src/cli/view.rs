//! `fractal view`: opens the interactive viewer ([`crate::viewer::run`]) on a built-in scene (its build-time kernels
//! and native evaluator) or a `.fractal` file (reloaded whenever it is saved). With no display it fails with a hint to
//! render an image instead.

use fractal_render::select::RendererOptions;

use crate::cli::args::ViewArgs;
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary, SceneOrigin};
use crate::viewer::{run, ViewerError, ViewerOptions, ViewerScene};

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
        precision: args.device.precision,
        ..ViewerOptions::default()
    };
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
