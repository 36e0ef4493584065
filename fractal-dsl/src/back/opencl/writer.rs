//! The OpenCL C writer: the OpenCL C [`Dialect`] of the shared GPU program ([`crate::back::kernel`]) — its
//! spellings, the `Frame` and `Sample` structs, and the `render` and `probe` kernel signatures — in f32 or, for
//! devices with `cl_khr_fp64`, in f64 ([`Scalar`]). Scene functions that read the frame take it as their last
//! argument.

use std::fmt::Write;

use crate::back::kernel::{self, Dialect, KernelDialect};
use crate::back::syntax::common_math_name;
use crate::back::{f32_literal, f64_literal, Entry, FrameLayout, Level, Pass, Scalar};
use crate::lower::code::{MathFn, Ty};
use crate::lower::trace::Function;
use crate::lower::Program;

/// OpenCL C computing in one number type.
struct OpenCl(Scalar);

/// Writes traced leaf functions in OpenCL C (a function library, without kernels).
pub fn functions(functions: &[Function]) -> String {
    kernel::write_functions(functions, &OpenCl(Scalar::F32))
}

/// Writes the complete OpenCL C program for `entry`, in f32.
pub fn write(program: &Program, entry: Entry) -> String {
    write_in(program, entry, Scalar::F32)
}

/// Writes the complete OpenCL C program for `entry`, computing in `scalar`. An f64 program enables `cl_khr_fp64`
/// and reads its frame in f64; its outputs (pixels, traces, probe results) are those of the f32 program.
pub fn write_in(program: &Program, entry: Entry, scalar: Scalar) -> String {
    kernel::write(program, entry, &OpenCl(scalar))
}

impl OpenCl {
    fn wide(&self) -> bool {
        self.0 == Scalar::F64
    }
}

impl Dialect for OpenCl {
    fn language(&self) -> &'static str {
        "OpenCL C"
    }
    fn sample_struct(&self) -> String {
        let mut out = "typedef struct {\n".to_string();
        for (name, ty) in crate::lower::code::SAMPLE_FIELDS {
            let _ = writeln!(out, "    {} {name};", self.type_name(ty));
        }
        out.push_str("} Sample;\n\n");
        out
    }

    fn type_name(&self, ty: Ty) -> &'static str {
        match (ty, self.wide()) {
            (Ty::F, false) => "float",
            (Ty::V3, false) => "float3",
            (Ty::Pair, false) => "float2",
            (Ty::F, true) => "double",
            (Ty::V3, true) => "double3",
            (Ty::Pair, true) => "double2",
            (Ty::Bool, _) => "int",
            (Ty::Int, _) => "uint",
            (Ty::Orbit, _) => "__constant const Frame*",
            (Ty::Sample, _) => "Sample",
        }
    }
    fn vec4_type(&self) -> &'static str {
        if self.wide() {
            "double4"
        } else {
            "float4"
        }
    }
    fn lit(&self, v: f64) -> String {
        match self.0 {
            Scalar::F32 => format!("{}f", f32_literal(v)),
            Scalar::F64 => f64_literal(v),
        }
    }
    fn bool_lit(&self, v: bool) -> &'static str {
        if v {
            "1"
        } else {
            "0"
        }
    }
    fn cast(&self, ty: &str, v: &str) -> String {
        format!("({ty}){v}")
    }
    fn construct(&self, ty: &str, components: &str) -> String {
        format!("({ty})({components})")
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        match f {
            MathFn::Abs => "fabs",
            MathFn::Min => "fmin",
            MathFn::Max => "fmax",
            MathFn::Ln => "log",
            _ => common_math_name(f),
        }
    }
    fn frame_field(&self, field: &str) -> String {
        format!("frame->{field}")
    }

    fn frame_parameter(&self) -> Option<&'static str> {
        Some("__constant const Frame*")
    }
    fn global_constant(&self, name: &str, ty: &str, value: &str) -> String {
        format!("__constant {ty} {name} = {value};")
    }
    fn to_f32x4(&self, v: &str) -> String {
        match self.0 {
            Scalar::F32 => v.to_string(),
            Scalar::F64 => format!("convert_float4({v})"),
        }
    }
    fn read_f32x3(&self, v: &str) -> String {
        match self.0 {
            Scalar::F32 => v.to_string(),
            Scalar::F64 => format!("convert_double3({v})"),
        }
    }
}

impl KernelDialect for OpenCl {
    fn declarations(&self, out: &mut String, layout: FrameLayout, _entry: Entry, _refine: bool) {
        if self.wide() {
            out.push_str("#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n\n");
        }
        let slot = self.vec4_type();
        out.push_str("typedef struct {\n");
        for field in FrameLayout::CAMERA_FIELDS {
            let _ = writeln!(out, "    {slot} {field};");
        }
        let _ = writeln!(out, "    {slot} lights[{}];", 2 * layout.lights);
        if layout.params > 0 {
            let _ = writeln!(out, "    {slot} params[{}];", layout.param_slots());
        }
        if layout.orbit > 0 {
            let _ = writeln!(out, "    {slot} reference;");
            let _ = writeln!(out, "    {slot} orbit[{}];", layout.orbit_slots());
        }
        out.push_str("} Frame;\n\n");
        out.push_str(&self.sample_struct());
    }
    fn render_open(&self, out: &mut String, entry: Entry, pass: Pass) -> [&'static str; 2] {
        let traces = if entry == Entry::Trace { ", __global float4* traces" } else { "" };
        let first = if pass == Pass::Refine { ", __global const uint* first" } else { "" };
        let _ = writeln!(
            out,
            "__kernel void {}(__global uint* out, __constant const Frame* frame{traces}{first}) {{",
            entry.entry_point(pass)
        );
        for (axis, name) in ["x", "y"].into_iter().enumerate() {
            let _ = writeln!(out, "{}const int {name} = (int)get_global_id({axis});", Level(1));
        }
        ["x", "y"]
    }
    fn pixel_index_type(&self) -> &'static str {
        "int"
    }
    fn clamp_index(&self, i: &str, step: i32, size: &str) -> String {
        if step < 0 {
            format!("max({i} - 1, 0)")
        } else {
            format!("min({i} + 1, {size} - 1)")
        }
    }
    fn first_shown(&self, index: &str) -> String {
        let word = format!("first[{index}]");
        let bytes = format!("(uint3)({word} & 255u, ({word} >> 8) & 255u, ({word} >> 16) & 255u)");
        format!("convert_{}({bytes}) / {}", self.type_name(Ty::V3), self.lit(255.0))
    }
    fn pack_pixel(&self) -> &'static [&'static str] {
        &[
            "const uint r = (uint)(col.x * 255.0f + 0.5f);",
            "const uint g = (uint)(col.y * 255.0f + 0.5f);",
            "const uint b = (uint)(col.z * 255.0f + 0.5f);",
            "out[y * w + x] = r | (g << 8) | (b << 16) | (255u << 24);",
        ]
    }
    fn probe_open(&self, out: &mut String) -> &'static str {
        out.push_str(
            "__kernel void probe(__global const float4* points, __global float4* out, __constant const Frame* frame, uint n) {\n",
        );
        let _ = writeln!(out, "{}const uint i = (uint)get_global_id(0);", Level(1));
        "n"
    }
    fn probe_output(&self) -> &'static str {
        "out"
    }
}
