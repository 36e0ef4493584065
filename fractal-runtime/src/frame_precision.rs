//! `--precision`: the number type of each frame the commands that render and the viewer draw, chosen per frame by
//! the view ([`fractal_render::choose_precision`]) or given, and said once each time it changes. The view is probed
//! again only when the frame or the scene changes (a still view's passes, a resting viewer's redraws reuse it).

use fractal_dsl::eval::Evaluator;
use fractal_dsl::Scene;
use fractal_render::choose_precision::decide;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::precision::{Precision, PrecisionChoice};

/// The precision of each frame of one command or viewer, the last one it said, and the view it was chosen for.
#[derive(Clone, Debug)]
pub struct FramePrecision {
    choice: PrecisionChoice,
    /// Printed before each line it says (`fractal: NAME: `, or nothing).
    label: String,
    said: Option<Precision>,
    last: Option<(Frame, Scene, Precision)>,
}

impl FramePrecision {
    pub fn new(choice: PrecisionChoice, label: impl Into<String>) -> FramePrecision {
        FramePrecision { choice, label: label.into(), said: None, last: None }
    }

    /// The precision of `frame` of `scene` (whose CPU evaluators are `evaluator` and `wide`); the first frame's and
    /// each change are printed with the reason.
    pub fn of(
        &mut self,
        scene: &Scene,
        frame: &Frame,
        evaluator: &dyn Evaluator<f32>,
        wide: &dyn Evaluator<f64>,
    ) -> Result<Precision, RenderError> {
        if let Some((f, s, precision)) = &self.last {
            if f == frame && s == scene {
                return Ok(*precision);
            }
        }
        let chosen = decide(self.choice, scene, frame, evaluator, wide)?;
        if self.said != Some(chosen.precision) {
            eprintln!("{}precision {chosen}", self.label);
            self.said = Some(chosen.precision);
        }
        self.last = Some((frame.clone(), scene.clone(), chosen.precision));
        Ok(chosen.precision)
    }

    /// The precision said last (`None` before the first frame).
    pub fn said(&self) -> Option<Precision> {
        self.said
    }
}
