//! The interpreter: walks the IR directly, generic over f32 and f64. The f64 instance is the accuracy reference.
//!
//! [`Interpreter::new`] folds the scene once and compiles it into a tree of operations with everything that does not
//! depend on the point settled ahead: union order and guard boxes, parameter slots, which Mandelbulb form to call,
//! rotation constants. Evaluation then allocates nothing. The rules are those of [`crate::eval`]; the arithmetic is
//! spelled in the same order as the kernels' lowering so the two agree to the last bit wherever the math functions do.

use crate::analyse::{fold, guarded_bound, union_order};
use crate::eval::{Env, Evaluator, Sample};
use crate::ir::*;
use crate::math::*;
use crate::sdf;

/// A compiled scalar expression.
#[derive(Clone, Debug)]
enum Num {
    Lit(f64),
    Time,
    /// Slot in [`Env::params`], and the declared default for a slot the caller did not fill.
    Param(usize, f64),
    Neg(Box<Num>),
    Bin(BinOp, Box<Num>, Box<Num>),
    Call(Func, Box<[Num]>),
}

impl Num {
    fn compile(e: &Expr, params: &[ParamDecl]) -> Num {
        match e {
            Expr::Lit(v) => Num::Lit(*v),
            Expr::Time => Num::Time,
            Expr::Param(p) => match params.iter().position(|q| q.name == p.name) {
                Some(i) => Num::Param(i, p.default),
                // Every parameter of a scene is listed by `Scene::params`; a stray one reads its default.
                None => Num::Lit(p.default),
            },
            Expr::Neg(a) => Num::Neg(Box::new(Num::compile(a, params))),
            Expr::Bin(op, a, b) => Num::Bin(*op, Box::new(Num::compile(a, params)), Box::new(Num::compile(b, params))),
            Expr::Call(f, args) => Num::Call(*f, args.iter().map(|a| Num::compile(a, params)).collect()),
        }
    }

    #[inline]
    fn eval<F: Real>(&self, env: &Env<F>) -> F {
        match self {
            Num::Lit(v) => F::c(*v),
            Num::Time => env.time,
            Num::Param(i, default) => env.params.get(*i).copied().unwrap_or_else(|| F::c(*default)),
            Num::Neg(a) => -a.eval(env),
            Num::Bin(op, a, b) => {
                let (a, b) = (a.eval(env), b.eval(env));
                match op {
                    BinOp::Add => a + b,
                    BinOp::Sub => a - b,
                    BinOp::Mul => a * b,
                    BinOp::Div => a / b,
                }
            }
            Num::Call(f, args) => {
                let mut v = [F::zero(); 3];
                for (slot, a) in v.iter_mut().zip(args.iter()) {
                    *slot = a.eval(env);
                }
                f.apply(&v)
            }
        }
    }
}

/// A compiled 3-vector expression.
#[derive(Clone, Debug)]
struct Num3([Num; 3]);

impl Num3 {
    fn compile(v: &Vec3Expr, params: &[ParamDecl]) -> Num3 {
        Num3([0, 1, 2].map(|i| Num::compile(&v.0[i], params)))
    }
    #[inline]
    fn eval<F: Real>(&self, env: &Env<F>) -> V3<F> {
        v3(self.0[0].eval(env), self.0[1].eval(env), self.0[2].eval(env))
    }
}

/// Per axis: `None` where the expression folded to the literal 0 (the axis is left alone, as the kernels do).
fn per_axis(v: &Vec3Expr, params: &[ParamDecl]) -> [Option<Num>; 3] {
    [0, 1, 2].map(|i| (v.0[i].as_lit() != Some(0.0)).then(|| Num::compile(&v.0[i], params)))
}

#[derive(Clone, Debug)]
enum Paint {
    Rgb(Num3),
    OrbitTrap(Num3, Num3),
}

#[derive(Clone, Debug)]
struct Mat {
    albedo: Paint,
    ambient: Num,
    diffuse: Num,
    specular: Num,
    shininess: Num,
}

impl Mat {
    fn compile(m: &Material, params: &[ParamDecl]) -> Mat {
        Mat {
            albedo: match &m.albedo {
                Albedo::Rgb(c) => Paint::Rgb(Num3::compile(c, params)),
                Albedo::OrbitTrap(a, b) => Paint::OrbitTrap(Num3::compile(a, params), Num3::compile(b, params)),
            },
            ambient: Num::compile(&m.ambient, params),
            diffuse: Num::compile(&m.diffuse, params),
            specular: Num::compile(&m.specular, params),
            shininess: Num::compile(&m.shininess, params),
        }
    }

    /// The material of a leaf; `trap` is the fractal's orbit trap, for fractal leaves.
    fn leaf<F: Real>(&self, env: &Env<F>, trap: Option<F>) -> Fields<F> {
        let albedo = match (&self.albedo, trap) {
            (Paint::Rgb(c), _) => c.eval(env),
            (Paint::OrbitTrap(a, _), None) => a.eval(env),
            (Paint::OrbitTrap(a, b), Some(t)) => mix3(a.eval(env), b.eval(env), t),
        };
        Fields {
            albedo,
            ambient: self.ambient.eval(env),
            diffuse: self.diffuse.eval(env),
            specular: self.specular.eval(env),
            shininess: self.shininess.eval(env),
        }
    }
}

/// The material part of a [`Sample`].
#[derive(Clone, Copy, Debug)]
struct Fields<F> {
    albedo: V3<F>,
    ambient: F,
    diffuse: F,
    specular: F,
    shininess: F,
}

impl<F: Real> Fields<F> {
    fn mix(self, o: Fields<F>, w: F) -> Fields<F> {
        Fields {
            albedo: mix3(self.albedo, o.albedo, w),
            ambient: mix(self.ambient, o.ambient, w),
            diffuse: mix(self.diffuse, o.diffuse, w),
            specular: mix(self.specular, o.specular, w),
            shininess: mix(self.shininess, o.shininess, w),
        }
    }
}

#[derive(Clone, Debug)]
enum Leaf {
    Sphere(Num),
    Box(Num3),
    RoundBox(Num3, Num),
    Torus(Num, Num),
    Capsule(Num3, Num3, Num),
    Cylinder(Num, Num),
    Cone(Num, Num, Num),
    Plane(Num3, Num),
    Octahedron(Num),
    Ellipsoid(Num3),
}

#[derive(Clone, Debug)]
enum Estimator {
    /// Power 8 by the trig-free polynomial form.
    Mandelbulb8 {
        iterations: u32,
        bailout: Num,
    },
    Mandelbulb {
        power: Num,
        iterations: u32,
        bailout: Num,
    },
    Menger {
        levels: u32,
    },
    Sierpinski {
        levels: u32,
    },
    Julia {
        c: [Num; 4],
        iterations: u32,
        bailout: Num,
    },
    Mandelbox {
        scale: Num,
        iterations: u32,
        min_radius: Num,
        fold_limit: Num,
    },
}

/// A union child's guard box (the child is skipped while the box is no nearer than the nearest distance so far).
#[derive(Clone, Copy, Debug)]
struct Guard {
    center: [f64; 3],
    half: [f64; 3],
}

#[derive(Clone, Debug)]
enum Op {
    Leaf(Leaf),
    Fractal {
        estimator: Estimator,
        step: f64,
    },
    /// A union or intersection of nothing: no geometry.
    Empty,
    /// Children in evaluation order, each with its guard (never on the first).
    Union(Vec<(Op, Option<Guard>)>),
    Intersect(Vec<Op>),
    Subtract(Box<Op>, Box<Op>),
    SmoothUnion(Vec<Op>, Num),
    SmoothIntersect(Vec<Op>, Num),
    SmoothSubtract(Box<Op>, Box<Op>, Num),
    Translate(Box<Op>, Num3),
    /// Unit axis, its outer product k·kᵀ and cross-product matrix [k]×, and the angle.
    Rotate {
        child: Box<Op>,
        outer: [[f64; 3]; 3],
        cross: [[f64; 3]; 3],
        angle: Num,
    },
    Scale(Box<Op>, Num),
    Repeat {
        child: Box<Op>,
        period: [Option<Num>; 3],
        count: Option<[u32; 3]>,
    },
    Twist(Box<Op>, Num),
    Bend(Box<Op>, Num),
    Round(Box<Op>, Num),
    Onion(Box<Op>, Num),
    Elongate(Box<Op>, [Option<Num>; 3]),
    Material(Box<Op>, Box<Mat>),
}

struct Compiler<'a> {
    params: &'a [ParamDecl],
}

impl Compiler<'_> {
    fn num(&self, e: &Expr) -> Num {
        Num::compile(e, self.params)
    }
    fn num3(&self, v: &Vec3Expr) -> Num3 {
        Num3::compile(v, self.params)
    }
    fn boxed(&self, n: &Node) -> Box<Op> {
        Box::new(self.node(n))
    }

    fn node(&self, n: &Node) -> Op {
        match n {
            Node::Prim(p) => Op::Leaf(self.prim(p)),
            Node::Fractal(f) => Op::Fractal { estimator: self.fractal(f), step: f.kind.step_factor() },
            Node::Union(children) if children.is_empty() => Op::Empty,
            Node::Union(children) => Op::Union(
                union_order(children)
                    .into_iter()
                    .enumerate()
                    .map(|(pos, i)| {
                        let guard =
                            guarded_bound(children, pos).map(|b| Guard { center: b.center(), half: b.half_extents() });
                        (self.node(&children[i]), guard)
                    })
                    .collect(),
            ),
            Node::Intersect(c) | Node::SmoothUnion(c, _) | Node::SmoothIntersect(c, _) if c.is_empty() => Op::Empty,
            Node::Intersect(c) => Op::Intersect(c.iter().map(|c| self.node(c)).collect()),
            Node::Subtract(a, b) => Op::Subtract(self.boxed(a), self.boxed(b)),
            Node::SmoothUnion(c, k) => Op::SmoothUnion(c.iter().map(|c| self.node(c)).collect(), self.num(k)),
            Node::SmoothIntersect(c, k) => Op::SmoothIntersect(c.iter().map(|c| self.node(c)).collect(), self.num(k)),
            Node::SmoothSubtract(a, b, k) => Op::SmoothSubtract(self.boxed(a), self.boxed(b), self.num(k)),
            Node::Translate(c, v) => Op::Translate(self.boxed(c), self.num3(v)),
            Node::Rotate(c, axis, angle) => {
                let k = axis.unit();
                Op::Rotate {
                    child: self.boxed(c),
                    outer: [0, 1, 2].map(|i| [0, 1, 2].map(|j| k[i] * k[j])),
                    cross: [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]],
                    angle: self.num(angle),
                }
            }
            Node::Scale(c, s) => Op::Scale(self.boxed(c), self.num(s)),
            Node::Repeat(c, period) => {
                Op::Repeat { child: self.boxed(c), period: per_axis(period, self.params), count: None }
            }
            Node::RepeatLimited(c, period, count) => {
                Op::Repeat { child: self.boxed(c), period: per_axis(period, self.params), count: Some(*count) }
            }
            Node::Twist(c, k) => Op::Twist(self.boxed(c), self.num(k)),
            Node::Bend(c, k) => Op::Bend(self.boxed(c), self.num(k)),
            Node::Round(c, r) => Op::Round(self.boxed(c), self.num(r)),
            Node::Onion(c, t) => Op::Onion(self.boxed(c), self.num(t)),
            Node::Elongate(c, h) => Op::Elongate(self.boxed(c), per_axis(h, self.params)),
            Node::Material(c, m) => Op::Material(self.boxed(c), Box::new(Mat::compile(m, self.params))),
        }
    }

    fn prim(&self, p: &Prim) -> Leaf {
        match p {
            Prim::Sphere { radius } => Leaf::Sphere(self.num(radius)),
            Prim::Box { half } => Leaf::Box(self.num3(half)),
            Prim::RoundBox { half, radius } => Leaf::RoundBox(self.num3(half), self.num(radius)),
            Prim::Torus { major, minor } => Leaf::Torus(self.num(major), self.num(minor)),
            Prim::Capsule { a, b, radius } => Leaf::Capsule(self.num3(a), self.num3(b), self.num(radius)),
            Prim::Cylinder { radius, half_height } => Leaf::Cylinder(self.num(radius), self.num(half_height)),
            Prim::Cone { half_height, bottom, top } => {
                Leaf::Cone(self.num(half_height), self.num(bottom), self.num(top))
            }
            Prim::Plane { normal, offset } => Leaf::Plane(self.num3(normal), self.num(offset)),
            Prim::Octahedron { size } => Leaf::Octahedron(self.num(size)),
            Prim::Ellipsoid { radii } => Leaf::Ellipsoid(self.num3(radii)),
        }
    }

    fn fractal(&self, f: &Fractal) -> Estimator {
        let iterations = f.iterations_or_default();
        match &f.kind {
            FractalKind::Mandelbulb { power } if power.as_lit() == Some(8.0) => {
                Estimator::Mandelbulb8 { iterations, bailout: self.num(&f.bailout_or_default()) }
            }
            FractalKind::Mandelbulb { power } => {
                Estimator::Mandelbulb { power: self.num(power), iterations, bailout: self.num(&f.bailout_or_default()) }
            }
            FractalKind::Menger => Estimator::Menger { levels: iterations },
            FractalKind::Sierpinski => Estimator::Sierpinski { levels: iterations },
            FractalKind::Julia { c } => Estimator::Julia {
                c: [0, 1, 2, 3].map(|i| self.num(&c.0[i])),
                iterations,
                bailout: self.num(&f.bailout_or_default()),
            },
            FractalKind::Mandelbox { scale } => Estimator::Mandelbox {
                scale: self.num(scale),
                iterations,
                min_radius: self.num(&f.min_radius_or_default()),
                fold_limit: self.num(&f.fold_limit_or_default()),
            },
        }
    }
}

/// Evaluates a scene by walking its (folded, compiled) tree; see the module documentation.
#[derive(Clone, Debug)]
pub struct Interpreter {
    root: Op,
    default_material: Mat,
    params: Vec<ParamDecl>,
    guards: bool,
}

impl Interpreter {
    /// Folds and compiles `scene`. [`Env::params`] slot i holds the value of `scene.params()[i]`.
    pub fn new(scene: &Scene) -> Interpreter {
        let params = scene.params();
        let folded = fold::fold_scene(scene);
        let compiler = Compiler { params: &params };
        Interpreter {
            root: compiler.node(&folded.root),
            default_material: Mat::compile(&Material::default_surface(), &params),
            params,
            guards: true,
        }
    }

    /// The same scene with every union child evaluated, guard boxes ignored: the reference the guards are tested
    /// against.
    pub fn without_bound_guards(mut self) -> Interpreter {
        self.guards = false;
        self
    }

    /// The parameters in slot order.
    pub fn params(&self) -> &[ParamDecl] {
        &self.params
    }

    /// Parameter defaults in slot order, for building an [`Env`].
    pub fn default_params<F: Real>(&self) -> Vec<F> {
        self.params.iter().map(|p| F::c(p.default)).collect()
    }

    /// Signed distance in precision `F`.
    pub fn distance_in<F: Real>(&self, p: V3<F>, env: &Env<F>) -> F {
        self.dist(&self.root, p, env)
    }

    /// Distance and material in precision `F`.
    pub fn sample_in<F: Real>(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        let (distance, f) = self.surf(&self.root, p, env, &self.default_material);
        Sample {
            distance,
            albedo: f.albedo,
            ambient: f.ambient,
            diffuse: f.diffuse,
            specular: f.specular,
            shininess: f.shininess,
        }
    }

    fn skip<F: Real>(&self, guard: &Option<Guard>, p: V3<F>, nearest: F) -> bool {
        match guard {
            Some(g) if self.guards => {
                let c = v3(F::c(g.center[0]), F::c(g.center[1]), F::c(g.center[2]));
                let h = v3(F::c(g.half[0]), F::c(g.half[1]), F::c(g.half[2]));
                // Evaluated only while the box is nearer than what we have (the same comparison as the kernels).
                let worth_it = sdf::sd_box(p - c, h) < nearest;
                !worth_it
            }
            _ => false,
        }
    }

    fn dist<F: Real>(&self, op: &Op, p: V3<F>, env: &Env<F>) -> F {
        match op {
            Op::Leaf(l) => leaf(l, p, env),
            Op::Fractal { estimator, step } => estimate(estimator, p, env)[0] * F::c(*step),
            Op::Empty => F::infinity(),
            Op::Union(children) => {
                let mut d = self.dist(&children[0].0, p, env);
                for (child, guard) in &children[1..] {
                    if !self.skip(guard, p, d) {
                        d = d.min(self.dist(child, p, env));
                    }
                }
                d
            }
            Op::Intersect(children) => {
                let mut d = self.dist(&children[0], p, env);
                for c in &children[1..] {
                    d = d.max(self.dist(c, p, env));
                }
                d
            }
            Op::Subtract(a, b) => self.dist(a, p, env).max(-self.dist(b, p, env)),
            Op::SmoothUnion(children, k) => {
                let k = k.eval(env);
                let mut d = self.dist(&children[0], p, env);
                for c in &children[1..] {
                    d = sdf::smooth_min(d, self.dist(c, p, env), k);
                }
                d
            }
            Op::SmoothIntersect(children, k) => {
                let k = k.eval(env);
                let mut d = self.dist(&children[0], p, env);
                for c in &children[1..] {
                    d = sdf::smooth_max(d, self.dist(c, p, env), k);
                }
                d
            }
            Op::SmoothSubtract(a, b, k) => {
                let k = k.eval(env);
                sdf::smooth_max(self.dist(a, p, env), -self.dist(b, p, env), k)
            }
            Op::Material(c, _) => self.dist(c, p, env),
            _ => {
                let (child, q, post) = self.domain(op, p, env);
                post.apply(self.dist(child, q, env))
            }
        }
    }

    fn surf<F: Real>(&self, op: &Op, p: V3<F>, env: &Env<F>, m: &Mat) -> (F, Fields<F>) {
        match op {
            Op::Leaf(l) => (leaf(l, p, env), m.leaf(env, None)),
            Op::Fractal { estimator, step } => {
                let [d, trap] = estimate(estimator, p, env);
                (d * F::c(*step), m.leaf(env, Some(trap)))
            }
            Op::Empty => (F::infinity(), m.leaf(env, None)),
            Op::Union(children) => {
                let mut acc = self.surf(&children[0].0, p, env, m);
                for (child, guard) in &children[1..] {
                    if self.skip(guard, p, acc.0) {
                        continue;
                    }
                    let s = self.surf(child, p, env, m);
                    let fields = if s.0 < acc.0 { s.1 } else { acc.1 };
                    acc = (acc.0.min(s.0), fields);
                }
                acc
            }
            Op::Intersect(children) => {
                let mut acc = self.surf(&children[0], p, env, m);
                for c in &children[1..] {
                    let s = self.surf(c, p, env, m);
                    let fields = if acc.0 < s.0 { s.1 } else { acc.1 };
                    acc = (acc.0.max(s.0), fields);
                }
                acc
            }
            Op::Subtract(a, b) => {
                let (d, f) = self.surf(a, p, env, m);
                (d.max(-self.dist(b, p, env)), f)
            }
            Op::SmoothUnion(children, k) | Op::SmoothIntersect(children, k) => {
                let is_union = matches!(op, Op::SmoothUnion(..));
                let k = k.eval(env);
                let mut acc = self.surf(&children[0], p, env, m);
                for c in &children[1..] {
                    let s = self.surf(c, p, env, m);
                    let (d, w) = if is_union {
                        (sdf::smooth_min(acc.0, s.0, k), sdf::blend_weight(acc.0, s.0, k))
                    } else {
                        (sdf::smooth_max(acc.0, s.0, k), sdf::blend_weight(s.0, acc.0, k))
                    };
                    acc = (d, acc.1.mix(s.1, w));
                }
                acc
            }
            Op::SmoothSubtract(a, b, k) => {
                let k = k.eval(env);
                let (d, f) = self.surf(a, p, env, m);
                (sdf::smooth_max(d, -self.dist(b, p, env), k), f)
            }
            Op::Material(c, inner) => self.surf(c, p, env, inner),
            _ => {
                let (child, q, post) = self.domain(op, p, env);
                let (d, f) = self.surf(child, q, env, m);
                (post.apply(d), f)
            }
        }
    }

    /// The single-child operations that move the point and then adjust the child's distance.
    fn domain<'a, F: Real>(&self, op: &'a Op, p: V3<F>, env: &Env<F>) -> (&'a Op, V3<F>, Post<F>) {
        match op {
            Op::Translate(c, off) => (c, p - off.eval(env), Post::Keep),
            Op::Rotate { child, outer, cross, angle } => {
                // p rotated by −angle (so the shape turns by +angle): Rodrigues' matrix c·I + (1 − c)·k·kᵀ − s·[k]×.
                let a = angle.eval(env);
                let c = a.cos();
                let s = -a.sin();
                let one_minus_c = F::one() - c;
                let pc = [p.x, p.y, p.z];
                let q = [0, 1, 2].map(|i| {
                    let mut sum = F::zero();
                    for j in 0..3 {
                        let diag = if i == j { c } else { F::zero() };
                        let e = diag + one_minus_c * F::c(outer[i][j]) + s * F::c(cross[i][j]);
                        sum = sum + e * pc[j];
                    }
                    sum
                });
                (child, v3(q[0], q[1], q[2]), Post::Keep)
            }
            Op::Scale(c, s) => {
                let s = s.eval(env);
                (c, p / s, Post::Mul(s))
            }
            Op::Repeat { child, period, count } => {
                let pc = [p.x, p.y, p.z];
                let q = [0, 1, 2].map(|i| match &period[i] {
                    None => pc[i],
                    Some(per) => {
                        let per = per.eval(env);
                        let mut cell = (pc[i] / per + F::c(0.5)).floor();
                        if let Some(n) = count {
                            cell = clamp(cell, F::c(-(n[i] as f64)), F::c(n[i] as f64));
                        }
                        pc[i] - per * cell
                    }
                });
                (child, v3(q[0], q[1], q[2]), Post::Keep)
            }
            Op::Twist(c, k) | Op::Bend(c, k) => {
                // Twist turns the xz plane by k·y; bend turns the xy plane by k·x.
                let twist = matches!(op, Op::Twist(..));
                let k = k.eval(env);
                let (a, b, driver) = if twist { (p.x, p.z, p.y) } else { (p.x, p.y, p.x) };
                let angle = k * driver;
                let (si, co) = (angle.sin(), angle.cos());
                let ra = co * a - si * b;
                let rb = si * a + co * b;
                let q = if twist { v3(ra, p.y, rb) } else { v3(ra, rb, p.z) };
                // The map's largest stretch at radius ρ: (v + sqrt(v² + 4))/2 with v = |k|·ρ (as the lowering).
                let v = k.abs() * (a * a + b * b).sqrt();
                let stretch = (v + (v * v + F::c(4.0)).sqrt()) * F::c(0.5);
                (c, q, Post::Div(stretch))
            }
            Op::Round(c, r) => (c, p, Post::Sub(r.eval(env))),
            Op::Onion(c, t) => (c, p, Post::AbsSub(t.eval(env))),
            Op::Elongate(c, h) => {
                let pc = [p.x, p.y, p.z];
                let q = [0, 1, 2].map(|i| match &h[i] {
                    None => pc[i],
                    Some(h) => {
                        let h = h.eval(env);
                        pc[i] - clamp(pc[i], -h, h)
                    }
                });
                (c, v3(q[0], q[1], q[2]), Post::Keep)
            }
            _ => unreachable!("domain() is only called for single-child point operations"),
        }
    }
}

/// What a domain operation does to its child's distance.
#[derive(Clone, Copy)]
enum Post<F> {
    Keep,
    Mul(F),
    Div(F),
    Sub(F),
    AbsSub(F),
}

impl<F: Real> Post<F> {
    #[inline]
    fn apply(self, d: F) -> F {
        match self {
            Post::Keep => d,
            Post::Mul(s) => d * s,
            Post::Div(s) => d / s,
            Post::Sub(r) => d - r,
            Post::AbsSub(t) => d.abs() - t,
        }
    }
}

fn leaf<F: Real>(l: &Leaf, p: V3<F>, env: &Env<F>) -> F {
    match l {
        Leaf::Sphere(r) => sdf::sd_sphere(p, r.eval(env)),
        Leaf::Box(h) => sdf::sd_box(p, h.eval(env)),
        Leaf::RoundBox(h, r) => sdf::sd_round_box(p, h.eval(env), r.eval(env)),
        Leaf::Torus(a, b) => sdf::sd_torus(p, a.eval(env), b.eval(env)),
        Leaf::Capsule(a, b, r) => sdf::sd_capsule(p, a.eval(env), b.eval(env), r.eval(env)),
        Leaf::Cylinder(r, h) => sdf::sd_cylinder(p, r.eval(env), h.eval(env)),
        Leaf::Cone(h, r1, r2) => sdf::sd_cone(p, h.eval(env), r1.eval(env), r2.eval(env)),
        Leaf::Plane(n, o) => sdf::sd_plane(p, n.eval(env), o.eval(env)),
        Leaf::Octahedron(s) => sdf::sd_octahedron(p, s.eval(env)),
        Leaf::Ellipsoid(r) => sdf::sd_ellipsoid(p, r.eval(env)),
    }
}

fn estimate<F: Real>(e: &Estimator, p: V3<F>, env: &Env<F>) -> [F; 2] {
    match e {
        Estimator::Mandelbulb8 { iterations, bailout } => sdf::de_mandelbulb8(p, *iterations, bailout.eval(env)),
        Estimator::Mandelbulb { power, iterations, bailout } => {
            sdf::de_mandelbulb(p, power.eval(env), *iterations, bailout.eval(env))
        }
        Estimator::Menger { levels } => sdf::de_menger(p, *levels),
        Estimator::Sierpinski { levels } => sdf::de_sierpinski(p, *levels),
        Estimator::Julia { c, iterations, bailout } => {
            let c = [c[0].eval(env), c[1].eval(env), c[2].eval(env), c[3].eval(env)];
            sdf::de_julia(p, c, *iterations, bailout.eval(env))
        }
        Estimator::Mandelbox { scale, iterations, min_radius, fold_limit } => {
            sdf::de_mandelbox(p, scale.eval(env), *iterations, min_radius.eval(env), fold_limit.eval(env))
        }
    }
}

impl Evaluator<f32> for Interpreter {
    fn distance(&self, p: V3<f32>, env: &Env<f32>) -> f32 {
        self.distance_in(p, env)
    }
    fn sample(&self, p: V3<f32>, env: &Env<f32>) -> Sample<f32> {
        self.sample_in(p, env)
    }
}

impl Evaluator<f64> for Interpreter {
    fn distance(&self, p: V3<f64>, env: &Env<f64>) -> f64 {
        self.distance_in(p, env)
    }
    fn sample(&self, p: V3<f64>, env: &Env<f64>) -> Sample<f64> {
        self.sample_in(p, env)
    }
}
