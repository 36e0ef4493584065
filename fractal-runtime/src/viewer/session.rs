//! What a viewer session is given and what it gives back: the scene, the options, the summary of what it did and
//! the errors that end it.
//!
//! Apart from the facade (`mod.rs`), which starts a session, so the game loop and the no-display fallback read these
//! types without reading their caller.

use std::path::PathBuf;

use fractal_dsl::{CompiledScene, Scene};
use fractal_render::camera::Pose;
use fractal_render::device::DeviceInfo;
use fractal_render::frame::ParamValues;
use fractal_render::precision::PrecisionChoice;
use fractal_render::select::{BackendChoice, RendererOptions};

use super::scale::RenderScale;
use super::script::ScriptedStep;

/// The scene a viewer shows.
#[derive(Clone, Debug)]
pub enum ViewerScene {
    /// A scene compiled at build time (`scene!`, `scene_file!`): its kernels, and its native evaluator for the CPU.
    Compiled { name: String, scene: &'static CompiledScene },
    /// A `.fractal` file, loaded and compiled at run time (the interpreter draws it on the CPU) and reloaded whenever
    /// it is saved.
    File(PathBuf),
    /// A scene value built at run time (builder API), compiled when the viewer starts.
    Built { name: String, scene: Box<Scene> },
}

impl ViewerScene {
    pub fn compiled(name: impl Into<String>, scene: &'static CompiledScene) -> ViewerScene {
        ViewerScene::Compiled { name: name.into(), scene }
    }
    pub fn file(path: impl Into<PathBuf>) -> ViewerScene {
        ViewerScene::File(path.into())
    }
    /// A scene made with the builder, validated here so a broken one is refused before any window opens.
    pub fn built(name: impl Into<String>, scene: Scene) -> Result<ViewerScene, fractal_dsl::validate::InvalidScene> {
        fractal_dsl::validate::checked(&scene)?;
        Ok(ViewerScene::Built { name: name.into(), scene: Box::new(scene) })
    }
    /// The name shown in the title and used for screenshot files.
    pub fn name(&self) -> String {
        match self {
            ViewerScene::Compiled { name, .. } | ViewerScene::Built { name, .. } => name.clone(),
            ViewerScene::File(path) => {
                path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scene".to_string())
            }
        }
    }
}

/// How frames reach the window.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PresentMode {
    /// [`PresentMode::Gpu`] where the wgpu adapter is a GPU; [`PresentMode::Softbuffer`] where it is the CPU (a
    /// software rasteriser such as lavapipe), which draws the full-screen pass slower than the host stretches the
    /// frame (`docs/performance.md`, "The viewer's frame").
    #[default]
    Auto,
    /// A wgpu surface when the backend is wgpu and a surface can be made: the frame goes from the kernel to the
    /// window on the device; softbuffer otherwise.
    Gpu,
    /// Always read frames back and present them through softbuffer.
    Softbuffer,
}

impl std::str::FromStr for PresentMode {
    type Err = String;
    fn from_str(text: &str) -> Result<PresentMode, String> {
        match text {
            "auto" => Ok(PresentMode::Auto),
            "gpu" => Ok(PresentMode::Gpu),
            "host" => Ok(PresentMode::Softbuffer),
            _ => Err(format!("--present takes auto, gpu or host, got `{text}`")),
        }
    }
}

/// Everything about a viewer session that is not the scene.
#[derive(Clone, Debug)]
pub struct ViewerOptions {
    pub backend: BackendChoice,
    pub renderer: RendererOptions,
    /// Window inner size in physical pixels; also the size of the PNG written when there is no display.
    pub window_size: (u32, u32),
    /// Where to place the window (physical pixels from the top-left of the screen); the window system decides when
    /// `None`.
    pub window_position: Option<(i32, i32)>,
    pub render_scale: RenderScale,
    pub present: PresentMode,
    /// Camera speed in scene units per second (Shift: 4×).
    pub move_speed: f64,
    /// Radians of turn per pixel of mouse motion.
    pub mouse_sensitivity: f64,
    /// A TOML camera path to play instead of the scene's camera (see [`super::path_file`]).
    pub camera_path: Option<PathBuf>,
    /// Start values of `param(..)`s by name (the others start at their defaults); each must lie in its range.
    pub params: Vec<(String, f64)>,
    /// Scene time at start, in seconds.
    pub start_time: f64,
    /// Start with time paused.
    pub paused: bool,
    /// Advance time and movement by this many seconds per frame instead of the measured frame time (deterministic
    /// runs: scripts, recordings).
    pub fixed_time_step: Option<f64>,
    /// Folder for screenshots taken with F12 / K.
    pub screenshot_dir: PathBuf,
    /// Reload a `.fractal` scene file when it changes.
    pub watch: bool,
    /// Scripted input: when set, the viewer plays these steps instead of waiting for the user and exits at the end.
    pub script: Option<Vec<ScriptedStep>>,
    /// Print the controls at start-up.
    pub print_help: bool,
    /// The most rays a pixel may take (`None`: the scene's `samples`).
    pub samples: Option<u32>,
    /// While nothing that changes the picture changes, refine it with progressive passes (module `still`).
    pub accumulate: bool,
    /// The number type of each frame; a frame in f64 is drawn by the CPU renderer whatever the backend.
    pub precision: PrecisionChoice,
    /// Whether the panel shows at start (`None`: in a window without a script, yes; scripted or headless, no).
    pub panel: Option<bool>,
}

impl Default for ViewerOptions {
    fn default() -> Self {
        ViewerOptions {
            backend: BackendChoice::Auto,
            renderer: RendererOptions::default(),
            window_size: (1280, 720),
            window_position: None,
            render_scale: RenderScale::default(),
            present: PresentMode::Auto,
            move_speed: 1.0,
            mouse_sensitivity: 0.003,
            camera_path: None,
            params: Vec::new(),
            start_time: 0.0,
            paused: false,
            fixed_time_step: None,
            screenshot_dir: PathBuf::from("."),
            watch: true,
            script: None,
            print_help: true,
            samples: None,
            accumulate: true,
            panel: None,
            precision: PrecisionChoice::Auto,
        }
    }
}

/// What was on screen when a screenshot was taken: enough to render the same image offline.
#[derive(Clone, Debug)]
pub struct ScreenshotInfo {
    pub path: PathBuf,
    /// The scene as rendered, with the viewer's effect toggles applied to its settings.
    pub scene: Scene,
    pub pose: Pose,
    pub time: f64,
    pub params: ParamValues,
    /// Size of the rendered image (before upscaling).
    pub render_size: (u32, u32),
    /// Size of the window (and of the screenshot).
    pub window_size: (u32, u32),
    pub device: DeviceInfo,
    /// `"wgpu surface"` or `"softbuffer"`.
    pub presenter: &'static str,
    /// The progressive passes whose mean the window showed (the view stood still); 0 for a frame drawn as usual.
    pub passes: u32,
    /// Where the UI (panel, editor, error line) was drawn over the frame: x, y, width, height in window pixels.
    pub ui_rect: Option<(u32, u32, u32, u32)>,
    /// The editor's text as `line:column: message` when it did not compile (the picture is the last good one).
    pub source_error: Option<String>,
}

/// What a viewer session did.
#[derive(Clone, Debug, Default)]
pub struct ViewerSummary {
    pub frames: u64,
    pub screenshots: Vec<ScreenshotInfo>,
    /// The stills rendered (F9), in order.
    pub stills: Vec<PathBuf>,
    /// The flights recorded (R), as the scene files written.
    pub flights: Vec<PathBuf>,
    /// The device of the last frame drawn.
    pub device: Option<DeviceInfo>,
    pub presenter: Option<&'static str>,
}

/// Why a viewer could not run.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// No window system to open a window on.
    #[error("no display: {0}")]
    NoDisplay(String),
    /// The scene could not be loaded (missing file, `file:line:column: message` for broken text).
    #[error("{0}")]
    Scene(String),
    /// The camera path file could not be used.
    #[error("{0}")]
    CameraPath(String),
    /// No backend could render the scene.
    #[error(transparent)]
    Render(#[from] fractal_render::error::RenderError),
    #[error(transparent)]
    Frame(#[from] fractal_render::error::FrameError),
    /// The window system failed after the window opened.
    #[error("window error: {0}")]
    Window(String),
    #[error("cannot write {path}: {message}")]
    Output { path: PathBuf, message: String },
    /// A scripted step could not be played (a UI input naming a widget that is not on screen).
    #[error("{0}")]
    Script(String),
}
