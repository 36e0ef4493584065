//! `--precision`: the number type of each frame the commands that render draw, chosen per frame by the view
//! ([`fractal_render::choose_precision`]) or given, and said once each time it changes.

use fractal_render::choose_precision::decide;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::precision::{Precision, PrecisionChoice};

use crate::cli::scene::LoadedScene;

/// The precision of each frame of one command, and the last one it said.
#[derive(Clone, Debug)]
pub struct FramePrecision {
    choice: PrecisionChoice,
    said: Option<Precision>,
}

impl FramePrecision {
    pub fn new(choice: PrecisionChoice) -> FramePrecision {
        FramePrecision { choice, said: None }
    }

    /// The precision of `frame` of `loaded`; the first frame's and each change are printed with the reason.
    pub fn of(&mut self, loaded: &LoadedScene, frame: &Frame) -> Result<Precision, RenderError> {
        let chosen = decide(self.choice, &loaded.scene, frame, loaded.evaluator(), loaded.evaluator_wide())?;
        if self.said != Some(chosen.precision) {
            eprintln!("fractal: {}: precision {chosen}", loaded.name);
            self.said = Some(chosen.precision);
        }
        Ok(chosen.precision)
    }
}
