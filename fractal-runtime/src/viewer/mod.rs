//! The interactive viewer (`fractal view <scene>` and the examples): a winit window that renders a scene every frame
//! with whichever backend was selected, lets the user fly the camera, toggle effects, change `param(..)` values and
//! take screenshots, and reloads a `.fractal` file whenever it is saved.
//!
//! The game loop (module `app`) runs once per frame: poll input → update time, camera and parameters → render →
//! present.
//! - Rendering: on a GPU, wgpu frames are computed into a storage buffer and drawn to a wgpu surface by a small
//!   full-screen pass that also upscales them (module `present`); CPU and OpenCL frames, wgpu frames on a software
//!   rasteriser (lavapipe, where the host stretches a frame faster than the pass does) and wgpu frames when no surface
//!   can be had (it says so on stderr) are read back and presented through softbuffer ([`PresentMode`]).
//! - Without a window, [`run_headless`] runs the same game loop into a window-sized texture (or host memory) and
//!   times its frames (`fractal view --headless`).
//! - The render size is a fraction of the window ([`RenderScale`]); by default the fraction adapts to hold a target
//!   frame rate, and the image is upscaled to the window (nearest pixel).
//! - Effects (shadows, ambient occlusion, glow, fog) are compiled into the kernels, so a toggle recompiles them with
//!   [`fractal_dsl::compile`]; `param(..)` values are uniforms, so changing one only repacks the frame.
//! - While nothing that changes the picture changes (camera, time where something moves with it, parameters,
//!   effects, scene, sizes), each frame adds a progressive pass and the window shows their mean, refining it to the
//!   pixel-integrated image, up to 256 passes; any change starts over (module `still`;
//!   [`ViewerOptions::accumulate`] turns it off).
//! - The panel and the scene editor are egui (module `ui`), drawn by egui-wgpu on the wgpu surface and rasterised
//!   on the host for softbuffer; bookmarks (module `bookmarks`) and flights (module `flight`) are written beside the
//!   scene.
//! - With no display, [`run`] returns [`ViewerError::NoDisplay`] and [`run_or_render`] renders a PNG instead.
//!
//! Controls (also printed at start-up, and again with H):
//!
//! | key | does |
//! |---|---|
//! | left click | capture the mouse (look around) |
//! | Esc | release the mouse; quits when the mouse is not captured |
//! | W A S D | move forward / left / back / right (takes the camera off its path) |
//! | Q / E | move down / up |
//! | Shift | move 4× faster (held) |
//! | + / − | move speed ×1.25 / ÷1.25 |
//! | ] / [ | mouse sensitivity ×1.25 / ÷1.25 |
//! | mouse wheel | field of view |
//! | C | back to the scene's camera (or the loaded camera path) |
//! | P | print the camera pose as a `.fractal` `key(..)` and a TOML `[[key]]` |
//! | 1 / 2 / 3 / 4 | shadows none → hard → soft / ambient occlusion / glow / fog (recompiles the kernels) |
//! | Space | pause or resume time |
//! | ← / → | time −1 s / +1 s |
//! | Tab / Shift+Tab | select the next / previous `param(..)` |
//! | ↑ / ↓ | increase / decrease the selected parameter (Shift: 5× the step), within its range |
//! | Backspace | reset the selected parameter to its default |
//! | F12 or K | save a PNG screenshot (the file name is printed) |
//! | O / F2 | show or hide the panel / the scene's source (edits recompile on a pause; Ctrl+S saves) |
//! | B / F9 / R / Enter | bookmark the view / render a still beside the scene / start or stop recording a flight / add a flight key |
//! | H | print the controls |

mod app;
mod bookmarks;
mod camera_control;
pub mod controls;
mod effects;
mod engine;
mod fallback;
mod flight;
mod live_scene;
mod params;
pub mod path_file;
mod present;
mod scale;
pub mod screenshot;
mod script;
mod session;
mod still;
mod title;
mod ui;

use std::path::{Path, PathBuf};

use fractal_render::device::DeviceInfo;

pub use app::{run_headless, FrameKind, HeadlessRun};
pub use controls::{Action, Move};
pub use fallback::{display_available, render_png};
pub use path_file::{load_camera_path, parse_camera_path, CameraPathFile};
pub use present::PassTimes;
pub use scale::RenderScale;
pub use screenshot::{read_png, write_png};
pub use script::{ScriptedStep, MAX_IDLE};
pub use session::{PresentMode, ScreenshotInfo, ViewerError, ViewerOptions, ViewerScene, ViewerSummary};
pub use ui::UiInput;

/// Opens the viewer and runs it until the window is closed (or the script ends). Returns
/// [`ViewerError::NoDisplay`] when there is no window system; [`run_or_render`] falls back to a PNG then.
pub fn run(scene: ViewerScene, options: ViewerOptions) -> Result<ViewerSummary, ViewerError> {
    display_available().map_err(ViewerError::NoDisplay)?;
    app::run(scene, options)
}

/// What [`run_or_render`] did.
#[derive(Clone, Debug)]
pub enum Outcome {
    Viewed(ViewerSummary),
    /// There was no display; the scene was rendered to this PNG instead.
    Rendered {
        path: PathBuf,
        device: DeviceInfo,
    },
}

/// [`run`], or, with no display, renders the scene at the window size to `png` and says so in one line on stdout.
pub fn run_or_render(scene: ViewerScene, options: ViewerOptions, png: &Path) -> Result<Outcome, ViewerError> {
    match run(scene.clone(), options.clone()) {
        Err(ViewerError::NoDisplay(reason)) => {
            let device = render_png(&scene, &options, png)?;
            println!(
                "no display ({reason}): rendered {} at {}x{} with {} to {} instead",
                scene.name(),
                options.window_size.0,
                options.window_size.1,
                device.backend,
                png.display()
            );
            Ok(Outcome::Rendered { path: png.to_path_buf(), device })
        }
        other => other.map(Outcome::Viewed),
    }
}

/// The `main` of the examples: views `scene`, or renders it to `<png_stem>.png` in the current directory when there
/// is no display. Errors are printed; the exit code is 0 on success.
pub fn example_main(png_stem: &str, scene: ViewerScene) -> std::process::ExitCode {
    let png = PathBuf::from(format!("{png_stem}.png"));
    match run_or_render(scene, ViewerOptions::default(), &png) {
        Ok(_) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}
