//! Code writers, one module per target language, all of the same shape (naga's `back/` is the model):
//! `back/<lang>/writer.rs` spells the lowered program ([`crate::lower`]) — the traced leaf functions and the scene
//! functions alike; no formula is written here. What is shared lives here and in sibling modules: the uniform layout
//! both GPU languages read, indentation and number formatting (this file); the statement walker over lowered bodies
//! ([`syntax`]); the whole GPU program — function framing, normal, ambient occlusion, shadows and the `render` /
//! `probe` kernels, or the same functions as a library for other engines — written once against a per-language
//! [`kernel::Dialect`], which is all the OpenCL C, WGSL, GLSL and HLSL writers implement ([`kernel`]). The kernels
//! spell the ray program of [`crate::ray`] (the CPU renderer runs it natively); its constants live there.

pub mod glsl;
pub mod hlsl;
pub mod kernel;
pub mod opencl;
pub mod rust;
pub mod syntax;
pub mod wgsl;

use std::fmt;

use crate::lower::Program;

/// Indentation level; `Display` writes four spaces per level (naga's `back::Level`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Level(pub usize);

impl Level {
    pub fn next(self) -> Level {
        Level(self.0 + 1)
    }
}

impl fmt::Display for Level {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        (0..self.0).try_for_each(|_| f.write_str("    "))
    }
}

/// Formats a constant as the shortest decimal that reads back as the same f32, with a decimal point or exponent so
/// every language takes it as floating point: the literals of an f32 kernel, exact for it.
pub fn f32_literal(v: f64) -> String {
    let v = v as f32;
    // Validation rejects non-finite constants; a clear marker beats a silently wrong kernel.
    decimal(format!("{v:?}"), v.is_finite())
}

/// Formats a constant as the shortest decimal that reads back as the same f64, with a decimal point or exponent: the
/// literals of an f64 kernel ([`Scalar::F64`]).
pub fn f64_literal(v: f64) -> String {
    decimal(format!("{v:?}"), v.is_finite())
}

/// A float's shortest decimal (Rust's `{:?}`) with a decimal point or exponent, so every language takes it as
/// floating point.
fn decimal(s: String, finite: bool) -> String {
    if !finite {
        "(0.0 /* non-finite constant */)".to_string()
    } else if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

/// The number type a GPU kernel computes in. Every kernel has an f32 form; OpenCL also writes an f64 form for devices
/// with `cl_khr_fp64`, drawn where the view needs more than f32 (the runtime's precision choice). An f64 kernel reads
/// the same [`FrameLayout`] slots in f64: the host fills them from the same values, the camera position to the
/// precision the host keeps it (an f32 frame holds it rounded to f32).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Scalar {
    #[default]
    F32,
    F64,
}

impl Scalar {
    /// The bytes of one frame slot (four numbers).
    pub fn slot_bytes(self) -> usize {
        match self {
            Scalar::F32 => 16,
            Scalar::F64 => 32,
        }
    }
}

/// The uniform block both GPU languages read, as float4 slots (16 bytes each), in this order:
///
/// | slot | xyz | w |
/// |---|---|---|
/// | 0 | camera position | time in seconds |
/// | 1 | camera right · tan(fov/2) | image width in pixels |
/// | 2 | camera up · tan(fov/2) | image height in pixels |
/// | 3 | camera forward (unit) | pixel footprint per unit distance: 2·tan(fov/2)/height |
/// | 4 + 2i | light i: direction towards the light (directional, unit) or position (point) | 0 directional, 1 point |
/// | 5 + 2i | light i: colour · intensity | unused |
/// | 4 + 2L + j/4 | `params[j]` in component j % 4 | |
/// | R = 4 + 2L + ⌈P/4⌉ | `reference`: x = index of the reference orbit's last entry (only with an orbit) | |
/// | R + 1 + i/2 | `orbit[i / 2]`: entry i of the reference orbit in xy (even i) or zw (odd i) | |
///
/// Pixel (x, y) looks along forward + u·right + v·up with u = (2(x + 0.5) − w)/h and v = −(2(y + 0.5) − h)/h.
/// The reference orbit ([`crate::formula::mandelbrot`](mod@crate::formula::mandelbrot)) is that of the camera
/// position's pattern coordinates; the sample function reads the hit point relative to the camera, rd·t.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameLayout {
    pub lights: usize,
    pub params: usize,
    /// Entries of the reference orbit the frame holds (0: none, and no `reference` slot).
    pub orbit: usize,
}

impl FrameLayout {
    /// The camera's slots, in order: its position (relative to the anchor; w: the time), right, up and forward axes
    /// (w: width, height, footprint) and the anchor ([`crate::ray::View`]).
    pub const CAMERA_FIELDS: [&'static str; 5] = ["origin", "right", "up", "forward", "anchor"];
    pub const CAMERA_SLOTS: usize = Self::CAMERA_FIELDS.len();
    pub fn light_slot(&self, i: usize) -> usize {
        Self::CAMERA_SLOTS + 2 * i
    }
    pub fn params_slot(&self) -> usize {
        Self::CAMERA_SLOTS + 2 * self.lights
    }
    /// Number of float4 slots holding params.
    pub fn param_slots(&self) -> usize {
        self.params.div_ceil(4)
    }
    /// The `reference` slot (meaningful only when the frame holds an orbit).
    pub fn reference_slot(&self) -> usize {
        self.params_slot() + self.param_slots()
    }
    /// The slot of orbit entries 2k and 2k + 1.
    pub fn orbit_slot(&self, k: usize) -> usize {
        self.reference_slot() + 1 + k
    }
    /// Number of float4 slots holding the orbit.
    pub fn orbit_slots(&self) -> usize {
        self.orbit.div_ceil(2)
    }
    pub fn slots(&self) -> usize {
        self.reference_slot() + if self.orbit > 0 { 1 + self.orbit_slots() } else { 0 }
    }
    pub fn bytes(&self) -> usize {
        self.slots() * 16
    }
}

/// Which kernel a writer produces for a scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Entry {
    /// `render`: one invocation per pixel, packed RGBA8 (R in the low byte) into `out[y·w + x]`.
    /// OpenCL: `__kernel void render(__global uint* out, __constant Frame* frame)`, global size ≥ (w, h).
    /// WGSL: `@compute @workgroup_size(8, 8, 1) fn render`, binding 0 = `array<u32>` (read_write storage),
    /// binding 1 = the frame uniform.
    Render,
    /// `probe`: evaluates the scene at points, for agreement tests. Input point i is `points[i].xyz`; output
    /// `out[2i] = (distance, ambient, diffuse, specular)`, `out[2i + 1] = (albedo.rgb, shininess)`.
    /// OpenCL: `__kernel void probe(__global const float4* points, __global float4* out, __constant Frame* frame,
    /// uint n)`. WGSL: `@compute @workgroup_size(64) fn probe`, binding 0 = out `array<vec4<f32>>`, binding 1 = frame,
    /// binding 2 = points `array<vec4<f32>>` (read-only storage); n = arrayLength(points).
    Probe,
    /// `trace`: the `render` kernel that also writes what its march did at each pixel, for measuring a GPU's render
    /// against the ground truth and for depth and normal images. Pixel i = y·w + x writes, beside `out[i]`,
    /// `traces[3i] = (normal, t)` (the normal 0 at a miss; t where the march stopped), `traces[3i + 1] = (steps,
    /// hit, out of steps, 0)` (the flags 1 or 0) and `traces[3i + 2] = (colour, 0)`, the linear colour before
    /// clamping and gamma. OpenCL: `__kernel void trace(__global uint* out, __constant Frame* frame, __global float4*
    /// traces)`. WGSL: `@compute @workgroup_size(8, 8, 1) fn trace`, the render kernel's bindings and binding 2 =
    /// `traces`, `array<vec4<f32>>` (read_write storage).
    Trace,
}

/// The passes of a `render` or `trace` kernel. A scene that takes one sample a pixel draws in the first; one that
/// takes more has a second entry point, `refine`, which reads the first pass's pixels (binding 3 in WGSL, a
/// `__global const uint* first` argument after the others in OpenCL), adds samples where a pixel needs them
/// ([`crate::ray::pixel::refine`]) and writes every pixel's final value to the entry's own outputs (binding 0 or
/// `out`; a trace kernel also the samples and colour words of the pixels it refined).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    First,
    Refine,
}

/// The line a kernel writes before its `refine` entry point ([`has_refine`]).
pub const REFINE_MARK: &str = "// The second pass: more samples where the first pass's neighbours differ.";

/// Whether a `render` or `trace` kernel has the second pass ([`Pass::Refine`]), i.e. its scene takes more than one
/// sample a pixel.
pub fn has_refine(source: &str) -> bool {
    source.contains(REFINE_MARK)
}

impl Entry {
    /// The name of the entry point of `pass` in a kernel for this entry, in both GPU languages.
    pub fn entry_point(self, pass: Pass) -> &'static str {
        match pass {
            Pass::First => self.name(),
            Pass::Refine => "refine",
        }
    }

    /// The entry point's name in both GPU languages.
    pub fn name(self) -> &'static str {
        match self {
            Entry::Render => "render",
            Entry::Probe => "probe",
            Entry::Trace => "trace",
        }
    }
}

impl Program {
    pub fn layout(&self) -> FrameLayout {
        FrameLayout {
            lights: self.lights.len(),
            params: self.params.len(),
            orbit: self.reference.map_or(0, |r| r.entries()),
        }
    }
}
