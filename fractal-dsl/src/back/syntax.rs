//! What differs between the languages when spelling lowered code — [`Syntax`] — and the one spelling of a body all
//! writers share ([`Spelling`]), with the sample result's field names ([`sample_fields`]). The Rust writer frames
//! the bodies itself; the GPU languages' framing is [`super::kernel`].

use std::collections::{HashMap, HashSet};
use std::fmt::Write;

use super::Level;
use crate::formula::Leaf;
use crate::ir::BinOp;
use crate::lower::code::SAMPLE_FIELDS;
use crate::lower::code::{is_inline, operands, Body, CmpOp, FrameField, LogicOp, MathFn, Op, SceneFn, Stmt, Ty, Val};
use crate::lower::SampleVals;

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
    /// The frame's reference orbit as a call passes it to a leaf function; `None` where the callee reads the frame
    /// itself (and the argument is left out).
    fn orbit(&self) -> Option<String>;
    /// Entry `index` (an atom: an F holding a whole number) of the frame's reference orbit, as a Pair.
    fn orbit_entry(&self, index: &str) -> String;
    /// The index of the reference orbit's last entry, as an F.
    fn orbit_last(&self) -> String;
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
    /// A call of a scene function (in the ray program's bodies).
    fn scene_call(&self, f: SceneFn, args: &[String]) -> String {
        format!("{}({})", f.name(), args.join(", "))
    }
    /// A field of a Sample (an atom).
    fn field(&self, sample: &str, name: &str) -> String {
        format!("{sample}.{name}")
    }
    /// A value of the kernel's frame (in the ray program's bodies).
    fn frame(&self, field: FrameField) -> String {
        format!("frame.{}", field.path())
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String;
    /// How tightly [`Syntax::select`]'s spelling binds (a call binds like a name).
    fn select_prec(&self) -> Prec {
        Prec::Atom
    }
    fn if_open(&self, cond: &str) -> String;
    /// The first line of a loop running `count` times; `depth` numbers nested loops (0 outermost).
    fn loop_open(&self, count: &str, depth: usize) -> String;
    /// Leaves the innermost loop when `cond` holds.
    fn break_if(&self, cond: &str) -> String {
        format!("if {cond} {{ break; }}")
    }
    /// A comparison of two F values (operands spelled at additive precedence), giving a Bool.
    fn cmp(&self, op: CmpOp, x: &str, y: &str) -> String {
        format!("({x} {} {y})", op.symbol())
    }
    /// The symbol of a logical operator on Bools.
    fn logic_symbol(&self, op: LogicOp) -> &'static str {
        match op {
            LogicOp::And => "&&",
            LogicOp::Or => "||",
        }
    }
    /// Whether the code runs on lanes of values (a packet) as well as on scalars: then a Bool is a mask, an `if`
    /// runs its body when any lane's condition holds and its assignments take effect only in those lanes, and a loop
    /// runs until every lane has left it ([`Spelling`] writes the masks). Such a language spells `any(mask)`, masked
    /// assignments as `select` and masks combined with `&`, `|` and `!`.
    fn per_lane(&self) -> bool {
        false
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

/// How tightly a spelled expression binds, to parenthesise only where the languages need it (C's rules, which
/// WGSL and Rust share for these operators). A single operation keeps its operand grouping exactly: floating-point
/// addition is not associative, so `a + (b + c)` keeps its parentheses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Prec {
    /// `c ? a : b` (OpenCL's select).
    Ternary,
    Or,
    And,
    Add,
    Mul,
    Unary,
    /// Names, literals, calls, constructors, components, parenthesised comparisons.
    Atom,
}

fn bin_prec(op: BinOp) -> Prec {
    match op {
        BinOp::Add | BinOp::Sub => Prec::Add,
        BinOp::Mul | BinOp::Div => Prec::Mul,
    }
}

/// Spells one body: each value by name, except values spelled where they are used — literals, arguments,
/// components, comparisons, and any value used exactly once in the block that defines it (so `a * b + c` reads as
/// one expression instead of a chain of single-use names). Loads of variables keep their names: they read a
/// variable at one point of the program.
pub struct Spelling<'a> {
    body: &'a Body,
    syn: &'a dyn Syntax,
    /// Values whose definition is spelled at their one use.
    folded: HashSet<Val>,
}

impl<'a> Spelling<'a> {
    /// The spelling of `body` whose `results` are used (returned) in its top block.
    pub fn new(body: &'a Body, syn: &'a dyn Syntax, results: &[Val]) -> Spelling<'a> {
        let mut uses: HashMap<Val, (usize, usize)> = HashMap::new();
        let mut defined_in: HashMap<Val, usize> = HashMap::new();
        let mut next_block = 1;
        for &r in results {
            count_use(body, r, 0, &mut uses);
        }
        count_stmts(body, &body.stmts, 0, &mut next_block, &mut uses, &mut defined_in);
        let folded = defined_in
            .into_iter()
            .filter(|(v, block)| {
                !matches!(body.op(*v), Some(Op::Load(_))) && uses.get(v).is_some_and(|&(n, at)| n == 1 && at == *block)
            })
            .map(|(v, _)| v)
            .collect();
        Spelling { body, syn, folded }
    }

    /// A value as an operand or a result.
    pub fn value(&self, v: Val) -> String {
        self.spelled(v).0
    }

    fn spelled(&self, v: Val) -> (String, Prec) {
        match self.body.op(v) {
            Some(op) if is_inline(op) || self.folded.contains(&v) => self.op(op),
            _ => (name(v), Prec::Atom),
        }
    }

    /// `v` spelled as an operand that needs at least `prec`.
    fn operand(&self, v: Val, prec: Prec) -> String {
        let (text, own) = self.spelled(v);
        if own < prec {
            format!("({text})")
        } else {
            text
        }
    }

    fn op(&self, op: &Op) -> (String, Prec) {
        let syn = self.syn;
        let any = |v: &Val| self.value(*v);
        let atom = |text: String| (text, Prec::Atom);
        match op {
            Op::Lit(b) => atom(syn.lit(f64::from_bits(b.0))),
            Op::BoolLit(v) => atom(syn.bool_lit(*v)),
            Op::IntLit(n) => atom(syn.int(*n)),
            Op::Time => atom(syn.time()),
            Op::Param(i) => atom(syn.param(*i)),
            Op::Arg(name) => atom(name.to_string()),
            Op::Orbit => atom(syn.orbit().unwrap_or_default()),
            Op::OrbitEntry(i) => atom(syn.orbit_entry(&self.operand(*i, Prec::Atom))),
            Op::OrbitLast => atom(syn.orbit_last()),
            Op::MakeV3(x, y, z) => atom(syn.make_v3(&any(x), &any(y), &any(z))),
            Op::MakePair(d, t) => atom(syn.make_pair(&any(d), &any(t))),
            Op::Comp(v, i) => atom(syn.comp(&self.operand(*v, Prec::Atom), self.body.ty(*v), *i)),
            Op::Neg(v) => (format!("-{}", self.operand(*v, Prec::Unary)), Prec::Unary),
            Op::Not(v) => (format!("!{}", self.operand(*v, Prec::Unary)), Prec::Unary),
            Op::Bin(op, x, y) => {
                let p = bin_prec(*op);
                // The right operand of the same precedence is parenthesised: the grouping is the computation.
                let right = self.operand(*y, if p == Prec::Add { Prec::Mul } else { Prec::Unary });
                (format!("{} {} {right}", self.operand(*x, p), op.symbol()), p)
            }
            Op::Logic(op, x, y) => {
                let (p, tighter) = match op {
                    LogicOp::And => (Prec::And, Prec::Add),
                    LogicOp::Or => (Prec::Or, Prec::And),
                };
                let symbol = syn.logic_symbol(*op);
                (format!("{} {symbol} {}", self.operand(*x, p), self.operand(*y, tighter)), p)
            }
            Op::Math(f, args) => atom(syn.math(*f, &args.iter().map(any).collect::<Vec<_>>())),
            Op::Call(leaf, args) => {
                // An orbit argument is left out where the callee reads the frame itself.
                let passed = |v: &&Val| syn.orbit().is_some() || self.body.op(**v) != Some(&Op::Orbit);
                atom(syn.call(*leaf, &args.iter().filter(passed).map(any).collect::<Vec<_>>()))
            }
            Op::Scene(f, args) => atom(syn.scene_call(*f, &args.iter().map(any).collect::<Vec<_>>())),
            Op::Field(v, i) => atom(syn.field(&self.operand(*v, Prec::Atom), SAMPLE_FIELDS[*i as usize].0)),
            Op::Frame(field) => atom(syn.frame(*field)),
            Op::Cmp(op, x, y) => atom(syn.cmp(*op, &self.operand(*x, Prec::Add), &self.operand(*y, Prec::Add))),
            Op::Select(c, t, f) => {
                let operand = |v: &Val| self.operand(*v, Prec::Or);
                (syn.select(&operand(c), &operand(t), &operand(f)), syn.select_prec())
            }
            Op::Load(v) => atom(name(*v)),
        }
    }

    /// Writes the statements of the body at `level`.
    pub fn write(&self, out: &mut String, level: Level) {
        if self.syn.per_lane() {
            self.lane_stmts(out, &self.body.stmts, level, &Lanes::default(), &std::cell::Cell::new(0));
        } else {
            self.stmts(out, &self.body.stmts, level, 0);
        }
    }

    /// A `Let` (unless spelled at its use) or a `Var`: the same in every language and mode.
    fn declaration(&self, out: &mut String, s: &Stmt, level: Level) {
        let line = match s {
            Stmt::Let { val, .. } if self.folded.contains(val) => return,
            Stmt::Let { val, ty, op } => self.syn.declare(&name(*val), *ty, &self.op(op).0, false),
            Stmt::Var { var, ty, init } => self.syn.declare(&name(*var), *ty, &self.value(*init), true),
            _ => return,
        };
        let _ = writeln!(out, "{level}{line}");
    }

    /// The statements in a per-lane language ([`Syntax::per_lane`]): `lanes` names the masks in force.
    fn lane_stmts(&self, out: &mut String, stmts: &[Stmt], level: Level, lanes: &Lanes, next: &std::cell::Cell<usize>) {
        let syn = self.syn;
        let fresh = |prefix: &str| {
            let n = next.get();
            next.set(n + 1);
            format!("{prefix}{n}")
        };
        for s in stmts {
            match s {
                Stmt::Let { .. } | Stmt::Var { .. } => self.declaration(out, s, level),
                Stmt::Assign { var, value } => {
                    let (var, value) = (name(*var), self.value(*value));
                    let assigned = match &lanes.mask {
                        // Only F variables are assigned under a condition (the lowering's `when` and `iterate`).
                        Some(mask) => format!("select({mask}, {value}, {var})"),
                        None => value,
                    };
                    let _ = writeln!(out, "{level}{var} = {assigned};");
                }
                Stmt::If { cond, body } => {
                    let mask = fresh("m");
                    let cond = self.operand(*cond, Prec::Unary);
                    let value = lanes.mask.as_ref().map_or(cond.clone(), |outer| format!("{outer} & {cond}"));
                    let _ = writeln!(out, "{level}let {mask} = {value};");
                    let _ = writeln!(out, "{level}if any({mask}) {{");
                    let inner = Lanes { mask: Some(mask), live: lanes.live.clone() };
                    self.lane_stmts(out, body, level.next(), &inner, next);
                    let _ = writeln!(out, "{level}}}");
                }
                Stmt::Loop { count, body } => {
                    let live = fresh("live");
                    let all = format!("{}::splat(true)", syn.type_name(Ty::Bool));
                    let init = lanes.mask.clone().unwrap_or(all);
                    let _ = writeln!(out, "{level}let mut {live} = {init};");
                    let _ = writeln!(out, "{level}for _ in 0..{} {{", self.value(*count));
                    let inner = Lanes { mask: Some(live.clone()), live: Some(live) };
                    self.lane_stmts(out, body, level.next(), &inner, next);
                    let _ = writeln!(out, "{level}}}");
                }
                Stmt::BreakIf { cond } => {
                    let live = lanes.live.as_ref().expect("a loop's exit is inside the loop");
                    let mut leaving = self.operand(*cond, Prec::Unary);
                    if let Some(mask) = lanes.mask.as_ref().filter(|m| *m != live) {
                        leaving = format!("({mask} & {leaving})");
                    }
                    let _ = writeln!(out, "{level}{live} = {live} & !{leaving};");
                    let _ = writeln!(out, "{level}if !any({live}) {{ break; }}");
                }
            }
        }
    }

    fn stmts(&self, out: &mut String, stmts: &[Stmt], level: Level, loops: usize) {
        let syn = self.syn;
        for s in stmts {
            match s {
                Stmt::Let { .. } | Stmt::Var { .. } => self.declaration(out, s, level),
                Stmt::Assign { var, value } => {
                    let _ = writeln!(out, "{level}{} = {};", name(*var), self.value(*value));
                }
                Stmt::If { cond, body } => {
                    let _ = writeln!(out, "{level}{}", syn.if_open(&self.value(*cond)));
                    self.stmts(out, body, level.next(), loops);
                    let _ = writeln!(out, "{level}}}");
                }
                Stmt::Loop { count, body } => {
                    let _ = writeln!(out, "{level}{}", syn.loop_open(&self.value(*count), loops));
                    self.stmts(out, body, level.next(), loops + 1);
                    let _ = writeln!(out, "{level}}}");
                }
                Stmt::BreakIf { cond } => {
                    let _ = writeln!(out, "{level}{}", syn.break_if(&self.value(*cond)));
                }
            }
        }
    }
}

/// The masks in force where per-lane statements are written: the lanes an assignment takes effect in, and the
/// innermost loop's lanes still running.
#[derive(Clone, Debug, Default)]
struct Lanes {
    mask: Option<String>,
    live: Option<String>,
}

/// Counts a use of `v` in `block`: (number of uses, block of the last use); a value spelled in place is used where
/// its user is, so its operands are counted there too.
fn count_use(body: &Body, v: Val, block: usize, uses: &mut HashMap<Val, (usize, usize)>) {
    let entry = uses.entry(v).or_insert((0, block));
    *entry = (entry.0 + 1, block);
    if let Some(op) = body.op(v).filter(|op| is_inline(op)) {
        for w in operands(op) {
            count_use(body, w, block, uses);
        }
    }
}

fn count_stmts(
    body: &Body,
    stmts: &[Stmt],
    block: usize,
    next_block: &mut usize,
    uses: &mut HashMap<Val, (usize, usize)>,
    defined_in: &mut HashMap<Val, usize>,
) {
    for s in stmts {
        match s {
            Stmt::Let { val, op, .. } => {
                defined_in.insert(*val, block);
                for w in operands(op) {
                    count_use(body, w, block, uses);
                }
            }
            Stmt::Var { init: v, .. } | Stmt::Assign { value: v, .. } | Stmt::BreakIf { cond: v } => {
                count_use(body, *v, block, uses)
            }
            Stmt::If { cond: v, body: inner } | Stmt::Loop { count: v, body: inner } => {
                count_use(body, *v, block, uses);
                let own = *next_block;
                *next_block += 1;
                count_stmts(body, inner, own, next_block, uses, defined_in);
            }
        }
    }
}
