//! Choosing a backend: `wgpu`, `opencl`, `cpu`, or `auto`, which tries them in that order and falls back when a
//! backend has no device, is not built in, or refuses a kernel, noting each step so the caller can say which device
//! it got and why.

use std::fmt;
use std::str::FromStr;

use crate::backend::cpu::CpuRenderer;
use crate::backend::wgpu::WgpuRenderer;
use crate::device::{Backend, DeviceInfo};
use crate::error::RenderError;
use crate::image::Image;
use crate::renderer::{RenderJob, Renderer, Traced};

/// The `--backend` choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum BackendChoice {
    /// wgpu, then OpenCL (when built in), then CPU.
    #[default]
    Auto,
    Only(Backend),
}

/// A backend name that is none of `auto`, `wgpu`, `opencl`, `cpu`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown backend `{0}`: expected auto, wgpu, opencl or cpu")]
pub struct UnknownBackend(pub String);

impl FromStr for BackendChoice {
    type Err = UnknownBackend;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "auto" => Ok(BackendChoice::Auto),
            "wgpu" => Ok(BackendChoice::Only(Backend::Wgpu)),
            "opencl" => Ok(BackendChoice::Only(Backend::OpenCl)),
            "cpu" => Ok(BackendChoice::Only(Backend::Cpu)),
            _ => Err(UnknownBackend(s.to_string())),
        }
    }
}

impl fmt::Display for BackendChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BackendChoice::Auto => f.write_str("auto"),
            BackendChoice::Only(b) => b.fmt(f),
        }
    }
}

/// Settings that apply to whichever backend is opened.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RendererOptions {
    /// OpenCL: build without `-cl-fast-relaxed-math`.
    pub precise: bool,
}

/// Whether this build includes the OpenCL backend (cargo feature `opencl`).
pub const OPENCL_BUILT: bool = cfg!(feature = "opencl");

/// Opens a renderer of one backend.
pub fn open(backend: Backend, options: &RendererOptions) -> Result<Box<dyn Renderer>, RenderError> {
    match backend {
        Backend::Wgpu => Ok(Box::new(WgpuRenderer::new()?)),
        Backend::OpenCl => open_opencl(options),
        Backend::Cpu => Ok(Box::new(CpuRenderer::new())),
    }
}

#[cfg(feature = "opencl")]
fn open_opencl(options: &RendererOptions) -> Result<Box<dyn Renderer>, RenderError> {
    Ok(Box::new(crate::backend::opencl::OpenClRenderer::new(options.precise)?))
}

#[cfg(not(feature = "opencl"))]
fn open_opencl(_options: &RendererOptions) -> Result<Box<dyn Renderer>, RenderError> {
    Err(RenderError::NotBuilt { backend: Backend::OpenCl, hint: "rebuild with `--features opencl`" })
}

/// Opens the chosen backend; `auto` gives an [`AutoRenderer`]. Ask the result's [`Renderer::device`] which device it
/// got and [`Renderer::take_notes`] what was skipped.
pub fn select(choice: BackendChoice, options: &RendererOptions) -> Result<Box<dyn Renderer>, RenderError> {
    match choice {
        BackendChoice::Auto => Ok(Box::new(AutoRenderer::new(options)?)),
        BackendChoice::Only(backend) => open(backend, options),
    }
}

/// A renderer that moves down the chain wgpu → OpenCL → CPU whenever the current backend cannot draw a job (no device,
/// kernel rejected, image too large, no kernel for it), and stays on the backend that worked.
pub struct AutoRenderer {
    options: RendererOptions,
    current: Box<dyn Renderer>,
    remaining: Vec<Backend>,
    notes: Vec<String>,
    /// Whether a frame drawn on the CPU for its precision was noted already.
    wide_noted: bool,
}

impl AutoRenderer {
    pub fn new(options: &RendererOptions) -> Result<AutoRenderer, RenderError> {
        let mut remaining = Backend::ALL.to_vec();
        let mut notes = Vec::new();
        let mut failures = Vec::new();
        let current = next_renderer(&mut remaining, options, &mut notes, &mut failures)
            .ok_or(RenderError::AllBackendsFailed(failures))?;
        Ok(AutoRenderer { options: *options, current, remaining, notes, wide_noted: false })
    }

    /// The backends not yet tried, in the order they would be.
    pub fn remaining(&self) -> &[Backend] {
        &self.remaining
    }
}

/// Opens the first backend of `remaining` that has a device, removing every one tried.
fn next_renderer(
    remaining: &mut Vec<Backend>,
    options: &RendererOptions,
    notes: &mut Vec<String>,
    failures: &mut Vec<String>,
) -> Option<Box<dyn Renderer>> {
    while !remaining.is_empty() {
        let backend = remaining.remove(0);
        match open(backend, options) {
            Ok(renderer) => {
                notes.push(format!("using {}", renderer.device()));
                return Some(renderer);
            }
            Err(e) => {
                notes.push(format!("skipping {backend}: {e}"));
                failures.push(format!("{backend}: {e}"));
            }
        }
    }
    None
}

impl AutoRenderer {
    /// Whether `job` asks for a precision the current backend does not draw in ([`Renderer::draws_in`]): such a
    /// frame is drawn on the CPU, and the frames after it go back to the current backend (the first such frame's
    /// note says so).
    fn wider_than_current(&mut self, job: &RenderJob) -> bool {
        let wider = !self.current.draws_in(job);
        // Said once, not for every frame of a sequence.
        if wider && !self.wide_noted {
            self.wide_noted = true;
            let device = self.current.device();
            self.notes.push(format!(
                "a frame in {} drawn on the CPU: {} ({}) does not compute in it",
                job.precision, device.name, device.backend
            ));
        }
        wider
    }

    /// Runs `draw` on the current backend, moving to the next one while the failure is the backend's.
    fn with_fallback<T>(
        &mut self,
        mut draw: impl FnMut(&mut dyn Renderer) -> Result<T, RenderError>,
    ) -> Result<T, RenderError> {
        let mut failures = Vec::new();
        loop {
            match draw(self.current.as_mut()) {
                Ok(drawn) => return Ok(drawn),
                Err(e) if e.is_backend_specific() => {
                    let backend = self.current.device().backend;
                    self.notes.push(format!("{backend} failed, falling back: {e}"));
                    failures.push(format!("{backend}: {e}"));
                    match next_renderer(&mut self.remaining, &self.options, &mut self.notes, &mut failures) {
                        Some(next) => self.current = next,
                        None => return Err(RenderError::AllBackendsFailed(failures)),
                    }
                }
                Err(e) => return Err(e),
            }
        }
    }
}

impl Renderer for AutoRenderer {
    fn render(&mut self, job: &RenderJob) -> Result<Image, RenderError> {
        match self.wider_than_current(job) {
            true => CpuRenderer::new().render(job),
            false => self.with_fallback(|r| r.render(job)),
        }
    }

    /// The current backend's batch where it draws every job; from a frame it failed on, frame by frame with the
    /// fallback of [`Renderer::render`].
    fn render_batch(&mut self, jobs: &[RenderJob]) -> Vec<Result<Image, RenderError>> {
        let mut drawn = Vec::with_capacity(jobs.len());
        if jobs.iter().all(|job| self.current.draws_in(job)) {
            drawn = self.current.render_batch(jobs);
            if let Some(failed) = drawn.iter().position(|d| d.as_ref().is_err_and(RenderError::is_backend_specific)) {
                drawn.truncate(failed);
            }
        }
        let rest = &jobs[drawn.len()..];
        drawn.extend(rest.iter().map(|job| self.render(job)).collect::<Vec<_>>());
        drawn
    }

    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError> {
        match self.wider_than_current(job) {
            true => CpuRenderer::new().trace(job),
            false => self.with_fallback(|r| r.trace(job)),
        }
    }

    fn device(&self) -> DeviceInfo {
        self.current.device()
    }

    fn draws_in(&self, job: &RenderJob) -> bool {
        self.current.draws_in(job) || job.kernels.cpu.is_some_and(|cpu| cpu.wide.is_some())
    }

    fn take_notes(&mut self) -> Vec<String> {
        let mut notes = std::mem::take(&mut self.notes);
        notes.extend(self.current.take_notes());
        notes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backend_names_parse() {
        assert_eq!("auto".parse(), Ok(BackendChoice::Auto));
        assert_eq!("WGPU".parse(), Ok(BackendChoice::Only(Backend::Wgpu)));
        assert_eq!("opencl".parse(), Ok(BackendChoice::Only(Backend::OpenCl)));
        assert_eq!("cpu".parse(), Ok(BackendChoice::Only(Backend::Cpu)));
        let err = "vulkan".parse::<BackendChoice>().unwrap_err();
        assert_eq!(err.to_string(), "unknown backend `vulkan`: expected auto, wgpu, opencl or cpu");
        for choice in [BackendChoice::Auto, BackendChoice::Only(Backend::OpenCl)] {
            assert_eq!(choice.to_string().parse(), Ok(choice));
        }
    }

    #[cfg(not(feature = "opencl"))]
    #[test]
    fn opencl_says_how_to_get_it() {
        let err = open(Backend::OpenCl, &RendererOptions::default()).err().expect("not built");
        assert!(err.to_string().contains("--features opencl"), "{err}");
    }
}
