//! The Rust writer: spells the lowered scene functions as two generic functions — distance and sample — that the
//! `scene!` macro compiles into the user's crate as the native evaluator (f32, f64 and eight-lane packet instances of
//! the same code: choices are masks, see [`Syntax::per_lane`]). Leaves call [`crate::formula`] directly: the
//! functions the interpreter runs and the kernels' leaf functions are traced from.

use std::fmt::Write;

use crate::back::syntax::{self, common_math_name, Spelling, Syntax};
use crate::back::Level;
use crate::formula::Leaf;
use crate::lower::code::{CmpOp, LogicOp, MathFn, Ty};
use crate::lower::Program;

struct RustSyntax;

impl Syntax for RustSyntax {
    fn type_name(&self, ty: Ty) -> &'static str {
        match ty {
            Ty::F => "F",
            Ty::V3 => "V3<F>",
            Ty::Pair => "[F; 2]",
            Ty::Bool => "F::Mask",
            Ty::Int => "u32",
            Ty::Orbit => "Orbit<'_>",
            Ty::Sample => "Sample<F>",
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
    fn bool_lit(&self, v: bool) -> String {
        format!("<F::Mask as Mask>::splat({v})")
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
    fn frame(&self, field: crate::lower::code::FrameField) -> String {
        // The scene functions read only the anchor; the ray program is run natively, not spelled.
        assert_eq!(field, crate::lower::code::FrameField::Anchor, "a scene function reads only the frame's anchor");
        "env.anchor()".to_string()
    }
    fn orbit(&self) -> Option<String> {
        Some("env.reference_orbit()".to_string())
    }
    fn orbit_entry(&self, index: &str) -> String {
        format!("F::orbit_entry(env.reference_orbit(), {index})")
    }
    fn orbit_last(&self) -> String {
        "F::orbit_last(env.reference_orbit())".to_string()
    }
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String {
        format!("V3 {{ x: {x}, y: {y}, z: {z} }}")
    }
    fn make_pair(&self, distance: &str, trap: &str) -> String {
        format!("[{distance}, {trap}]")
    }
    fn comp(&self, v: &str, ty: Ty, i: u8) -> String {
        match ty {
            Ty::Pair => format!("{v}[{i}]"),
            _ => format!("{v}.{}", ["x", "y", "z"][i as usize]),
        }
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        common_math_name(f)
    }
    fn call(&self, leaf: Leaf, args: &[String]) -> String {
        format!("formula::{}({})", leaf.name(), args.join(", "))
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        format!("select({cond}, {if_true}, {if_false})")
    }
    fn if_open(&self, cond: &str) -> String {
        format!("if {cond} {{")
    }
    fn loop_open(&self, count: &str, _depth: usize) -> String {
        format!("for _ in 0..{count} {{")
    }
    fn cmp(&self, op: CmpOp, x: &str, y: &str) -> String {
        match op {
            CmpOp::Lt => format!("lt({x}, {y})"),
            CmpOp::Le => format!("le({x}, {y})"),
        }
    }
    fn logic_symbol(&self, op: LogicOp) -> &'static str {
        match op {
            LogicOp::And => "&",
            LogicOp::Or => "|",
        }
    }
    fn per_lane(&self) -> bool {
        true
    }
}

/// The names of the functions [`write()`] emits.
pub const DISTANCE_FN: &str = "__fractal_distance";
pub const SAMPLE_FN: &str = "__fractal_sample";
/// Emitted only for a scene shaded by its gradient ([`Program::normal`]).
pub const NORMAL_FN: &str = "__fractal_normal";

/// Rust source of the native evaluator: `fn __fractal_distance<F: HostNum>(p, env) -> F`,
/// `fn __fractal_sample<F: HostNum>(p, env) -> Sample<F>` and, for a scene shaded by its gradient,
/// `fn __fractal_normal<F: HostNum>(p, env) -> V3<F>`. `krate` is the path of fractal-dsl in the user's crate.
pub fn write(program: &Program, krate: &str) -> String {
    let mut out = String::new();
    let header = |out: &mut String, name: &str, ret: &str| {
        let _ = writeln!(out, "#[allow(unused_parens, unused_variables, unused_imports, clippy::all)]");
        // Inlined into the packet instances' AVX2 copies, so the whole evaluation is compiled for AVX2 there.
        let _ = writeln!(out, "#[inline(always)]");
        let _ = writeln!(
            out,
            "fn {name}<F: {krate}::formula::HostNum>(p: {krate}::number::math::V3<F>, env: &{krate}::eval::Env<F>) -> {ret} {{"
        );
        let _ = writeln!(out, "    use {krate}::number::math::*;");
        let _ = writeln!(out, "    use {krate}::formula;");
    };
    header(&mut out, DISTANCE_FN, "F");
    let spelling = Spelling::new(&program.distance, &RustSyntax, &[program.distance_result]);
    spelling.write(&mut out, Level(1));
    let _ = writeln!(out, "    {}", spelling.value(program.distance_result));
    out.push_str("}\n\n");

    header(&mut out, SAMPLE_FN, &format!("{krate}::eval::Sample<F>"));
    if program.reference.is_some() {
        let _ = writeln!(out, "    let {} = env.reference_offset(p);", crate::lower::REFERENCE_OFFSET);
    }
    let spelling = Spelling::new(&program.sample, &RustSyntax, &program.sample_result.all());
    spelling.write(&mut out, Level(1));
    let r = program.sample_result;
    let _ = writeln!(out, "    {krate}::eval::Sample {{");
    for (field, v) in syntax::sample_fields(&r) {
        let _ = writeln!(out, "        {field}: {},", spelling.value(v));
    }
    out.push_str("    }\n}\n");

    if let Some((body, result)) = &program.normal {
        out.push('\n');
        header(&mut out, NORMAL_FN, &format!("{krate}::number::math::V3<F>"));
        let spelling = Spelling::new(body, &RustSyntax, &[*result]);
        spelling.write(&mut out, Level(1));
        let _ = writeln!(out, "    {}", spelling.value(*result));
        out.push_str("}\n");
    }
    out
}
