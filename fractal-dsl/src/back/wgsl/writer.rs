//! The WGSL writer: the WGSL [`Dialect`] of the shared GPU program ([`crate::back::kernel`]) — its spellings, the
//! `Frame` and `Sample` structs, the bindings of each entry point, and the `render` and `probe` entry signatures — in
//! f32 or, for devices with `SHADER_F64`, in f64 ([`Scalar`]), where the elementary functions Vulkan leaves undefined
//! in f64 are the traced ones of [`crate::lower::portable`]. Every function reads the frame as the module-scope
//! uniform `frame`.

use std::fmt::Write;

use crate::back::kernel::{self, Dialect, KernelDialect};
use crate::back::syntax::{common_math_name, Prec};
use crate::back::{f32_literal, f64_literal, Entry, FrameLayout, Level, Pass, Scalar};
use crate::lower::code::{MathFn, Ty, SAMPLE_FIELDS};
use crate::lower::portable;
use crate::lower::trace::Function;
use crate::lower::Program;

/// WGSL computing in one number type.
struct Wgsl(Scalar);

/// Writes traced leaf functions in WGSL (a function library, without kernels).
pub fn functions(functions: &[Function]) -> String {
    kernel::write_functions(functions, &Wgsl(Scalar::F32))
}

/// Writes `program` as a function library ([`kernel::write_library`]).
pub fn library(program: &Program, lib: &kernel::Library) -> String {
    kernel::write_library(program, lib, &Wgsl(Scalar::F32))
}

/// Writes the complete WGSL module for `entry`, in f32.
pub fn write(program: &Program, entry: Entry) -> String {
    write_in(program, entry, Scalar::F32)
}

/// Writes the complete WGSL module for `entry`, computing in `scalar`. An f64 module needs the device feature
/// `SHADER_F64` and reads its frame in f64; its outputs (pixels, traces, probe results) are those of the f32 module.
pub fn write_in(program: &Program, entry: Entry, scalar: Scalar) -> String {
    kernel::write(program, entry, &Wgsl(scalar))
}

impl Wgsl {
    fn wide(&self) -> bool {
        self.0 == Scalar::F64
    }
}

impl Dialect for Wgsl {
    fn language(&self) -> &'static str {
        "WGSL"
    }
    fn sample_struct(&self) -> String {
        let mut out = "struct Sample {\n".to_string();
        for (name, ty) in SAMPLE_FIELDS {
            let _ = writeln!(out, "    {name}: {},", self.type_name(ty));
        }
        out.push_str("}\n\n");
        out
    }

    fn type_name(&self, ty: Ty) -> &'static str {
        match (ty, self.wide()) {
            (Ty::F, false) => "f32",
            (Ty::V3, false) => "vec3<f32>",
            (Ty::Pair, false) => "vec2<f32>",
            (Ty::F, true) => "f64",
            (Ty::V3, true) => "vec3<f64>",
            (Ty::Pair, true) => "vec2<f64>",
            (Ty::Bool, _) => "bool",
            (Ty::Int, _) => "u32",
            // Never declared: WGSL functions read the orbit from the module's `frame`.
            (Ty::Orbit, _) => "Frame",
            (Ty::Sample, _) => "Sample",
        }
    }
    fn vec4_type(&self) -> &'static str {
        if self.wide() {
            "vec4<f64>"
        } else {
            "vec4<f32>"
        }
    }
    fn lit(&self, v: f64) -> String {
        match self.0 {
            Scalar::F32 => f32_literal(v),
            Scalar::F64 => format!("{}lf", f64_literal(v)),
        }
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        match f {
            MathFn::Ln => "log",
            _ => common_math_name(f),
        }
    }
    fn math_call(&self, f: MathFn, args: &[String]) -> String {
        if self.wide() && !portable::exact_in_f64(f) {
            return format!("{}({})", portable::name(f), args.join(", "));
        }
        match f {
            // Vulkan drivers' acos loses most of its precision near ±1 (lavapipe: ~1e-4 radians at the Mandelbulb's
            // pole), where atan2 of the same angle's sine and cosine keeps full precision.
            MathFn::Acos => format!("atan2(sqrt(1.0 - {x} * {x}), {x})", x = args[0]),
            _ => format!("{}({})", self.math_name(f), args.join(", ")),
        }
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        format!("select({if_false}, {if_true}, {cond})")
    }
    fn select_prec(&self) -> Prec {
        Prec::Atom
    }

    fn declare(&self, name: &str, ty: &str, value: &str, mutable: bool) -> String {
        let kw = if mutable { "var" } else { "let" };
        format!("{kw} {name}: {ty} = {value};")
    }
    fn local(&self, name: &str, _ty: &str, value: &str, mutable: bool) -> String {
        let kw = if mutable { "var" } else { "let" };
        format!("{kw} {name} = {value};")
    }
    fn counted_loop_over(&self, index: &str, count: &str) -> String {
        format!("for (var {index} = 0u; {index} < {count}; {index}++) {{")
    }

    fn function_open(&self, ret: &str, name: &str, params: &[(&str, &str)]) -> String {
        let params: Vec<String> = params.iter().map(|(name, ty)| format!("{name}: {ty}")).collect();
        format!("fn {name}({}) -> {ret} {{", params.join(", "))
    }
    fn sample_return(&self, fields: &[(&str, String)]) -> Vec<String> {
        let values: Vec<&str> = fields.iter().map(|(_, value)| value.as_str()).collect();
        vec![format!("return Sample({});", values.join(", "))]
    }
    fn global_constant(&self, name: &str, ty: &str, value: &str) -> String {
        format!("const {name}: {ty} = {value};")
    }
    fn portable_math(&self) -> bool {
        self.wide()
    }
    fn to_f32x4(&self, v: &str) -> String {
        match self.0 {
            Scalar::F32 => v.to_string(),
            Scalar::F64 => format!("vec4<f32>({v})"),
        }
    }
    fn read_f32x3(&self, v: &str) -> String {
        match self.0 {
            Scalar::F32 => v.to_string(),
            Scalar::F64 => format!("vec3<f64>({v})"),
        }
    }
    fn to_f32(&self, v: &str) -> String {
        match self.0 {
            Scalar::F32 => v.to_string(),
            Scalar::F64 => format!("f32({v})"),
        }
    }
}

impl KernelDialect for Wgsl {
    fn declarations(&self, out: &mut String, layout: FrameLayout, entry: Entry, refine: bool) {
        let slot = self.vec4_type();
        out.push_str("struct Frame {\n");
        for field in FrameLayout::CAMERA_FIELDS {
            let _ = writeln!(out, "    {field}: {slot},");
        }
        let _ = writeln!(out, "    lights: array<{slot}, {}>,", 2 * layout.lights);
        if layout.params > 0 {
            let _ = writeln!(out, "    params: array<{slot}, {}>,", layout.param_slots());
        }
        if layout.orbit > 0 {
            let _ = writeln!(out, "    reference: {slot},");
            let _ = writeln!(out, "    orbit: array<{slot}, {}>,", layout.orbit_slots());
        }
        out.push_str("}\n\n");
        out.push_str(&self.sample_struct());
        match entry {
            Entry::Render => {
                out.push_str("@group(0) @binding(0) var<storage, read_write> out_px: array<u32>;\n");
                out.push_str("@group(0) @binding(1) var<uniform> frame: Frame;\n\n");
            }
            Entry::Trace => {
                out.push_str("@group(0) @binding(0) var<storage, read_write> out_px: array<u32>;\n");
                out.push_str("@group(0) @binding(1) var<uniform> frame: Frame;\n");
                out.push_str("@group(0) @binding(2) var<storage, read_write> traces: array<vec4<f32>>;\n\n");
            }
            Entry::Probe => {
                out.push_str("@group(0) @binding(0) var<storage, read_write> probe_out: array<vec4<f32>>;\n");
                out.push_str("@group(0) @binding(1) var<uniform> frame: Frame;\n");
                out.push_str("@group(0) @binding(2) var<storage, read> points: array<vec4<f32>>;\n\n");
            }
        }
        if refine {
            out.push_str("// The first pass's pixels, which the second pass reads.\n");
            out.push_str("@group(0) @binding(3) var<storage, read> first_px: array<u32>;\n\n");
        }
    }
    fn render_open(&self, out: &mut String, entry: Entry, pass: Pass) -> [&'static str; 2] {
        out.push_str("@compute @workgroup_size(8, 8, 1)\n");
        let _ = writeln!(out, "fn {}(@builtin(global_invocation_id) gid: vec3<u32>) {{", entry.entry_point(pass));
        ["gid.x", "gid.y"]
    }
    fn pixel_index_type(&self) -> &'static str {
        "u32"
    }
    fn clamp_index(&self, i: &str, step: i32, size: &str) -> String {
        if step < 0 {
            format!("max({i}, 1u) - 1u")
        } else {
            format!("min({i} + 1u, {size} - 1u)")
        }
    }
    fn first_shown(&self, index: &str) -> String {
        let shown = format!("unpack4x8unorm(first_px[{index}]).xyz");
        match self.0 {
            Scalar::F32 => shown,
            Scalar::F64 => format!("vec3<f64>({shown})"),
        }
    }
    fn pack_pixel(&self) -> &'static [&'static str] {
        &[
            "let c = vec3<u32>(col * 255.0 + 0.5);",
            "out_px[gid.y * w + gid.x] = c.x | (c.y << 8u) | (c.z << 16u) | (255u << 24u);",
        ]
    }
    fn probe_open(&self, out: &mut String) -> &'static str {
        out.push_str("@compute @workgroup_size(64, 1, 1)\n");
        out.push_str("fn probe(@builtin(global_invocation_id) gid: vec3<u32>) {\n");
        for text in [
            "// Keeps the frame binding in the pipeline's layout even when the scene reads nothing from it.",
            "_ = frame.origin;",
            "let i = gid.x;",
        ] {
            let _ = writeln!(out, "{}{text}", Level(1));
        }
        "arrayLength(&points)"
    }
    fn probe_output(&self) -> &'static str {
        "probe_out"
    }
}
