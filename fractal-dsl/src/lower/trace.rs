//! Tracing: the symbolic [`Num`] that records the formulas it runs into lowered code ([`super::code`]).
//!
//! A [`Sym`] is a value in the function being traced; arithmetic, math, comparisons and selects on it append to that
//! function's [`Builder`] (held per thread while [`trace`] runs, so formulas need no context argument). Loops
//! ([`Num::iterate`]) become counted loops with an early exit over variables; [`Num::when`] becomes an `if` over
//! variables; a call of a leaf ([`CallLeaf::leaf`]) becomes a call of the named function, whose body is traced once by
//! [`trace_leaf`].

use std::cell::RefCell;
use std::ops::{Add, BitAnd, BitOr, Div, Mul, Neg, Not, Sub};

use super::code::{Body, Builder, CmpOp, FrameField, LogicOp, MathFn, SceneFn, Ty, Val};
use crate::formula::leaf::{ArgKind, LeafArg, LeafOut, RetKind};
use crate::formula::{CallLeaf, Leaf};
use crate::ir::BinOp;
use crate::number::math::{v3, V3};
use crate::number::{Carry, Mask, Num};

thread_local! {
    /// The builders of the functions being traced on this thread, innermost last.
    static TRACING: RefCell<Vec<Builder>> = const { RefCell::new(Vec::new()) };
}

/// Runs `f` on the builder of the function being traced.
fn with<R>(f: impl FnOnce(&mut Builder) -> R) -> R {
    TRACING.with(|t| {
        let mut stack = t.borrow_mut();
        let b = stack.last_mut().expect("symbolic values exist only inside lower::trace::trace");
        f(b)
    })
}

/// Traces `f` into a fresh function body: `f` makes its arguments with the builder and returns its results.
pub fn trace<R>(f: impl FnOnce() -> R) -> (Body, R) {
    TRACING.with(|t| t.borrow_mut().push(Builder::new()));
    // Pop the builder even if `f` panics, so a later trace on this thread starts clean.
    struct Pop;
    impl Drop for Pop {
        fn drop(&mut self) {
            TRACING.with(|t| t.borrow_mut().pop());
        }
    }
    let guard = Pop;
    let result = f();
    let builder = TRACING.with(|t| t.borrow_mut().pop()).expect("the builder pushed above");
    std::mem::forget(guard);
    (builder.finish(), result)
}

/// A number in the function being traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sym(pub Val);

/// A truth value in the function being traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SymMask(pub Val);

/// A loop count in the function being traced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SymCount(pub Val);

impl Sym {
    /// A named parameter of type F.
    pub fn arg(name: &'static str) -> Sym {
        Sym(Sym::arg_of(name, Ty::F))
    }
    /// A named parameter of any type.
    pub fn arg_of(name: &'static str, ty: Ty) -> Val {
        with(|b| b.arg(name, ty))
    }
    pub fn time() -> Sym {
        Sym(with(|b| b.time()))
    }
    pub fn param(slot: usize) -> Sym {
        Sym(with(|b| b.param(slot)))
    }
    /// The components of a V3 value.
    pub fn components(v: Val) -> V3<Sym> {
        let [x, y, z] = [0, 1, 2].map(|i| Sym(with(|b| b.comp(v, i))));
        v3(x, y, z)
    }
    /// A V3 value from components.
    pub fn vector(v: V3<Sym>) -> Val {
        with(|b| b.v3(v.x.0, v.y.0, v.z.0))
    }
    /// A call of a scene function.
    pub fn scene_call(f: SceneFn, args: Vec<Val>) -> Val {
        with(|b| b.scene(f, args))
    }
    /// Field `i` of a Sample value ([`super::code::SAMPLE_FIELDS`]).
    pub fn field(sample: Val, i: u8) -> Val {
        with(|b| b.field(sample, i))
    }
    /// A value of the kernel's frame.
    pub fn frame(field: FrameField) -> Val {
        with(|b| b.frame(field))
    }
}

macro_rules! sym_bin {
    ($($tr:ident $f:ident $op:ident),*) => {$(
        impl $tr for Sym {
            type Output = Sym;
            fn $f(self, o: Sym) -> Sym {
                Sym(with(|b| b.bin(BinOp::$op, self.0, o.0)))
            }
        }
    )*};
}
sym_bin!(Add add Add, Sub sub Sub, Mul mul Mul, Div div Div);

impl Neg for Sym {
    type Output = Sym;
    fn neg(self) -> Sym {
        Sym(with(|b| b.neg(self.0)))
    }
}

impl BitAnd for SymMask {
    type Output = SymMask;
    fn bitand(self, o: SymMask) -> SymMask {
        SymMask(with(|b| b.logic(LogicOp::And, self.0, o.0)))
    }
}
impl BitOr for SymMask {
    type Output = SymMask;
    fn bitor(self, o: SymMask) -> SymMask {
        SymMask(with(|b| b.logic(LogicOp::Or, self.0, o.0)))
    }
}
impl Not for SymMask {
    type Output = SymMask;
    fn not(self) -> SymMask {
        SymMask(with(|b| b.not(self.0)))
    }
}
impl Mask for SymMask {
    fn splat(v: bool) -> Self {
        SymMask(with(|b| b.bool_lit(v)))
    }
}

impl Carry<Sym> for Sym {
    fn map_nums(self, f: &mut impl FnMut(Sym) -> Sym) -> Self {
        f(self)
    }
    fn zip_nums(self, other: Self, f: &mut impl FnMut(Sym, Sym) -> Sym) -> Self {
        f(self, other)
    }
}

fn math(f: MathFn, args: &[Sym]) -> Sym {
    Sym(with(|b| b.math(f, args.iter().map(|a| a.0).collect())))
}

/// Turns every number of `state` into a variable, loaded afresh by [`load_all`].
fn declare_all<S: Carry<Sym>>(state: S) -> S {
    state.map_nums(&mut |v| Sym(with(|b| b.var(v.0))))
}
fn load_all<S: Carry<Sym>>(vars: S) -> S {
    vars.map_nums(&mut |v| Sym(with(|b| b.load(v.0))))
}
/// Assigns each variable of `vars` its number in `values`, where that is not the variable's `current` value (a
/// number the step left alone needs no assignment, and a variable never assigned is a constant).
fn assign_changed<S: Carry<Sym>>(vars: S, current: S, values: S) -> S {
    let mut loaded = Vec::new();
    current.map_nums(&mut |v| {
        loaded.push(v);
        v
    });
    let mut k = 0;
    vars.zip_nums(values, &mut |var, value| {
        if value != loaded[k] {
            with(|b| b.assign(var.0, value.0));
        }
        k += 1;
        var
    })
}

impl Num for Sym {
    type Mask = SymMask;
    type Count = SymCount;

    fn lit(v: f64) -> Self {
        Sym(with(|b| b.lit(v)))
    }
    fn count(n: u32) -> SymCount {
        SymCount(with(|b| b.int(n)))
    }
    fn abs(x: Self) -> Self {
        math(MathFn::Abs, &[x])
    }
    fn sqrt(x: Self) -> Self {
        math(MathFn::Sqrt, &[x])
    }
    fn floor(x: Self) -> Self {
        math(MathFn::Floor, &[x])
    }
    fn sin(x: Self) -> Self {
        math(MathFn::Sin, &[x])
    }
    fn cos(x: Self) -> Self {
        math(MathFn::Cos, &[x])
    }
    fn acos(x: Self) -> Self {
        math(MathFn::Acos, &[x])
    }
    fn atan2(y: Self, x: Self) -> Self {
        math(MathFn::Atan2, &[y, x])
    }
    fn exp2(x: Self) -> Self {
        math(MathFn::Exp2, &[x])
    }
    fn ln(x: Self) -> Self {
        math(MathFn::Ln, &[x])
    }
    fn pow(x: Self, y: Self) -> Self {
        math(MathFn::Pow, &[x, y])
    }
    fn min(a: Self, b: Self) -> Self {
        math(MathFn::Min, &[a, b])
    }
    fn max(a: Self, b: Self) -> Self {
        math(MathFn::Max, &[a, b])
    }
    fn lt(a: Self, b: Self) -> SymMask {
        SymMask(with(|bl| bl.cmp(CmpOp::Lt, a.0, b.0)))
    }
    fn le(a: Self, b: Self) -> SymMask {
        SymMask(with(|bl| bl.cmp(CmpOp::Le, a.0, b.0)))
    }
    fn select(m: SymMask, a: Self, b: Self) -> Self {
        Sym(with(|bl| bl.select(m.0, a.0, b.0)))
    }
    fn mix(a: Self, b: Self, t: Self) -> Self {
        // Mixing a value with itself (a material field two shapes share) is that value.
        if a == b {
            return a;
        }
        a + (b - a) * t
    }

    fn iterate<S: Carry<Self>>(n: SymCount, init: S, active: impl Fn(&S) -> SymMask, step: impl Fn(S) -> S) -> S {
        let vars = declare_all(init);
        with(|b| b.begin_loop());
        let current = load_all(vars);
        let go_on = active(&current);
        with(|b| b.break_unless(go_on.0));
        let next = step(current);
        let vars = assign_changed(vars, current, next);
        with(|b| b.end_loop(n.0));
        load_all(vars)
    }

    fn orbit_entry(_orbit: crate::number::Orbit<'_>, index: Self) -> [Self; 2] {
        let entry = with(|b| b.orbit_entry(index.0));
        [0, 1].map(|i| Sym(with(|b| b.comp(entry, i))))
    }
    fn orbit_last(_orbit: crate::number::Orbit<'_>) -> Self {
        Sym(with(|b| b.orbit_last()))
    }

    fn when<S: Carry<Self>>(cond: SymMask, state: S, body: impl FnOnce(S) -> S) -> S {
        match with(|b| b.bool_value(cond.0)) {
            Some(true) => return body(state),
            Some(false) => return state,
            None => {}
        }
        let vars = declare_all(state);
        with(|b| b.begin_if(cond.0));
        let loaded = load_all(vars);
        let next = body(loaded);
        let vars = assign_changed(vars, loaded, next);
        with(|b| b.end_if());
        load_all(vars)
    }
}

impl CallLeaf for Sym {
    fn leaf(leaf: Leaf, args: &[LeafArg<Self>]) -> LeafOut<Self> {
        let vals: Vec<Val> = args
            .iter()
            .map(|a| match a {
                LeafArg::F(x) => x.0,
                LeafArg::V3(v) => Sym::vector(*v),
                LeafArg::Count(n) => n.0,
                LeafArg::Orbit(_) => with(|b| b.orbit()),
            })
            .collect();
        let result = with(|b| b.call(leaf, vals));
        match leaf.returns() {
            RetKind::F => LeafOut::F(Sym(result)),
            RetKind::Pair => LeafOut::Pair([0, 1].map(|i| Sym(with(|b| b.comp(result, i))))),
        }
    }
}

/// A leaf function traced into a named function of the lowered code.
#[derive(Clone, Debug, PartialEq)]
pub struct Function {
    pub leaf: Leaf,
    /// Parameter names and types, in order.
    pub params: Vec<(&'static str, Ty)>,
    pub body: Body,
    /// The returned value (F or Pair).
    pub result: Val,
    pub returns: Ty,
}

impl Function {
    pub fn name(&self) -> &'static str {
        self.leaf.name()
    }
}

/// Traces the body of `leaf` with symbolic parameters.
pub fn trace_leaf(leaf: Leaf) -> Function {
    let params: Vec<(&'static str, Ty)> = leaf
        .params()
        .iter()
        .map(|&(name, kind)| {
            let ty = match kind {
                ArgKind::F => Ty::F,
                ArgKind::V3 => Ty::V3,
                ArgKind::Count => Ty::Int,
                ArgKind::Orbit => Ty::Orbit,
            };
            (name, ty)
        })
        .collect();
    let (body, (result, returns)) = trace(|| {
        let args: Vec<LeafArg<Sym>> = params
            .iter()
            .map(|&(name, ty)| match ty {
                Ty::V3 => LeafArg::V3(Sym::components(Sym::arg_of(name, Ty::V3))),
                Ty::Int => LeafArg::Count(SymCount(Sym::arg_of(name, Ty::Int))),
                // The orbit is the frame's: its entries are read by `Num::orbit_entry`, not from this slice.
                Ty::Orbit => LeafArg::Orbit(&[]),
                _ => LeafArg::F(Sym::arg(name)),
            })
            .collect();
        match leaf.eval(&args) {
            LeafOut::F(d) => (d.0, Ty::F),
            LeafOut::Pair([d, t]) => (with(|b| b.pair(d.0, t.0)), Ty::Pair),
        }
    });
    Function { leaf, params, body: body.pruned(&[result]), result, returns }
}
