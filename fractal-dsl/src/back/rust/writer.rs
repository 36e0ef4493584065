//! The Rust writer: spells the lowered bodies as two generic functions — distance and sample — that the `scene!`
//! macro compiles into the user's crate as the native evaluator (f32 and f64 instances of the same code). Leaves call
//! [`crate::sdf`], the functions the interpreter calls too.

use std::fmt::Write;

use crate::back::syntax::{self, group_julia, Syntax};
use crate::back::{Helper, Level};
use crate::lower::code::{MathFn, Ty};
use crate::lower::Program;

struct RustSyntax;

impl Syntax for RustSyntax {
    fn type_name(&self, ty: Ty) -> &'static str {
        match ty {
            Ty::F => "F",
            Ty::V3 => "V3<F>",
            Ty::Pair => "[F; 2]",
            Ty::Bool => "bool",
        }
    }
    fn declare(&self, name: &str, ty: Ty, value: &str, mutable: bool) -> String {
        let m = if mutable { "mut " } else { "" };
        format!("let {m}{name}: {} = {value};", self.type_name(ty))
    }
    fn lit(&self, v: f64) -> String {
        // f64 Debug output round-trips exactly; `c` rounds it to F the same way the kernels' f32 literals are.
        format!("c::<F>({v:?})")
    }
    fn int(&self, v: u32) -> String {
        v.to_string()
    }
    fn time(&self) -> String {
        "env.time".to_string()
    }
    fn param(&self, slot: usize) -> String {
        format!("env.params[{slot}]")
    }
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String {
        format!("V3 {{ x: {x}, y: {y}, z: {z} }}")
    }
    fn comp(&self, v: &str, ty: Ty, i: u8) -> String {
        match ty {
            Ty::Pair => format!("{v}[{i}]"),
            _ => format!("{v}.{}", ["x", "y", "z"][i as usize]),
        }
    }
    fn math(&self, f: MathFn, a: &[String]) -> String {
        match f {
            MathFn::Sin => format!("{}.sin()", a[0]),
            MathFn::Cos => format!("{}.cos()", a[0]),
            MathFn::Abs => format!("{}.abs()", a[0]),
            MathFn::Sqrt => format!("{}.sqrt()", a[0]),
            MathFn::Floor => format!("{}.floor()", a[0]),
            MathFn::Min => format!("{}.min({})", a[0], a[1]),
            MathFn::Max => format!("{}.max({})", a[0], a[1]),
            MathFn::Pow => format!("{}.powf({})", a[0], a[1]),
            MathFn::Clamp => format!("clamp({}, {}, {})", a[0], a[1], a[2]),
            MathFn::Mix => format!("mix({}, {}, {})", a[0], a[1], a[2]),
        }
    }
    fn length(&self, v: &str) -> String {
        format!("length({v})")
    }
    fn call(&self, h: Helper, args: &[String]) -> String {
        let args =
            if h == Helper::DeJulia { group_julia(args, |c| format!("[{}]", c.join(", "))) } else { args.to_vec() };
        format!("sdf::{}({})", h.name(), args.join(", "))
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        format!("select({cond}, {if_true}, {if_false})")
    }
    fn less(&self, a: &str, b: &str) -> String {
        format!("{a} < {b}")
    }
    fn if_open(&self, cond: &str) -> String {
        format!("if {cond} {{")
    }
}

/// The names of the two functions [`write`] emits.
pub const DISTANCE_FN: &str = "__fractal_distance";
pub const SAMPLE_FN: &str = "__fractal_sample";

/// Rust source of the native evaluator: `fn __fractal_distance<F: Real>(p, env) -> F` and
/// `fn __fractal_sample<F: Real>(p, env) -> Sample<F>`. `krate` is the path of fractal-dsl in the user's crate.
pub fn write(program: &Program, krate: &str) -> String {
    let mut out = String::new();
    let header = |out: &mut String, name: &str, ret: &str| {
        let _ = writeln!(out, "#[allow(unused_parens, unused_variables, unused_imports, clippy::all)]");
        let _ = writeln!(
            out,
            "fn {name}<F: {krate}::math::Real>(p: {krate}::math::V3<F>, env: &{krate}::eval::Env<F>) -> {ret} {{"
        );
        let _ = writeln!(out, "    use {krate}::math::*;");
        let _ = writeln!(out, "    use {krate}::sdf;");
    };
    header(&mut out, DISTANCE_FN, "F");
    syntax::write_body(&mut out, &program.distance, &RustSyntax, Level(1));
    let _ = writeln!(out, "    {}", syntax::atom(&program.distance, &RustSyntax, program.distance_result));
    out.push_str("}\n\n");

    header(&mut out, SAMPLE_FN, &format!("{krate}::eval::Sample<F>"));
    syntax::write_body(&mut out, &program.sample, &RustSyntax, Level(1));
    let r = program.sample_result;
    let _ = writeln!(out, "    {krate}::eval::Sample {{");
    for (field, v) in syntax::sample_fields(&r) {
        let _ = writeln!(out, "        {field}: {},", syntax::atom(&program.sample, &RustSyntax, v));
    }
    out.push_str("    }\n}\n");
    out
}
