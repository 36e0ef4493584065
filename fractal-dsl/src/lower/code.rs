//! The lowered form every writer spells: typed SSA values in statement blocks with a little control flow (`if`,
//! counted loops with an early exit), built with constant folding, algebraic identities and common-subexpression
//! reuse so the kernels carry only work that matters. The tracer ([`mod@super::trace`]) records into a [`Builder`].

use std::collections::HashMap;

use crate::formula::Leaf;
use crate::ir::BinOp;

/// The type of a value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Ty {
    F,
    V3,
    /// A fractal's (distance, orbit trap).
    Pair,
    Bool,
    /// A loop count.
    Int,
    /// The frame's perturbation reference orbit ([`crate::number::Orbit`]), handed to the leaf function that reads it.
    Orbit,
    /// The scene's sample: distance and material ([`crate::eval::Sample`]).
    Sample,
}

/// The scene functions the ray program calls ([`crate::ray::SceneFns`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SceneFn {
    /// `scene_de(p)`: the distance.
    Distance,
    /// `scene_sample(p)` (or `scene_sample(p, dp)` with a perturbation reference): a [`Ty::Sample`].
    Sample,
    /// `scene_normal(p, e)`: the unit normal at p, taps e apart (V3); a scene shaded by its gradient reads no `e`.
    Normal,
    /// `scene_ao(p, n)`: ambient occlusion at p along the normal n.
    Occlusion,
    /// `scene_shadow(ro, rd, limit, eps)`: the light reaching ro along rd within limit.
    Shadow,
}

impl SceneFn {
    pub fn name(self) -> &'static str {
        match self {
            SceneFn::Distance => "scene_de",
            SceneFn::Sample => "scene_sample",
            SceneFn::Normal => "scene_normal",
            SceneFn::Occlusion => "scene_ao",
            SceneFn::Shadow => "scene_shadow",
        }
    }
    /// The type of the function's result.
    pub fn returns(self) -> Ty {
        match self {
            SceneFn::Sample => Ty::Sample,
            SceneFn::Normal => Ty::V3,
            SceneFn::Distance | SceneFn::Occlusion | SceneFn::Shadow => Ty::F,
        }
    }
}

/// The fields of a [`Ty::Sample`], in order, with their types.
pub const SAMPLE_FIELDS: [(&str, Ty); 6] = [
    ("distance", Ty::F),
    ("albedo", Ty::V3),
    ("ambient", Ty::F),
    ("diffuse", Ty::F),
    ("specular", Ty::F),
    ("shininess", Ty::F),
];

/// What the ray program reads of a kernel's frame ([`crate::back::FrameLayout`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FrameField {
    /// The camera's position relative to the anchor, and its right, up and forward axes (V3).
    Origin,
    Right,
    Up,
    Forward,
    /// The image's width and height in pixels (F).
    Width,
    Height,
    /// The pixel footprint per unit distance along a ray (F).
    Footprint,
    /// Light i's unit direction towards it (directional) or position relative to the anchor (point) (V3).
    LightPosition(usize),
    /// The frame's anchor: positions the ray program computes are relative to it, and the scene functions add it
    /// back ([`crate::eval::Env::anchor`]) (V3).
    Anchor,
    /// Light i's colour times intensity (V3).
    LightRadiance(usize),
}

impl FrameField {
    pub fn ty(self) -> Ty {
        match self {
            FrameField::Width | FrameField::Height | FrameField::Footprint => Ty::F,
            _ => Ty::V3,
        }
    }
    /// Where the frame holds it: the field and component of the frame uniform.
    pub fn path(self) -> String {
        match self {
            FrameField::Origin => "origin.xyz".into(),
            FrameField::Right => "right.xyz".into(),
            FrameField::Up => "up.xyz".into(),
            FrameField::Forward => "forward.xyz".into(),
            FrameField::Width => "right.w".into(),
            FrameField::Height => "up.w".into(),
            FrameField::Footprint => "forward.w".into(),
            FrameField::Anchor => "anchor.xyz".into(),
            FrameField::LightPosition(i) => format!("lights[{}].xyz", 2 * i),
            FrameField::LightRadiance(i) => format!("lights[{}].xyz", 2 * i + 1),
        }
    }
}

/// A value: an SSA name, or a mutable variable (see [`Stmt::Var`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Val(pub u32);

/// Scalar math functions (on F).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MathFn {
    Sin,
    Cos,
    Acos,
    /// `atan2(y, x)`.
    Atan2,
    Abs,
    Sqrt,
    Floor,
    Exp2,
    /// Natural logarithm.
    Ln,
    Min,
    Max,
    Pow,
}

impl MathFn {
    /// The value for constant arguments (f64; the kernels see it rounded to f32).
    pub fn fold(self, a: &[f64]) -> f64 {
        match self {
            MathFn::Sin => a[0].sin(),
            MathFn::Cos => a[0].cos(),
            MathFn::Acos => a[0].acos(),
            MathFn::Atan2 => a[0].atan2(a[1]),
            MathFn::Abs => a[0].abs(),
            MathFn::Sqrt => a[0].sqrt(),
            MathFn::Floor => a[0].floor(),
            MathFn::Exp2 => a[0].exp2(),
            MathFn::Ln => a[0].ln(),
            MathFn::Min => a[0].min(a[1]),
            MathFn::Max => a[0].max(a[1]),
            MathFn::Pow => a[0].powf(a[1]),
        }
    }
}

/// Comparisons (on F), giving a Bool.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CmpOp {
    Lt,
    Le,
}

impl CmpOp {
    pub fn symbol(self) -> &'static str {
        match self {
            CmpOp::Lt => "<",
            CmpOp::Le => "<=",
        }
    }
}

/// Logical operators on Bool.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LogicOp {
    And,
    Or,
}

/// Floats are compared by bits so literals can key the reuse table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Bits(pub u64);

#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Op {
    Lit(Bits),
    BoolLit(bool),
    IntLit(u32),
    Time,
    Param(usize),
    /// A parameter of the function being built, by name.
    Arg(&'static str),
    /// The frame's reference orbit, as an argument of a leaf call.
    Orbit,
    /// Entry (a Pair) of the frame's reference orbit at an index (an F holding a whole number ≤ the last index).
    OrbitEntry(Val),
    /// The index of the reference orbit's last entry (an F).
    OrbitLast,
    MakeV3(Val, Val, Val),
    /// A fractal's (distance, orbit trap).
    MakePair(Val, Val),
    /// Component 0..3 of a V3 or 0..2 of a Pair.
    Comp(Val, u8),
    Neg(Val),
    /// F∘F.
    Bin(BinOp, Val, Val),
    Math(MathFn, Vec<Val>),
    Call(Leaf, Vec<Val>),
    /// A call of a scene function.
    Scene(SceneFn, Vec<Val>),
    /// Field i of a Sample ([`SAMPLE_FIELDS`]).
    Field(Val, u8),
    /// A value of the kernel's frame.
    Frame(FrameField),
    Cmp(CmpOp, Val, Val),
    Logic(LogicOp, Val, Val),
    Not(Val),
    Select(Val, Val, Val),
    /// The current value of a variable.
    Load(Val),
}

#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    Let {
        val: Val,
        ty: Ty,
        op: Op,
    },
    Var {
        var: Val,
        ty: Ty,
        init: Val,
    },
    Assign {
        var: Val,
        value: Val,
    },
    If {
        cond: Val,
        body: Vec<Stmt>,
    },
    /// Runs `body` `count` times (an Int value); [`Stmt::BreakIf`] leaves it early.
    Loop {
        count: Val,
        body: Vec<Stmt>,
    },
    /// Leaves the innermost loop when `cond` holds.
    BreakIf {
        cond: Val,
    },
}

/// Values a writer spells in place rather than naming: the values that read no other (literals, time, params,
/// arguments, the frame's orbit), components and comparisons (whose operands are immutable values, so spelling them
/// where used reads the same numbers).
pub fn is_inline(op: &Op) -> bool {
    match op {
        // Named once where the ray program reads it (a local, not a load of the uniform at every use in a loop).
        Op::Frame(_) => false,
        Op::Comp(..) | Op::Field(..) | Op::Cmp(..) => true,
        _ => operands(op).is_empty(),
    }
}

/// What kind of block is open.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Block {
    Top,
    If,
    Loop,
}

/// Builds one function body.
#[derive(Debug)]
pub struct Builder {
    /// Type and defining op of every value (variables: their initial op is None).
    defs: Vec<(Ty, Option<Op>)>,
    /// Statement blocks under construction; the last is the innermost open block.
    blocks: Vec<(Block, Vec<Stmt>)>,
    /// Reuse tables, one per open block (a value defined inside a block is not visible after it).
    reuse: Vec<HashMap<Op, Val>>,
    /// The conditions of the `if`s open around the point being built: true there.
    holding: Vec<Val>,
}

impl Default for Builder {
    fn default() -> Self {
        Builder::new()
    }
}

impl Builder {
    pub fn new() -> Builder {
        Builder {
            defs: Vec::new(),
            blocks: vec![(Block::Top, Vec::new())],
            reuse: vec![HashMap::new()],
            holding: Vec::new(),
        }
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
    /// A truth value known here: a literal, or the condition of an `if` being built around this point.
    pub fn bool_value(&self, v: Val) -> Option<bool> {
        match self.op(v) {
            Some(Op::BoolLit(b)) => Some(*b),
            _ if self.holding.contains(&v) => Some(true),
            _ => None,
        }
    }

    fn push(&mut self, stmt: Stmt) {
        self.blocks.last_mut().expect("a block is always open").1.push(stmt);
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
    pub fn bool_lit(&mut self, v: bool) -> Val {
        self.emit(Ty::Bool, Op::BoolLit(v))
    }
    pub fn int(&mut self, v: u32) -> Val {
        self.emit(Ty::Int, Op::IntLit(v))
    }
    pub fn time(&mut self) -> Val {
        self.emit(Ty::F, Op::Time)
    }
    pub fn param(&mut self, i: usize) -> Val {
        self.emit(Ty::F, Op::Param(i))
    }
    /// A parameter of the function being built.
    pub fn arg(&mut self, name: &'static str, ty: Ty) -> Val {
        self.emit(ty, Op::Arg(name))
    }
    pub fn orbit(&mut self) -> Val {
        self.emit(Ty::Orbit, Op::Orbit)
    }
    pub fn orbit_entry(&mut self, index: Val) -> Val {
        self.emit(Ty::Pair, Op::OrbitEntry(index))
    }
    pub fn orbit_last(&mut self) -> Val {
        self.emit(Ty::F, Op::OrbitLast)
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
    pub fn pair(&mut self, distance: Val, trap: Val) -> Val {
        self.emit(Ty::Pair, Op::MakePair(distance, trap))
    }
    pub fn comp(&mut self, v: Val, i: u8) -> Val {
        match self.op(v) {
            Some(Op::MakeV3(x, y, z)) => return [*x, *y, *z][i as usize],
            Some(Op::MakePair(d, t)) => return [*d, *t][i as usize],
            _ => {}
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
        self.emit(Ty::F, Op::Neg(a))
    }

    /// Scalar arithmetic with folding (two literals) and identities (x+0, x−0, 0−x, x·1, x/1, x·−1, x·0).
    pub fn bin(&mut self, op: BinOp, a: Val, b: Val) -> Val {
        let (la, lb) = (self.lit_value(a), self.lit_value(b));
        // A fold that leaves the finite numbers (1/0, a formula's overflow) stays an operation: no language spells
        // an infinite literal alike, and the device computes it as it computes any other.
        if let (Some(x), Some(y)) = (la, lb) {
            let v = op.apply(x, y);
            if v.is_finite() {
                return self.lit(v);
            }
        }
        match (op, la, lb) {
            (BinOp::Add, Some(0.0), _) => return b,
            (BinOp::Add | BinOp::Sub, _, Some(0.0)) => return a,
            (BinOp::Sub, Some(0.0), _) => return self.neg(b),
            (BinOp::Mul, Some(1.0), _) => return b,
            (BinOp::Mul | BinOp::Div, _, Some(1.0)) => return a,
            (BinOp::Mul, _, Some(-1.0)) => return self.neg(a),
            (BinOp::Mul, Some(-1.0), _) => return self.neg(b),
            (BinOp::Mul, Some(0.0), _) | (BinOp::Mul, _, Some(0.0)) => return self.lit(0.0),
            _ => {}
        }
        self.emit(Ty::F, Op::Bin(op, a, b))
    }

    pub fn math(&mut self, f: MathFn, args: Vec<Val>) -> Val {
        if let Some(lits) = args.iter().map(|a| self.lit_value(*a)).collect::<Option<Vec<f64>>>() {
            let v = f.fold(&lits);
            if v.is_finite() {
                return self.lit(v);
            }
        }
        if matches!(f, MathFn::Min | MathFn::Max) && args[0] == args[1] {
            return args[0];
        }
        self.emit(Ty::F, Op::Math(f, args))
    }
    pub fn call(&mut self, leaf: Leaf, args: Vec<Val>) -> Val {
        let ty = match leaf.returns() {
            crate::formula::leaf::RetKind::F => Ty::F,
            crate::formula::leaf::RetKind::Pair => Ty::Pair,
        };
        self.emit(ty, Op::Call(leaf, args))
    }
    pub fn scene(&mut self, f: SceneFn, args: Vec<Val>) -> Val {
        self.emit(f.returns(), Op::Scene(f, args))
    }
    /// Field `i` of the Sample `v`.
    pub fn field(&mut self, v: Val, i: u8) -> Val {
        self.emit(SAMPLE_FIELDS[i as usize].1, Op::Field(v, i))
    }
    pub fn frame(&mut self, field: FrameField) -> Val {
        self.emit(field.ty(), Op::Frame(field))
    }
    pub fn cmp(&mut self, op: CmpOp, a: Val, b: Val) -> Val {
        if let (Some(x), Some(y)) = (self.lit_value(a), self.lit_value(b)) {
            return self.bool_lit(match op {
                CmpOp::Lt => x < y,
                CmpOp::Le => x <= y,
            });
        }
        self.emit(Ty::Bool, Op::Cmp(op, a, b))
    }
    pub fn logic(&mut self, op: LogicOp, a: Val, b: Val) -> Val {
        match (op, self.bool_value(a), self.bool_value(b)) {
            (LogicOp::And, Some(true), _) | (LogicOp::Or, Some(false), _) => b,
            (LogicOp::And, _, Some(true)) | (LogicOp::Or, _, Some(false)) => a,
            (LogicOp::And, Some(false), _) | (LogicOp::And, _, Some(false)) => self.bool_lit(false),
            (LogicOp::Or, Some(true), _) | (LogicOp::Or, _, Some(true)) => self.bool_lit(true),
            _ if a == b => a,
            _ => self.emit(Ty::Bool, Op::Logic(op, a, b)),
        }
    }
    pub fn not(&mut self, a: Val) -> Val {
        if let Some(v) = self.bool_value(a) {
            return self.bool_lit(!v);
        }
        if let Some(Op::Not(inner)) = self.op(a) {
            return *inner;
        }
        self.emit(Ty::Bool, Op::Not(a))
    }
    pub fn select(&mut self, cond: Val, a: Val, b: Val) -> Val {
        if a == b {
            return a;
        }
        match self.bool_value(cond) {
            Some(true) => return a,
            Some(false) => return b,
            None => {}
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

    fn open(&mut self, kind: Block) {
        self.blocks.push((kind, Vec::new()));
        self.reuse.push(HashMap::new());
    }
    fn close(&mut self, kind: Block) -> Vec<Stmt> {
        let (open, body) = self.blocks.pop().expect("a block was opened");
        assert_eq!(open, kind, "blocks close in the order they opened");
        self.reuse.pop();
        body
    }
    /// Opens `if (cond) { … }`; statements go inside until [`Builder::end_if`], and know `cond` true.
    pub fn begin_if(&mut self, cond: Val) {
        self.open(Block::If);
        self.holding.push(cond);
    }
    pub fn end_if(&mut self) {
        let body = self.close(Block::If);
        let cond = self.holding.pop().expect("an if was opened");
        self.push(Stmt::If { cond, body });
    }
    /// Opens a counted loop; statements go inside until [`Builder::end_loop`].
    pub fn begin_loop(&mut self) {
        self.open(Block::Loop);
    }
    /// Leaves the innermost loop unless `cond` holds (nothing is written when `cond` is the constant true).
    pub fn break_unless(&mut self, cond: Val) {
        let stop = self.not(cond);
        if self.bool_value(stop) != Some(false) {
            self.push(Stmt::BreakIf { cond: stop });
        }
    }
    pub fn end_loop(&mut self, count: Val) {
        let body = self.close(Block::Loop);
        self.push(Stmt::Loop { count, body });
    }

    /// Finishes the body: its statements and the type/op table the writers read.
    pub fn finish(mut self) -> Body {
        assert_eq!(self.blocks.len(), 1, "every block opened was closed");
        Body { stmts: self.blocks.pop().map(|(_, s)| s).unwrap_or_default(), defs: self.defs }
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

    /// The body without the values nothing reads: tracing records everything a formula computes (a fractal's orbit
    /// trap where only its distance is wanted, say); only what reaches `results` or control flow stays, and a
    /// variable nothing live reads goes with its assignments.
    pub fn pruned(mut self, results: &[Val]) -> Body {
        let mut live = vec![false; self.defs.len()];
        loop {
            let before = live.iter().filter(|l| **l).count();
            for &v in results {
                self.mark(v, &mut live);
            }
            self.mark_stmts(&self.stmts, &mut live);
            if live.iter().filter(|l| **l).count() == before {
                break;
            }
        }
        fn keep(stmts: Vec<Stmt>, live: &[bool]) -> Vec<Stmt> {
            stmts
                .into_iter()
                .filter_map(|s| match s {
                    Stmt::Let { val, .. } if !live[val.0 as usize] => None,
                    Stmt::Var { var, .. } | Stmt::Assign { var, .. } if !live[var.0 as usize] => None,
                    Stmt::If { cond, body } => Some(Stmt::If { cond, body: keep(body, live) }),
                    Stmt::Loop { count, body } => Some(Stmt::Loop { count, body: keep(body, live) }),
                    s => Some(s),
                })
                .collect()
        }
        self.stmts = keep(std::mem::take(&mut self.stmts), &live);
        self
    }

    /// Marks `v` live, with the operands of an inline value (spelled where it is used).
    fn mark(&self, v: Val, live: &mut [bool]) {
        live[v.0 as usize] = true;
        if let Some(op) = self.op(v).filter(|op| is_inline(op)) {
            for w in operands(op) {
                self.mark(w, live);
            }
        }
    }

    fn mark_stmts(&self, stmts: &[Stmt], live: &mut [bool]) {
        for s in stmts {
            match s {
                Stmt::Let { val, op, .. } => {
                    if live[val.0 as usize] {
                        for w in operands(op) {
                            self.mark(w, live);
                        }
                    }
                }
                // A variable's values matter only where something live reads it.
                Stmt::Var { var, init: v, .. } | Stmt::Assign { var, value: v } => {
                    if live[var.0 as usize] {
                        self.mark(*v, live)
                    }
                }
                Stmt::BreakIf { cond: v } => self.mark(*v, live),
                Stmt::If { cond: v, body } | Stmt::Loop { count: v, body } => {
                    self.mark(*v, live);
                    self.mark_stmts(body, live);
                }
            }
        }
    }
}

/// The values an op reads.
pub fn operands(op: &Op) -> Vec<Val> {
    match op {
        Op::Lit(_)
        | Op::BoolLit(_)
        | Op::IntLit(_)
        | Op::Time
        | Op::Param(_)
        | Op::Arg(_)
        | Op::Orbit
        | Op::OrbitLast
        | Op::Frame(_) => vec![],
        Op::MakeV3(a, b, c) | Op::Select(a, b, c) => vec![*a, *b, *c],
        Op::Comp(a, _) | Op::Field(a, _) | Op::Neg(a) | Op::Not(a) | Op::Load(a) | Op::OrbitEntry(a) => vec![*a],
        Op::Bin(_, a, b) | Op::Cmp(_, a, b) | Op::Logic(_, a, b) | Op::MakePair(a, b) => vec![*a, *b],
        Op::Math(_, args) | Op::Call(_, args) | Op::Scene(_, args) => args.clone(),
    }
}

/// Calls `f` on the op of every statement and on every inline value statements read, recursively through blocks.
pub fn visit_ops(body: &Body, f: &mut dyn FnMut(&Op)) {
    visit_stmts(body, &body.stmts, f)
}

fn visit_stmts(body: &Body, stmts: &[Stmt], f: &mut dyn FnMut(&Op)) {
    let inline = |v: Val, f: &mut dyn FnMut(&Op)| {
        if let Some(op) = body.op(v) {
            if is_inline(op) {
                f(op);
                for w in operands(op) {
                    if let Some(inner) = body.op(w).filter(|o| is_inline(o)) {
                        f(inner)
                    }
                }
            }
        }
    };
    for s in stmts {
        match s {
            Stmt::Let { op, .. } => {
                f(op);
                for v in operands(op) {
                    inline(v, f);
                }
            }
            Stmt::Var { init: v, .. } | Stmt::Assign { value: v, .. } | Stmt::BreakIf { cond: v } => inline(*v, f),
            Stmt::If { cond: v, body: inner } | Stmt::Loop { count: v, body: inner } => {
                inline(*v, f);
                visit_stmts(body, inner, f)
            }
        }
    }
}
