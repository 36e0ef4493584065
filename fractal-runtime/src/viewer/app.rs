//! The game loop: once per frame, poll input (keys, mouse, the script, the watched file), update time, camera and
//! parameters, render, and present — and recover from what can go wrong on the way (a kernel the driver rejects, a
//! backend that fails, a surface that cannot present) without panicking. What each key, click or scripted step
//! changes is module `input`'s; a winit event loop drives the frames in a window (module `window`), a plain loop
//! drives them without one (module `headless`); this file owns the state and the frame.

use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use fractal_render::camera::Pose;
use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::Image;
use fractal_render::precision::Precision;
use fractal_render::renderer::RenderJob;
use winit::window::Window;

mod headless;
mod input;
mod passes;
mod source;
mod views;
mod window;

pub use headless::{run_headless, FrameKind, HeadlessRun};
pub use window::run;

use crate::frame_precision::FramePrecision;

use super::bookmarks::Bookmarks;
use super::camera_control::{FlyCamera, SPRINT_FACTOR};
use super::controls::Move;
use super::effects::{describe, EffectOverrides};
use super::engine::{Engine, EngineChain};
use super::flight::Flight;
use super::live_scene::{FileWatch, LiveScene};
use super::params::ParamControl;
use super::path_file::{load_camera_path, CameraPathFile};
use super::present::{GpuFrameError, GpuPresenter, SoftPresenter};
use super::scale::ScaleController;
use super::screenshot::write_png;
use super::script::ScriptPlayer;
use super::session::{PresentMode, ScreenshotInfo, ViewerError, ViewerOptions, ViewerScene, ViewerSummary};
use super::still::{Accumulator, Plan, StillKey};
use super::title::{title, FrameClock, TitleFacts};
use super::ui::{PanelView, Ui, UiAction};

/// Longest time step of one frame: after a stall (a slow recompile, a dragged window) the camera does not jump.
const MAX_DT: f64 = 0.25;
/// The time slider's range when the scene has no camera path to take it from.
const DEFAULT_TIME_SPAN: f64 = 60.0;
/// The size of a still (F9) until the panel changes it.
const DEFAULT_STILL_SIZE: (u32, u32) = (1920, 1080);
/// Progressive passes of a still until the panel changes it: 64 samples a pixel, box-filtered.
const DEFAULT_STILL_PASSES: u32 = 64;

impl App {
    /// The viewer's state for `scene`, with its engine open; `headless` draws to a window-sized target with no
    /// window (module `headless`).
    fn start(scene: ViewerScene, options: ViewerOptions, headless: bool) -> Result<App, ViewerError> {
        let overrides = EffectOverrides::default().with_samples(options.samples);
        let live = LiveScene::load(&scene).and_then(|l| l.with_overrides(&overrides)).map_err(ViewerError::Scene)?;
        let path_file =
            options.camera_path.as_deref().map(load_camera_path).transpose().map_err(ViewerError::CameraPath)?;
        let watch = match (&scene, options.watch) {
            (ViewerScene::File(path), true) => {
                let text = fractal_dsl::parse::read_source(path).ok();
                match FileWatch::new(path, text) {
                    Ok(watch) => Some(watch),
                    Err(e) => {
                        eprintln!("not watching {} for changes: {e}", path.display());
                        None
                    }
                }
            }
            _ => None,
        };
        let mut chain = EngineChain::new(options.backend, options.renderer);
        let mut notes = Vec::new();
        let engine = chain.next(&mut notes);
        for note in notes {
            println!("{note}");
        }
        let mut app = App::new(scene, options, live, path_file, watch, chain, engine?)?;
        app.ui.editor = Some(app.editor());
        app.headless = headless;
        // No one sees a headless run's panel unless a script shows it (its screenshots are the frame's).
        app.panel_shown = app.options.panel.unwrap_or(app.panel_shown && !headless);
        Ok(app)
    }

    /// What the session did, or the error that ended it.
    fn finish(mut self) -> Result<ViewerSummary, ViewerError> {
        self.summary.device = Some(self.engine.device());
        self.summary.presenter = self.presenter.as_ref().map(Presenter::name);
        match self.fatal {
            Some(e) => Err(e),
            None => Ok(self.summary),
        }
    }
}

enum Presenter {
    Gpu(Box<GpuPresenter>),
    Soft(SoftPresenter),
}

impl Presenter {
    fn name(&self) -> &'static str {
        match self {
            Presenter::Gpu(gpu) => gpu.name(),
            Presenter::Soft(soft) => soft.name(),
        }
    }
}

/// Why a frame was not shown.
enum DrawError {
    Render(RenderError),
    Present(String),
}

/// A scene state to return to when a change (reload or toggle) gives kernels the driver rejects.
struct LastGood {
    live: LiveScene,
    params: ParamControl,
    overrides: EffectOverrides,
}

struct App {
    options: ViewerOptions,
    source: ViewerScene,
    live: LiveScene,
    last_good: Option<LastGood>,
    overrides: EffectOverrides,
    params: ParamControl,
    watch: Option<FileWatch>,
    path_file: Option<CameraPathFile>,
    /// The user's camera; `None` while the scene's camera (or the camera path file) is followed.
    fly: Option<FlyCamera>,
    last_pose: Option<Pose>,
    held: HashSet<Move>,
    sprint: bool,
    shift: bool,
    captured: bool,
    move_speed: f64,
    sensitivity: f64,
    time: f64,
    paused: bool,
    chain: EngineChain,
    engine: Engine,
    window: Option<Arc<Window>>,
    presenter: Option<Presenter>,
    scale: ScaleController,
    clock: FrameClock,
    last_frame_at: Option<Instant>,
    render_size: (u32, u32),
    script: Option<ScriptPlayer>,
    screenshot_request: Option<PathBuf>,
    summary: ViewerSummary,
    fatal: Option<ViewerError>,
    /// The last message printed by a per-frame check, so a persisting problem is printed once.
    last_report: Option<String>,
    /// Whether the panel is shown (`O`); the UI (panel and editor), its pixels as last drawn and the changes made in
    /// it, applied at the start of the next frame.
    panel_shown: bool,
    ui: Ui,
    ui_actions: Vec<UiAction>,
    /// The bookmarks beside the scene (read when first needed) and the size stills are rendered at.
    bookmarks: Option<Bookmarks>,
    still_size: (u32, u32),
    still_passes: u32,
    /// The flight being recorded (R).
    flight: Option<Flight>,
    /// Progressive passes while the view stands still.
    still: Accumulator,
    /// Input arrived since the last frame: a resting viewer draws the next frame now.
    woken: bool,
    /// Each frame's precision, and the last one said.
    precision: FramePrecision,
    /// The backend that drew the last frame in f64: the engine's where it computes in f64, else the CPU.
    wide_backend: Backend,
    /// No window: frames go to a target of the window's size (module `headless`).
    headless: bool,
    /// How the last frame was drawn, for the headless run's report.
    last_plan: Option<(Plan, Precision)>,
    /// The session ends after this frame (a key, the script's end, an error with nowhere left to go).
    exit: bool,
}

impl App {
    fn new(
        source: ViewerScene,
        options: ViewerOptions,
        live: LiveScene,
        path_file: Option<CameraPathFile>,
        watch: Option<FileWatch>,
        chain: EngineChain,
        engine: Engine,
    ) -> Result<App, ViewerError> {
        let mut params = ParamControl::new(&live.scene, None);
        for (name, value) in &options.params {
            params.set(name, *value)?;
        }
        Ok(App {
            source,
            params,
            last_good: None,
            overrides: EffectOverrides::default().with_samples(options.samples),
            watch,
            path_file,
            fly: None,
            last_pose: None,
            held: HashSet::new(),
            sprint: false,
            shift: false,
            captured: false,
            move_speed: options.move_speed,
            sensitivity: options.mouse_sensitivity,
            time: if options.start_time.is_finite() { options.start_time } else { 0.0 },
            paused: options.paused,
            chain,
            engine,
            window: None,
            presenter: None,
            scale: ScaleController::new(options.render_scale),
            clock: FrameClock::new(Instant::now()),
            last_frame_at: None,
            render_size: (0, 0),
            script: options.script.clone().map(ScriptPlayer::new),
            screenshot_request: None,
            summary: ViewerSummary::default(),
            fatal: None,
            last_report: None,
            // A scripted run (tests, benchmarks) draws the frame alone, so its screenshots are the render's.
            panel_shown: options.script.is_none(),
            ui: Ui::new(None),
            ui_actions: Vec::new(),
            bookmarks: None,
            still_size: DEFAULT_STILL_SIZE,
            still_passes: DEFAULT_STILL_PASSES,
            flight: None,
            still: Accumulator::new(options.accumulate),
            woken: false,
            precision: FramePrecision::new(options.precision, ""),
            wide_backend: Backend::Cpu,
            headless: false,
            last_plan: None,
            exit: false,
            live,
            options,
        })
    }

    /// A wgpu surface for wgpu frames when allowed and possible, softbuffer otherwise; without a window, a texture
    /// or host memory in their place. The UI's next frame gives it every texture egui has sent.
    fn make_presenter(&mut self) -> Result<Presenter, ViewerError> {
        self.ui.resend_textures();
        let gpu = match (self.options.present, &self.engine) {
            (PresentMode::Gpu, _) => true,
            (PresentMode::Auto, Engine::Wgpu(renderer)) => renderer.adapter_info().device_type != wgpu::DeviceType::Cpu,
            _ => false,
        };
        let Some(window) = self.window.clone() else {
            if !self.headless {
                return Err(ViewerError::Window("no window".to_string()));
            }
            if let (true, Engine::Wgpu(renderer)) = (gpu, &self.engine) {
                match GpuPresenter::offscreen(renderer) {
                    Ok(gpu) => return Ok(Presenter::Gpu(Box::new(gpu))),
                    Err(e) => eprintln!("wgpu target unavailable ({e}): presenting through host memory"),
                }
            }
            return Ok(Presenter::Soft(SoftPresenter::offscreen()));
        };
        if let (true, Engine::Wgpu(renderer)) = (gpu, &self.engine) {
            match GpuPresenter::new(renderer, window.clone()) {
                Ok(gpu) => return Ok(Presenter::Gpu(Box::new(gpu))),
                Err(e) => eprintln!("wgpu surface unavailable ({e}): presenting through softbuffer"),
            }
        }
        SoftPresenter::new(window).map(Presenter::Soft).map_err(ViewerError::Window)
    }

    fn report(&mut self, message: String) {
        if self.last_report.as_ref() != Some(&message) {
            eprintln!("{message}");
            self.last_report = Some(message);
        }
    }

    /// Lays the UI out and draws it for this frame (the panel while shown, the editor while open); what the user
    /// changed is applied at the start of the next frame.
    fn draw_ui(&mut self, window_size: (u32, u32)) {
        let bookmarks = if self.panel_shown { self.bookmark_names() } else { Vec::new() };
        let view = self.panel_shown.then(|| self.panel_view(bookmarks));
        let window = self.window.clone();
        let actions = self.ui.frame(window.as_deref(), window_size, view.as_ref());
        self.ui_actions.extend(actions);
    }

    /// What the panel shows of the current state.
    fn panel_view(&self, bookmarks: Vec<String>) -> PanelView {
        let timing = match self.clock.average() {
            Some(s) => format!("{:.1} ms, {:.0} FPS", s * 1e3, 1.0 / s.max(1e-9)),
            None => "measuring".to_string(),
        };
        let settings = &self.live.scene.settings;
        let (params, selected) = self.params.rows();
        let (w, h) = self.render_size;
        let status = match self.precision.said() {
            Some(Precision::F64) => format!("{} in f64 (the view asks for it), {timing}, {w}x{h}", self.wide_backend),
            _ => format!("{} in f32, {timing}, {w}x{h}", self.engine.device().backend),
        } + if self.flight.is_some() { ", recording a flight (R stops)" } else { "" };
        PanelView {
            scene: self.live.name.clone(),
            status,
            still: self.still.describe(),
            time: self.time,
            time_span: self.time_span(),
            paused: self.paused,
            samples: settings.samples,
            steps: settings.max_steps,
            epsilon: settings.epsilon,
            shadows: settings.shadows,
            ambient_occlusion: settings.ambient_occlusion.is_some(),
            glow: settings.glow.is_some(),
            fog: settings.fog.is_some(),
            params,
            selected,
            following_path: self.fly.is_none(),
            editable: true,
            editor_open: self.ui.editor.as_ref().is_some_and(|e| e.open),
            bookmarks,
            still_size: self.still_size,
            still_passes: self.still_passes,
        }
    }

    /// The time slider's range: to the scene's last camera key, or a minute.
    fn time_span(&self) -> f64 {
        match &self.live.scene.camera.placement {
            fractal_dsl::CameraPlacement::Path { keys, .. } => {
                keys.last().map_or(DEFAULT_TIME_SPAN, |k| k.time).max(self.time).max(1.0)
            }
            _ => DEFAULT_TIME_SPAN.max(self.time),
        }
    }

    // ---- frame ----

    /// The pose of the scene's camera (or the camera path file) at the current time.
    fn scene_pose(&self) -> Result<Pose, String> {
        match &self.path_file {
            Some(file) => Ok(file.path.pose(self.time, file.fov_degrees.unwrap_or(self.live.scene.camera.fov_degrees))),
            None => {
                let params = self.params.values();
                Pose::from_camera(&self.live.scene.camera, self.time, &|d| params.lookup(d)).map_err(|e| e.to_string())
            }
        }
    }

    fn pose(&mut self) -> Option<Pose> {
        let pose = match &self.fly {
            Some(fly) => Ok(fly.pose()),
            None => self.scene_pose(),
        };
        match pose {
            Ok(pose) => {
                self.last_pose = Some(pose);
                Some(pose)
            }
            Err(e) => {
                self.report(format!("camera: {e}"));
                self.last_pose
            }
        }
    }

    fn frame(&mut self) {
        let now = Instant::now();
        let measured = self.last_frame_at.map(|at| now.duration_since(at).as_secs_f64());
        self.last_frame_at = Some(now);
        let dt = self.options.fixed_time_step.filter(|s| s.is_finite()).unwrap_or(measured.unwrap_or(0.0).min(MAX_DT));

        if let Some(script) = &mut self.script {
            let step = script.next_frame(now);
            if step.finished {
                self.exit = true;
                return;
            }
            step.press.into_iter().for_each(|a| self.press(a));
            step.release.into_iter().for_each(|a| self.release(a));
            for action in step.trigger {
                self.trigger(action);
            }
            if step.look != (0.0, 0.0) {
                self.look(step.look.0, step.look.1);
            }
            if step.screenshot.is_some() {
                self.screenshot_request = step.screenshot;
            }
            for input in &step.ui {
                if let Err(e) = self.ui.script(input) {
                    self.stop(ViewerError::Script(e));
                    return;
                }
            }
        }
        self.apply_ui_actions();
        self.poll_reload();
        self.poll_editor(now);

        if let Some(fly) = &mut self.fly {
            let speed = self.move_speed * if self.sprint { SPRINT_FACTOR } else { 1.0 };
            fly.step(self.held.iter().copied(), speed, dt);
        }
        if let (Some(flight), Some(pose)) = (&mut self.flight, self.fly.map(|f| f.pose()).or(self.last_pose)) {
            flight.record(&pose, dt);
        }
        if let Some(window_size) = self.window_size() {
            self.draw_frame(window_size);
            if let Some(seconds) = measured {
                // Standing still holds the render scale: the passes keep the size they started at.
                if !self.still.still() {
                    self.scale.record(seconds);
                }
                if let (true, Some(window)) = (self.clock.record(seconds, now), &self.window) {
                    self.update_title(window);
                }
            }
        }
        // Time moves on even when a frame could not be drawn, so a problem at one time (a camera or light that
        // degenerates there) does not freeze the viewer at it.
        if !self.paused {
            self.time += dt;
        }
    }

    /// The window's size in pixels (the size asked for, without a window); `None` before the window opens.
    fn window_size(&self) -> Option<(u32, u32)> {
        match &self.window {
            Some(window) => Some((window.inner_size().width, window.inner_size().height)),
            None => self.headless.then_some(self.options.window_size),
        }
    }

    /// Renders and presents the current state, saving a requested screenshot of it.
    fn draw_frame(&mut self, window_size: (u32, u32)) {
        let Some(pose) = self.pose() else {
            return;
        };
        if window_size.0 == 0 || window_size.1 == 0 {
            return;
        }
        let render_size = self.scale.render_size(window_size);
        let frame =
            match Frame::new(&self.live.scene, &pose, self.time, render_size.0, render_size.1, self.params.values()) {
                Ok(frame) => frame,
                Err(e) => {
                    self.report(format!("cannot draw this frame: {e}"));
                    return;
                }
            };
        let want_screenshot = self.screenshot_request.is_some();
        let presenter = self.presenter.as_ref().map_or("none", Presenter::name);
        let key = StillKey::new(&self.live.scene, &frame, window_size, self.engine.device().backend, presenter);
        self.render_size = render_size;
        let precision = self.frame_precision(&frame);
        let plan = self.still.plan(key);
        self.last_plan = Some((plan, precision));
        let drawn = match (plan, precision) {
            (Plan::Frame, Precision::F32) => {
                self.draw_ui(window_size);
                self.draw(&frame, window_size, want_screenshot)
            }
            (Plan::Frame, _) => self.draw_wide(&frame, window_size, want_screenshot),
            (plan, _) => self.draw_still(plan, (&frame, precision), window_size, want_screenshot),
        };
        match drawn {
            Ok(shown) => {
                self.last_good = None;
                self.summary.frames += 1;
                if let Some(path) = self.screenshot_request.take() {
                    self.save_screenshot(path, shown, &pose, render_size, window_size);
                }
            }
            Err(e) => self.recover(e),
        }
    }

    fn draw(&mut self, frame: &Frame, window_size: (u32, u32), screenshot: bool) -> Result<Option<Image>, DrawError> {
        match (&mut self.presenter, &mut self.engine) {
            (Some(Presenter::Gpu(gpu)), Engine::Wgpu(renderer)) => {
                let ui = Some(self.ui.paint());
                gpu.draw(renderer, (self.live.wgsl(), frame), window_size, screenshot, ui).map_err(|e| match e {
                    GpuFrameError::Render(e) => DrawError::Render(e),
                    GpuFrameError::Surface(e) => DrawError::Present(e),
                })
            }
            (Some(Presenter::Soft(soft)), engine) => {
                let image =
                    engine.renderer().render(&RenderJob::new(self.live.kernels(), frame)).map_err(DrawError::Render)?;
                soft.present(&image, window_size, self.ui.overlay().as_ref()).map_err(DrawError::Present)?;
                Ok(if screenshot { soft.screenshot() } else { None })
            }
            (Some(Presenter::Gpu(_)), Engine::Other(_)) => {
                Err(DrawError::Present("the wgpu surface cannot show frames of this backend".to_string()))
            }
            (None, _) => Ok(None),
        }
    }

    fn save_screenshot(
        &mut self,
        path: PathBuf,
        shown: Option<Image>,
        pose: &Pose,
        render_size: (u32, u32),
        window_size: (u32, u32),
    ) {
        let Some(image) = shown else {
            // Nothing was presented this frame (surface busy or resizing): try again on the next one.
            self.screenshot_request = Some(path);
            return;
        };
        match write_png(&image, &path) {
            Ok(()) => {
                println!("saved screenshot {}", path.display());
                self.summary.screenshots.push(ScreenshotInfo {
                    path,
                    scene: self.live.scene.clone(),
                    pose: *pose,
                    time: self.time,
                    params: self.params.values().clone(),
                    render_size,
                    window_size,
                    device: self.engine.device(),
                    presenter: self.presenter.as_ref().map_or("none", Presenter::name),
                    passes: self.still.shown(),
                    ui_rect: self.ui.rect(),
                    source_error: self.ui.editor.as_ref().and_then(|e| e.error.as_ref()).map(|e| match e.at {
                        Some((line, column)) => format!("{line}:{column}: {}", e.message),
                        None => e.message.clone(),
                    }),
                });
            }
            Err(e) => eprintln!("cannot save the screenshot {}: {e}", path.display()),
        }
    }

    /// After a failed frame: back to the last good scene, down the backend chain, or to softbuffer; a failure with
    /// nowhere left to go ends the viewer with the error.
    fn recover(&mut self, error: DrawError) {
        self.still.reset();
        match error {
            DrawError::Present(message) => {
                if matches!(self.presenter, Some(Presenter::Gpu(_))) {
                    eprintln!("wgpu surface failed ({message}): presenting through softbuffer");
                    let soft = match self.window.clone() {
                        Some(window) => SoftPresenter::new(window),
                        None => Ok(SoftPresenter::offscreen()),
                    };
                    match soft {
                        Ok(soft) => self.presenter = Some(Presenter::Soft(soft)),
                        Err(e) => self.stop(ViewerError::Window(e)),
                    }
                } else {
                    self.stop(ViewerError::Window(message));
                }
            }
            DrawError::Render(error) => {
                if matches!(error, RenderError::KernelRejected { .. }) {
                    if let Some(good) = self.last_good.take() {
                        eprintln!("{error}\nkeeping the last good scene");
                        self.live = good.live;
                        self.params = good.params;
                        self.overrides = good.overrides;
                        return;
                    }
                }
                if error.is_backend_specific() && self.chain.has_more() {
                    let backend = self.engine.device().backend;
                    eprintln!("{backend} failed, falling back: {error}");
                    let mut notes = Vec::new();
                    let next = self.chain.next(&mut notes);
                    notes.iter().for_each(|n| eprintln!("{n}"));
                    match next {
                        Ok(engine) => {
                            self.engine = engine;
                            match self.make_presenter() {
                                Ok(p) => self.presenter = Some(p),
                                Err(e) => self.stop(e),
                            }
                        }
                        Err(e) => self.stop(e.into()),
                    }
                } else {
                    self.stop(error.into());
                }
            }
        }
    }

    fn stop(&mut self, error: ViewerError) {
        eprintln!("error: {error}");
        self.fatal = Some(error);
        self.exit = true;
    }

    fn update_title(&self, window: &Window) {
        let effects = describe(&self.live.scene.settings);
        let param = self.params.describe();
        let backend = self.engine.device().backend.to_string();
        let passes = self.still.describe();
        window.set_title(&title(&TitleFacts {
            scene: &self.live.name,
            frame_seconds: self.clock.average(),
            render_size: self.render_size,
            scale: self.scale.scale(),
            backend: &backend,
            time: self.time,
            paused: self.paused,
            effects: &effects,
            param: param.as_deref(),
            following_path: self.fly.is_none(),
            passes: passes.as_deref(),
        }));
    }
}
