//! A frame of a view standing still: the next progressive pass (module `still` says when and why), drawn by whichever
//! renderer draws and shown through either presenter as a host image, or the picture shown already, again. The game
//! loop (`app.rs`) picks this over the usual frame. A frame in f64 (`--precision`) is drawn here too, by the
//! engine's renderer where it computes in f64 (OpenCL `cl_khr_fp64`, wgpu `SHADER_F64`), else by the CPU renderer,
//! and shown the same way.

use fractal_render::backend::cpu::CpuRenderer;
use fractal_render::device::Backend;
use fractal_render::frame::Frame;
use fractal_render::image::Image;
use fractal_render::precision::Precision;
use fractal_render::renderer::{RenderJob, Renderer};

use super::{App, DrawError, Presenter};
use crate::viewer::engine::Engine;
use crate::viewer::present::GpuFrameError;
use crate::viewer::still::Plan;

impl App {
    /// Draws `plan` (a pass, or a rest) of `frame`; the presented window when `screenshot` is set.
    /// A frame in f64 takes its passes on the CPU where the engine does not compute in f64.
    pub(super) fn draw_still(
        &mut self,
        plan: Plan,
        (frame, precision): (&Frame, Precision),
        window_size: (u32, u32),
        screenshot: bool,
    ) -> Result<Option<Image>, DrawError> {
        let picture = match plan {
            Plan::Pass if self.engine_draws(frame, precision) => {
                self.still.pass(self.engine.renderer(), &self.live, (frame, precision)).map_err(DrawError::Render)?
            }
            Plan::Pass => {
                self.still.pass(&mut CpuRenderer::new(), &self.live, (frame, precision)).map_err(DrawError::Render)?
            }
            Plan::Frame | Plan::Rest => None,
        };
        self.show(picture.as_ref(), window_size, screenshot)
    }

    /// Whether the engine's renderer draws `frame` in `precision` (f32 always; f64 where it computes in it); noted
    /// for the panel when the precision is wider.
    fn engine_draws(&mut self, frame: &Frame, precision: Precision) -> bool {
        let job = RenderJob::new(self.live.kernels(), frame).with_precision(precision);
        let draws = self.engine.renderer().draws_in(&job);
        if precision != Precision::F32 {
            self.wide_backend = if draws { self.engine.device().backend } else { Backend::Cpu };
        }
        draws
    }

    /// Shows `picture` (a host image; `None`: the picture shown already, again) through either presenter, with the
    /// panel drawn anew.
    pub(super) fn show(
        &mut self,
        picture: Option<&Image>,
        window_size: (u32, u32),
        screenshot: bool,
    ) -> Result<Option<Image>, DrawError> {
        // After the pass, so the panel counts it.
        self.draw_ui(window_size);
        match (&mut self.presenter, &mut self.engine) {
            (Some(Presenter::Gpu(gpu)), Engine::Wgpu(renderer)) => {
                let ui = Some(self.ui.paint());
                let shown = match picture {
                    Some(image) => gpu.show(renderer, image, window_size, screenshot, ui),
                    None => gpu.redraw(renderer, window_size, screenshot, ui),
                };
                shown.map_err(|e| match e {
                    GpuFrameError::Render(e) => DrawError::Render(e),
                    GpuFrameError::Surface(e) => DrawError::Present(e),
                })
            }
            (Some(Presenter::Soft(soft)), _) => {
                let overlay = self.ui.overlay();
                let overlay = overlay.as_ref();
                match picture {
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

    /// The precision of `frame` (`--precision`: given, or the one the view asks for), said on stderr when it changes;
    /// f32 with a report where the view cannot be probed.
    pub(super) fn frame_precision(&mut self, frame: &Frame) -> Precision {
        let live = &self.live;
        match self.precision.of(&live.scene, frame, live.evaluator(), live.evaluator_wide()) {
            Ok(precision) => precision,
            Err(e) => {
                self.report(format!("cannot choose this frame's precision, drawing it in f32: {e}"));
                Precision::F32
            }
        }
    }

    /// Draws `frame` in f64 (with the engine's renderer where it computes in f64, else on the CPU) and shows it.
    pub(super) fn draw_wide(
        &mut self,
        frame: &Frame,
        window_size: (u32, u32),
        screenshot: bool,
    ) -> Result<Option<Image>, DrawError> {
        let on_engine = self.engine_draws(frame, Precision::F64);
        let job = RenderJob::new(self.live.kernels(), frame).with_precision(Precision::F64);
        let image = match on_engine {
            true => self.engine.renderer().render(&job),
            false => CpuRenderer::new().render(&job),
        }
        .map_err(DrawError::Render)?;
        self.show(Some(&image), window_size, screenshot)
    }
}
