//! The number type a frame is drawn in, the `--precision` choice, and the figures and limits of the rule that picks
//! it from the view ([`crate::choose_precision`]). f64 runs on the CPU renderer and on GPU devices with f64 (OpenCL
//! `cl_khr_fp64`, wgpu `SHADER_F64`: the f64 kernels); a device without refuses a job in f64
//! ([`crate::renderer::Renderer::draws_in`]); double-single kernels are not built yet.

use std::fmt;
use std::str::FromStr;

/// The number type of a render.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Precision {
    /// Single precision: every backend.
    #[default]
    F32,
    /// Double precision: the CPU renderer, and the GPU backends where the device has f64.
    F64,
}

impl fmt::Display for Precision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Precision::F32 => "f32",
            Precision::F64 => "f64",
        })
    }
}

/// The `--precision` choice.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum PrecisionChoice {
    /// Per frame, by [`crate::choose_precision::choose`].
    #[default]
    Auto,
    Only(Precision),
}

/// A precision name that is none of `auto`, `f32`, `f64`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown precision `{0}`: expected auto, f32 or f64 (double-single, df64, is not built yet)")]
pub struct UnknownPrecision(pub String);

impl FromStr for PrecisionChoice {
    type Err = UnknownPrecision;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "auto" => Ok(PrecisionChoice::Auto),
            "f32" => Ok(PrecisionChoice::Only(Precision::F32)),
            "f64" => Ok(PrecisionChoice::Only(Precision::F64)),
            _ => Err(UnknownPrecision(s.to_string())),
        }
    }
}

impl fmt::Display for PrecisionChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PrecisionChoice::Auto => f.write_str("auto"),
            PrecisionChoice::Only(p) => p.fmt(f),
        }
    }
}

/// Rays per side of the probe grid, across the whole frame.
pub const PROBE: (u32, u32) = (16, 9);
/// The share of the probe's hits whose figures must stay within the limits (one stray hit on a fractal's crease does
/// not decide a frame; a tenth of them does).
pub const QUANTILE: f64 = 0.9;

/// How far f32 may fall from f64 at a hit for a frame to be drawn in f32.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// The f32 distance's difference from f64's, in hit epsilons.
    pub distance: f64,
    /// The angle between the f32 and f64 normals, in degrees (the accuracy budget allows 5° at its p99).
    pub normal_degrees: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits { distance: 0.25, normal_degrees: 1.0 }
    }
}

/// What f32 does at the probe's hits against f64, at [`QUANTILE`] of them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Probe {
    /// Probe rays that hit.
    pub hits: usize,
    /// The f32 hit point's (and camera's) rounding, in footprints at the hit (reported, not judged).
    pub position: f64,
    /// The f32 distance's difference from f64's, in hit epsilons.
    pub distance: f64,
    /// The angle between the normals f32 and f64 compute there, in degrees.
    pub normal_degrees: f64,
}

/// The precision a frame is drawn in, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct Chosen {
    pub precision: Precision,
    /// `None` when the precision was given rather than chosen.
    pub probe: Option<Probe>,
    pub reason: String,
}

impl fmt::Display for Chosen {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.precision, self.reason)
    }
}
