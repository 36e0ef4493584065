//! Formulas written in the scene language ([`crate::ir::formula`]), run in any [`Num`]: the map itself
//! ([`run_map`]), and around it the orbit, the distance estimate and the membership test, written once here for every
//! formula. The estimate's derivative is the orbit run in [`Dual`] numbers, so it is derived, never written: the
//! kernels trace it like any other formula.
//!
//! Every operation has one defined result on every backend: `sqrt`, `ln`, `acos`, `asin`, `exp` and a `pow` of a
//! non-integer exponent read their argument clamped into their domain, a division divides by at least 10⁻³⁰ in
//! magnitude (`x / 0` is x·10³⁰, `0 / 0` is 0), a `pow` of a small integer exponent is multiplied out (defined for
//! negative bases), and an orbit keeps its last iterate whose length and derivative are finite (below [`FINITE`]),
//! stopping there as if escaped. So a NaN or an infinity never reaches an estimate.

use std::sync::Arc;

use super::common::{DR_MAX, TINY};
use super::dual::Dual;
use super::lang::{FBin, FCmp, FExpr, FFunc, FLogic, Formula, FormulaKind, FormulaMap};
use crate::number::math::*;
use crate::number::{Mask, Num};

/// Largest length or derivative an orbit keeps: past it an iterate counts as escaped with the one before.
pub const FINITE: f64 = 1e30;
/// The step factor of a formula no one has measured: half the estimate (`fractal accuracy --estimators SCENE`
/// measures one, and `.step_factor(k)` sets it).
pub const UNMEASURED_STEP_FACTOR: f64 = 0.5;
/// Largest argument `exp` takes: e^80 ≈ 5.5·10³⁴ stays finite in f32.
const EXP_MAX: f64 = 80.0;
/// Largest integer exponent `pow` multiplies out.
const MULTIPLIED_POW: f64 = 16.0;

/// A value of a formula: a number, a vector of 2..4 numbers, or a truth value.
#[derive(Clone, Copy, Debug)]
pub enum Value<F: Num> {
    N(F),
    V([F; 4], u8),
    B(F::Mask),
}

impl<F: Num> Value<F> {
    #[inline(always)]
    fn num(self) -> F {
        match self {
            Value::N(x) => x,
            Value::V(v, _) => v[0],
            Value::B(_) => F::lit(0.0),
        }
    }
    #[inline(always)]
    fn mask(self) -> F::Mask {
        match self {
            Value::B(m) => m,
            _ => F::Mask::splat(false),
        }
    }
    /// The components (a number has one).
    #[inline(always)]
    fn comps(self) -> ([F; 4], usize) {
        match self {
            Value::N(x) => ([x; 4], 1),
            Value::V(v, n) => (v, n as usize),
            Value::B(_) => ([F::lit(0.0); 4], 1),
        }
    }
    #[inline(always)]
    fn vec(v: &[F]) -> Value<F> {
        let mut out = [F::lit(0.0); 4];
        out[..v.len()].copy_from_slice(v);
        Value::V(out, v.len() as u8)
    }
    #[inline(always)]
    fn v3(self) -> V3<F> {
        let (c, _) = self.comps();
        v3(c[0], c[1], c[2])
    }
}

/// A divisor at least [`TINY`] in magnitude (its sign kept, +TINY for 0): a formula's x / 0 is x·10³⁰ and 0 / 0 is
/// 0 on every backend, where IEEE division would give infinities and NaNs that fast-math kernels do not keep.
#[inline(always)]
fn away_from_zero<F: Num>(y: F) -> F {
    let tiny = F::lit(TINY);
    select(lt(abs(y), tiny), select(lt(y, F::lit(0.0)), -tiny, tiny), y)
}

/// `f` per component of `a` and `b`, a number standing for every component of the other.
#[inline(always)]
fn zip<F: Num>(a: Value<F>, b: Value<F>, f: impl Fn(F, F) -> F) -> Value<F> {
    match (a, b) {
        (Value::N(x), Value::N(y)) => Value::N(f(x, y)),
        _ => {
            let ((ac, an), (bc, bn)) = (a.comps(), b.comps());
            let n = an.max(bn);
            let pick = |c: &[F; 4], len: usize, i: usize| if len == 1 { c[0] } else { c[i] };
            let mut out = [F::lit(0.0); 4];
            for (i, o) in out.iter_mut().enumerate().take(n) {
                *o = f(pick(&ac, an, i), pick(&bc, bn, i));
            }
            Value::V(out, n as u8)
        }
    }
}

/// `f` per component.
#[inline(always)]
fn each<F: Num>(a: Value<F>, f: impl Fn(F) -> F) -> Value<F> {
    match a {
        Value::N(x) => Value::N(f(x)),
        Value::V(v, n) => Value::V(v.map(f), n),
        Value::B(m) => Value::B(m),
    }
}

/// x raised to a power: multiplied out for a whole exponent up to [`MULTIPLIED_POW`] (by squaring), else
/// `pow(max(x, 0), y)`.
#[inline(always)]
fn power<F: Num>(x: F, y: F, literal: Option<f64>) -> F {
    match literal {
        Some(n) if n.fract() == 0.0 && n.abs() <= MULTIPLIED_POW => {
            let (mut result, mut base, mut k) = (None::<F>, x, n.abs() as u32);
            while k > 0 {
                if k & 1 == 1 {
                    result = Some(result.map_or(base, |r| r * base));
                }
                k >>= 1;
                if k > 0 {
                    base = base * base;
                }
            }
            let r = result.unwrap_or_else(|| F::lit(1.0));
            if n < 0.0 {
                F::lit(1.0) / r
            } else {
                r
            }
        }
        _ => pow(max(x, F::lit(0.0)), y),
    }
}

/// Runs one map at (z, c): the next z, and the map's own scale where it gives one. `nums` are the formula's scene
/// numbers in [`Formula::each_num`] order (the `u16` of an expression indexes them); `literals` says which of them
/// are literals, and their values (a `pow` of a literal whole exponent is multiplied out).
#[inline]
pub fn run_map<F: Num>(
    map: &FormulaMap<u16>,
    nums: &[F],
    literals: &[Option<f64>],
    z: V3<F>,
    c: V3<F>,
) -> (V3<F>, Option<F>) {
    let mut run = Run { nums, literals, z, c, lets: Vec::with_capacity(map.lets.len()) };
    for (_, e) in &map.lets {
        let v = run.eval(e);
        run.lets.push(v);
    }
    let next = run.eval(&map.next).v3();
    let scale = map.scale.as_ref().map(|s| run.eval(s).num());
    (next, scale)
}

struct Run<'a, F: Num> {
    nums: &'a [F],
    literals: &'a [Option<f64>],
    z: V3<F>,
    c: V3<F>,
    lets: Vec<Value<F>>,
}

impl<F: Num> Run<'_, F> {
    fn literal(&self, e: &FExpr<u16>) -> Option<f64> {
        match e {
            FExpr::Num(i) => self.literals.get(*i as usize).copied().flatten(),
            FExpr::Neg(a) => self.literal(a).map(|v| -v),
            _ => None,
        }
    }

    fn eval(&self, e: &FExpr<u16>) -> Value<F> {
        match e {
            FExpr::Num(i) => Value::N(self.nums.get(*i as usize).copied().unwrap_or_else(|| F::lit(0.0))),
            FExpr::Arg(0) => Value::vec(&[self.z.x, self.z.y, self.z.z]),
            FExpr::Arg(_) => Value::vec(&[self.c.x, self.c.y, self.c.z]),
            FExpr::Let(i) => self.lets.get(*i as usize).copied().unwrap_or(Value::N(F::lit(0.0))),
            FExpr::Neg(a) => each(self.eval(a), |x| -x),
            FExpr::Bin(op, a, b) => {
                let (a, b) = (self.eval(a), self.eval(b));
                match op {
                    FBin::Add => zip(a, b, |x, y| x + y),
                    FBin::Sub => zip(a, b, |x, y| x - y),
                    FBin::Mul => zip(a, b, |x, y| x * y),
                    FBin::Div => zip(a, b, |x, y| x / away_from_zero(y)),
                }
            }
            FExpr::Call(f, args) => self.call(*f, args),
            FExpr::Swizzle(a, s) => {
                let (comps, _) = self.eval(a).comps();
                let picked: Vec<F> = s.index[..s.len as usize].iter().map(|&i| comps[i as usize]).collect();
                match picked.as_slice() {
                    [one] => Value::N(*one),
                    many => Value::vec(many),
                }
            }
            FExpr::Cmp(op, a, b) => {
                let (a, b) = (self.eval(a).num(), self.eval(b).num());
                Value::B(match op {
                    FCmp::Lt => lt(a, b),
                    FCmp::Le => le(a, b),
                    FCmp::Gt => gt(a, b),
                    FCmp::Ge => ge(a, b),
                })
            }
            FExpr::Logic(op, a, b) => {
                let (a, b) = (self.eval(a).mask(), self.eval(b).mask());
                Value::B(match op {
                    FLogic::And => a & b,
                    FLogic::Or => a | b,
                })
            }
            FExpr::Not(a) => Value::B(!self.eval(a).mask()),
            FExpr::If(cond, a, b) => {
                let m = self.eval(cond).mask();
                match (self.eval(a), self.eval(b)) {
                    (Value::B(x), Value::B(y)) => Value::B((m & x) | (!m & y)),
                    (a, b) => zip(a, b, |x, y| select(m, x, y)),
                }
            }
        }
    }

    fn call(&self, f: FFunc, args: &[FExpr<u16>]) -> Value<F> {
        let arg = |i: usize| self.eval(&args[i]);
        let zero = F::lit(0.0);
        let one = F::lit(1.0);
        match f {
            FFunc::Vec2 | FFunc::Vec3 | FFunc::Vec4 => {
                let mut parts: Vec<F> = Vec::with_capacity(4);
                for i in 0..args.len() {
                    let (c, n) = arg(i).comps();
                    parts.extend_from_slice(&c[..n]);
                }
                parts.truncate(4);
                Value::vec(&parts)
            }
            FFunc::Length => Value::N(sqrt(dot_all(arg(0), arg(0)))),
            FFunc::Dot => Value::N(dot_all(arg(0), arg(1))),
            FFunc::Cross => {
                let (a, b) = (arg(0).v3(), arg(1).v3());
                let r = cross(a, b);
                Value::vec(&[r.x, r.y, r.z])
            }
            FFunc::Normalize => {
                let a = arg(0);
                let l = sqrt(dot_all(a, a));
                let inv = select(gt(l, F::lit(TINY)), one / max(l, F::lit(TINY)), zero);
                each(a, |x| x * inv)
            }
            FFunc::Abs => each(arg(0), abs),
            FFunc::Sign => each(arg(0), |x| select(gt(x, zero), one, select(lt(x, zero), -one, zero))),
            FFunc::Floor => each(arg(0), floor),
            FFunc::Fract => each(arg(0), |x| x - floor(x)),
            FFunc::Sqrt => each(arg(0), |x| sqrt(max(x, zero))),
            FFunc::Sin => each(arg(0), sin),
            FFunc::Cos => each(arg(0), cos),
            FFunc::Tan => each(arg(0), |x| sin(x) / away_from_zero(cos(x))),
            FFunc::Asin => each(arg(0), |x| {
                let x = clamp(x, -one, one);
                atan2(x, sqrt(max(one - x * x, zero)))
            }),
            FFunc::Acos => each(arg(0), |x| acos(clamp(x, -one, one))),
            FFunc::Atan => each(arg(0), |x| atan2(x, one)),
            FFunc::Atan2 => zip(arg(0), arg(1), atan2),
            FFunc::Exp => each(arg(0), |x| exp2(min(x, F::lit(EXP_MAX)) * F::lit(core::f64::consts::LOG2_E))),
            FFunc::Ln => each(arg(0), |x| ln(max(x, F::lit(TINY)))),
            FFunc::Pow => {
                let literal = self.literal(&args[1]);
                let y = arg(1).num();
                each(arg(0), |x| power(x, y, literal))
            }
            FFunc::Min => zip(arg(0), arg(1), min),
            FFunc::Max => zip(arg(0), arg(1), max),
            FFunc::Clamp => {
                let lo = zip(arg(0), arg(1), max);
                zip(lo, arg(2), min)
            }
            FFunc::Mix => {
                let (a, b, t) = (arg(0), arg(1), arg(2));
                let d = zip(b, a, |y, x| y - x);
                zip(a, zip(d, t, |d, t| d * t), |x, y| x + y)
            }
            FFunc::Cmul => {
                let ((a, _), (b, _)) = (arg(0).comps(), arg(1).comps());
                Value::vec(&[a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0]])
            }
            FFunc::Csqr => {
                let (a, _) = arg(0).comps();
                Value::vec(&[a[0] * a[0] - a[1] * a[1], F::lit(2.0) * a[0] * a[1]])
            }
            FFunc::Qmul => {
                let ((a, _), (b, _)) = (arg(0).comps(), arg(1).comps());
                Value::vec(&quaternion_product(a, b))
            }
            FFunc::Qsqr => {
                let (a, _) = arg(0).comps();
                Value::vec(&quaternion_product(a, a))
            }
            FFunc::BoxFold => {
                let l = arg(1).num();
                each(arg(0), |x| clamp(x, -l, l) * F::lit(2.0) - x)
            }
            FFunc::SphereFold => {
                let a = arg(0);
                let (min_r, fixed) = (arg(1).num(), arg(2).num());
                let (min2, fixed2) = (min_r * min_r, fixed * fixed);
                let r2 = dot_all(a, a);
                let k = select(
                    lt(r2, min2),
                    fixed2 / max(min2, F::lit(TINY)),
                    select(lt(r2, fixed2), fixed2 / max(r2, F::lit(TINY)), one),
                );
                each(a, |x| x * k)
            }
        }
    }
}

/// The sum of the products of the components.
#[inline(always)]
fn dot_all<F: Num>(a: Value<F>, b: Value<F>) -> F {
    let ((ac, n), (bc, _)) = (a.comps(), b.comps());
    (1..n).fold(ac[0] * bc[0], |s, i| s + ac[i] * bc[i])
}

/// The quaternion product a·b, components (x, y, z, w) = x + iy + jz + kw.
#[inline(always)]
fn quaternion_product<F: Num>(a: [F; 4], b: [F; 4]) -> [F; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// A formula ready to run: its maps with scene numbers as indices into the numbers the caller evaluates.
#[derive(Clone, Debug)]
pub struct Ready {
    pub formula: Formula<u16>,
    /// Which numbers are literals, with their values.
    pub literals: Vec<Option<f64>>,
    pub iterations: u32,
    /// The formula compiled for the host, where it has been ([`crate::lower::tape`]): what f64 runs instead of
    /// walking the formula's tree.
    pub host: Option<Arc<dyn HostCode>>,
}

/// Two ready formulas are alike when their formulas, numbers and iterations are: host code is compiled from those.
impl PartialEq for Ready {
    fn eq(&self, o: &Ready) -> bool {
        self.formula == o.formula && self.literals == o.literals && self.iterations == o.iterations
    }
}

/// A formula compiled for the host in f64: [`membership`] and [`estimate`] with the same arguments, computing what
/// they compute.
pub trait HostCode: Send + Sync + std::fmt::Debug {
    fn membership(&self, nums: &[f64], p: [f64; 3], bailout: f64) -> f64;
    /// None where the code was compiled for the other `signed`.
    fn estimate(&self, nums: &[f64], p: [f64; 3], bailout: f64, signed: bool) -> Option<[f64; 2]>;
}

/// What the orbit carries: z with its Jacobian rows (as dual numbers), and [|z|, the norm of the Jacobian, the orbit
/// trap, the steps taken, whether it goes on (1) or stopped at a non-finite iterate (0)].
type Orbit<F> = ([Dual<F>; 3], [F; 5]);

/// The Frobenius norm of the Jacobian (rows: the derivatives of z's components): at least its largest singular value.
/// The orbit watches it for overflow and the derivative cap.
#[inline(always)]
fn jacobian_norm<F: Num>(z: &[Dual<F>; 3]) -> F {
    let mut s = F::lit(0.0);
    for zi in z {
        for d in zi.d {
            s = s + d * d;
        }
    }
    sqrt(s)
}

/// A bound on the Jacobian's largest singular value, the norm a fold's estimate divides by: √λ with λ the least of
/// two bounds on the largest eigenvalue of JᵀJ, its trace and its largest absolute row sum (Gershgorin). Never below
/// the singular value, so (|z| − bailout) / it stays at or below the estimate the exact norm gives; exact for a
/// conformal map (JᵀJ a multiple of I), where the Frobenius norm would read √3 times too much.
#[inline(always)]
fn spectral_bound<F: Num>(z: &[Dual<F>; 3]) -> F {
    let a = |k: usize, l: usize| z[0].d[k] * z[0].d[l] + z[1].d[k] * z[1].d[l] + z[2].d[k] * z[2].d[l];
    let (a00, a11, a22, a01, a02, a12) = (a(0, 0), a(1, 1), a(2, 2), a(0, 1), a(0, 2), a(1, 2));
    let trace = a00 + a11 + a22;
    let rows = max(max(a00 + abs(a01) + abs(a02), a11 + abs(a01) + abs(a12)), a22 + abs(a02) + abs(a12));
    sqrt(min(trace, rows))
}

/// |∇|zₙ||, the gradient of the last iterate's length with respect to the point: Jᵀ·zₙ / |zₙ| with J the Jacobian
/// the orbit carries (rows: the derivatives of z's components). An escape-time estimate divides by it: the potential
/// G = ln|zₙ| / kⁿ has |∇G| = |∇|zₙ|| / (|zₙ| kⁿ), so 0.5·G / |∇G| is 0.5·|zₙ|·ln|zₙ| / |∇|zₙ|| (Hubbard and Douady's
/// estimate, in 3D as in the plane). It reads J along zₙ only: a map that stretches space across the orbit's
/// direction (a bulb's angles) does not shrink the estimate where that stretch does not move the potential.
#[inline(always)]
fn radial_gradient<F: Num>(z: &[Dual<F>; 3], r: F) -> F {
    let g = |k: usize| z[0].v * z[0].d[k] + z[1].v * z[1].d[k] + z[2].v * z[2].d[k];
    let (g0, g1, g2) = (g(0), g(1), g(2));
    sqrt(g0 * g0 + g1 * g1 + g2 * g2) / max(r, F::lit(TINY))
}

/// The orbit of a formula from `p`: every map in turn, one per iteration, up to `ready.iterations`; an escape-time
/// orbit stops past `escape` or once its derivative passes [`DR_MAX`]. Returns the last state.
#[inline]
fn orbit<F: Num>(ready: &Ready, nums: &[F], p: V3<F>, escape: F) -> Orbit<F> {
    let formula = &ready.formula;
    let duals: Vec<Dual<F>> = nums.iter().map(|&n| Dual::constant(n)).collect();
    let point = [Dual::variable(p.x, 0), Dual::variable(p.y, 1), Dual::variable(p.z, 2)];
    let c = v3(point[0], point[1], point[2]);
    let own_scale = formula.own_scale();
    let escape_time = formula.kind == FormulaKind::EscapeTime;
    let maps = formula.maps.len().max(1);
    let rounds = (ready.iterations as usize).div_ceil(maps) as u32;
    let total = F::lit(f64::from(ready.iterations));
    let r0 = length(p);
    let (one, zero) = (F::lit(1.0), F::lit(0.0));
    let finite = F::lit(FINITE);
    F::iterate(
        F::count(rounds),
        (point, [r0, one, r0, zero, one]),
        |&(_, [r, jn, _, _, alive])| {
            let going = lt(zero, alive);
            if escape_time {
                going & le(r, escape) & le(jn, F::lit(DR_MAX))
            } else {
                going
            }
        },
        |state| {
            let mut state = state;
            for map in &formula.maps {
                let (z, [r, jn, trap, steps, alive]) = state;
                let zv = v3(z[0], z[1], z[2]);
                let (next, scale) = if own_scale {
                    // The map's own scale stands for the derivative: run it in F alone.
                    let (n, s) = run_map(map, nums, &ready.literals, v3(z[0].v, z[1].v, z[2].v), p);
                    ([Dual::constant(n.x), Dual::constant(n.y), Dual::constant(n.z)], s)
                } else {
                    let (n, s) = run_map(map, &duals, &ready.literals, zv, c);
                    ([n.x, n.y, n.z], s.map(|s| s.v))
                };
                let r_next = sqrt(next[0].v * next[0].v + next[1].v * next[1].v + next[2].v * next[2].v);
                let jn_next = match scale {
                    Some(s) => jn * abs(s),
                    None => jacobian_norm(&next),
                };
                // This step counts where the orbit still goes on, has steps left, and stays finite. With one map the
                // loop's own test has said the first two.
                let finite_next = le(r_next, finite) & le(jn_next, finite);
                let go = if maps == 1 {
                    None
                } else if escape_time {
                    Some(lt(zero, alive) & lt(steps, total) & le(r, escape) & le(jn, F::lit(DR_MAX)))
                } else {
                    Some(lt(zero, alive) & lt(steps, total))
                };
                let take = go.map_or(finite_next, |go| go & finite_next);
                let stopped = go.map_or(!finite_next, |go| go & !finite_next);
                let keep = |a: Dual<F>, b: Dual<F>| Dual::select(take, a, b);
                state = (
                    [keep(next[0], z[0]), keep(next[1], z[1]), keep(next[2], z[2])],
                    [
                        select(take, r_next, r),
                        select(take, jn_next, jn),
                        select(take, min(trap, r_next), trap),
                        select(take, steps + one, steps),
                        select(stopped, zero, alive),
                    ],
                );
            }
            state
        },
    )
}

/// The escape radius of an escape-time formula, the bailout limited so |z|² stays finite in f32.
#[inline(always)]
fn escape_radius<F: Num>(bailout: F) -> F {
    min(bailout, F::lit(1e15))
}

/// The distance estimate and orbit trap of a formula at `p` (the estimate signed by membership if `signed`: ≤ 0
/// where the orbit never escapes, for `membership_hits`). `nums` are the formula's scene numbers.
#[inline]
pub fn estimate<F: Num>(ready: &Ready, nums: &[F], p: V3<F>, bailout: F, signed: bool) -> [F; 2] {
    estimate_and_orbit(ready, nums, p, bailout, signed).0
}

/// [`estimate`], and the direction the potential grows in: Jᵀ·zₙ normalised (zero where the orbit carries no
/// Jacobian, a map giving its own scale). This is the gradient of the estimate with its divisor held constant, up
/// to its length: the normal a shaded surface takes ([`crate::eval::walk::Walk::gradient`]). The estimate's own
/// gradient is not: its divisor |∇|zₙ|| wobbles at the scale of the orbit's detail, and its value jumps where the
/// orbit escapes one iteration sooner, which tilts a normal by tens of degrees (`docs/formulas.md`).
#[inline]
pub fn estimate_and_gradient<F: Num>(ready: &Ready, nums: &[F], p: V3<F>, bailout: F, signed: bool) -> ([F; 2], V3<F>) {
    let (estimate, z) = estimate_and_orbit(ready, nums, p, bailout, signed);
    (estimate, potential_direction(&z))
}

/// [`estimate`] and the orbit's last z with its Jacobian rows, which only the gradient reads.
#[inline(always)]
fn estimate_and_orbit<F: Num>(ready: &Ready, nums: &[F], p: V3<F>, bailout: F, signed: bool) -> ([F; 2], [Dual<F>; 3]) {
    let escape = escape_radius(bailout);
    let (z, [r, jn, trap, _, _]) = orbit(ready, nums, p, escape);
    let jn = match ready.formula.kind {
        _ if ready.formula.own_scale() => jn,
        FormulaKind::EscapeTime => radial_gradient(&z, r),
        FormulaKind::Fold => spectral_bound(&z),
    };
    let jn = max(jn, F::lit(TINY));
    let trap = min(trap, F::lit(1.0));
    let estimate = match ready.formula.kind {
        FormulaKind::EscapeTime => {
            let e = F::lit(0.5) * ln(max(r, F::lit(TINY))) * r / jn;
            let e = if signed { select(le(r, escape), -abs(e), e) } else { e };
            [e, trap]
        }
        FormulaKind::Fold => [(r - bailout) / jn, trap],
    };
    (estimate, z)
}

/// Jᵀ·zₙ normalised (zero where it is): the direction |zₙ| grows in. Scaled by its largest component first, as
/// Jᵀ·zₙ may pass f32's range when squared.
#[inline(always)]
fn potential_direction<F: Num>(z: &[Dual<F>; 3]) -> V3<F> {
    let g = |k: usize| z[0].v * z[0].d[k] + z[1].v * z[1].d[k] + z[2].v * z[2].d[k];
    let g = v3(g(0), g(1), g(2));
    let largest = max(max(max(abs(g.x), abs(g.y)), abs(g.z)), F::lit(TINY));
    let scaled = g / largest;
    scaled / max(length(scaled), F::lit(TINY))
}

/// The set's own membership test at `p`, from the orbit alone: −1 inside; outside, a lower bound on the distance to
/// the set where one follows from the definition (an escape-time set lies within its bailout), else [`TINY`].
#[inline]
pub fn membership<F: Num>(ready: &Ready, nums: &[F], p: V3<F>, bailout: F) -> F {
    let escape = escape_radius(bailout);
    let r = orbit_plain(ready, nums, p, escape);
    let (inside, apart) = match ready.formula.kind {
        FormulaKind::EscapeTime => (le(r, escape), length(p) - escape),
        FormulaKind::Fold => (le(r, bailout), F::lit(0.0)),
    };
    select(inside, F::lit(-1.0), max(apart, F::lit(TINY)))
}

/// The orbit in `F` alone (no derivative, a map's own scale unread), as [`orbit`] takes it; returns the last |z|.
#[inline]
fn orbit_plain<F: Num>(ready: &Ready, nums: &[F], p: V3<F>, escape: F) -> F {
    let formula = &ready.formula;
    let escape_time = formula.kind == FormulaKind::EscapeTime;
    let maps = formula.maps.len().max(1);
    let rounds = (ready.iterations as usize).div_ceil(maps) as u32;
    let total = F::lit(f64::from(ready.iterations));
    let (one, zero) = (F::lit(1.0), F::lit(0.0));
    let (_, [r, _, _]) = F::iterate(
        F::count(rounds),
        (p, [length(p), zero, one]),
        |&(_, [r, _, alive])| if escape_time { lt(zero, alive) & le(r, escape) } else { lt(zero, alive) },
        |state| {
            let mut state = state;
            for map in &formula.maps {
                let (z, [r, steps, alive]) = state;
                let (next, _) = run_map(map, nums, &ready.literals, z, p);
                let r_next = length(next);
                let finite_next = le(r_next, F::lit(FINITE));
                let go = if maps == 1 {
                    None
                } else if escape_time {
                    Some(lt(zero, alive) & lt(steps, total) & le(r, escape))
                } else {
                    Some(lt(zero, alive) & lt(steps, total))
                };
                let take = go.map_or(finite_next, |go| go & finite_next);
                let stopped = go.map_or(!finite_next, |go| go & !finite_next);
                state = (
                    v3(select(take, next.x, z.x), select(take, next.y, z.y), select(take, next.z, z.z)),
                    [select(take, r_next, r), select(take, steps + one, steps), select(stopped, zero, alive)],
                );
            }
            state
        },
    );
    r
}
