//! Key bindings: which key does what ([`binding`]), the actions keys and scripts share ([`Action`]), and the help text.

use winit::keyboard::KeyCode;

/// A direction the camera moves in while its key is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Move {
    Forward,
    Back,
    Left,
    Right,
    Down,
    Up,
}

/// Everything a key (or a scripted step) can ask the viewer to do.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Action {
    /// Held: moves the camera.
    Move(Move),
    /// Held: moves 4× faster.
    Sprint,
    /// Shadows none → hard → soft → none.
    CycleShadows,
    ToggleAmbientOcclusion,
    ToggleGlow,
    ToggleFog,
    TogglePause,
    TimeForward,
    TimeBack,
    Screenshot,
    PrintPose,
    NextParam,
    PreviousParam,
    IncreaseParam,
    DecreaseParam,
    ResetParam,
    FasterMovement,
    SlowerMovement,
    MoreSensitive,
    LessSensitive,
    /// Back to the scene's camera (or the loaded camera path).
    FollowScenePath,
    /// Release the mouse, or quit when it is not captured.
    ReleaseOrQuit,
    Help,
    /// Show or hide the panel (sliders for time and parameters, quality, frame time).
    TogglePanel,
    /// Show or hide the scene's source beside the picture.
    ToggleEditor,
    /// Save the current view (camera, time, parameters) as a bookmark beside the scene.
    Bookmark,
    /// Start recording a flight, or end it and write it beside the scene (a `.fractal` and a glTF camera).
    RecordFlight,
    /// While recording a flight: a key at the current view now (besides the one a second).
    FlightKey,
    /// Render the current view at the still size (the panel's) to a PNG beside the scene.
    RenderStill,
    /// Max steps ×2 / ÷2 (recompiles the kernels).
    MoreSteps,
    FewerSteps,
    /// Hit epsilon ÷2 / ×2 (recompiles the kernels).
    FinerEpsilon,
    CoarserEpsilon,
}

impl Action {
    /// Whether the action lasts while its key is held (rather than happening once per press).
    pub fn is_held(self) -> bool {
        matches!(self, Action::Move(_) | Action::Sprint)
    }
}

/// The action of `key`; `shift` tells whether a Shift key is down (Shift+Tab selects the previous parameter).
pub fn binding(key: KeyCode, shift: bool) -> Option<Action> {
    use KeyCode::*;
    Some(match key {
        KeyW => Action::Move(Move::Forward),
        KeyS => Action::Move(Move::Back),
        KeyA => Action::Move(Move::Left),
        KeyD => Action::Move(Move::Right),
        KeyQ => Action::Move(Move::Down),
        KeyE => Action::Move(Move::Up),
        ShiftLeft | ShiftRight => Action::Sprint,
        Digit1 | Numpad1 => Action::CycleShadows,
        Digit2 | Numpad2 => Action::ToggleAmbientOcclusion,
        Digit3 | Numpad3 => Action::ToggleGlow,
        Digit4 | Numpad4 => Action::ToggleFog,
        Space => Action::TogglePause,
        ArrowRight => Action::TimeForward,
        ArrowLeft => Action::TimeBack,
        F12 | KeyK => Action::Screenshot,
        KeyP => Action::PrintPose,
        Tab if shift => Action::PreviousParam,
        Tab => Action::NextParam,
        ArrowUp => Action::IncreaseParam,
        ArrowDown => Action::DecreaseParam,
        Backspace => Action::ResetParam,
        Equal | NumpadAdd => Action::FasterMovement,
        Minus | NumpadSubtract => Action::SlowerMovement,
        BracketRight => Action::MoreSensitive,
        BracketLeft => Action::LessSensitive,
        KeyC => Action::FollowScenePath,
        Escape => Action::ReleaseOrQuit,
        KeyH | F1 => Action::Help,
        KeyO => Action::TogglePanel,
        F2 => Action::ToggleEditor,
        KeyB => Action::Bookmark,
        F9 => Action::RenderStill,
        KeyR => Action::RecordFlight,
        Enter | NumpadEnter => Action::FlightKey,
        Digit0 | Numpad0 => Action::MoreSteps,
        Digit9 | Numpad9 => Action::FewerSteps,
        Digit8 | Numpad8 => Action::FinerEpsilon,
        Digit7 | Numpad7 => Action::CoarserEpsilon,
        _ => return None,
    })
}

/// The controls, one line each.
pub const HELP: &str = "\
controls:
  left click        capture the mouse (look around); Esc releases it, Esc again quits
  W A S D / Q E     move forward, left, back, right / down, up (Shift: 4x faster)
  + / -             move speed x1.25 / /1.25      ] / [   mouse sensitivity x1.25 / /1.25
  mouse wheel       field of view                 C       back to the scene's camera path
  P                 print the camera pose (as a .fractal camera(..) line, a key(..) and a TOML [[key]])
  1 2 3 4           shadows none/hard/soft, ambient occlusion, glow, fog (recompiles the kernels)
  0 / 9, 8 / 7      max steps x2 / /2, hit epsilon /2 / x2 (recompiles the kernels)
  O                 show / hide the panel: time, quality, effects and a slider (or typed value) per param(..)
  F2                show / hide the scene's source: edits recompile when you pause, Ctrl+S saves
  B                 bookmark this view (camera, time, params) beside the scene; the panel restores it
  R                 record a flight / stop and write it beside the scene (a camera_path .fractal and a glTF);
                    a key a second, and Enter adds one where you are
  F9                render this view at the panel's still size to a PNG beside the scene
  Space             pause / resume time           <- / -> time -1 s / +1 s
  Tab / Shift+Tab   next / previous param(..)     Up / Down  change it (Shift: 5x)   Backspace  reset it
  F12 or K          save a PNG screenshot         H       this help
standing still (time paused, or nothing moving with it) refines the picture pass by pass, up to 256 passes";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_documented_key_is_bound() {
        let keys = [
            (KeyCode::KeyW, Action::Move(Move::Forward)),
            (KeyCode::KeyQ, Action::Move(Move::Down)),
            (KeyCode::KeyE, Action::Move(Move::Up)),
            (KeyCode::F12, Action::Screenshot),
            (KeyCode::KeyK, Action::Screenshot),
            (KeyCode::KeyP, Action::PrintPose),
            (KeyCode::Escape, Action::ReleaseOrQuit),
            (KeyCode::Digit1, Action::CycleShadows),
            (KeyCode::KeyO, Action::TogglePanel),
            (KeyCode::F2, Action::ToggleEditor),
            (KeyCode::KeyB, Action::Bookmark),
            (KeyCode::F9, Action::RenderStill),
            (KeyCode::KeyR, Action::RecordFlight),
            (KeyCode::Enter, Action::FlightKey),
            (KeyCode::Digit0, Action::MoreSteps),
            (KeyCode::Digit9, Action::FewerSteps),
            (KeyCode::Digit8, Action::FinerEpsilon),
            (KeyCode::Digit7, Action::CoarserEpsilon),
        ];
        for (key, action) in keys {
            assert_eq!(binding(key, false), Some(action), "{key:?}");
        }
        assert_eq!(binding(KeyCode::Tab, false), Some(Action::NextParam));
        assert_eq!(binding(KeyCode::Tab, true), Some(Action::PreviousParam));
        assert_eq!(binding(KeyCode::KeyZ, false), None);
        assert!(Action::Sprint.is_held() && !Action::Screenshot.is_held());
    }
}
