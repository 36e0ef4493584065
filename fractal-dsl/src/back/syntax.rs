//! What differs between the languages when spelling a lowered body — [`Syntax`] — and the one statement walker all
//! writers share ([`write_body`]), with the sample result's field names ([`sample_fields`]). The Rust writer frames
//! the bodies itself; the GPU languages' framing is [`super::kernel`].

use std::fmt::Write;

use super::{Helper, Level};
use crate::lower::code::{Arg, Body, MathFn, Op, Stmt, Ty, Val};
use crate::lower::SampleVals;

/// How one language spells values and statements.
pub trait Syntax {
    fn type_name(&self, ty: Ty) -> &'static str;
    /// A complete declaration statement (with its `;`).
    fn declare(&self, name: &str, ty: Ty, value: &str, mutable: bool) -> String;
    fn lit(&self, v: f64) -> String;
    fn int(&self, v: u32) -> String;
    fn time(&self) -> String;
    fn param(&self, slot: usize) -> String;
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String;
    fn comp(&self, v: &str, ty: Ty, i: u8) -> String;
    fn math(&self, f: MathFn, args: &[String]) -> String;
    fn length(&self, v: &str) -> String;
    /// A helper call; `args` are already spelled, the Julia constant as four scalars (see [`group_julia`]).
    fn call(&self, h: Helper, args: &[String]) -> String;
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String;
    fn less(&self, a: &str, b: &str) -> String;
    fn if_open(&self, cond: &str) -> String;
}

/// The name of a value in every language.
pub fn name(v: Val) -> String {
    format!("v{}", v.0)
}

/// Spells a value where it is used: inline values in place, everything else by name.
pub fn atom(body: &Body, syn: &dyn Syntax, v: Val) -> String {
    match body.op(v) {
        Some(op @ (Op::Lit(_) | Op::Time | Op::Param(_) | Op::Point | Op::Less(..))) => spell_op(body, syn, op),
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

/// The Julia helper takes its constant as one 4-vector: `wrap` spells the vector from the four scalars.
pub fn group_julia(args: &[String], wrap: impl Fn(&[String]) -> String) -> Vec<String> {
    let mut out = vec![args[0].clone(), wrap(&args[1..5])];
    out.extend_from_slice(&args[5..]);
    out
}

fn spell_op(body: &Body, syn: &dyn Syntax, op: &Op) -> String {
    let a = |v: &Val| atom(body, syn, *v);
    match op {
        Op::Lit(b) => syn.lit(f64::from_bits(b.0)),
        Op::Time => syn.time(),
        Op::Param(i) => syn.param(*i),
        Op::Point => "p".to_string(),
        Op::MakeV3(x, y, z) => syn.make_v3(&a(x), &a(y), &a(z)),
        Op::Comp(v, i) => syn.comp(&a(v), body.ty(*v), *i),
        Op::Neg(v) => format!("-{}", a(v)),
        Op::Bin(op, x, y) => format!("{} {} {}", a(x), op.symbol(), a(y)),
        Op::Math(f, args) => syn.math(*f, &args.iter().map(a).collect::<Vec<_>>()),
        Op::Length(v) => syn.length(&a(v)),
        Op::Call(h, args) => {
            let spelled: Vec<String> = args
                .iter()
                .map(|arg| match arg {
                    Arg::Val(v) => a(v),
                    Arg::Int(n) => syn.int(*n),
                })
                .collect();
            syn.call(*h, &spelled)
        }
        Op::Less(x, y) => syn.less(&a(x), &a(y)),
        Op::Select(c, t, f) => syn.select(&a(c), &a(t), &a(f)),
        Op::Load(v) => name(*v),
    }
}

/// Writes the statements of a body at `level`.
pub fn write_body(out: &mut String, body: &Body, syn: &dyn Syntax, level: Level) {
    write_stmts(out, body, &body.stmts, syn, level);
}

fn write_stmts(out: &mut String, body: &Body, stmts: &[Stmt], syn: &dyn Syntax, level: Level) {
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
                write_stmts(out, body, inner, syn, level.next());
                let _ = writeln!(out, "{level}}}");
            }
        }
    }
}
