//! A frame of a view standing still: the next progressive pass (module `still` says when and why), drawn by whichever
//! renderer draws and shown through either presenter as a host image, or the picture shown already, again. The game
//! loop (`app.rs`) picks this over the usual frame.

use fractal_render::frame::Frame;
use fractal_render::image::Image;

use super::{App, DrawError, Presenter};
use crate::viewer::engine::Engine;
use crate::viewer::present::GpuFrameError;
use crate::viewer::still::Plan;

impl App {
    /// Draws `plan` (a pass, or a rest) of `frame`; the presented window when `screenshot` is set.
    pub(super) fn draw_still(
        &mut self,
        plan: Plan,
        frame: &Frame,
        window_size: (u32, u32),
        screenshot: bool,
    ) -> Result<Option<Image>, DrawError> {
        let picture = match plan {
            Plan::Pass => self.still.pass(self.engine.renderer(), &self.live, frame).map_err(DrawError::Render)?,
            Plan::Frame | Plan::Rest => None,
        };
        // After the pass, so the panel counts it.
        self.overlay = self.panel(window_size.0);
        let overlay = self.overlay.as_ref();
        match (&mut self.presenter, &mut self.engine) {
            (Some(Presenter::Gpu(gpu)), Engine::Wgpu(renderer)) => {
                let shown = match &picture {
                    Some(image) => gpu.show(renderer, image, window_size, screenshot, overlay),
                    None => gpu.redraw(renderer, window_size, screenshot, overlay),
                };
                shown.map_err(|e| match e {
                    GpuFrameError::Render(e) => DrawError::Render(e),
                    GpuFrameError::Surface(e) => DrawError::Present(e),
                })
            }
            (Some(Presenter::Soft(soft)), _) => {
                match &picture {
                    Some(image) => soft.present(image, window_size, overlay),
                    None => soft.redraw(window_size, overlay),
                }
                .map_err(DrawError::Present)?;
                Ok(if screenshot { soft.screenshot() } else { None })
            }
            (Some(Presenter::Gpu(_)), Engine::Other(_)) => {
                Err(DrawError::Present("the wgpu surface cannot show frames of this backend".to_string()))
            }
            (None, _) => Ok(None),
        }
    }
}
