//! Which renderer the viewer draws with. The wgpu renderer is kept as itself (not boxed as a [`Renderer`]) so its
//! device can also draw to the window's surface; `auto` moves down wgpu → OpenCL → CPU when a backend has no device
//! or fails, as [`fractal_render::select::AutoRenderer`] does.

use fractal_render::backend::wgpu::WgpuRenderer;
use fractal_render::device::{Backend, DeviceInfo};
use fractal_render::error::RenderError;
use fractal_render::renderer::Renderer;
use fractal_render::select::{self, BackendChoice, RendererOptions};

/// The renderer in use.
pub enum Engine {
    Wgpu(Box<WgpuRenderer>),
    Other(Box<dyn Renderer>),
}

impl Engine {
    pub fn device(&self) -> DeviceInfo {
        match self {
            Engine::Wgpu(r) => r.device(),
            Engine::Other(r) => r.device(),
        }
    }

    pub fn renderer(&mut self) -> &mut dyn Renderer {
        match self {
            Engine::Wgpu(r) => &mut **r,
            Engine::Other(r) => &mut **r,
        }
    }
}

/// Opens the chosen backend and keeps the backends `auto` may still fall back to.
pub struct EngineChain {
    options: RendererOptions,
    remaining: Vec<Backend>,
}

impl EngineChain {
    pub fn new(choice: BackendChoice, options: RendererOptions) -> EngineChain {
        let remaining = match choice {
            BackendChoice::Auto => Backend::ALL.to_vec(),
            BackendChoice::Only(backend) => vec![backend],
        };
        EngineChain { options, remaining }
    }

    /// Opens the next backend that has a device; `notes` says what was skipped and what was chosen.
    pub fn next(&mut self, notes: &mut Vec<String>) -> Result<Engine, RenderError> {
        let mut failures = Vec::new();
        while !self.remaining.is_empty() {
            let backend = self.remaining.remove(0);
            let opened = match backend {
                // Timestamps where the adapter has them: a viewer run without a window times its passes.
                Backend::Wgpu => WgpuRenderer::with_features(wgpu::Backends::all(), wgpu::Features::TIMESTAMP_QUERY)
                    .map(|r| Engine::Wgpu(Box::new(r))),
                other => select::open(other, &self.options).map(Engine::Other),
            };
            match opened {
                Ok(engine) => {
                    notes.push(format!("using {}", engine.device()));
                    return Ok(engine);
                }
                Err(e) => {
                    notes.push(format!("skipping {backend}: {e}"));
                    failures.push(format!("{backend}: {e}"));
                }
            }
        }
        if failures.is_empty() {
            failures.push("no backend is left to try".to_string());
        }
        Err(RenderError::AllBackendsFailed(failures))
    }

    pub fn has_more(&self) -> bool {
        !self.remaining.is_empty()
    }
}
