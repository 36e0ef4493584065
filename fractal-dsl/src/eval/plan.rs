//! The plan: a scene folded and prepared for evaluation, with everything that does not depend on the point settled
//! ahead — union order and guard boxes, parameter slots, which leaf function each primitive and fractal calls,
//! rotation constants. The walker ([`super::walk`]) runs a plan in any [`crate::number::Num`]: the interpreter runs it
//! in f32 and f64, the lowering traces it into kernel code.

use crate::analyse::{fold, guarded_bound, union_order};
use crate::eval::Env;
use crate::formula::leaf::{LeafArg, LeafOut};
use crate::formula::user::Ready;
use crate::formula::{CallLeaf, Leaf};
use crate::ir::formula::Formula;
use crate::ir::fractal::CallArg;
use crate::ir::op::Meaning;
use crate::ir::*;
use crate::number::math::{v3, V3};

/// A compiled scalar expression.
#[derive(Clone, Debug)]
pub enum Term {
    Lit(f64),
    Time,
    /// A coordinate of the point (displacements only; see [`Term::eval_at`]).
    Point(u8),
    /// Slot in [`Env::params`], and the declared default for a slot the caller did not fill.
    Param(usize, f64),
    Neg(Box<Term>),
    Bin(BinOp, Box<Term>, Box<Term>),
    Call(Func, Box<[Term]>),
    /// `mandelbrot(a, b, iterations)` of two point coordinates, in a world-coordinate material: computed by
    /// perturbation around the environment's reference ([`mod@crate::analyse::reference`]).
    PerturbedMandelbrot {
        axes: [u8; 2],
        iterations: u32,
    },
}

impl Term {
    fn compile(e: &Expr, params: &[ParamDecl]) -> Term {
        Term::compile_in(e, params, None)
    }

    /// Compiles `e`; `mandelbrot` calls of the point coordinates `perturbed` become [`Term::PerturbedMandelbrot`].
    fn compile_in(e: &Expr, params: &[ParamDecl], perturbed: Option<[u8; 2]>) -> Term {
        if let Some((axes, iterations)) = crate::analyse::reference::perturbable(e) {
            if perturbed == Some(axes) {
                return Term::PerturbedMandelbrot { axes, iterations };
            }
        }
        let compile = |e: &Expr| Box::new(Term::compile_in(e, params, perturbed));
        match e {
            Expr::Lit(v) => Term::Lit(*v),
            Expr::Time => Term::Time,
            Expr::Point(axis) => Term::Point(*axis),
            Expr::Param(p) => match params.iter().position(|q| q.name == p.name) {
                Some(i) => Term::Param(i, p.default),
                // Every parameter of a scene is listed by `Scene::params`; a stray one reads its default.
                None => Term::Lit(p.default),
            },
            Expr::Neg(a) => Term::Neg(compile(a)),
            Expr::Bin(op, a, b) => Term::Bin(*op, compile(a), compile(b)),
            Expr::Call(f, args) => Term::Call(*f, args.iter().map(|a| *compile(a)).collect()),
        }
    }

    /// The value, where the point is not known (validation keeps `x`, `y`, `z` inside displacements).
    #[inline]
    pub fn eval<F: CallLeaf>(&self, env: &Env<F>) -> F {
        self.eval_at(env, None)
    }

    /// The value at the point `p` (a displacement's amount); without one, a coordinate reads NaN.
    #[inline]
    pub fn eval_at<F: CallLeaf>(&self, env: &Env<F>, p: Option<V3<F>>) -> F {
        match self {
            Term::Lit(v) => F::lit(*v),
            Term::Time => env.time,
            Term::Point(axis) => p.map_or(F::lit(f64::NAN), |p| [p.x, p.y, p.z][*axis as usize % 3]),
            Term::Param(i, default) => env.params.get(*i).copied().unwrap_or_else(|| F::lit(*default)),
            Term::Neg(a) => -a.eval_at(env, p),
            Term::Bin(op, a, b) => op.apply(a.eval_at(env, p), b.eval_at(env, p)),
            Term::Call(f, args) => {
                let mut v = [F::lit(0.0); Func::MAX_ARITY];
                for (slot, a) in v.iter_mut().zip(args.iter()) {
                    *slot = a.eval_at(env, p);
                }
                let octaves = match args.last() {
                    Some(Term::Lit(n)) => f.count(Some(*n)),
                    _ => 0,
                };
                f.apply(&v, octaves)
            }
            Term::PerturbedMandelbrot { axes, iterations } => {
                let Some(p) = p else { return F::lit(f64::NAN) };
                let offset = env.reference_offset(p);
                let offset = [offset.x, offset.y, offset.z];
                let args = [
                    LeafArg::F(offset[axes[0] as usize % 3]),
                    LeafArg::F(offset[axes[1] as usize % 3]),
                    LeafArg::Count(F::count(*iterations)),
                    LeafArg::F(F::lit(crate::formula::mandelbrot::inverse_count(*iterations))),
                    LeafArg::Orbit(env.reference_orbit()),
                ];
                F::leaf(Leaf::MandelbrotPerturbed, &args).distance()
            }
        }
    }
}

/// A compiled 3-vector expression.
#[derive(Clone, Debug)]
pub struct Term3(pub [Term; 3]);

impl Term3 {
    fn compile(v: &Vec3Expr, params: &[ParamDecl]) -> Term3 {
        Term3::compile_in(v, params, None)
    }
    fn compile_in(v: &Vec3Expr, params: &[ParamDecl], perturbed: Option<[u8; 2]>) -> Term3 {
        Term3([0, 1, 2].map(|i| Term::compile_in(&v.0[i], params, perturbed)))
    }
    /// The vector's value when every component is a literal.
    pub fn constant(&self) -> Option<[f64; 3]> {
        match &self.0 {
            [Term::Lit(x), Term::Lit(y), Term::Lit(z)] => Some([*x, *y, *z]),
            _ => None,
        }
    }
    #[inline]
    pub fn eval<F: CallLeaf>(&self, env: &Env<F>) -> V3<F> {
        self.eval_at(env, None)
    }
    /// The value at the point `p` (a material's pattern).
    #[inline]
    pub fn eval_at<F: CallLeaf>(&self, env: &Env<F>, p: Option<V3<F>>) -> V3<F> {
        v3(self.0[0].eval_at(env, p), self.0[1].eval_at(env, p), self.0[2].eval_at(env, p))
    }
}

/// An argument of a leaf call, after the point.
#[derive(Clone, Debug)]
pub enum ArgTerm {
    Num(Term),
    Vec(Term3),
    Count(u32),
}

impl ArgTerm {
    fn compile(a: &ArgValue, params: &[ParamDecl]) -> ArgTerm {
        match a {
            ArgValue::Num(e) => ArgTerm::Num(Term::compile(e, params)),
            ArgValue::Vec3(v) => ArgTerm::Vec(Term3::compile(v, params)),
        }
    }
    #[inline]
    pub fn eval<F: CallLeaf>(&self, env: &Env<F>) -> LeafArg<'static, F> {
        match self {
            ArgTerm::Num(t) => LeafArg::F(t.eval(env)),
            ArgTerm::Vec(t) => LeafArg::V3(t.eval(env)),
            ArgTerm::Count(n) => LeafArg::Count(F::count(*n)),
        }
    }
}

/// A leaf call: the function and its arguments after the point.
#[derive(Clone, Debug)]
pub struct LeafCall {
    pub leaf: Leaf,
    pub args: Vec<ArgTerm>,
}

#[derive(Clone, Debug)]
pub enum Paint {
    Rgb(Term3),
    OrbitTrap(Term3, Term3),
}

/// A compiled material.
#[derive(Clone, Debug)]
pub struct Mat {
    pub albedo: Paint,
    pub ambient: Term,
    pub diffuse: Term,
    pub specular: Term,
    pub shininess: Term,
}

impl Mat {
    /// Compiles a material; its `mandelbrot` calls of the point coordinates `perturbed` are perturbed.
    fn compile(m: &Material, params: &[ParamDecl], perturbed: Option<[u8; 2]>) -> Mat {
        let vec = |v| Term3::compile_in(v, params, perturbed);
        let num = |e| Term::compile_in(e, params, perturbed);
        Mat {
            albedo: match &m.albedo {
                Albedo::Rgb(c) => Paint::Rgb(vec(c)),
                Albedo::OrbitTrap(a, b) => Paint::OrbitTrap(vec(a), vec(b)),
            },
            ambient: num(&m.ambient),
            diffuse: num(&m.diffuse),
            specular: num(&m.specular),
            shininess: num(&m.shininess),
        }
    }
}

/// A union child's guard box (the child is skipped while the box is no nearer than the nearest distance so far).
#[derive(Clone, Copy, Debug)]
pub struct Guard {
    pub center: [f64; 3],
    pub half: [f64; 3],
}

/// A node of the plan.
#[derive(Clone, Debug)]
pub enum Step {
    /// A primitive: the leaf's distance at the point.
    Leaf(LeafCall),
    /// A fractal: its estimate × the step factor, and the orbit trap for materials.
    Fractal {
        call: LeafCall,
        step: f64,
    },
    /// A fractal written in the scene language: its estimate × the step factor, and the orbit trap.
    Formula {
        call: Box<FormulaCall>,
        step: f64,
    },
    /// A union or intersection of nothing: no geometry.
    Empty,
    Op(OpStep),
    Material(Box<Step>, Box<Mat>),
}

/// A fractal written in the scene language, ready to run ([`crate::formula::user`]): its maps with their scene numbers
/// as terms, and its bailout.
#[derive(Clone, Debug)]
pub struct FormulaCall {
    pub ready: Ready,
    /// The formula's scene numbers, in the order its maps index them.
    pub nums: Vec<Term>,
    pub bailout: Term,
    /// The estimate is signed by membership (the scene's `membership_hits`).
    pub signed: bool,
}

impl FormulaCall {
    fn compile(f: &Fractal, formula: &Formula, params: &[ParamDecl], signed: bool) -> FormulaCall {
        let mut nums = Vec::new();
        let indexed = formula.map_nums(&mut |e: &Expr| {
            nums.push(Term::compile(e, params));
            (nums.len() - 1) as u16
        });
        let literals = nums.iter().map(|t| if let Term::Lit(v) = t { Some(*v) } else { None }).collect();
        FormulaCall {
            ready: Ready { formula: indexed, literals, iterations: f.iterations_or_default(), host: None },
            nums,
            bailout: Term::compile(&f.bailout_or_default(), params),
            signed,
        }
    }

    /// The estimate and orbit trap at `p` (for the ground truth's numbers, its membership: [`CallLeaf::formula`]).
    #[inline]
    pub fn run<F: CallLeaf>(&self, p: V3<F>, env: &Env<F>) -> LeafOut<F> {
        let nums: Vec<F> = self.nums.iter().map(|t| t.eval(env)).collect();
        F::formula(&self.ready, &nums, p, self.bailout.eval(env), self.signed)
    }
}

/// `x` as the f32 nearest it and the rest, x − f32(x): subtracted in turn from an anchor near x, the two keep x to
/// about 48 bits where x alone would be rounded to 24.
fn high_and_rest(x: f64) -> (f64, f64) {
    let high = f64::from(x as f32);
    (high, x - high)
}

/// The rest of a split vector, where any component has one.
fn rest_of<F: CallLeaf>(rest: [f64; 3]) -> Option<V3<F>> {
    (rest != [0.0; 3]).then(|| V3 { x: F::lit(rest[0]), y: F::lit(rest[1]), z: F::lit(rest[2]) })
}

/// A constant vector split as [`OpStep::vec_split`] splits a literal one.
pub fn split_constant<F: CallLeaf>(c: [f64; 3]) -> (V3<F>, Option<V3<F>>) {
    let parts = c.map(high_and_rest);
    (V3 { x: F::lit(parts[0].0), y: F::lit(parts[1].0), z: F::lit(parts[2].0) }, rest_of(parts.map(|p| p.1)))
}

/// An operator: what it means, its shapes and its arguments.
#[derive(Clone, Debug)]
pub struct OpStep {
    pub meaning: Meaning,
    /// The shapes in evaluation order (a union takes cheap ones first), each with its guard (union shapes only,
    /// never the first).
    pub shapes: Vec<(Step, Option<Guard>)>,
    pub args: Vec<ArgTerm>,
}

impl OpStep {
    /// The argument at `i` as a number.
    #[inline]
    pub fn num<F: CallLeaf>(&self, i: usize, env: &Env<F>) -> F {
        match &self.args[i] {
            ArgTerm::Num(t) => t.eval(env),
            ArgTerm::Vec(v) => v.0[0].eval(env),
            ArgTerm::Count(n) => F::lit(*n as f64),
        }
    }
    /// The argument at `i` as a number that may read the point `p`.
    #[inline]
    pub fn num_at<F: CallLeaf>(&self, i: usize, env: &Env<F>, p: V3<F>) -> F {
        match &self.args[i] {
            ArgTerm::Num(t) => t.eval_at(env, Some(p)),
            _ => self.num(i, env),
        }
    }
    /// The argument at `i` as a vector.
    #[inline]
    pub fn vec<F: CallLeaf>(&self, i: usize, env: &Env<F>) -> V3<F> {
        match &self.args[i] {
            ArgTerm::Vec(v) => v.eval(env),
            _ => V3::splat(self.num(i, env)),
        }
    }
    /// The argument at `i` as a vector split into the part an f32 holds and, where that is not all of it, the rest
    /// ([`split_constant`] for each literal component; other components whole, with no rest).
    pub fn vec_split<F: CallLeaf>(&self, i: usize, env: &Env<F>) -> (V3<F>, Option<V3<F>>) {
        let terms = match &self.args[i] {
            ArgTerm::Vec(v) => [&v.0[0], &v.0[1], &v.0[2]],
            ArgTerm::Num(t) => [t; 3],
            ArgTerm::Count(_) => return (self.vec(i, env), None),
        };
        let parts = terms.map(|t| match t {
            Term::Lit(x) => Ok(high_and_rest(*x)),
            other => Err(other.eval(env)),
        });
        let high = parts.map(|p| p.map_or_else(|whole| whole, |(h, _)| F::lit(h)));
        let rest = parts.map(|p| p.map_or(0.0, |(_, r)| r));
        (V3 { x: high[0], y: high[1], z: high[2] }, rest_of(rest))
    }
    /// The argument at `i` as a vector, with `None` on axes whose expression folded to the literal 0.
    pub fn per_axis(&self, i: usize) -> [Option<&Term>; 3] {
        match &self.args[i] {
            ArgTerm::Vec(v) => [0, 1, 2].map(|k| (!matches!(v.0[k], Term::Lit(z) if z == 0.0)).then_some(&v.0[k])),
            ArgTerm::Num(t) => [Some(t); 3],
            ArgTerm::Count(_) => [None; 3],
        }
    }
    /// The argument at `i` as a vector of constants (a rotation axis, repeat counts).
    pub fn constant3(&self, i: usize) -> [f64; 3] {
        match &self.args[i] {
            ArgTerm::Vec(v) => v.constant().unwrap_or([0.0; 3]),
            ArgTerm::Num(Term::Lit(x)) => [*x; 3],
            _ => [0.0; 3],
        }
    }
    /// The shape at `i` in evaluation order.
    #[inline]
    pub fn shape(&self, i: usize) -> &Step {
        &self.shapes[i].0
    }
}

/// A scene prepared for evaluation: the folded tree as [`Step`]s, the default material and the parameter slots.
#[derive(Clone, Debug)]
pub struct Plan {
    pub root: Step,
    pub default_material: Mat,
    /// The parameters in slot order ([`Scene::params`]).
    pub params: Vec<ParamDecl>,
    /// The perturbation reference the frame provides for the scene's Mandelbrot patterns.
    pub reference: Option<crate::analyse::ReferenceSpec>,
}

impl Plan {
    /// Folds and prepares `scene`. [`Env::params`] slot i holds the value of `scene.params()[i]`.
    pub fn new(scene: &Scene) -> Plan {
        Plan::folded(&fold::fold_scene(scene), scene.params())
    }

    /// Prepares a scene already folded, whose parameter slots (taken before folding, which may drop a parameter's
    /// only use) are `params`.
    pub fn folded(folded: &Scene, params: Vec<ParamDecl>) -> Plan {
        Plan::folded_with(folded, params, true)
    }

    /// [`Plan::folded`], with the Mandelbrot patterns perturbed around a reference only when `perturb` (a
    /// function library has no frame to hold the reference's orbit, so it iterates them plainly).
    pub fn folded_with(folded: &Scene, params: Vec<ParamDecl>, perturb: bool) -> Plan {
        let reference = crate::analyse::reference(&folded.root).filter(|_| perturb);
        let compiler =
            Compiler { params: &params, perturbed: reference.map(|r| r.axes), signed: folded.settings.membership_hits };
        Plan {
            root: compiler.node(&folded.root, true),
            default_material: Mat::compile(&Material::default_surface(), &params, None),
            params,
            reference,
        }
    }
}

impl Plan {
    /// Calls `f` on every fractal written in the scene language (to compile it for the host, say:
    /// [`crate::lower::tape`]).
    pub fn formula_calls_mut(&mut self, f: &mut impl FnMut(&mut FormulaCall)) {
        fn visit(step: &mut Step, f: &mut impl FnMut(&mut FormulaCall)) {
            match step {
                Step::Formula { call, .. } => f(call),
                Step::Op(op) => op.shapes.iter_mut().for_each(|(s, _)| visit(s, f)),
                Step::Material(s, _) => visit(s, f),
                Step::Leaf(_) | Step::Fractal { .. } | Step::Empty => {}
            }
        }
        visit(&mut self.root, f)
    }

    /// Whether the ray program's normal is the scene's gradient ([`crate::eval::walk::Walk::gradient`]) rather than
    /// its tetrahedral difference: where the scene has an escape-time formula whose orbit carries a Jacobian. Its
    /// estimate jumps between escape bands and its divisor wobbles within one, so taps a pixel apart straddle them;
    /// the potential's direction does neither (`docs/formulas.md`, "Where the smooth maps' normals go wrong").
    pub fn shaded_by_gradient(&self) -> bool {
        fn visit(step: &Step) -> bool {
            match step {
                Step::Formula { call, .. } => {
                    let f = &call.ready.formula;
                    f.kind == crate::formula::lang::FormulaKind::EscapeTime && !f.own_scale()
                }
                Step::Op(op) => op.shapes.iter().any(|(s, _)| visit(s)),
                Step::Material(s, _) => visit(s),
                Step::Leaf(_) | Step::Fractal { .. } | Step::Empty => false,
            }
        }
        visit(&self.root)
    }
}

struct Compiler<'a> {
    params: &'a [ParamDecl],
    /// The axes of the perturbed Mandelbrot patterns, if any.
    perturbed: Option<[u8; 2]>,
    /// Fractals call their estimates signed by membership (the scene's `membership_hits`).
    signed: bool,
}

impl Compiler<'_> {
    fn num(&self, e: &Expr) -> Term {
        Term::compile(e, self.params)
    }
    fn call(&self, leaf: Leaf, args: Vec<ArgTerm>) -> LeafCall {
        LeafCall { leaf, args }
    }

    /// The step for `n`; `world` when its point is the world point (its materials' patterns may be perturbed).
    fn node(&self, n: &Node, world: bool) -> Step {
        match n {
            Node::Prim(p) => Step::Leaf(self.prim(p)),
            Node::Fractal(f) => match (self.fractal(f), f.formula()) {
                (Some(call), _) => Step::Fractal { call, step: f.step_factor_or_default() },
                (None, Some(formula)) => Step::Formula {
                    call: Box::new(FormulaCall::compile(f, formula, self.params, self.signed)),
                    step: f.step_factor_or_default(),
                },
                (None, None) => Step::Empty,
            },
            Node::Op(op) if op.shapes.is_empty() => Step::Empty,
            Node::Op(op) => {
                let meaning = op.decl().meaning;
                let world = world && meaning.keeps_point();
                let shapes = if meaning == Meaning::Union {
                    union_order(&op.shapes)
                        .into_iter()
                        .enumerate()
                        .map(|(pos, i)| {
                            let guard = guarded_bound(&op.shapes, pos)
                                .map(|b| Guard { center: b.center(), half: b.half_extents() });
                            (self.node(&op.shapes[i], world), guard)
                        })
                        .collect()
                } else {
                    op.shapes.iter().map(|s| (self.node(s, world), None)).collect()
                };
                let mut args: Vec<ArgTerm> = op.args.iter().map(|a| ArgTerm::compile(a, self.params)).collect();
                if let (Meaning::Displace, Some(ArgValue::Num(amount))) = (meaning, op.args.first()) {
                    // The divisor that keeps the displaced distance a lower bound, fixed when the plan is made.
                    args.push(ArgTerm::Num(Term::Lit(1.0 + crate::analyse::slope::slope(amount))));
                }
                Step::Op(OpStep { meaning, shapes, args })
            }
            Node::Material(c, m) => {
                let perturbed = self.perturbed.filter(|_| world);
                Step::Material(Box::new(self.node(c, world)), Box::new(Mat::compile(m, self.params, perturbed)))
            }
        }
    }

    fn prim(&self, p: &Prim) -> LeafCall {
        let args = p.args.iter().map(|a| ArgTerm::compile(a, self.params)).collect();
        self.call(p.decl().leaf, args)
    }

    fn fractal(&self, f: &Fractal) -> Option<LeafCall> {
        let (leaf, args) = f.call()?;
        let leaf = match f.decl().membership.signed_for(leaf) {
            Some(signed) if self.signed => signed,
            _ => leaf,
        };
        let args = args
            .into_iter()
            .map(|a| match a {
                CallArg::Num(e) => ArgTerm::Num(self.num(&e)),
                CallArg::Count(n) => ArgTerm::Count(n),
            })
            .collect();
        Some(self.call(leaf, args))
    }
}
