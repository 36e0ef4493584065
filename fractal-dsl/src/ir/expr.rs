//! Scalar expressions: anything that stands where a number goes (a literal, `t`, a `param(..)`, arithmetic).

use std::fmt;

/// A named uniform the viewer can change without recompiling: `param("name", default, min..max)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamDecl {
    pub name: String,
    pub default: f64,
    pub min: f64,
    pub max: f64,
}

/// Binary arithmetic operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    Add,
    Sub,
    Mul,
    Div,
}

/// Built-in scalar functions callable in expressions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Func {
    Sin,
    Cos,
    Abs,
    Sqrt,
    Min,
    Max,
    Pow,
    Clamp,
    Mix,
    /// 2D gradient noise ([`crate::formula::noise`]).
    Noise2,
    Noise3,
    /// Octaves of 2D noise; the last argument is the octave count, a whole-number literal.
    Fbm2,
    Fbm3,
    /// The 2D Mandelbrot set's smooth escape count over the iteration count (the last argument, a whole-number
    /// literal), in (0, 1]; 0 inside the set.
    Mandelbrot,
}

impl Func {
    pub const ALL: [Func; 14] = [
        Func::Sin,
        Func::Cos,
        Func::Abs,
        Func::Sqrt,
        Func::Min,
        Func::Max,
        Func::Pow,
        Func::Clamp,
        Func::Mix,
        Func::Noise2,
        Func::Noise3,
        Func::Fbm2,
        Func::Fbm3,
        Func::Mandelbrot,
    ];
    /// Most arguments a function takes.
    pub const MAX_ARITY: usize = 4;
    /// The name used in scene source, and by every shading language.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Abs => "abs",
            Func::Sqrt => "sqrt",
            Func::Min => "min",
            Func::Max => "max",
            Func::Pow => "pow",
            Func::Clamp => "clamp",
            Func::Mix => "mix",
            Func::Noise2 => "noise2",
            Func::Noise3 => "noise3",
            Func::Fbm2 => "fbm2",
            Func::Fbm3 => "fbm3",
            Func::Mandelbrot => "mandelbrot",
        }
    }
    pub fn arity(self) -> usize {
        match self {
            Func::Sin | Func::Cos | Func::Abs | Func::Sqrt => 1,
            Func::Min | Func::Max | Func::Pow | Func::Noise2 => 2,
            Func::Clamp | Func::Mix | Func::Noise3 | Func::Fbm2 | Func::Mandelbrot => 3,
            Func::Fbm3 => 4,
        }
    }
    pub fn from_name(name: &str) -> Option<Func> {
        Func::ALL.into_iter().find(|f| f.name() == name)
    }
    /// For a function whose last argument is a count (a whole-number literal, not a value): its name and the
    /// largest count allowed.
    pub fn count_arg(self) -> Option<(&'static str, u32)> {
        match self {
            Func::Fbm2 | Func::Fbm3 => Some(("octaves", crate::formula::noise::MAX_OCTAVES)),
            Func::Mandelbrot => Some(("iterations", crate::formula::mandelbrot::MAX_MANDELBROT_ITERATIONS)),
            _ => None,
        }
    }
    /// Whether the last argument is a count ([`Func::count_arg`]).
    pub fn takes_count(self) -> bool {
        self.count_arg().is_some()
    }
    /// The count of a call from its last argument's literal (validation keeps it a whole number within
    /// [`Func::count_arg`]); 0 for other functions.
    pub fn count(self, last: Option<f64>) -> u32 {
        match (self.count_arg(), last) {
            (Some((_, most)), Some(n)) if n.is_finite() => n.clamp(0.0, most as f64) as u32,
            _ => 0,
        }
    }
}

/// A scalar expression.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Lit(f64),
    /// Scene time in seconds, `t` in source.
    Time,
    /// A coordinate of the point a distance is asked at, `x`, `y` or `z` in source (0, 1, 2): only a displacement
    /// (`.displace(..)`) and a material may read it.
    Point(u8),
    Param(Box<ParamDecl>),
    Neg(Box<Expr>),
    Bin(BinOp, Box<Expr>, Box<Expr>),
    Call(Func, Vec<Expr>),
}

impl Expr {
    /// The literal value, if this expression is one.
    pub fn as_lit(&self) -> Option<f64> {
        match self {
            Expr::Lit(v) => Some(*v),
            _ => None,
        }
    }
    /// Number of nodes, for the size cap.
    pub fn size(&self) -> usize {
        match self {
            Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => 1,
            Expr::Neg(e) => 1 + e.size(),
            Expr::Bin(_, a, b) => 1 + a.size() + b.size(),
            Expr::Call(_, args) => 1 + args.iter().map(Expr::size).sum::<usize>(),
        }
    }
    /// Calls `f` on every parameter declaration in this expression.
    pub fn visit_params<'a>(&'a self, f: &mut dyn FnMut(&'a ParamDecl)) {
        match self {
            Expr::Lit(_) | Expr::Time | Expr::Point(_) => {}
            Expr::Param(p) => f(p),
            Expr::Neg(e) => e.visit_params(f),
            Expr::Bin(_, a, b) => {
                a.visit_params(f);
                b.visit_params(f);
            }
            Expr::Call(_, args) => args.iter().for_each(|a| a.visit_params(f)),
        }
    }
    /// Whether the expression reads `t`.
    pub fn uses_time(&self) -> bool {
        match self {
            Expr::Time => true,
            Expr::Lit(_) | Expr::Point(_) | Expr::Param(_) => false,
            Expr::Neg(e) => e.uses_time(),
            Expr::Bin(_, a, b) => a.uses_time() || b.uses_time(),
            Expr::Call(_, args) => args.iter().any(Expr::uses_time),
        }
    }
    /// Whether the expression reads the point (`x`, `y`, `z`).
    pub fn uses_point(&self) -> bool {
        match self {
            Expr::Point(_) => true,
            Expr::Lit(_) | Expr::Time | Expr::Param(_) => false,
            Expr::Neg(e) => e.uses_point(),
            Expr::Bin(_, a, b) => a.uses_point() || b.uses_point(),
            Expr::Call(_, args) => args.iter().any(Expr::uses_point),
        }
    }
    /// Evaluates with the given time and parameter lookup (host-side: lights, camera, folding checks). The point is
    /// not known here: `x`, `y` and `z` are NaN (validation keeps them inside displacements).
    pub fn eval(&self, time: f64, param: &dyn Fn(&ParamDecl) -> f64) -> f64 {
        match self {
            Expr::Lit(v) => *v,
            Expr::Time => time,
            Expr::Point(_) => f64::NAN,
            Expr::Param(p) => param(p),
            Expr::Neg(e) => -e.eval(time, param),
            Expr::Bin(op, a, b) => op.apply(a.eval(time, param), b.eval(time, param)),
            Expr::Call(f, args) => {
                let v: Vec<f64> = args.iter().map(|a| a.eval(time, param)).collect();
                f.apply(&v, f.count(args.last().and_then(Expr::as_lit)))
            }
        }
    }
    /// Evaluates with parameters at their defaults.
    pub fn eval_default(&self, time: f64) -> f64 {
        self.eval(time, &|p| p.default)
    }
}

impl BinOp {
    /// Applies the operator in any [`crate::number::Num`] (f64 for folding).
    pub fn apply<F: crate::number::Num>(self, a: F, b: F) -> F {
        match self {
            BinOp::Add => a + b,
            BinOp::Sub => a - b,
            BinOp::Mul => a * b,
            BinOp::Div => a / b,
        }
    }
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
        }
    }
}

impl Func {
    /// Applies the function: the semantics every backend must reproduce, in f64 for folding and host-side values and
    /// in f32 or f64 for the interpreter. Noise and the Mandelbrot pattern run through the leaf table (one function
    /// per kernel); `count` is the literal count of those that take one (see [`Func::count`]), unused otherwise.
    pub fn apply<F: crate::formula::CallLeaf>(self, v: &[F], count: u32) -> F {
        use crate::formula::leaf::LeafArg;
        use crate::formula::Leaf;
        use crate::number::*;
        // Made only for the functions that take a count, so the others trace no extra constant.
        let counted = || LeafArg::Count(F::count(count));
        match self {
            Func::Sin => sin(v[0]),
            Func::Cos => cos(v[0]),
            Func::Abs => abs(v[0]),
            Func::Sqrt => sqrt(v[0]),
            Func::Min => min(v[0], v[1]),
            Func::Max => max(v[0], v[1]),
            Func::Pow => pow(v[0], v[1]),
            Func::Clamp => clamp(v[0], v[1], v[2]),
            Func::Mix => mix(v[0], v[1], v[2]),
            Func::Noise2 => F::leaf(Leaf::Noise2, &[LeafArg::F(v[0]), LeafArg::F(v[1])]).distance(),
            Func::Noise3 => F::leaf(Leaf::Noise3, &[LeafArg::V3(crate::number::math::v3(v[0], v[1], v[2]))]).distance(),
            Func::Fbm2 => F::leaf(Leaf::Fbm2, &[LeafArg::F(v[0]), LeafArg::F(v[1]), counted()]).distance(),
            Func::Fbm3 => {
                F::leaf(Leaf::Fbm3, &[LeafArg::V3(crate::number::math::v3(v[0], v[1], v[2])), counted()]).distance()
            }
            Func::Mandelbrot => {
                let inverse = LeafArg::F(F::lit(crate::formula::mandelbrot::inverse_count(count)));
                F::leaf(Leaf::Mandelbrot, &[LeafArg::F(v[0]), LeafArg::F(v[1]), counted(), inverse]).distance()
            }
        }
    }
}

macro_rules! from_num {
    ($($t:ty),*) => {$(
        impl From<$t> for Expr {
            fn from(v: $t) -> Expr { Expr::Lit(v as f64) }
        }
    )*};
}
from_num!(f32, f64, i32, u32);

macro_rules! expr_ops {
    ($($tr:ident $f:ident $op:ident),*) => {$(
        impl<R: Into<Expr>> core::ops::$tr<R> for Expr {
            type Output = Expr;
            fn $f(self, r: R) -> Expr { Expr::Bin(BinOp::$op, Box::new(self), Box::new(r.into())) }
        }
        impl core::ops::$tr<Expr> for f64 {
            type Output = Expr;
            fn $f(self, r: Expr) -> Expr { Expr::Bin(BinOp::$op, Box::new(Expr::Lit(self)), Box::new(r)) }
        }
        impl core::ops::$tr<Expr> for f32 {
            type Output = Expr;
            fn $f(self, r: Expr) -> Expr { Expr::Bin(BinOp::$op, Box::new(Expr::Lit(self as f64)), Box::new(r)) }
        }
    )*};
}
expr_ops!(Add add Add, Sub sub Sub, Mul mul Mul, Div div Div);

impl core::ops::Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        Expr::Neg(Box::new(self))
    }
}

/// A 3-vector of expressions (`vec3(..)` and `rgb(..)` in source).
#[derive(Clone, Debug, PartialEq)]
pub struct Vec3Expr(pub [Expr; 3]);

impl Vec3Expr {
    pub fn lits(&self) -> Option<[f64; 3]> {
        Some([self.0[0].as_lit()?, self.0[1].as_lit()?, self.0[2].as_lit()?])
    }
    pub fn eval(&self, time: f64, param: &dyn Fn(&ParamDecl) -> f64) -> [f64; 3] {
        [self.0[0].eval(time, param), self.0[1].eval(time, param), self.0[2].eval(time, param)]
    }
    pub fn eval_default(&self, time: f64) -> [f64; 3] {
        self.eval(time, &|p| p.default)
    }
    pub fn splat(e: impl Into<Expr>) -> Vec3Expr {
        let e = e.into();
        Vec3Expr([e.clone(), e.clone(), e])
    }
}

impl From<glam::Vec3> for Vec3Expr {
    fn from(v: glam::Vec3) -> Self {
        Vec3Expr([v.x.into(), v.y.into(), v.z.into()])
    }
}
impl From<glam::DVec3> for Vec3Expr {
    fn from(v: glam::DVec3) -> Self {
        Vec3Expr([v.x.into(), v.y.into(), v.z.into()])
    }
}
impl From<[f64; 3]> for Vec3Expr {
    fn from(v: [f64; 3]) -> Self {
        Vec3Expr(v.map(Expr::Lit))
    }
}

/// A 4-vector of expressions (`vec4(..)`: the quaternion Julia constant).
#[derive(Clone, Debug, PartialEq)]
pub struct Vec4Expr(pub [Expr; 4]);

impl From<glam::Vec4> for Vec4Expr {
    fn from(v: glam::Vec4) -> Self {
        Vec4Expr([v.x.into(), v.y.into(), v.z.into(), v.w.into()])
    }
}
impl From<[f64; 4]> for Vec4Expr {
    fn from(v: [f64; 4]) -> Self {
        Vec4Expr(v.map(Expr::Lit))
    }
}

impl fmt::Display for BinOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.symbol())
    }
}

/// Expressions built in Rust (`e = e + 1.0` in a loop) may nest far deeper than the native stack allows: as for
/// [`super::Node`], operands are moved onto a heap stack so each node drops with nothing left to recurse into.
impl Drop for Expr {
    fn drop(&mut self) {
        let mut pending = Vec::new();
        self.detach_operands(&mut pending);
        while let Some(mut e) = pending.pop() {
            e.detach_operands(&mut pending);
        }
    }
}

impl Expr {
    fn detach_operands(&mut self, into: &mut Vec<Expr>) {
        let mut detach = |e: &mut Box<Expr>| {
            if matches!(**e, Expr::Neg(_) | Expr::Bin(..) | Expr::Call(..)) {
                into.push(std::mem::replace(e, Expr::Time));
            }
        };
        match self {
            Expr::Neg(a) => detach(a),
            Expr::Bin(_, a, b) => {
                detach(a);
                detach(b);
            }
            Expr::Call(_, args) => into.append(args),
            Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => {}
        }
    }
}
