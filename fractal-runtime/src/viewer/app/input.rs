//! Input: what a key, a mouse motion or click, a slider drag or a scripted step does to the viewer's state — the
//! camera, time, effect toggles and parameters. The game loop (`app.rs`) routes events here and draws the result.

use winit::event::ElementState;
use winit::keyboard::KeyCode;
use winit::window::CursorGrabMode;

use super::{App, LastGood};
use crate::viewer::camera_control::{camera_line, describe_pose, FlyCamera};
use crate::viewer::controls::{binding, Action, HELP};
use crate::viewer::effects::describe;
use crate::viewer::params::ParamControl;
use crate::viewer::screenshot::next_screenshot_path;
use crate::viewer::ui::UiAction;

/// Factor of one press of +/− or [/].
const SPEED_STEP: f64 = 1.25;
/// Seconds per press of ←/→.
const TIME_STEP: f64 = 1.0;

impl App {
    pub(super) fn key(&mut self, code: KeyCode, state: ElementState, repeat: bool) {
        if matches!(code, KeyCode::ShiftLeft | KeyCode::ShiftRight) {
            self.shift = state.is_pressed();
        }
        let Some(action) = binding(code, self.shift) else {
            return;
        };
        if action.is_held() {
            if state.is_pressed() {
                self.press(action);
            } else {
                self.release(action);
            }
            return;
        }
        let repeats =
            matches!(action, Action::IncreaseParam | Action::DecreaseParam | Action::TimeForward | Action::TimeBack);
        if state.is_pressed() && (!repeat || repeats) {
            self.trigger(action);
        }
    }

    pub(super) fn press(&mut self, action: Action) {
        match action {
            Action::Move(m) => {
                self.take_control();
                self.held.insert(m);
            }
            Action::Sprint => self.sprint = true,
            _ => {}
        }
    }

    pub(super) fn release(&mut self, action: Action) {
        match action {
            Action::Move(m) => {
                self.held.remove(&m);
            }
            Action::Sprint => self.sprint = false,
            _ => {}
        }
    }

    pub(super) fn look(&mut self, dx: f64, dy: f64) {
        self.take_control();
        if let Some(fly) = &mut self.fly {
            fly.look(dx, dy, self.sensitivity);
        }
    }

    /// Leaves the scene's camera path for the user's camera, starting where the path was.
    pub(super) fn take_control(&mut self) {
        if self.fly.is_none() {
            let pose = self.last_pose.or_else(|| self.scene_pose().ok());
            if let Some(pose) = pose {
                self.fly = Some(FlyCamera::from_pose(&pose));
                if self.script.is_none() {
                    println!("free camera (C returns to the scene's camera)");
                }
            }
        }
    }

    pub(super) fn capture_mouse(&mut self) {
        let Some(window) = self.window.clone() else {
            return;
        };
        let grabbed = window
            .set_cursor_grab(CursorGrabMode::Locked)
            .or_else(|_| window.set_cursor_grab(CursorGrabMode::Confined));
        if let Err(e) = grabbed {
            // Relative motion still arrives without a grab; the cursor may just leave the window.
            self.report(format!("cannot grab the mouse: {e}"));
        }
        window.set_cursor_visible(false);
        // Without a window manager a click does not focus the window, and an unfocused window gets no keys.
        window.focus_window();
        self.captured = true;
    }

    pub(super) fn release_mouse(&mut self) {
        if let Some(window) = &self.window {
            let _ = window.set_cursor_grab(CursorGrabMode::None);
            window.set_cursor_visible(true);
        }
        self.captured = false;
    }

    pub(super) fn trigger(&mut self, action: Action) {
        let authored = self.live.authored().settings.clone();
        match action {
            Action::Move(_) | Action::Sprint => {}
            Action::CycleShadows => {
                self.overrides.cycle_shadows(&authored);
                self.apply_overrides();
            }
            Action::ToggleAmbientOcclusion => {
                self.overrides.toggle_ambient_occlusion(&authored);
                self.apply_overrides();
            }
            Action::ToggleGlow => {
                self.overrides.toggle_glow(&authored);
                self.apply_overrides();
            }
            Action::ToggleFog => {
                self.overrides.toggle_fog(&authored);
                self.apply_overrides();
            }
            Action::TogglePause => {
                self.paused = !self.paused;
                println!("time {} at t = {:.3}", if self.paused { "paused" } else { "running" }, self.time);
            }
            Action::TimeForward => self.time += TIME_STEP,
            Action::TimeBack => self.time -= TIME_STEP,
            Action::Screenshot => {
                self.screenshot_request = Some(next_screenshot_path(&self.options.screenshot_dir, &self.live.name));
            }
            Action::PrintPose => {
                let pose = self.fly.map(|f| f.pose()).or(self.last_pose).or_else(|| self.scene_pose().ok());
                if let Some(pose) = &pose {
                    println!("{}", camera_line(pose));
                }
                match pose {
                    Some(pose) => println!("{}", describe_pose(&pose, self.time)),
                    None => println!("no camera pose yet"),
                }
            }
            Action::NextParam => self.say_param(|p| p.select(1)),
            Action::PreviousParam => self.say_param(|p| p.select(-1)),
            Action::IncreaseParam => {
                let coarse = self.shift;
                self.say_param(|p| p.nudge(1.0, coarse));
            }
            Action::DecreaseParam => {
                let coarse = self.shift;
                self.say_param(|p| p.nudge(-1.0, coarse));
            }
            Action::ResetParam => self.say_param(ParamControl::reset),
            Action::FasterMovement => {
                self.move_speed *= SPEED_STEP;
                println!("move speed {:.3} units/s", self.move_speed);
            }
            Action::SlowerMovement => {
                self.move_speed /= SPEED_STEP;
                println!("move speed {:.3} units/s", self.move_speed);
            }
            Action::MoreSensitive => {
                self.sensitivity *= SPEED_STEP;
                println!("mouse sensitivity {:.5} rad/pixel", self.sensitivity);
            }
            Action::LessSensitive => {
                self.sensitivity /= SPEED_STEP;
                println!("mouse sensitivity {:.5} rad/pixel", self.sensitivity);
            }
            Action::FollowScenePath => {
                self.fly = None;
                println!("following the scene's camera");
            }
            Action::ReleaseOrQuit => {
                if self.captured {
                    self.release_mouse();
                } else {
                    self.exit = true;
                }
            }
            Action::Help => println!("{HELP}"),
            Action::TogglePanel => self.panel_shown = !self.panel_shown,
            Action::Bookmark => self.save_bookmark(),
            Action::RenderStill => self.render_still(),
            Action::RecordFlight => self.toggle_flight(),
            Action::FlightKey => match &mut self.flight {
                Some(flight) => {
                    flight.key_now();
                    println!("flight key added");
                }
                None => println!("not recording a flight (R starts one)"),
            },
            Action::ToggleEditor => {
                if let Some(editor) = &mut self.ui.editor {
                    editor.open = !editor.open;
                }
            }
            Action::MoreSteps | Action::FewerSteps => {
                self.overrides.scale_steps(&authored, if action == Action::MoreSteps { 2.0 } else { 0.5 });
                self.apply_overrides();
            }
            Action::FinerEpsilon | Action::CoarserEpsilon => {
                self.overrides.scale_epsilon(&authored, if action == Action::FinerEpsilon { 0.5 } else { 2.0 });
                self.apply_overrides();
            }
        }
    }

    /// Applies what the user changed in the UI last frame: what a key does for the same change, so both stay one.
    pub(super) fn apply_ui_actions(&mut self) {
        for action in std::mem::take(&mut self.ui_actions) {
            match action {
                UiAction::SetTime(t) => self.time = t,
                UiAction::SetParam(i, value) => {
                    self.params.set_index(i, value);
                }
                UiAction::ResetParam(i) => self.say_param(|p| p.reset_index(i)),
                UiAction::SetSamples(n) => {
                    self.overrides.set_samples(n);
                    self.apply_overrides();
                }
                UiAction::SetSteps(n) => {
                    self.overrides.set_steps(n);
                    self.apply_overrides();
                }
                UiAction::SetEpsilon(e) => {
                    self.overrides.set_epsilon(e);
                    self.apply_overrides();
                }
                UiAction::Key(action) => self.trigger(action),
                UiAction::ToggleEditor => self.trigger(Action::ToggleEditor),
                UiAction::SourceEdited => {}
                UiAction::SaveSource => self.save_source(),
                UiAction::GoToBookmark(name) => self.go_to_bookmark(&name),
                UiAction::SetStill((w, h), passes) => {
                    self.still_size = (w.max(1), h.max(1));
                    self.still_passes = passes.max(1);
                }
            }
        }
    }

    fn say_param(&mut self, change: impl FnOnce(&mut ParamControl) -> Option<String>) {
        match change(&mut self.params) {
            Some(text) => println!("param {text}"),
            None => println!("this scene has no param(..) values"),
        }
    }

    /// Recompiles the kernels with the current effect overrides.
    fn apply_overrides(&mut self) {
        let next = match self.live.with_overrides(&self.overrides) {
            Ok(next) => next,
            Err(e) => return eprintln!("{e}"),
        };
        println!("{} (kernels recompiled)", describe(&next.scene.settings));
        let previous = std::mem::replace(&mut self.live, next);
        if self.last_good.is_none() {
            self.last_good =
                Some(LastGood { live: previous, params: self.params.clone(), overrides: self.overrides.clone() });
        }
    }
}
