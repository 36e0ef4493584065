//! The game loop: a winit [`ApplicationHandler`] that, once per frame, polls input (keys, mouse, the script, the
//! watched file), updates time, camera and parameters, renders, and presents — and recovers from what can go wrong on
//! the way (a kernel the driver rejects, a backend that fails, a surface that cannot present) without panicking.
//! What each key, click or scripted step changes is module `input`'s; this file owns the state and the frame.

use std::collections::HashSet;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use fractal_render::camera::Pose;
use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::Image;
use fractal_render::precision::Precision;
use fractal_render::renderer::RenderJob;
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{DeviceEvent, DeviceId, ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::PhysicalKey;
use winit::window::{Window, WindowId};

mod input;
mod passes;

use crate::frame_precision::FramePrecision;

use super::camera_control::{FlyCamera, SPRINT_FACTOR};
use super::controls::{Move, HELP};
use super::effects::{describe, describe_quality, EffectOverrides};
use super::engine::{Engine, EngineChain};
use super::live_scene::{FileWatch, LiveScene};
use super::panel::{Overlay, PanelContent, SliderTarget};
use super::params::ParamControl;
use super::path_file::{load_camera_path, CameraPathFile};
use super::present::{GpuFrameError, GpuPresenter, SoftPresenter};
use super::scale::ScaleController;
use super::screenshot::write_png;
use super::script::ScriptPlayer;
use super::session::{PresentMode, ScreenshotInfo, ViewerError, ViewerOptions, ViewerScene, ViewerSummary};
use super::still::{Accumulator, Plan, StillKey};
use super::title::{title, FrameClock, TitleFacts};

/// Longest time step of one frame: after a stall (a slow recompile, a dragged window) the camera does not jump.
const MAX_DT: f64 = 0.25;
/// Pixels of scroll per mouse-wheel line.
const PIXELS_PER_LINE: f64 = 40.0;
/// The time slider's range when the scene has no camera path to take it from.
const DEFAULT_TIME_SPAN: f64 = 60.0;
/// Time between frames while the viewer rests (standing still with every pass drawn): input, the watched file and
/// the panel are still looked at, and nothing is rendered.
const REST_FRAME: Duration = Duration::from_millis(50);

pub fn run(scene: ViewerScene, options: ViewerOptions) -> Result<ViewerSummary, ViewerError> {
    let overrides = EffectOverrides::default().with_samples(options.samples);
    let live = LiveScene::load(&scene).and_then(|l| l.with_overrides(&overrides)).map_err(ViewerError::Scene)?;
    let path_file =
        options.camera_path.as_deref().map(load_camera_path).transpose().map_err(ViewerError::CameraPath)?;
    let event_loop = build_event_loop()?;
    event_loop.set_control_flow(ControlFlow::Poll);
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
    let engine = engine?;
    let mut app = App::new(scene, options, live, path_file, watch, chain, engine)?;
    event_loop.run_app(&mut app).map_err(|e| ViewerError::Window(e.to_string()))?;
    app.summary.device = Some(app.engine.device());
    app.summary.presenter = app.presenter.as_ref().map(Presenter::name);
    match app.fatal {
        Some(e) => Err(e),
        None => Ok(app.summary),
    }
}

/// An event loop that may run on any thread (tests run the viewer off the main thread). A window system that is
/// missing or refuses the connection is [`ViewerError::NoDisplay`].
fn build_event_loop() -> Result<EventLoop<()>, ViewerError> {
    let built = std::panic::catch_unwind(|| {
        let mut builder = EventLoop::builder();
        #[cfg(any(
            target_os = "linux",
            target_os = "dragonfly",
            target_os = "freebsd",
            target_os = "netbsd",
            target_os = "openbsd"
        ))]
        {
            winit::platform::x11::EventLoopBuilderExtX11::with_any_thread(&mut builder, true);
            winit::platform::wayland::EventLoopBuilderExtWayland::with_any_thread(&mut builder, true);
        }
        builder.build()
    });
    match built {
        Ok(Ok(event_loop)) => Ok(event_loop),
        Ok(Err(e)) => Err(ViewerError::NoDisplay(format!("cannot connect to the window system: {e}"))),
        Err(_) => Err(ViewerError::NoDisplay("the window system library failed to start".to_string())),
    }
}

enum Presenter {
    Gpu(GpuPresenter),
    Soft(SoftPresenter),
}

impl Presenter {
    fn name(&self) -> &'static str {
        match self {
            Presenter::Gpu(_) => "wgpu surface",
            Presenter::Soft(_) => "softbuffer",
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
    /// Whether the panel is shown (`O`), the panel as last drawn, the slider being dragged and the cursor.
    panel_shown: bool,
    overlay: Option<Overlay>,
    dragging: Option<SliderTarget>,
    cursor: (f64, f64),
    /// Progressive passes while the view stands still.
    still: Accumulator,
    /// Input arrived since the last frame: a resting viewer draws the next frame now.
    woken: bool,
    /// Each frame's precision, and the last one said.
    precision: FramePrecision,
    /// The backend that drew the last frame in f64: the engine's where it computes in f64, else the CPU.
    wide_backend: Backend,
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
            overlay: None,
            dragging: None,
            cursor: (0.0, 0.0),
            still: Accumulator::new(options.accumulate),
            woken: false,
            precision: FramePrecision::new(options.precision, ""),
            wide_backend: Backend::Cpu,
            live,
            options,
        })
    }

    fn open_window(&mut self, event_loop: &ActiveEventLoop) -> Result<(), ViewerError> {
        let (width, height) = self.options.window_size;
        let mut attributes = Window::default_attributes()
            .with_title(format!("fractal — {}", self.live.name))
            .with_inner_size(PhysicalSize::new(width.max(1), height.max(1)));
        if let Some((x, y)) = self.options.window_position {
            attributes = attributes.with_position(PhysicalPosition::new(x, y));
        }
        let window = event_loop
            .create_window(attributes)
            .map(Arc::new)
            .map_err(|e| ViewerError::NoDisplay(format!("cannot open a window: {e}")))?;
        self.window = Some(window);
        self.presenter = Some(self.make_presenter()?);
        println!(
            "viewing {} with {} ({})",
            self.live.name,
            self.engine.device(),
            self.presenter.as_ref().map_or("no presenter", Presenter::name)
        );
        if self.options.print_help && self.script.is_none() {
            println!("{HELP}");
        }
        Ok(())
    }

    /// A wgpu surface for wgpu frames when allowed and possible, softbuffer otherwise.
    fn make_presenter(&self) -> Result<Presenter, ViewerError> {
        let Some(window) = self.window.clone() else {
            return Err(ViewerError::Window("no window".to_string()));
        };
        if let (PresentMode::Auto, Engine::Wgpu(renderer)) = (self.options.present, &self.engine) {
            match GpuPresenter::new(renderer, window.clone()) {
                Ok(gpu) => return Ok(Presenter::Gpu(gpu)),
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

    /// The panel for the current state, or `None` while it is hidden.
    fn panel(&self, window_width: u32) -> Option<Overlay> {
        if !self.panel_shown {
            return None;
        }
        let timing = match self.clock.average() {
            Some(s) => format!("{:.1} ms, {:.0} FPS", s * 1e3, 1.0 / s.max(1e-9)),
            None => "measuring".to_string(),
        };
        let settings = &self.live.scene.settings;
        let (params, selected) = self.params.rows();
        let mut status = vec![
            self.live.name.clone(),
            match self.precision.said() {
                Some(Precision::F64) => format!(
                    "{} in f64 (the view asks for it), {timing}, {}x{}",
                    self.wide_backend, self.render_size.0, self.render_size.1
                ),
                _ => {
                    format!("{}, {timing}, {}x{}", self.engine.device().backend, self.render_size.0, self.render_size.1)
                }
            },
        ];
        status.extend(self.still.describe().map(|passes| format!("still: {passes}")));
        let content = PanelContent {
            status,
            time: self.time,
            time_span: self.time_span(),
            paused: self.paused,
            quality: vec![
                format!("{} (0/9, 8/7)", describe_quality(settings)),
                format!("{} (1-4)", describe(settings)),
            ],
            params,
            selected,
        };
        Some(super::panel::draw(&content, super::panel::scale_for(window_width)))
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

    fn poll_reload(&mut self) {
        let (Some(watch), ViewerScene::File(path)) = (&mut self.watch, &self.source) else {
            return;
        };
        let Some(text) = watch.poll() else {
            return;
        };
        let loaded = text
            .and_then(|text| LiveScene::from_text(self.live.name.clone(), path, &text))
            .and_then(|loaded| loaded.with_overrides(&self.overrides));
        match loaded {
            Ok(loaded) => {
                println!("reloaded {}", path.display());
                let next = loaded;
                let params = ParamControl::new(&next.scene, Some(&self.params));
                let previous = std::mem::replace(&mut self.live, next);
                let previous_params = std::mem::replace(&mut self.params, params);
                if self.last_good.is_none() {
                    self.last_good =
                        Some(LastGood { live: previous, params: previous_params, overrides: self.overrides.clone() });
                }
                self.last_report = None;
            }
            // The last good scene stays on screen.
            Err(e) => eprintln!("{e}"),
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

    fn frame(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        let measured = self.last_frame_at.map(|at| now.duration_since(at).as_secs_f64());
        self.last_frame_at = Some(now);
        let dt = self.options.fixed_time_step.filter(|s| s.is_finite()).unwrap_or(measured.unwrap_or(0.0).min(MAX_DT));

        if let Some(script) = &mut self.script {
            let step = script.next_frame(now);
            if step.finished {
                event_loop.exit();
                return;
            }
            step.press.into_iter().for_each(|a| self.press(a));
            step.release.into_iter().for_each(|a| self.release(a));
            for action in step.trigger {
                self.trigger(action, event_loop);
            }
            if step.look != (0.0, 0.0) {
                self.look(step.look.0, step.look.1);
            }
            if step.screenshot.is_some() {
                self.screenshot_request = step.screenshot;
            }
        }
        self.poll_reload();

        if let Some(fly) = &mut self.fly {
            let speed = self.move_speed * if self.sprint { SPRINT_FACTOR } else { 1.0 };
            fly.step(self.held.iter().copied(), speed, dt);
        }
        if let Some(window) = self.window.clone() {
            self.draw_frame(&window, event_loop);
            if let Some(seconds) = measured {
                // Standing still holds the render scale: the passes keep the size they started at.
                if !self.still.still() {
                    self.scale.record(seconds);
                }
                if self.clock.record(seconds, now) {
                    self.update_title(&window);
                }
            }
        }
        // Time moves on even when a frame could not be drawn, so a problem at one time (a camera or light that
        // degenerates there) does not freeze the viewer at it.
        if !self.paused {
            self.time += dt;
        }
    }

    /// Renders and presents the current state, saving a requested screenshot of it.
    fn draw_frame(&mut self, window: &Window, event_loop: &ActiveEventLoop) {
        let size = window.inner_size();
        let window_size = (size.width, size.height);
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
        let drawn = match (self.still.plan(key), precision) {
            (Plan::Frame, Precision::F32) => {
                self.overlay = self.panel(window_size.0);
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
            Err(e) => self.recover(e, event_loop),
        }
    }

    fn draw(&mut self, frame: &Frame, window_size: (u32, u32), screenshot: bool) -> Result<Option<Image>, DrawError> {
        match (&mut self.presenter, &mut self.engine) {
            (Some(Presenter::Gpu(gpu)), Engine::Wgpu(renderer)) => {
                let overlay = self.overlay.as_ref();
                gpu.draw(renderer, self.live.wgsl(), frame, window_size, screenshot, overlay).map_err(|e| match e {
                    GpuFrameError::Render(e) => DrawError::Render(e),
                    GpuFrameError::Surface(e) => DrawError::Present(e),
                })
            }
            (Some(Presenter::Soft(soft)), engine) => {
                let image =
                    engine.renderer().render(&RenderJob::new(self.live.kernels(), frame)).map_err(DrawError::Render)?;
                soft.present(&image, window_size, self.overlay.as_ref()).map_err(DrawError::Present)?;
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
                });
            }
            Err(e) => eprintln!("cannot save the screenshot {}: {e}", path.display()),
        }
    }

    /// After a failed frame: back to the last good scene, down the backend chain, or to softbuffer; a failure with
    /// nowhere left to go ends the viewer with the error.
    fn recover(&mut self, error: DrawError, event_loop: &ActiveEventLoop) {
        self.still.reset();
        match error {
            DrawError::Present(message) => {
                if matches!(self.presenter, Some(Presenter::Gpu(_))) {
                    eprintln!("wgpu surface failed ({message}): presenting through softbuffer");
                    let soft = self.window.clone().ok_or_else(|| "no window".to_string()).and_then(SoftPresenter::new);
                    match soft {
                        Ok(soft) => self.presenter = Some(Presenter::Soft(soft)),
                        Err(e) => self.stop(ViewerError::Window(e), event_loop),
                    }
                } else {
                    self.stop(ViewerError::Window(message), event_loop);
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
                                Err(e) => self.stop(e, event_loop),
                            }
                        }
                        Err(e) => self.stop(e.into(), event_loop),
                    }
                } else {
                    self.stop(error.into(), event_loop);
                }
            }
        }
    }

    fn stop(&mut self, error: ViewerError, event_loop: &ActiveEventLoop) {
        eprintln!("error: {error}");
        self.fatal = Some(error);
        event_loop.exit();
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

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        if let Err(e) = self.open_window(event_loop) {
            self.fatal = Some(e);
            event_loop.exit();
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let scripted = self.script.is_some();
        if !matches!(event, WindowEvent::RedrawRequested) {
            self.woken = true;
        }
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::RedrawRequested => self.frame(event_loop),
            // A script drives the camera on its own; the user's keys and mouse would make the run irreproducible.
            _ if scripted => {}
            WindowEvent::KeyboardInput { event, .. } => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    self.key(code, event.state, event.repeat, event_loop);
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = (position.x, position.y);
                if let Some(target) = self.dragging {
                    self.slide(target, position.x);
                }
            }
            WindowEvent::MouseInput { state: ElementState::Pressed, button: MouseButton::Left, .. }
                if !self.captured =>
            {
                let (x, y) = self.cursor;
                match self.overlay.as_ref().map(|o| (o.contains(x, y), o.slider_at(x, y))) {
                    Some((_, Some(slider))) => {
                        self.dragging = Some(slider.target);
                        self.slide(slider.target, x);
                    }
                    // A click on the panel's text does nothing; anywhere else it takes the mouse to look around.
                    Some((true, None)) => {}
                    _ => self.capture_mouse(),
                }
            }
            WindowEvent::MouseInput { state: ElementState::Released, button: MouseButton::Left, .. } => {
                self.dragging = None;
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y as f64,
                    MouseScrollDelta::PixelDelta(p) => p.y / PIXELS_PER_LINE,
                };
                self.take_control();
                if let Some(fly) = &mut self.fly {
                    // Scrolling up narrows the view (zooms in).
                    fly.zoom(-lines);
                }
            }
            WindowEvent::Focused(false) => {
                self.release_mouse();
                self.held.clear();
                self.sprint = false;
                self.shift = false;
            }
            _ => {}
        }
    }

    fn device_event(&mut self, _event_loop: &ActiveEventLoop, _id: DeviceId, event: DeviceEvent) {
        if let DeviceEvent::MouseMotion { delta } = event {
            if self.captured && self.script.is_none() {
                self.woken = true;
                self.look(delta.0, delta.1);
            }
        }
    }

    /// The next frame at once, or, while the viewer rests, after [`REST_FRAME`] or the next input.
    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(window) = &self.window else {
            return;
        };
        if self.still.resting() && !self.woken {
            if let Some(due) = self.last_frame_at.map(|at| at + REST_FRAME).filter(|&due| Instant::now() < due) {
                event_loop.set_control_flow(ControlFlow::WaitUntil(due));
                return;
            }
        }
        self.woken = false;
        event_loop.set_control_flow(ControlFlow::Poll);
        window.request_redraw();
    }
}
