//! The CPU dispatcher: the scene through [`CpuRenderer`], the baseline through its scalar Rust port; the kernel time
//! is the whole frame.

use std::time::Instant;

use fractal_render::backend::cpu::CpuRenderer;
use fractal_render::device::DeviceInfo;
use fractal_render::error::RenderError;
use fractal_render::renderer::Renderer;

use super::dispatch::{millis, KernelClock, Timed, Timer, Work};
use crate::bench::baseline;

pub(crate) struct CpuTimer {
    renderer: CpuRenderer,
}

impl CpuTimer {
    pub fn new() -> CpuTimer {
        CpuTimer { renderer: CpuRenderer::new() }
    }
}

impl Timer for CpuTimer {
    fn device(&self) -> DeviceInfo {
        self.renderer.device()
    }

    fn clock(&self) -> KernelClock {
        KernelClock::WholeFrame
    }

    fn computes_f64(&self) -> bool {
        true
    }

    fn run(&mut self, work: &Work) -> Result<Timed, RenderError> {
        let start = Instant::now();
        let image = match work {
            Work::Generated(job) => self.renderer.render(job)?,
            Work::Baseline { width, height } => baseline::render(*width, *height),
        };
        let ms = millis(start.elapsed());
        Ok(Timed { image, kernel_ms: ms, frame_ms: ms })
    }
}
