//! The scene walker: the meaning of every node — CSG, transforms, domain operations, materials, union guards —
//! written once, generic over [`Num`]. The interpreter runs it in f32 and f64; the lowering runs it on symbolic
//! values to record the kernels' `scene_de` and `scene_sample` ([`crate::lower`]). The rules are listed in
//! [`crate::eval`].

use crate::eval::plan::{split_constant, Guard, LeafCall, Mat, OpStep, Paint, Plan, Step, Term};
use crate::eval::{Env, Sample};
use crate::formula::dual::Dual;
use crate::formula::leaf::{LeafArg, LeafOut};
use crate::formula::{CallLeaf, Leaf, TINY};
use crate::ir::op::Meaning;
use crate::number::math::*;

/// Most arguments a leaf function takes, the point included.
const MAX_LEAF_ARGS: usize = 8;

/// The material part of a [`Sample`].
#[derive(Clone, Copy, Debug)]
pub struct Fields<F> {
    pub albedo: V3<F>,
    pub ambient: F,
    pub diffuse: F,
    pub specular: F,
    pub shininess: F,
}

impl<F: CallLeaf> Carry<F> for Fields<F> {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(F) -> F) -> Self {
        Fields {
            albedo: self.albedo.map_nums(f),
            ambient: f(self.ambient),
            diffuse: f(self.diffuse),
            specular: f(self.specular),
            shininess: f(self.shininess),
        }
    }
    #[inline(always)]
    fn zip_nums(self, o: Self, f: &mut impl FnMut(F, F) -> F) -> Self {
        Fields {
            albedo: self.albedo.zip_nums(o.albedo, f),
            ambient: f(self.ambient, o.ambient),
            diffuse: f(self.diffuse, o.diffuse),
            specular: f(self.specular, o.specular),
            shininess: f(self.shininess, o.shininess),
        }
    }
}

impl<F: CallLeaf> Fields<F> {
    /// Mixed towards `o` by `w` (smooth blends).
    #[inline(always)]
    fn mix(self, o: Fields<F>, w: F) -> Fields<F> {
        self.zip_nums(o, &mut |a, b| mix(a, b, w))
    }
    /// `a` where `m`, else `b`.
    #[inline(always)]
    fn select(m: F::Mask, a: Fields<F>, b: Fields<F>) -> Fields<F> {
        a.zip_nums(b, &mut |x, y| select(m, x, y))
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
    SubDiv(F, F),
}

impl<F: CallLeaf> Post<F> {
    #[inline(always)]
    fn apply(self, d: F) -> F {
        match self {
            Post::Keep => d,
            Post::Mul(s) => d * s,
            Post::Div(s) => d / s,
            Post::Sub(r) => d - r,
            Post::AbsSub(t) => abs(d) - t,
            Post::SubDiv(a, k) => (d - a) / k,
        }
    }
}

/// A point as the walker carries it: `rel` from the frame's anchor where there is one ([`Env::anchor`]), else the
/// point itself. Translations move the anchor, so the large parts of a far scene's coordinates cancel before the
/// small offset is added; any other operation, a guard and a leaf take the whole point.
#[derive(Clone, Copy, Debug)]
struct At<F> {
    anchor: Option<V3<F>>,
    rel: V3<F>,
}

impl<F: CallLeaf> At<F> {
    #[inline(always)]
    fn of(p: V3<F>, env: &Env<F>) -> At<F> {
        At { anchor: env.anchor, rel: p }
    }
    #[inline(always)]
    fn own(p: V3<F>) -> At<F> {
        At { anchor: None, rel: p }
    }
    /// The point moved by −t: the anchor by t's f32 part and then its rest (`split`, see [`OpStep::vec_split`]), a
    /// point of its own by t `whole`.
    #[inline(always)]
    fn minus(self, whole: impl FnOnce() -> V3<F>, split: impl FnOnce() -> (V3<F>, Option<V3<F>>)) -> At<F> {
        match self.anchor {
            Some(a) => {
                let (high, rest) = split();
                let a = a - high;
                At { anchor: Some(rest.map_or(a, |rest| a - rest)), rel: self.rel }
            }
            None => At::own(self.rel - whole()),
        }
    }
    /// The point moved by a translation.
    #[inline(always)]
    fn translated(self, op: &OpStep, env: &Env<F>) -> At<F> {
        self.minus(|| op.vec(0, env), || op.vec_split(0, env))
    }
    #[inline(always)]
    fn whole(self) -> V3<F> {
        self.anchor.map_or(self.rel, |a| a + self.rel)
    }
}

/// Evaluates a [`Plan`] in any [`Num`].
#[derive(Clone, Copy, Debug)]
pub struct Walk<'a> {
    pub plan: &'a Plan,
    /// Whether union children behind a bound are skipped while the bound is no nearer than the nearest so far.
    pub guards: bool,
}

impl Walk<'_> {
    /// Signed distance at `p`.
    #[inline]
    pub fn distance<F: CallLeaf>(&self, p: V3<F>, env: &Env<F>) -> F {
        self.dist(&self.plan.root, At::of(p, env), env)
    }

    /// The distance's gradient at `p`, by forward-mode differentiation: the walk run in [`Dual`] numbers with the
    /// point's coordinates as the variables. How a leaf and a formula are differentiated: `CallLeaf for Dual`
    /// ([`crate::formula`]). The frame's time and parameters are constants; the walk reads no perturbation reference
    /// here, as [`Walk::distance`] is called without one.
    #[inline]
    pub fn gradient<F: CallLeaf>(&self, p: V3<F>, env: &Env<F>) -> V3<F> {
        let params: Vec<Dual<F>> = env.params.iter().map(|&x| Dual::constant(x)).collect();
        let env = Env {
            time: Dual::constant(env.time),
            params: &params,
            reference: None,
            anchor: env.anchor.map(|a| v3(Dual::constant(a.x), Dual::constant(a.y), Dual::constant(a.z))),
        };
        let p = v3(Dual::variable(p.x, 0), Dual::variable(p.y, 1), Dual::variable(p.z, 2));
        let [x, y, z] = self.distance(p, &env).d;
        v3(x, y, z)
    }

    /// Distance and material at `p`.
    #[inline]
    pub fn sample<F: CallLeaf>(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        let at = At::of(p, env);
        let (distance, f) = self.surf(&self.plan.root, at, env, &self.plan.default_material, at);
        Sample {
            distance,
            albedo: f.albedo,
            ambient: f.ambient,
            diffuse: f.diffuse,
            specular: f.specular,
            shininess: f.shininess,
        }
    }

    /// Whether a guarded child is worth evaluating: its box is nearer than `nearest` (the kernels' comparison).
    #[inline]
    fn guard<F: CallLeaf>(&self, guard: &Option<Guard>, p: At<F>, nearest: F) -> Option<F::Mask> {
        let g = guard.as_ref().filter(|_| self.guards)?;
        let center = || v3(c(g.center[0]), c(g.center[1]), c(g.center[2]));
        let half = v3(c(g.half[0]), c(g.half[1]), c(g.half[2]));
        // The centre split as a translation's literal is: the guard of a translated child shares its point.
        let at = p.minus(center, || split_constant(g.center)).whole();
        let to_box = F::leaf(Leaf::SdBox, &[LeafArg::V3(at), LeafArg::V3(half)]).distance();
        Some(lt(to_box, nearest))
    }

    fn dist<F: CallLeaf>(&self, step: &Step, p: At<F>, env: &Env<F>) -> F {
        let op = match step {
            Step::Leaf(call) => return leaf(call, p.whole(), env).distance(),
            Step::Fractal { call, step } => return leaf(call, p.whole(), env).distance() * c(*step),
            Step::Formula { call, step } => return call.run(p.whole(), env).distance() * c(*step),
            Step::Empty => return c(f64::INFINITY),
            Step::Material(child, _) => return self.dist(child, p, env),
            Step::Op(op) => op,
        };
        let rest = || op.shapes[1..].iter();
        match op.meaning {
            Meaning::Union => {
                let mut d = self.dist(op.shape(0), p, env);
                for (child, guard) in rest() {
                    d = match self.guard(guard, p, d) {
                        Some(worth_it) => F::when(
                            worth_it,
                            d,
                            #[inline(always)]
                            |d| min(d, self.dist(child, p, env)),
                        ),
                        None => min(d, self.dist(child, p, env)),
                    };
                }
                d
            }
            Meaning::Intersect => rest().fold(self.dist(op.shape(0), p, env), |d, (s, _)| max(d, self.dist(s, p, env))),
            Meaning::Subtract => max(self.dist(op.shape(0), p, env), -self.dist(op.shape(1), p, env)),
            Meaning::SmoothUnion | Meaning::SmoothIntersect => {
                let blend = if op.meaning == Meaning::SmoothUnion { Leaf::SmoothMin } else { Leaf::SmoothMax };
                let k = op.num(0, env);
                rest().fold(self.dist(op.shape(0), p, env), |d, (s, _)| leaf3(blend, d, self.dist(s, p, env), k))
            }
            Meaning::SmoothSubtract => {
                let k = op.num(0, env);
                leaf3(Leaf::SmoothMax, self.dist(op.shape(0), p, env), -self.dist(op.shape(1), p, env), k)
            }
            // The commonest operation, without `domain`'s general result (a tenth of the interpreter's time on a
            // union of translated primitives).
            Meaning::Translate => self.dist(op.shape(0), p.translated(op, env), env),
            _ => {
                let (q, post) = domain(op, p.whole(), env);
                post.apply(self.dist(op.shape(0), At::own(q), env))
            }
        }
    }

    /// Distance and material at `p` under the material `m`, whose expressions read the point `mp` (where `m` was
    /// applied, in that node's coordinates: a pattern moves with its shape).
    fn surf<F: CallLeaf>(&self, step: &Step, p: At<F>, env: &Env<F>, m: &Mat, mp: At<F>) -> (F, Fields<F>) {
        let op = match step {
            Step::Leaf(call) => return (leaf(call, p.whole(), env).distance(), leaf_fields(m, env, None, mp)),
            Step::Fractal { call, step } => {
                let out = leaf(call, p.whole(), env);
                return (out.distance() * c(*step), leaf_fields(m, env, out.trap(), mp));
            }
            Step::Formula { call, step } => {
                let out = call.run(p.whole(), env);
                return (out.distance() * c(*step), leaf_fields(m, env, out.trap(), mp));
            }
            Step::Empty => return (c(f64::INFINITY), leaf_fields(m, env, None, mp)),
            Step::Material(child, inner) => return self.surf(child, p, env, inner, p),
            Step::Op(op) => op,
        };
        let rest = || op.shapes[1..].iter();
        match op.meaning {
            Meaning::Union => {
                let mut acc = self.surf(op.shape(0), p, env, m, mp);
                for (child, guard) in rest() {
                    let nearest = |(d, f): (F, Fields<F>)| {
                        let (ds, fs) = self.surf(child, p, env, m, mp);
                        (min(d, ds), Fields::select(lt(ds, d), fs, f))
                    };
                    acc = match self.guard(guard, p, acc.0) {
                        Some(worth_it) => F::when(worth_it, acc, nearest),
                        None => nearest(acc),
                    };
                }
                acc
            }
            Meaning::Intersect => rest().fold(self.surf(op.shape(0), p, env, m, mp), |acc, (s, _)| {
                let (ds, fs) = self.surf(s, p, env, m, mp);
                (max(acc.0, ds), Fields::select(lt(acc.0, ds), fs, acc.1))
            }),
            Meaning::Subtract => {
                let (d, f) = self.surf(op.shape(0), p, env, m, mp);
                (max(d, -self.dist(op.shape(1), p, env)), f)
            }
            Meaning::SmoothUnion | Meaning::SmoothIntersect => {
                let union = op.meaning == Meaning::SmoothUnion;
                let k = op.num(0, env);
                rest().fold(self.surf(op.shape(0), p, env, m, mp), |acc, (s, _)| {
                    let (ds, fs) = self.surf(s, p, env, m, mp);
                    let (d, w) = if union {
                        (leaf3(Leaf::SmoothMin, acc.0, ds, k), leaf3(Leaf::BlendWeight, acc.0, ds, k))
                    } else {
                        (leaf3(Leaf::SmoothMax, acc.0, ds, k), leaf3(Leaf::BlendWeight, ds, acc.0, k))
                    };
                    (d, acc.1.mix(fs, w))
                })
            }
            Meaning::SmoothSubtract => {
                let k = op.num(0, env);
                let (d, f) = self.surf(op.shape(0), p, env, m, mp);
                (leaf3(Leaf::SmoothMax, d, -self.dist(op.shape(1), p, env), k), f)
            }
            Meaning::Translate => self.surf(op.shape(0), p.translated(op, env), env, m, mp),
            _ => {
                let (q, post) = domain(op, p.whole(), env);
                let (d, f) = self.surf(op.shape(0), At::own(q), env, m, mp);
                (post.apply(d), f)
            }
        }
    }
}

/// Calls a primitive's or fractal's leaf function at `p`.
#[inline]
fn leaf<F: CallLeaf>(call: &LeafCall, p: V3<F>, env: &Env<F>) -> LeafOut<F> {
    // Filled with counts, the smallest argument, not with the point: copying a packet's point into every unused slot
    // cost a tenth of the interpreter's time on a union of 16 spheres.
    let mut args = [LeafArg::Count(F::count(0)); MAX_LEAF_ARGS];
    args[0] = LeafArg::V3(p);
    for (slot, a) in args[1..].iter_mut().zip(&call.args) {
        *slot = a.eval(env);
    }
    F::leaf(call.leaf, &args[..=call.args.len()])
}

/// Calls a leaf of three numbers (the smooth blends).
#[inline]
fn leaf3<F: CallLeaf>(leaf: Leaf, a: F, b: F, k: F) -> F {
    F::leaf(leaf, &[LeafArg::F(a), LeafArg::F(b), LeafArg::F(k)]).distance()
}

/// The material of a leaf under `m`, its expressions reading the point `mp`; `trap` is the fractal's orbit trap, for
/// fractal leaves.
#[inline]
fn leaf_fields<F: CallLeaf>(m: &Mat, env: &Env<F>, trap: Option<F>, mp: At<F>) -> Fields<F> {
    let at = Some(mp.whole());
    let albedo = match (&m.albedo, trap) {
        (Paint::Rgb(c), _) => c.eval_at(env, at),
        (Paint::OrbitTrap(a, _), None) => a.eval_at(env, at),
        (Paint::OrbitTrap(a, b), Some(t)) => mix3(a.eval_at(env, at), b.eval_at(env, at), t),
    };
    Fields {
        albedo,
        ambient: m.ambient.eval_at(env, at),
        diffuse: m.diffuse.eval_at(env, at),
        specular: m.specular.eval_at(env, at),
        shininess: m.shininess.eval_at(env, at),
    }
}

/// Each axis of `p` moved by `f(axis, coordinate, term)`, or left alone where the term folded to 0.
#[inline]
fn per_axis<F: CallLeaf>(p: V3<F>, terms: [Option<&Term>; 3], env: &Env<F>, f: impl Fn(usize, F, F) -> F) -> V3<F> {
    let pc = [p.x, p.y, p.z];
    let q = [0, 1, 2].map(|i| match terms[i] {
        None => pc[i],
        Some(t) => f(i, pc[i], t.eval(env)),
    });
    v3(q[0], q[1], q[2])
}

/// The single-shape operations: where they move the point, and what they then do to the shape's distance.
fn domain<F: CallLeaf>(op: &OpStep, p: V3<F>, env: &Env<F>) -> (V3<F>, Post<F>) {
    match op.meaning {
        Meaning::Translate => (p - op.vec(0, env), Post::Keep),
        Meaning::Rotate(axis) => {
            // p rotated by −angle (so the shape turns by +angle): Rodrigues' matrix c·I + (1 − c)·k·kᵀ − s·[k]×.
            let (k, angle) = match axis {
                Some(k) => (k, op.num(0, env)),
                None => (op.constant3(0), op.num(1, env)),
            };
            let outer = [0, 1, 2].map(|i| [0, 1, 2].map(|j| k[i] * k[j]));
            let cross = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
            let co = cos(angle);
            let s = -sin(angle);
            let one_minus_c = c::<F>(1.0) - co;
            let pc = [p.x, p.y, p.z];
            let q = [0, 1, 2].map(|i| {
                let mut sum = c::<F>(0.0);
                for j in 0..3 {
                    let diag = if i == j { co } else { c(0.0) };
                    let e = diag + one_minus_c * c(outer[i][j]) + s * c(cross[i][j]);
                    sum = sum + e * pc[j];
                }
                sum
            });
            (v3(q[0], q[1], q[2]), Post::Keep)
        }
        Meaning::Scale => {
            let s = op.num(0, env);
            (p / s, Post::Mul(s))
        }
        Meaning::Repeat { limited } => {
            let count = limited.then(|| op.constant3(1));
            let terms = op.per_axis(0);
            let q = per_axis(p, terms, env, |axis, x, per| {
                let cell = floor(x / per + c(0.5));
                let cell = match count {
                    Some(n) => clamp(cell, c(-n[axis]), c(n[axis])),
                    None => cell,
                };
                let repeated = x - per * cell;
                // A literal 0 leaves its axis unrepeated (folded away above); a period that reaches 0 at run time
                // (a `param` slid to 0) must mean the same, not 0 · floor(x / 0) = NaN.
                match terms[axis] {
                    Some(Term::Lit(_)) => repeated,
                    _ => select(le(per, c(0.0)), x, repeated),
                }
            });
            (q, Post::Keep)
        }
        Meaning::Twist | Meaning::Bend => {
            // Twist turns the xz plane by k·y; bend turns the xy plane by k·x. At radius ρ from the axis the map
            // stretches space by up to (v + sqrt(v² + 4))/2 with v = |k|·ρ (the Jacobian's largest singular value), so
            // the child's distance is divided by that to stay a lower bound.
            let twist = op.meaning == Meaning::Twist;
            let k = op.num(0, env);
            let (a, b, driver) = if twist { (p.x, p.z, p.y) } else { (p.x, p.y, p.x) };
            let angle = k * driver;
            let (si, co) = (sin(angle), cos(angle));
            let ra = co * a - si * b;
            let rb = si * a + co * b;
            let q = if twist { v3(ra, p.y, rb) } else { v3(ra, rb, p.z) };
            let v = abs(k) * sqrt(a * a + b * b);
            let stretch = (v + sqrt(v * v + c(4.0))) * c(0.5);
            (q, Post::Div(stretch))
        }
        Meaning::Round => (p, Post::Sub(op.num(0, env))),
        Meaning::Onion => (p, Post::AbsSub(op.num(0, env))),
        Meaning::Elongate => (per_axis(p, op.per_axis(0), env, |_, x, h| x - clamp(x, -h, h)), Post::Keep),
        Meaning::PlaneFold => {
            let n = op.constant3(0);
            let n = v3(c::<F>(n[0]), c(n[1]), c(n[2]));
            (p - n * (c::<F>(2.0) * min(dot(p, n), c(0.0))), Post::Keep)
        }
        Meaning::AbsFold => {
            let axes = op.constant3(0);
            let fold = |i: usize, x: F| if axes[i] != 0.0 { abs(x) } else { x };
            (v3(fold(0, p.x), fold(1, p.y), fold(2, p.z)), Post::Keep)
        }
        Meaning::BoxFold => {
            let l = op.num(0, env);
            (p.map(|x| clamp(x, -l, l) * c(2.0) - x), Post::Keep)
        }
        Meaning::SphereFold => {
            // Inside min_radius a plain scale by fixed²/min², between the radii inversion by fixed²/r², outside
            // nothing; the distance found there is divided by the same factor, as a scale's is.
            let (min_r, fixed) = (op.num(0, env), op.num(1, env));
            let (min2, fixed2) = (min_r * min_r, fixed * fixed);
            let r2 = dot(p, p);
            let f = select(lt(r2, min2), fixed2 / min2, select(lt(r2, fixed2), fixed2 / max(r2, c(TINY)), c(1.0)));
            (p * f, Post::Div(f))
        }
        Meaning::Displace => (p, Post::SubDiv(op.num_at(0, env, p), op.num(1, env))),
        Meaning::PolarRepeat => {
            // The point turned back about y by its sector's angle k·2π/n, so the sector around +x holds it. The
            // angle only picks k; turning by k·2π/n rather than taking the remainder of the angle keeps atan2's
            // error (several ulps on some GPU drivers) out of the point.
            let sector = c::<F>(std::f64::consts::TAU) / op.num(0, env);
            let turn = sector * floor(atan2(p.z, p.x) / sector + c(0.5));
            let (co, si) = (cos(turn), sin(turn));
            (v3(co * p.x + si * p.z, p.y, co * p.z - si * p.x), Post::Keep)
        }
        Meaning::Union
        | Meaning::Intersect
        | Meaning::Subtract
        | Meaning::SmoothUnion
        | Meaning::SmoothIntersect
        | Meaning::SmoothSubtract => unreachable!("combinations are evaluated by the walker, not as domain operations"),
    }
}
