//! The viewer without a window (`fractal view --headless`): the same game loop — the script's input if there is
//! one, time, camera, parameters, each frame's precision, the still view's passes, the presenter — drawing to a
//! target of the window's size: a wgpu texture, kept in flight as a swapchain keeps frames, or host memory. So what
//! a window would cost is measured where there is no display: each frame's host time, and where the device has
//! timestamps, its kernel's and its blit's device time.

use std::path::PathBuf;
use std::time::Instant;

use fractal_render::precision::Precision;

use super::{App, Presenter};
use crate::viewer::engine::Engine;
use crate::viewer::present::PassTimes;
use crate::viewer::session::{ViewerError, ViewerOptions, ViewerScene, ViewerSummary};
use crate::viewer::still::Plan;

/// How a frame of a headless run was drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameKind {
    /// By the kernel, into the presenter's buffer (the view moves, or accumulating is off).
    Kernel,
    /// In f64, on the host's side of the presenter (the view asks for it).
    Wide,
    /// A progressive pass of a view standing still.
    Pass,
    /// The passes are done: the picture drawn again.
    Rest,
    /// Nothing was drawn (the camera or the frame could not be made; the viewer said why).
    Skipped,
}

impl std::fmt::Display for FrameKind {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(match self {
            FrameKind::Kernel => "kernel frames",
            FrameKind::Wide => "f64 frames",
            FrameKind::Pass => "progressive passes",
            FrameKind::Rest => "redraws at rest",
            FrameKind::Skipped => "skipped frames",
        })
    }
}

/// What a headless run did and how long its frames took.
#[derive(Clone, Debug)]
pub struct HeadlessRun {
    pub summary: ViewerSummary,
    pub window_size: (u32, u32),
    /// The render size of the last frame.
    pub render_size: (u32, u32),
    /// Each frame's kind and host time in milliseconds: the game loop's frame, from input to the frame submitted
    /// (and, with frames in flight, the wait for the oldest one).
    pub frames: Vec<(FrameKind, f64)>,
    /// Of each frame's host time, the milliseconds spent waiting for the device's frames in flight (a wgpu
    /// texture's; zero elsewhere, where waiting is inside the renderer): the rest is the viewer's own work and the
    /// driver's on the host.
    pub waited_ms: Vec<f64>,
    /// The device times of the frames drawn through a wgpu texture, in order, where the device has timestamps.
    pub device_times: Vec<PassTimes>,
}

/// Runs the viewer on `scene` for `frames` frames with no window; the last frame as the window would show it is
/// saved to `screenshot` when given.
pub fn run_headless(
    scene: ViewerScene,
    options: ViewerOptions,
    frames: u64,
    screenshot: Option<PathBuf>,
) -> Result<HeadlessRun, ViewerError> {
    let mut app = App::start(scene, options, true)?;
    app.presenter = Some(app.make_presenter()?);
    println!(
        "viewing {} with {} ({}, no window)",
        app.live.name,
        app.engine.device(),
        app.presenter.as_ref().map_or("no presenter", Presenter::name)
    );
    let mut times = Vec::new();
    let mut waited_ms = Vec::new();
    let waited = |app: &App| match &app.presenter {
        Some(Presenter::Gpu(gpu)) => gpu.waited().as_secs_f64() * 1e3,
        _ => 0.0,
    };
    for i in 0..frames {
        if i + 1 == frames {
            app.screenshot_request = screenshot.clone();
        }
        app.last_plan = None;
        let (started, waited_before) = (Instant::now(), waited(&app));
        app.frame();
        if app.exit {
            break;
        }
        let kind = match app.last_plan {
            Some((Plan::Frame, Precision::F32)) => FrameKind::Kernel,
            Some((Plan::Frame, _)) => FrameKind::Wide,
            Some((Plan::Pass, _)) => FrameKind::Pass,
            Some((Plan::Rest, _)) => FrameKind::Rest,
            None => FrameKind::Skipped,
        };
        times.push((kind, started.elapsed().as_secs_f64() * 1e3));
        waited_ms.push(waited(&app) - waited_before);
    }
    let device_times = match (&mut app.presenter, &app.engine) {
        (Some(Presenter::Gpu(gpu)), Engine::Wgpu(renderer)) => gpu.finish(renderer).unwrap_or_else(|e| {
            eprintln!("cannot read the device's timestamps: {e:?}");
            Vec::new()
        }),
        _ => Vec::new(),
    };
    let (window_size, render_size) = (app.options.window_size, app.render_size);
    let summary = app.finish()?;
    Ok(HeadlessRun { summary, window_size, render_size, frames: times, waited_ms, device_times })
}
