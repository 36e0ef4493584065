//! What a renderer runs on: the [`Backend`] families and the [`DeviceInfo`] a renderer reports for the device it got.
//!
//! Plain data at the bottom of the crate: errors name a backend, renderers describe their device, and nothing here
//! depends on any other module of the crate.

use std::fmt;

/// The environment variable that makes a missing GPU backend (and the tools its tests need) an error instead of a
/// skip: `cargo xtask test` sets it to `1`, so CI cannot pass by skipping what it was meant to run.
pub const REQUIRE_GPU_BACKENDS: &str = "FRACTAL_REQUIRE_GPU_BACKENDS";

/// Whether a backend that cannot be opened is an error rather than a skip ([`REQUIRE_GPU_BACKENDS`] is `1`).
pub fn backends_required() -> bool {
    std::env::var(REQUIRE_GPU_BACKENDS).is_ok_and(|v| v == "1")
}

/// The three renderer families.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Backend {
    /// WGSL through wgpu (Vulkan, Metal, DX12, GL; lavapipe without a GPU).
    Wgpu,
    /// OpenCL C through an OpenCL platform (a GPU driver, or pocl on a CPU).
    OpenCl,
    /// The scene's CPU evaluator, threaded with rayon.
    Cpu,
}

impl Backend {
    pub const ALL: [Backend; 3] = [Backend::Wgpu, Backend::OpenCl, Backend::Cpu];
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Backend::Wgpu => "wgpu",
            Backend::OpenCl => "opencl",
            Backend::Cpu => "cpu",
        }
    }
}

impl fmt::Display for Backend {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Which device a renderer got.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeviceInfo {
    pub backend: Backend,
    /// The API under the backend: "Vulkan", "Metal", "OpenCL 3.0 PoCL …", "rayon".
    pub api: String,
    /// Device name, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
    pub name: String,
    /// Driver name and version, as the driver reports them.
    pub driver: String,
    /// Device kind: "Cpu", "DiscreteGpu", "IntegratedGpu", …
    pub device_type: String,
}

impl fmt::Display for DeviceInfo {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} on {} ({}, {}), driver {}", self.backend, self.name, self.api, self.device_type, self.driver)
    }
}
