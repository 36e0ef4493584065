//! What differs between the languages when spelling lowered code — [`Syntax`] — and the one statement walker all
//! writers share ([`write_body`]), with the sample result's field names ([`sample_fields`]). The Rust writer frames
//! the bodies itself; the GPU languages' framing is [`super::kernel`].

use std::fmt::Write;

use super::Level;
use crate::lower::code::{Body, LogicOp, MathFn, Op, Stmt, Ty, Val};
use crate::lower::SampleVals;
use crate::sdf::Leaf;

/// How one language spells values and statements. Operations every language spells alike (arithmetic, negation,
/// comparisons) are spelled by the walker.
pub trait Syntax {
    fn type_name(&self, ty: Ty) -> &'static str;
    /// A complete declaration statement (with its `;`).
    fn declare(&self, name: &str, ty: Ty, value: &str, mutable: bool) -> String;
    fn lit(&self, v: f64) -> String;
    fn bool_lit(&self, v: bool) -> String;
    /// A loop count constant.
    fn int(&self, v: u32) -> String;
    fn time(&self) -> String;
    fn param(&self, slot: usize) -> String;
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String;
    fn make_pair(&self, distance: &str, trap: &str) -> String;
    fn comp(&self, v: &str, ty: Ty, i: u8) -> String;
    /// The name of a math function.
    fn math_name(&self, f: MathFn) -> &'static str;
    /// A call of a math function (a language whose built-in falls short spells its polyfill here, once per
    /// operation).
    fn math(&self, f: MathFn, args: &[String]) -> String {
        format!("{}({})", self.math_name(f), args.join(", "))
    }
    /// A call of a leaf function.
    fn call(&self, leaf: Leaf, args: &[String]) -> String {
        format!("{}({})", leaf.name(), args.join(", "))
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String;
    fn if_open(&self, cond: &str) -> String;
    /// The first line of a loop running `count` times; `depth` numbers nested loops (0 outermost).
    fn loop_open(&self, count: &str, depth: usize) -> String;
    /// Leaves the innermost loop when `cond` holds.
    fn break_if(&self, cond: &str) -> String {
        format!("if {cond} {{ break; }}")
    }
}

/// The name of a value in every language.
pub fn name(v: Val) -> String {
    format!("v{}", v.0)
}

/// A math function's name where the languages agree (and Rust's, whose `ln` the GPU languages call `log`).
pub fn common_math_name(f: MathFn) -> &'static str {
    match f {
        MathFn::Sin => "sin",
        MathFn::Cos => "cos",
        MathFn::Acos => "acos",
        MathFn::Atan2 => "atan2",
        MathFn::Abs => "abs",
        MathFn::Sqrt => "sqrt",
        MathFn::Floor => "floor",
        MathFn::Exp2 => "exp2",
        MathFn::Ln => "ln",
        MathFn::Min => "min",
        MathFn::Max => "max",
        MathFn::Pow => "pow",
    }
}

/// Spells a value where it is used: inline values in place, everything else by name.
pub fn atom(body: &Body, syn: &dyn Syntax, v: Val) -> String {
    match body.op(v) {
        Some(op) if crate::lower::code::is_inline(op) => spell_op(body, syn, op),
        _ => name(v),
    }
}

/// The sample result's values by field name, in the field order of every language's `Sample`.
pub fn sample_fields(r: &SampleVals) -> [(&'static str, Val); 6] {
    [
        ("distance", r.distance),
        ("albedo", r.albedo),
        ("ambient", r.ambient),
        ("diffuse", r.diffuse),
        ("specular", r.specular),
        ("shininess", r.shininess),
    ]
}

fn spell_op(body: &Body, syn: &dyn Syntax, op: &Op) -> String {
    let a = |v: &Val| atom(body, syn, *v);
    match op {
        Op::Lit(b) => syn.lit(f64::from_bits(b.0)),
        Op::BoolLit(v) => syn.bool_lit(*v),
        Op::IntLit(n) => syn.int(*n),
        Op::Time => syn.time(),
        Op::Param(i) => syn.param(*i),
        Op::Arg(name) => name.to_string(),
        Op::MakeV3(x, y, z) => syn.make_v3(&a(x), &a(y), &a(z)),
        Op::MakePair(d, t) => syn.make_pair(&a(d), &a(t)),
        Op::Comp(v, i) => syn.comp(&a(v), body.ty(*v), *i),
        Op::Neg(v) => format!("-{}", a(v)),
        Op::Bin(op, x, y) => format!("{} {} {}", a(x), op.symbol(), a(y)),
        Op::Math(f, args) => syn.math(*f, &args.iter().map(a).collect::<Vec<_>>()),
        Op::Call(leaf, args) => syn.call(*leaf, &args.iter().map(a).collect::<Vec<_>>()),
        Op::Cmp(op, x, y) => format!("({} {} {})", a(x), op.symbol(), a(y)),
        Op::Logic(op, x, y) => {
            let symbol = match op {
                LogicOp::And => "&&",
                LogicOp::Or => "||",
            };
            format!("{} {symbol} {}", a(x), a(y))
        }
        Op::Not(v) => format!("!{}", a(v)),
        Op::Select(c, t, f) => syn.select(&a(c), &a(t), &a(f)),
        Op::Load(v) => name(*v),
    }
}

/// Writes the statements of a body at `level`.
pub fn write_body(out: &mut String, body: &Body, syn: &dyn Syntax, level: Level) {
    write_stmts(out, body, &body.stmts, syn, level, 0);
}

fn write_stmts(out: &mut String, body: &Body, stmts: &[Stmt], syn: &dyn Syntax, level: Level, loops: usize) {
    for s in stmts {
        match s {
            Stmt::Let { val, ty, op } => {
                let _ = writeln!(out, "{level}{}", syn.declare(&name(*val), *ty, &spell_op(body, syn, op), false));
            }
            Stmt::Var { var, ty, init } => {
                let _ = writeln!(out, "{level}{}", syn.declare(&name(*var), *ty, &atom(body, syn, *init), true));
            }
            Stmt::Assign { var, value } => {
                let _ = writeln!(out, "{level}{} = {};", name(*var), atom(body, syn, *value));
            }
            Stmt::If { cond, body: inner } => {
                let _ = writeln!(out, "{level}{}", syn.if_open(&atom(body, syn, *cond)));
                write_stmts(out, body, inner, syn, level.next(), loops);
                let _ = writeln!(out, "{level}}}");
            }
            Stmt::Loop { count, body: inner } => {
                let _ = writeln!(out, "{level}{}", syn.loop_open(&atom(body, syn, *count), loops));
                write_stmts(out, body, inner, syn, level.next(), loops + 1);
                let _ = writeln!(out, "{level}}}");
            }
            Stmt::BreakIf { cond } => {
                let _ = writeln!(out, "{level}{}", syn.break_if(&atom(body, syn, *cond)));
            }
        }
    }
}
