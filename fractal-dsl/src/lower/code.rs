//! The lowered form every writer spells: straight-line typed values with a little control flow, built with constant
//! folding, algebraic identities and common-subexpression reuse so the kernels carry only work that matters.

use std::collections::HashMap;

use crate::back::Helper;
use crate::ir::BinOp;

/// The type of a value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Ty {
    F,
    V3,
    /// A fractal's (distance, orbit trap).
    Pair,
    Bool,
}

/// A value: an SSA name, or a mutable variable (see [`Stmt::Var`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Val(pub u32);

/// Scalar math functions (on F).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MathFn {
    Sin,
    Cos,
    Abs,
    Sqrt,
    Floor,
    Min,
    Max,
    Pow,
    Clamp,
    Mix,
}

/// An argument of a helper call: a value or an integer immediate (iterations, levels).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Arg {
    Val(Val),
    Int(u32),
}

/// Floats are compared by bits so literals can key the reuse table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Bits(pub u64);

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    Lit(Bits),
    Time,
    Param(usize),
    /// The function's input point.
    Point,
    MakeV3(Val, Val, Val),
    /// Component 0..3 of a V3 or 0..2 of a Pair.
    Comp(Val, u8),
    Neg(Val),
    /// F∘F, V3∘V3, V3∘F (F∘V3 is never built: scalars go on the right).
    Bin(BinOp, Val, Val),
    Math(MathFn, Vec<Val>),
    Length(Val),
    Call(Helper, Vec<Arg>),
    Less(Val, Val),
    Select(Val, Val, Val),
    /// The current value of a variable.
    Load(Val),
}

#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    Let { val: Val, ty: Ty, op: Op },
    Var { var: Val, ty: Ty, init: Val },
    Assign { var: Val, value: Val },
    If { cond: Val, body: Vec<Stmt> },
}

/// Values a writer spells in place rather than naming: literals, time, params, the input point.
pub fn is_inline(op: &Op) -> bool {
    matches!(op, Op::Lit(_) | Op::Time | Op::Param(_) | Op::Point | Op::Less(..))
}

/// Builds one function body.
#[derive(Debug, Default)]
pub struct Builder {
    /// Type and defining op of every value (variables: their initial op is None).
    defs: Vec<(Ty, Option<Op>)>,
    /// Statement blocks under construction; the last is the innermost open `if`.
    blocks: Vec<Vec<Stmt>>,
    /// Reuse tables, one per open block (a value defined inside an `if` is not visible after it).
    reuse: Vec<HashMap<Op, Val>>,
}

impl Builder {
    pub fn new() -> Builder {
        Builder { defs: Vec::new(), blocks: vec![Vec::new()], reuse: vec![HashMap::new()] }
    }

    pub fn ty(&self, v: Val) -> Ty {
        self.defs[v.0 as usize].0
    }
    /// The op defining `v`, if it is an SSA value.
    pub fn op(&self, v: Val) -> Option<&Op> {
        self.defs[v.0 as usize].1.as_ref()
    }
    pub fn lit_value(&self, v: Val) -> Option<f64> {
        match self.op(v) {
            Some(Op::Lit(b)) => Some(f64::from_bits(b.0)),
            _ => None,
        }
    }

    fn push(&mut self, stmt: Stmt) {
        self.blocks.last_mut().expect("a block is always open").push(stmt);
    }

    fn emit(&mut self, ty: Ty, op: Op) -> Val {
        if !matches!(op, Op::Load(_)) {
            for table in self.reuse.iter().rev() {
                if let Some(v) = table.get(&op) {
                    return *v;
                }
            }
        }
        let val = Val(self.defs.len() as u32);
        self.defs.push((ty, Some(op.clone())));
        if !matches!(op, Op::Load(_)) {
            self.reuse.last_mut().expect("a table is always open").insert(op.clone(), val);
        }
        if !is_inline(&op) {
            self.push(Stmt::Let { val, ty, op });
        }
        val
    }

    pub fn lit(&mut self, v: f64) -> Val {
        // -0.0 and 0.0 behave alike in every formula here; one literal reads better.
        let v = if v == 0.0 { 0.0 } else { v };
        self.emit(Ty::F, Op::Lit(Bits(v.to_bits())))
    }
    pub fn time(&mut self) -> Val {
        self.emit(Ty::F, Op::Time)
    }
    pub fn param(&mut self, i: usize) -> Val {
        self.emit(Ty::F, Op::Param(i))
    }
    pub fn point(&mut self) -> Val {
        self.emit(Ty::V3, Op::Point)
    }
    pub fn v3(&mut self, x: Val, y: Val, z: Val) -> Val {
        if let (Some(Op::Comp(a, 0)), Some(Op::Comp(b, 1)), Some(Op::Comp(c, 2))) = (self.op(x), self.op(y), self.op(z))
        {
            if a == b && b == c && self.ty(*a) == Ty::V3 {
                return *a;
            }
        }
        self.emit(Ty::V3, Op::MakeV3(x, y, z))
    }
    pub fn v3_lits(&mut self, c: [f64; 3]) -> Val {
        let [x, y, z] = c.map(|v| self.lit(v));
        self.v3(x, y, z)
    }
    pub fn comp(&mut self, v: Val, i: u8) -> Val {
        if let Some(Op::MakeV3(x, y, z)) = self.op(v) {
            return [*x, *y, *z][i as usize];
        }
        self.emit(Ty::F, Op::Comp(v, i))
    }
    pub fn neg(&mut self, a: Val) -> Val {
        if let Some(x) = self.lit_value(a) {
            return self.lit(-x);
        }
        if let Some(Op::Neg(inner)) = self.op(a) {
            return *inner;
        }
        let ty = self.ty(a);
        self.emit(ty, Op::Neg(a))
    }

    /// Arithmetic with folding (two literals), identities (x+0, x·1, x/1, x·0 for scalars) and scalar-right order.
    pub fn bin(&mut self, op: BinOp, a: Val, b: Val) -> Val {
        let (ta, tb) = (self.ty(a), self.ty(b));
        if ta == Ty::F && tb == Ty::V3 {
            return match op {
                BinOp::Mul | BinOp::Add => self.bin(op, b, a),
                _ => {
                    let sa = self.splat(a);
                    self.bin(op, sa, b)
                }
            };
        }
        let (la, lb) = (self.lit_value(a), self.lit_value(b));
        if let (Some(x), Some(y)) = (la, lb) {
            return self.lit(op.apply(x, y));
        }
        let ty = if ta == Ty::V3 || tb == Ty::V3 { Ty::V3 } else { Ty::F };
        match (op, la, lb) {
            (BinOp::Add, Some(0.0), _) if tb == ty => return b,
            (BinOp::Add | BinOp::Sub, _, Some(0.0)) => return a,
            (BinOp::Sub, Some(0.0), _) if tb == ty => return self.neg(b),
            (BinOp::Mul, Some(1.0), _) if tb == ty => return b,
            (BinOp::Mul | BinOp::Div, _, Some(1.0)) => return a,
            (BinOp::Mul, _, Some(-1.0)) => return self.neg(a),
            (BinOp::Mul, Some(0.0), _) | (BinOp::Mul, _, Some(0.0)) if ty == Ty::F => return self.lit(0.0),
            _ => {}
        }
        self.emit(ty, Op::Bin(op, a, b))
    }
    pub fn add(&mut self, a: Val, b: Val) -> Val {
        self.bin(BinOp::Add, a, b)
    }
    pub fn sub(&mut self, a: Val, b: Val) -> Val {
        self.bin(BinOp::Sub, a, b)
    }
    pub fn mul(&mut self, a: Val, b: Val) -> Val {
        self.bin(BinOp::Mul, a, b)
    }
    pub fn div(&mut self, a: Val, b: Val) -> Val {
        self.bin(BinOp::Div, a, b)
    }
    pub fn splat(&mut self, a: Val) -> Val {
        self.emit(Ty::V3, Op::MakeV3(a, a, a))
    }

    pub fn math(&mut self, f: MathFn, args: Vec<Val>) -> Val {
        if let Some(lits) = args.iter().map(|a| self.lit_value(*a)).collect::<Option<Vec<f64>>>() {
            let v = match f {
                MathFn::Sin => lits[0].sin(),
                MathFn::Cos => lits[0].cos(),
                MathFn::Abs => lits[0].abs(),
                MathFn::Sqrt => lits[0].sqrt(),
                MathFn::Floor => lits[0].floor(),
                MathFn::Min => lits[0].min(lits[1]),
                MathFn::Max => lits[0].max(lits[1]),
                MathFn::Pow => lits[0].powf(lits[1]),
                MathFn::Clamp => lits[0].max(lits[1]).min(lits[2]),
                MathFn::Mix => lits[0] + (lits[1] - lits[0]) * lits[2],
            };
            return self.lit(v);
        }
        self.emit(Ty::F, Op::Math(f, args))
    }
    pub fn min(&mut self, a: Val, b: Val) -> Val {
        if a == b {
            return a;
        }
        self.math(MathFn::Min, vec![a, b])
    }
    pub fn max(&mut self, a: Val, b: Val) -> Val {
        if a == b {
            return a;
        }
        self.math(MathFn::Max, vec![a, b])
    }
    pub fn length(&mut self, v: Val) -> Val {
        self.emit(Ty::F, Op::Length(v))
    }
    pub fn call(&mut self, h: Helper, args: Vec<Arg>) -> Val {
        let ty = if h.returns_pair() { Ty::Pair } else { Ty::F };
        self.emit(ty, Op::Call(h, args))
    }
    pub fn less(&mut self, a: Val, b: Val) -> Val {
        self.emit(Ty::Bool, Op::Less(a, b))
    }
    pub fn select(&mut self, cond: Val, a: Val, b: Val) -> Val {
        if a == b {
            return a;
        }
        let ty = self.ty(a);
        self.emit(ty, Op::Select(cond, a, b))
    }

    /// Declares a mutable variable initialised to `init`.
    pub fn var(&mut self, init: Val) -> Val {
        let ty = self.ty(init);
        let var = Val(self.defs.len() as u32);
        self.defs.push((ty, None));
        self.push(Stmt::Var { var, ty, init });
        var
    }
    pub fn assign(&mut self, var: Val, value: Val) {
        self.push(Stmt::Assign { var, value });
    }
    pub fn load(&mut self, var: Val) -> Val {
        let ty = self.ty(var);
        self.emit(ty, Op::Load(var))
    }
    /// Opens `if (cond) { … }`; statements go inside until [`Builder::end_if`].
    pub fn begin_if(&mut self) {
        self.blocks.push(Vec::new());
        self.reuse.push(HashMap::new());
    }
    pub fn end_if(&mut self, cond: Val) {
        let body = self.blocks.pop().expect("begin_if opened a block");
        self.reuse.pop();
        self.push(Stmt::If { cond, body });
    }

    /// Finishes the body: its statements and the type/op table the writers read.
    pub fn finish(mut self) -> Body {
        assert_eq!(self.blocks.len(), 1, "every begin_if has its end_if");
        Body { stmts: self.blocks.pop().unwrap_or_default(), defs: self.defs }
    }
}

/// A finished function body.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    pub stmts: Vec<Stmt>,
    defs: Vec<(Ty, Option<Op>)>,
}

impl Body {
    pub fn ty(&self, v: Val) -> Ty {
        self.defs[v.0 as usize].0
    }
    pub fn op(&self, v: Val) -> Option<&Op> {
        self.defs[v.0 as usize].1.as_ref()
    }
    /// Whether `v` is a mutable variable rather than an SSA value.
    pub fn is_var(&self, v: Val) -> bool {
        self.defs[v.0 as usize].1.is_none()
    }
}
