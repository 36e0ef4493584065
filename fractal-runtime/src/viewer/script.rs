//! Scripted input: a list of steps the viewer plays instead of waiting for the user (tests, demos, recordings). The
//! viewer exits when the script ends.

use std::collections::VecDeque;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use super::controls::Action;
use super::ui::UiInput;

/// How long a scripted [`ScriptedStep::Idle`] may last at most; longer requests are clamped so a script always ends.
pub const MAX_IDLE: Duration = Duration::from_secs(600);

/// One step of a script. Steps that take no frame (press, release, trigger, look, screenshot) apply to the next frame
/// drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum ScriptedStep {
    /// Draw this many frames.
    Frames(u32),
    /// Hold an action's key down (movement, sprint) until [`ScriptedStep::Release`].
    Press(Action),
    Release(Action),
    /// Press and release a key once (toggles, time steps, parameter keys, printing the pose).
    Trigger(Action),
    /// Mouse motion in pixels, as if the mouse were captured.
    Look {
        dx: f64,
        dy: f64,
    },
    /// Save the next frame drawn, as presented in the window, to this PNG file; the steps after it apply to the
    /// frames after that one.
    Screenshot(PathBuf),
    /// Input to the UI through egui, as a pointer and keyboard give it: press a widget, type, … (it applies to the
    /// next frame drawn; a press and its release need a frame between them, as a click does).
    Ui(UiInput),
    /// Keep drawing frames for this long (at most [`MAX_IDLE`]), e.g. while another program looks at the
    /// window.
    Idle(Duration),
}

/// What the script does in one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScriptFrame {
    pub press: Vec<Action>,
    pub release: Vec<Action>,
    pub trigger: Vec<Action>,
    pub look: (f64, f64),
    pub screenshot: Option<PathBuf>,
    pub ui: Vec<UiInput>,
    /// The script is over: draw nothing more and exit.
    pub finished: bool,
}

/// Plays a script frame by frame.
#[derive(Clone, Debug)]
pub struct ScriptPlayer {
    steps: VecDeque<ScriptedStep>,
    idle_since: Option<Instant>,
}

impl ScriptPlayer {
    pub fn new(steps: Vec<ScriptedStep>) -> ScriptPlayer {
        ScriptPlayer { steps: steps.into(), idle_since: None }
    }

    /// The input of the next frame.
    pub fn next_frame(&mut self, now: Instant) -> ScriptFrame {
        let mut frame = ScriptFrame::default();
        loop {
            let Some(step) = self.steps.front_mut() else {
                // Steps gathered for this frame still get their frame; the script ends on the next call.
                frame.finished = frame == ScriptFrame::default();
                return frame;
            };
            match step {
                ScriptedStep::Frames(0) => {}
                ScriptedStep::Frames(n) => {
                    *n -= 1;
                    return frame;
                }
                ScriptedStep::Idle(d) => {
                    let since = *self.idle_since.get_or_insert(now);
                    if now.duration_since(since) < (*d).min(MAX_IDLE) {
                        return frame;
                    }
                    self.idle_since = None;
                }
                ScriptedStep::Press(a) => frame.press.push(*a),
                ScriptedStep::Release(a) => frame.release.push(*a),
                ScriptedStep::Trigger(a) => frame.trigger.push(*a),
                ScriptedStep::Ui(input) => frame.ui.push(input.clone()),
                ScriptedStep::Look { dx, dy } => {
                    frame.look.0 += *dx;
                    frame.look.1 += *dy;
                }
                ScriptedStep::Screenshot(path) => {
                    // The screenshot frame ends the frame's steps: what follows applies to later frames, so the
                    // picture shows the state the steps before it set up.
                    frame.screenshot = Some(path.clone());
                    self.steps.pop_front();
                    return frame;
                }
            }
            self.steps.pop_front();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::controls::Move;

    #[test]
    fn steps_are_spread_over_frames() {
        let fwd = Action::Move(Move::Forward);
        let mut p = ScriptPlayer::new(vec![
            ScriptedStep::Press(fwd),
            ScriptedStep::Frames(2),
            ScriptedStep::Release(fwd),
            ScriptedStep::Look { dx: 3.0, dy: -1.0 },
            ScriptedStep::Screenshot("a.png".into()),
            ScriptedStep::Screenshot("b.png".into()),
        ]);
        let now = Instant::now();
        let f1 = p.next_frame(now);
        assert_eq!(f1.press, vec![fwd]);
        assert!(!f1.finished);
        assert_eq!(p.next_frame(now), ScriptFrame::default());
        let f3 = p.next_frame(now);
        assert_eq!(
            (f3.release.clone(), f3.look, f3.screenshot.clone()),
            (vec![fwd], (3.0, -1.0), Some("a.png".into()))
        );
        let f4 = p.next_frame(now);
        assert_eq!(f4.screenshot, Some("b.png".into()));
        assert!(!f4.finished, "the screenshot frame is still drawn");
        assert!(p.next_frame(now).finished);
    }

    #[test]
    fn idle_lasts_its_time() {
        let mut p = ScriptPlayer::new(vec![ScriptedStep::Idle(Duration::from_millis(50))]);
        let start = Instant::now();
        assert!(!p.next_frame(start).finished);
        assert!(!p.next_frame(start + Duration::from_millis(10)).finished);
        assert!(p.next_frame(start + Duration::from_millis(60)).finished);
        assert!(ScriptPlayer::new(vec![]).next_frame(start).finished);
        let mut last_trigger = ScriptPlayer::new(vec![ScriptedStep::Trigger(Action::PrintPose)]);
        assert_eq!(last_trigger.next_frame(start).trigger, vec![Action::PrintPose], "a final trigger still runs");
        assert!(last_trigger.next_frame(start).finished);
    }
}
