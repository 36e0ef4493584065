//! The formula language: the iteration map of a fractal as a closure, `|z, c| expression`, over numbers, vectors
//! (vec2 for complex numbers, vec3, vec4 for quaternions) and truth values, with `let` bindings and `if` expressions.
//! The parser (`crate::parse::formula`) checks every type; the evaluator ([`crate::formula::user`]) runs a map in any
//! [`crate::number::Num`], and so in dual numbers for its derivative.
//!
//! A map's scene numbers (`t`, `param(..)`, literals) are `N`: the IR's expressions in a scene
//! ([`crate::ir::formula::Formula`]), indices of numbers computed ahead when a formula runs.

/// Arithmetic, per component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FBin {
    Add,
    Sub,
    Mul,
    Div,
}

impl FBin {
    pub fn symbol(self) -> &'static str {
        match self {
            FBin::Add => "+",
            FBin::Sub => "-",
            FBin::Mul => "*",
            FBin::Div => "/",
        }
    }
}

/// The type of a formula value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FTy {
    Num,
    /// A vector of 2, 3 or 4 numbers.
    Vec(u8),
    Bool,
}

impl FTy {
    /// How messages name it.
    pub fn name(self) -> &'static str {
        match self {
            FTy::Num => "a number",
            FTy::Vec(2) => "a vec2",
            FTy::Vec(3) => "a vec3",
            FTy::Vec(_) => "a vec4",
            FTy::Bool => "a truth value",
        }
    }
    /// Numbers in a value of this type.
    pub fn width(self) -> usize {
        match self {
            FTy::Num | FTy::Bool => 1,
            FTy::Vec(n) => n as usize,
        }
    }
}

/// Comparisons, giving truth values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FCmp {
    Lt,
    Le,
    Gt,
    Ge,
}

impl FCmp {
    pub fn symbol(self) -> &'static str {
        match self {
            FCmp::Lt => "<",
            FCmp::Le => "<=",
            FCmp::Gt => ">",
            FCmp::Ge => ">=",
        }
    }
}

/// `&&` and `||` on truth values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FLogic {
    And,
    Or,
}

macro_rules! formula_functions {
    ($($variant:ident $name:literal $arity:literal: $doc:literal;)*) => {
        /// The functions a formula may call. Unary math and `min`, `max`, `clamp`, `mix` apply per component to
        /// vectors, a number standing for every component.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum FFunc {
            $(#[doc = $doc] $variant,)*
        }

        impl FFunc {
            pub const ALL: &'static [FFunc] = &[$(FFunc::$variant,)*];
            /// The name in scene source.
            pub fn name(self) -> &'static str {
                match self {
                    $(FFunc::$variant => $name,)*
                }
            }
            pub fn arity(self) -> usize {
                match self {
                    $(FFunc::$variant => $arity,)*
                }
            }
            /// One line for the documentation.
            pub fn doc(self) -> &'static str {
                match self {
                    $(FFunc::$variant => $doc,)*
                }
            }
        }
    };
}

formula_functions! {
    Vec2 "vec2" 2: "vec2(x, y): a vector, or a complex number x + iy";
    Vec3 "vec3" 3: "vec3(x, y, z)";
    Vec4 "vec4" 4: "vec4(x, y, z, w): a vector, or the quaternion x + iy + jz + kw";
    Length "length" 1: "length(v): the Euclidean length";
    Dot "dot" 2: "dot(a, b)";
    Cross "cross" 2: "cross(a, b) of two vec3";
    Normalize "normalize" 1: "normalize(v): v / length(v), 0 for the zero vector";
    Abs "abs" 1: "abs(x), per component";
    Sign "sign" 1: "sign(x): −1, 0 or 1, per component";
    Floor "floor" 1: "floor(x), per component";
    Fract "fract" 1: "fract(x) = x − floor(x), per component";
    Sqrt "sqrt" 1: "sqrt(x), per component";
    Sin "sin" 1: "sin(x), per component";
    Cos "cos" 1: "cos(x), per component";
    Tan "tan" 1: "tan(x), per component";
    Asin "asin" 1: "asin(x), per component";
    Acos "acos" 1: "acos(x), per component";
    Atan "atan" 1: "atan(x), per component";
    Atan2 "atan2" 2: "atan2(y, x): the angle of (x, y)";
    Exp "exp" 1: "exp(x), per component";
    Ln "ln" 1: "ln(x): the natural logarithm, per component";
    Pow "pow" 2: "pow(x, y) of numbers; of a vector and a number, per component";
    Min "min" 2: "min(a, b), per component";
    Max "max" 2: "max(a, b), per component";
    Clamp "clamp" 3: "clamp(x, lo, hi), per component";
    Mix "mix" 3: "mix(a, b, t) = a + (b − a)·t, per component";
    Cmul "cmul" 2: "cmul(a, b): the product of two complex numbers (vec2)";
    Csqr "csqr" 1: "csqr(a): a complex number (vec2) squared";
    Qmul "qmul" 2: "qmul(a, b): the product of two quaternions (vec4)";
    Qsqr "qsqr" 1: "qsqr(a): a quaternion (vec4) squared";
    BoxFold "box_fold" 2: "box_fold(v, limit): each component folded at ±limit, clamp(x, −l, l)·2 − x";
    SphereFold "sphere_fold" 3: "sphere_fold(v, min_radius, fixed_radius): the Mandelbox's sphere inversion";
}

impl FFunc {
    pub fn from_name(name: &str) -> Option<FFunc> {
        FFunc::ALL.iter().copied().find(|f| f.name() == name)
    }
}

/// A component selection: `v.x`, `v.zy`, `v.xyz`; the indices 0..4 for x, y, z, w.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Swizzle {
    pub len: u8,
    pub index: [u8; 4],
}

impl Swizzle {
    pub const LETTERS: [char; 4] = ['x', 'y', 'z', 'w'];
    /// The swizzle's letters: `xy`.
    pub fn text(&self) -> String {
        self.index[..self.len as usize].iter().map(|&i| Self::LETTERS[i as usize]).collect()
    }
}

/// An expression of a formula; `N` is a scene number.
#[derive(Clone, Debug, PartialEq)]
pub enum FExpr<N> {
    /// A number of the scene: a literal, `t`, `param(..)`.
    Num(N),
    /// The closure's argument: 0 is z, 1 is c.
    Arg(u8),
    /// The value of a `let` binding of the map, by its index.
    Let(u16),
    Neg(Box<FExpr<N>>),
    /// Arithmetic on numbers and vectors, per component, a number standing for every component.
    Bin(FBin, Box<FExpr<N>>, Box<FExpr<N>>),
    Call(FFunc, Vec<FExpr<N>>),
    Swizzle(Box<FExpr<N>>, Swizzle),
    Cmp(FCmp, Box<FExpr<N>>, Box<FExpr<N>>),
    Logic(FLogic, Box<FExpr<N>>, Box<FExpr<N>>),
    Not(Box<FExpr<N>>),
    /// `if cond { a } else { b }`: both sides are computed, and each lane keeps one.
    If(Box<FExpr<N>>, Box<FExpr<N>>, Box<FExpr<N>>),
}

impl<N> FExpr<N> {
    /// The same expression with every scene number converted by `f`.
    pub fn map_nums<M>(&self, f: &mut impl FnMut(&N) -> M) -> FExpr<M> {
        let mut go = |e: &FExpr<N>| Box::new(e.map_nums(f));
        match self {
            FExpr::Num(n) => FExpr::Num(f(n)),
            FExpr::Arg(i) => FExpr::Arg(*i),
            FExpr::Let(i) => FExpr::Let(*i),
            FExpr::Neg(a) => FExpr::Neg(go(a)),
            FExpr::Bin(op, a, b) => {
                let a = go(a);
                FExpr::Bin(*op, a, go(b))
            }
            FExpr::Call(func, args) => FExpr::Call(*func, args.iter().map(|a| a.map_nums(f)).collect()),
            FExpr::Swizzle(a, s) => FExpr::Swizzle(go(a), *s),
            FExpr::Cmp(op, a, b) => {
                let a = go(a);
                FExpr::Cmp(*op, a, go(b))
            }
            FExpr::Logic(op, a, b) => {
                let a = go(a);
                FExpr::Logic(*op, a, go(b))
            }
            FExpr::Not(a) => FExpr::Not(go(a)),
            FExpr::If(c, a, b) => {
                let c = go(c);
                let a = go(a);
                FExpr::If(c, a, go(b))
            }
        }
    }

    /// Calls `f` on every scene number, in order.
    pub fn each_num<'a>(&'a self, f: &mut dyn FnMut(&'a N)) {
        match self {
            FExpr::Num(n) => f(n),
            FExpr::Arg(_) | FExpr::Let(_) => {}
            FExpr::Neg(a) | FExpr::Not(a) | FExpr::Swizzle(a, _) => a.each_num(f),
            FExpr::Bin(_, a, b) | FExpr::Cmp(_, a, b) | FExpr::Logic(_, a, b) => {
                a.each_num(f);
                b.each_num(f);
            }
            FExpr::Call(_, args) => args.iter().for_each(|a| a.each_num(f)),
            FExpr::If(c, a, b) => {
                c.each_num(f);
                a.each_num(f);
                b.each_num(f);
            }
        }
    }

    /// Nodes in the expression.
    pub fn size(&self) -> usize {
        1 + match self {
            FExpr::Num(_) | FExpr::Arg(_) | FExpr::Let(_) => 0,
            FExpr::Neg(a) | FExpr::Not(a) | FExpr::Swizzle(a, _) => a.size(),
            FExpr::Bin(_, a, b) | FExpr::Cmp(_, a, b) | FExpr::Logic(_, a, b) => a.size() + b.size(),
            FExpr::Call(_, args) => args.iter().map(FExpr::size).sum(),
            FExpr::If(c, a, b) => c.size() + a.size() + b.size(),
        }
    }
}

/// One iteration map: `|z, c| { let a = ..; ..; result }`, or a fold's `|z, c| { ..; (z, scale) }`.
#[derive(Clone, Debug, PartialEq)]
pub struct FormulaMap<N> {
    /// The closure's parameter names: z, then optionally c.
    pub params: Vec<String>,
    /// The `let` bindings in order, with their names (a later one may shadow an earlier one).
    pub lets: Vec<(String, FExpr<N>)>,
    /// The next z, a vec3.
    pub next: FExpr<N>,
    /// A fold's own scale factor for this step (`(z, scale)`), in place of the derived derivative.
    pub scale: Option<FExpr<N>>,
}

impl<N> FormulaMap<N> {
    pub fn map_nums<M>(&self, f: &mut impl FnMut(&N) -> M) -> FormulaMap<M> {
        FormulaMap {
            params: self.params.clone(),
            lets: self.lets.iter().map(|(n, e)| (n.clone(), e.map_nums(f))).collect(),
            next: self.next.map_nums(f),
            scale: self.scale.as_ref().map(|s| s.map_nums(f)),
        }
    }
    /// Every expression of the map, in order.
    pub fn exprs(&self) -> impl Iterator<Item = &FExpr<N>> {
        self.lets.iter().map(|(_, e)| e).chain(std::iter::once(&self.next)).chain(self.scale.as_ref())
    }
    pub fn size(&self) -> usize {
        self.exprs().map(FExpr::size).sum()
    }
}

/// How a formula's orbit becomes a distance estimate and a membership test.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FormulaKind {
    /// Escape time: the orbit runs while |z| ≤ bailout; the estimate is 0.5·|z|·ln|z| / |∇|z||, the gradient from
    /// the orbit's Jacobian with respect to the point; a point is in the set when its orbit never escapes.
    EscapeTime,
    /// A fold (Mandelbox, KIFS): the orbit runs every iteration; the estimate is (|z| − bailout) / ‖J‖ (or the
    /// product of the maps' own scales); a point is in the set when its last iterate lies within the bailout.
    Fold,
}

/// A formula: one map or a hybrid's cycle of maps applied in turn, one per iteration.
#[derive(Clone, Debug, PartialEq)]
pub struct Formula<N> {
    pub kind: FormulaKind,
    pub maps: Vec<FormulaMap<N>>,
}

impl<N> Formula<N> {
    pub fn map_nums<M>(&self, f: &mut impl FnMut(&N) -> M) -> Formula<M> {
        Formula { kind: self.kind, maps: self.maps.iter().map(|m| m.map_nums(f)).collect() }
    }
    /// Every scene number in the formula, in order.
    pub fn each_num<'a>(&'a self, f: &mut dyn FnMut(&'a N)) {
        for m in &self.maps {
            for e in m.exprs() {
                e.each_num(f);
            }
        }
    }
    /// Expression nodes in the formula.
    pub fn size(&self) -> usize {
        self.maps.iter().map(FormulaMap::size).sum()
    }
    /// Whether a map gives its own scale (`(z, scale)`): the estimate then needs no derivative.
    pub fn own_scale(&self) -> bool {
        self.maps.iter().all(|m| m.scale.is_some())
    }
}

/// Most maps in a hybrid.
pub const MAX_HYBRID_MAPS: usize = 16;
/// Most `let` bindings in one map.
pub const MAX_LETS: usize = 256;
/// Most expression nodes in one formula: a bound on the code one iteration becomes.
pub const MAX_FORMULA_NODES: usize = 4096;
