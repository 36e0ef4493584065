//! The viewer in a window: a winit event loop drives the game loop (`app.rs`) — a frame on each redraw request,
//! input as it comes, and rest between frames while the view stands still with every pass drawn. Module `headless`
//! drives the same loop with no window.

use std::sync::Arc;
use std::time::{Duration, Instant};

use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{DeviceEvent, DeviceId, ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::PhysicalKey;
use winit::window::{Window, WindowId};

use super::{App, Presenter};
use crate::viewer::controls::HELP;
use crate::viewer::session::{ViewerError, ViewerOptions, ViewerScene, ViewerSummary};

/// Pixels of scroll per mouse-wheel line.
const PIXELS_PER_LINE: f64 = 40.0;
/// Time between frames while the viewer rests (standing still with every pass drawn): input, the watched file and
/// the panel are still looked at, and nothing is rendered.
const REST_FRAME: Duration = Duration::from_millis(50);

/// Opens a window on `scene` and runs the viewer until it closes (or the script ends).
pub fn run(scene: ViewerScene, options: ViewerOptions) -> Result<ViewerSummary, ViewerError> {
    let event_loop = build_event_loop()?;
    event_loop.set_control_flow(ControlFlow::Poll);
    let mut app = App::start(scene, options, false)?;
    event_loop.run_app(&mut app).map_err(|e| ViewerError::Window(e.to_string()))?;
    app.finish()
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

impl App {
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
        self.ui.attach(&window);
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
        // The UI sees every event first; what it uses (a click on the panel, typing in the editor) goes no further.
        let used_by_ui = match (&self.window, scripted) {
            (Some(window), false) if !self.captured => {
                let window = window.clone();
                self.ui.on_window_event(&window, &event)
            }
            _ => false,
        };
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::RedrawRequested => self.frame(),
            // A script drives the camera on its own; the user's keys and mouse would make the run irreproducible.
            _ if scripted || used_by_ui => {}
            WindowEvent::KeyboardInput { event, .. } => {
                if let PhysicalKey::Code(code) = event.physical_key {
                    self.key(code, event.state, event.repeat);
                }
            }
            WindowEvent::MouseInput { state: ElementState::Pressed, button: MouseButton::Left, .. }
                if !self.captured =>
            {
                self.capture_mouse()
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
        if self.exit {
            event_loop.exit();
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
        if self.exit {
            event_loop.exit();
            return;
        }
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
