//! A formula written in the scene language, compiled for the host: its membership test and its estimate
//! ([`crate::formula::user`]) traced once into lowered code ([`super::code`]) and flattened into a [`Tape`], a list of
//! f64 instructions over numbered slots with jumps for the loops and `if`s. The ground truth decides membership
//! millions of times per image; walking the formula's tree for each (a value enum per operation, a vector per `let`)
//! is what made a formula scene's truth take many minutes. The tape reads the same traced code the kernels print, so
//! it computes what they compute, in f64.
//!
//! What a formula's code never holds (leaf calls, the frame, time: a formula's time is one of its numbers) makes
//! [`compile`] give up, and the caller keeps walking the tree.

use std::cell::RefCell;
use std::sync::Arc;

use super::code::{Body, CmpOp, LogicOp, MathFn, Op, Stmt, Ty, Val};
use super::trace::{trace, Sym};
use crate::eval::interp::Interpreter;
use crate::eval::plan::FormulaCall;
use crate::formula::user::{self, HostCode, Ready};
use crate::ir::BinOp;
use crate::number::math::V3;
use crate::number::Num;
use crate::validate::InvalidScene;
use crate::Scene;

/// One instruction: slots are indices into the tape's f64 slots (a truth value is 0 or 1, a loop count a whole
/// number).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ins {
    Copy(u32, u32),
    Neg(u32, u32),
    Bin(BinOp, u32, u32, u32),
    Math1(MathFn, u32, u32),
    Math2(MathFn, u32, u32, u32),
    Cmp(CmpOp, u32, u32, u32),
    Logic(LogicOp, u32, u32, u32),
    Not(u32, u32),
    /// dst, condition, if true, if false.
    Select(u32, u32, u32, u32),
    Jump(u32),
    /// Jumps when the slot is true (a `break`).
    JumpIf(u32, u32),
    /// Jumps when the slot is false (past an `if`'s body).
    JumpUnless(u32, u32),
    /// A loop's head: jumps out when the counter has run down, else counts one down.
    CountDown(u32, u32),
}

/// Straight-line f64 code with jumps: [`compile`] writes it, [`Tape::run`] runs it.
#[derive(Clone, Debug, PartialEq)]
pub struct Tape {
    code: Vec<Ins>,
    /// Every slot's value before a run: the literals; the rest are written before they are read.
    init: Vec<f64>,
    /// The slots of the point's components and of the bailout, where the code reads them.
    point: [Option<u32>; 3],
    bailout: Option<u32>,
    /// (slot, index into the formula's numbers) of the numbers that are not literals.
    nums: Vec<(u32, u16)>,
    /// The slots of the results.
    results: Vec<u32>,
}

thread_local! {
    /// The slots of the tape running on this thread (reused: a run allocates nothing once they have grown).
    static SLOTS: RefCell<Vec<f64>> = const { RefCell::new(Vec::new()) };
}

impl Tape {
    /// Runs the code at `p` with the formula's numbers `nums` and the bailout, writing the results into `out`.
    pub fn run(&self, nums: &[f64], p: [f64; 3], bailout: f64, out: &mut [f64]) {
        SLOTS.with(|slots| {
            let mut s = slots.borrow_mut();
            s.clear();
            s.extend_from_slice(&self.init);
            for (slot, x) in self.point.iter().zip(p) {
                if let Some(slot) = slot {
                    s[*slot as usize] = x;
                }
            }
            if let Some(slot) = self.bailout {
                s[slot as usize] = bailout;
            }
            for &(slot, i) in &self.nums {
                s[slot as usize] = nums.get(i as usize).copied().unwrap_or(0.0);
            }
            execute(&self.code, &mut s);
            for (o, r) in out.iter_mut().zip(&self.results) {
                *o = s[*r as usize];
            }
        })
    }
}

/// The machine: one pass over the code from its first instruction to its end.
fn execute(code: &[Ins], s: &mut [f64]) {
    let truth = |x: bool| if x { 1.0 } else { 0.0 };
    let mut pc = 0;
    while let Some(ins) = code.get(pc) {
        pc += 1;
        match *ins {
            Ins::Copy(d, a) => s[d as usize] = s[a as usize],
            Ins::Neg(d, a) => s[d as usize] = -s[a as usize],
            Ins::Bin(op, d, a, b) => s[d as usize] = op.apply(s[a as usize], s[b as usize]),
            Ins::Math1(f, d, a) => s[d as usize] = f.fold(&[s[a as usize]]),
            Ins::Math2(f, d, a, b) => s[d as usize] = f.fold(&[s[a as usize], s[b as usize]]),
            Ins::Cmp(op, d, a, b) => {
                let (x, y) = (s[a as usize], s[b as usize]);
                s[d as usize] = truth(match op {
                    CmpOp::Lt => x < y,
                    CmpOp::Le => x <= y,
                })
            }
            Ins::Logic(op, d, a, b) => {
                let (x, y) = (s[a as usize] != 0.0, s[b as usize] != 0.0);
                s[d as usize] = truth(match op {
                    LogicOp::And => x && y,
                    LogicOp::Or => x || y,
                })
            }
            Ins::Not(d, a) => s[d as usize] = truth(s[a as usize] == 0.0),
            Ins::Select(d, c, a, b) => s[d as usize] = if s[c as usize] != 0.0 { s[a as usize] } else { s[b as usize] },
            Ins::Jump(to) => pc = to as usize,
            Ins::JumpIf(c, to) => {
                if s[c as usize] != 0.0 {
                    pc = to as usize
                }
            }
            Ins::JumpUnless(c, to) => {
                if s[c as usize] == 0.0 {
                    pc = to as usize
                }
            }
            Ins::CountDown(n, to) => {
                if s[n as usize] < 1.0 {
                    pc = to as usize
                } else {
                    s[n as usize] -= 1.0
                }
            }
        }
    }
}

/// A formula's membership test and estimate on tapes ([`HostCode`]).
#[derive(Debug)]
struct FormulaTapes {
    membership: Tape,
    estimate: Tape,
    /// Whether the estimate is signed by membership.
    signed: bool,
}

impl HostCode for FormulaTapes {
    fn membership(&self, nums: &[f64], p: [f64; 3], bailout: f64) -> f64 {
        let mut out = [0.0];
        self.membership.run(nums, p, bailout, &mut out);
        out[0]
    }
    fn estimate(&self, nums: &[f64], p: [f64; 3], bailout: f64, signed: bool) -> Option<[f64; 2]> {
        if signed != self.signed {
            return None;
        }
        let mut out = [0.0; 2];
        self.estimate.run(nums, p, bailout, &mut out);
        Some(out)
    }
}

/// The formula's membership test and its estimate (signed by membership if `signed`) compiled for the host, or None
/// where its code holds what a tape does not run.
pub fn compile(ready: &Ready, signed: bool) -> Option<Arc<dyn HostCode>> {
    let membership = tape(ready, |nums, p, bailout| vec![user::membership(ready, nums, p, bailout)])?;
    let estimate = tape(ready, |nums, p, bailout| user::estimate(ready, nums, p, bailout, signed).to_vec())?;
    Some(Arc::new(FormulaTapes { membership, estimate, signed }))
}

/// Compiles `call`'s formula for the host and attaches it ([`Ready::host`]); left without where it does not compile.
pub fn attach(call: &mut FormulaCall) {
    call.ready.host = compile(&call.ready, call.signed);
}

/// The interpreter of `scene` with every formula compiled for the host: what f64 evaluation should use.
pub fn interpreter(scene: &Scene) -> Result<Interpreter, InvalidScene> {
    Ok(Interpreter::new(scene)?.with_formula_calls(&mut attach))
}

/// Traces `f` over the formula's numbers (literals as literals, the rest read from the caller), the point and the
/// bailout, and flattens its code.
fn tape(ready: &Ready, f: impl FnOnce(&[Sym], V3<Sym>, Sym) -> Vec<Sym>) -> Option<Tape> {
    let (body, results) = trace(|| {
        let nums: Vec<Sym> =
            (ready.literals.iter().enumerate()).map(|(i, l)| l.map_or_else(|| Sym::param(i), Sym::lit)).collect();
        let p = Sym::components(Sym::arg_of("p", Ty::V3));
        let bailout = Sym::arg("bailout");
        f(&nums, p, bailout).into_iter().map(|s| s.0).collect::<Vec<Val>>()
    });
    let body = body.pruned(&results);
    let mut flat = Flatten::new(&body);
    flat.stmts(&body.stmts)?;
    let results = results.iter().map(|&r| flat.operand(r)).collect::<Option<Vec<u32>>>()?;
    Some(Tape { code: flat.code, init: flat.init, point: flat.point, bailout: flat.bailout, nums: flat.nums, results })
}

/// Slots a value of a type takes, if a tape holds it.
fn width(ty: Ty) -> Option<u32> {
    match ty {
        Ty::F | Ty::Bool | Ty::Int => Some(1),
        Ty::V3 => Some(3),
        Ty::Pair => Some(2),
        Ty::Orbit | Ty::Sample => None,
    }
}

/// Flattens a body: each value and variable gets its slots where it is defined; a component is its value's slot;
/// a comparison (which the code spells where it is used) is computed where it is used.
struct Flatten<'a> {
    body: &'a Body,
    /// The first slot of each value and variable, once defined.
    slots: Vec<Option<u32>>,
    code: Vec<Ins>,
    init: Vec<f64>,
    point: [Option<u32>; 3],
    bailout: Option<u32>,
    nums: Vec<(u32, u16)>,
    /// The jumps out of each open loop, to be pointed at its end.
    breaks: Vec<Vec<usize>>,
}

impl<'a> Flatten<'a> {
    fn new(body: &'a Body) -> Flatten<'a> {
        Flatten {
            body,
            slots: Vec::new(),
            code: Vec::new(),
            init: Vec::new(),
            point: [None; 3],
            bailout: None,
            nums: Vec::new(),
            breaks: Vec::new(),
        }
    }

    fn alloc(&mut self, ty: Ty, init: f64) -> Option<u32> {
        let first = self.init.len() as u32;
        self.init.extend(std::iter::repeat_n(init, width(ty)? as usize));
        Some(first)
    }

    fn set(&mut self, v: Val, slot: u32) {
        let i = v.0 as usize;
        if self.slots.len() <= i {
            self.slots.resize(i + 1, None);
        }
        self.slots[i] = Some(slot);
    }

    fn defined(&self, v: Val) -> Option<u32> {
        self.slots.get(v.0 as usize).copied().flatten()
    }

    /// The slot holding `v` here, writing the code that computes it where the lowered code spells it in place.
    fn operand(&mut self, v: Val) -> Option<u32> {
        let op = match self.body.op(v) {
            // A variable: its slots are its `Var`'s.
            None => return self.defined(v),
            Some(op) => op.clone(),
        };
        if let Op::Cmp(c, a, b) = op {
            let (a, b) = (self.operand(a)?, self.operand(b)?);
            let d = match self.defined(v) {
                Some(d) => d,
                None => self.alloc(Ty::Bool, 0.0)?,
            };
            self.set(v, d);
            self.code.push(Ins::Cmp(c, d, a, b));
            return Some(d);
        }
        if let Some(slot) = self.defined(v) {
            return Some(slot);
        }
        let slot = match op {
            Op::Lit(bits) => self.alloc(Ty::F, f64::from_bits(bits.0))?,
            Op::BoolLit(b) => self.alloc(Ty::Bool, if b { 1.0 } else { 0.0 })?,
            Op::IntLit(n) => self.alloc(Ty::Int, f64::from(n))?,
            Op::Param(i) => {
                let slot = self.alloc(Ty::F, 0.0)?;
                self.nums.push((slot, u16::try_from(i).ok()?));
                slot
            }
            Op::Arg("p") => {
                let slot = self.alloc(Ty::V3, 0.0)?;
                self.point = [Some(slot), Some(slot + 1), Some(slot + 2)];
                slot
            }
            Op::Arg("bailout") => {
                let slot = self.alloc(Ty::F, 0.0)?;
                self.bailout = Some(slot);
                slot
            }
            // A component is its value's slot; computed afresh per use, as the code spells it.
            Op::Comp(a, i) => return Some(self.operand(a)? + u32::from(i)),
            _ => return None,
        };
        self.set(v, slot);
        Some(slot)
    }

    fn copy(&mut self, d: u32, a: u32, ty: Ty) -> Option<()> {
        for k in 0..width(ty)? {
            self.code.push(Ins::Copy(d + k, a + k));
        }
        Some(())
    }

    fn stmts(&mut self, stmts: &[Stmt]) -> Option<()> {
        for s in stmts {
            match s {
                Stmt::Let { val, ty, op } => {
                    let d = self.alloc(*ty, 0.0)?;
                    self.op(d, *ty, op)?;
                    self.set(*val, d);
                }
                Stmt::Var { var, ty, init } => {
                    let a = self.operand(*init)?;
                    let d = self.alloc(*ty, 0.0)?;
                    self.copy(d, a, *ty)?;
                    self.set(*var, d);
                }
                Stmt::Assign { var, value } => {
                    let (d, a) = (self.defined(*var)?, self.operand(*value)?);
                    self.copy(d, a, self.body.ty(*var))?;
                }
                Stmt::If { cond, body } => {
                    let c = self.operand(*cond)?;
                    let at = self.code.len();
                    self.code.push(Ins::JumpUnless(c, 0));
                    self.stmts(body)?;
                    self.code[at] = Ins::JumpUnless(c, self.code.len() as u32);
                }
                Stmt::Loop { count, body } => {
                    let n = self.operand(*count)?;
                    let counter = self.alloc(Ty::Int, 0.0)?;
                    self.code.push(Ins::Copy(counter, n));
                    let head = self.code.len();
                    self.code.push(Ins::CountDown(counter, 0));
                    self.breaks.push(Vec::new());
                    self.stmts(body)?;
                    self.code.push(Ins::Jump(head as u32));
                    let end = self.code.len() as u32;
                    self.code[head] = Ins::CountDown(counter, end);
                    for at in self.breaks.pop()? {
                        if let Ins::JumpIf(c, _) = self.code[at] {
                            self.code[at] = Ins::JumpIf(c, end);
                        }
                    }
                }
                Stmt::BreakIf { cond } => {
                    let c = self.operand(*cond)?;
                    self.breaks.last_mut()?.push(self.code.len());
                    self.code.push(Ins::JumpIf(c, 0));
                }
            }
        }
        Some(())
    }

    /// The code computing `op` into the slots from `d`.
    fn op(&mut self, d: u32, ty: Ty, op: &Op) -> Option<()> {
        let ins = match op {
            Op::Neg(a) => Ins::Neg(d, self.operand(*a)?),
            Op::Bin(o, a, b) => Ins::Bin(*o, d, self.operand(*a)?, self.operand(*b)?),
            Op::Math(f, args) => match args.as_slice() {
                [a] => Ins::Math1(*f, d, self.operand(*a)?),
                [a, b] => Ins::Math2(*f, d, self.operand(*a)?, self.operand(*b)?),
                _ => return None,
            },
            Op::Logic(o, a, b) => Ins::Logic(*o, d, self.operand(*a)?, self.operand(*b)?),
            Op::Not(a) => Ins::Not(d, self.operand(*a)?),
            Op::MakeV3(x, y, z) => {
                for (k, v) in [*x, *y, *z].into_iter().enumerate() {
                    let a = self.operand(v)?;
                    self.code.push(Ins::Copy(d + k as u32, a));
                }
                return Some(());
            }
            Op::MakePair(x, y) => {
                for (k, v) in [*x, *y].into_iter().enumerate() {
                    let a = self.operand(v)?;
                    self.code.push(Ins::Copy(d + k as u32, a));
                }
                return Some(());
            }
            Op::Select(c, a, b) => {
                let (c, a, b) = (self.operand(*c)?, self.operand(*a)?, self.operand(*b)?);
                for k in 0..width(ty)? {
                    self.code.push(Ins::Select(d + k, c, a + k, b + k));
                }
                return Some(());
            }
            Op::Load(var) => {
                let a = self.defined(*var)?;
                return self.copy(d, a, ty);
            }
            _ => return None,
        };
        self.code.push(ins);
        Some(())
    }
}
