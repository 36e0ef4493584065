//! Membership of a whole scene without distance estimates: the scene walker run on [`Member`], an f64 whose leaf calls
//! send every fractal estimator to its family's membership leaf ([`fractal_dsl::ir::fractal::Membership`]). Exact
//! primitives keep their exact f64 distance, CSG stays min and max, transforms move the point as they do for the
//! renderers; so the sign of [`SceneMembership::value`] is the scene's membership (≤ 0 inside), and where no fractal
//! is involved the value is the exact distance.
//!
//! What the sign cannot carry: operators that read a fractal's distance as a distance (`round`, `onion`, smooth
//! blends) see −1 or a tiny positive number instead, so over a fractal their truth is only approximate (no built-in
//! scene does that).

use std::ops::{Add, Div, Mul, Neg, Sub};

use fractal_dsl::eval::plan::Plan;
use fractal_dsl::eval::walk::Walk;
use fractal_dsl::eval::Env;
use fractal_dsl::formula::leaf::{LeafArg, LeafOut};
use fractal_dsl::formula::user::{self, Ready};
use fractal_dsl::formula::{CallLeaf, Leaf};
use fractal_dsl::number::math::{v3, Carry, Num, V3};
use fractal_dsl::vocab::fractals::families::FRACTALS;
use fractal_dsl::Scene;

/// An f64 whose fractal leaves answer membership instead of the estimate.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Member(pub f64);

macro_rules! binary {
    ($($tr:ident $f:ident $op:tt),*) => {$(
        impl $tr for Member {
            type Output = Member;
            #[inline(always)]
            fn $f(self, o: Member) -> Member {
                Member(self.0 $op o.0)
            }
        }
    )*};
}
binary!(Add add +, Sub sub -, Mul mul *, Div div /);

impl Neg for Member {
    type Output = Member;
    #[inline(always)]
    fn neg(self) -> Member {
        Member(-self.0)
    }
}

impl Carry<Member> for Member {
    #[inline(always)]
    fn map_nums(self, f: &mut impl FnMut(Member) -> Member) -> Self {
        f(self)
    }
    #[inline(always)]
    fn zip_nums(self, other: Self, f: &mut impl FnMut(Member, Member) -> Member) -> Self {
        f(self, other)
    }
}

macro_rules! unary {
    ($($name:ident => $e:expr),*) => {$(
        #[inline(always)]
        fn $name(x: Member) -> Member {
            let f: fn(f64) -> f64 = $e;
            Member(f(x.0))
        }
    )*};
}

/// Every operation is f64's; only leaf calls differ ([`CallLeaf`] below).
impl Num for Member {
    type Mask = bool;
    type Count = u32;
    #[inline(always)]
    fn lit(v: f64) -> Self {
        Member(v)
    }
    #[inline(always)]
    fn count(n: u32) -> u32 {
        n
    }
    unary!(abs => f64::abs, sqrt => f64::sqrt, floor => f64::floor, sin => f64::sin, cos => f64::cos,
        acos => f64::acos, exp2 => f64::exp2, ln => f64::ln);
    #[inline(always)]
    fn atan2(y: Self, x: Self) -> Self {
        Member(y.0.atan2(x.0))
    }
    #[inline(always)]
    fn pow(x: Self, y: Self) -> Self {
        Member(x.0.powf(y.0))
    }
    #[inline(always)]
    fn min(a: Self, b: Self) -> Self {
        Member(a.0.min(b.0))
    }
    #[inline(always)]
    fn max(a: Self, b: Self) -> Self {
        Member(a.0.max(b.0))
    }
    #[inline(always)]
    fn lt(a: Self, b: Self) -> bool {
        a.0 < b.0
    }
    #[inline(always)]
    fn le(a: Self, b: Self) -> bool {
        a.0 <= b.0
    }
    #[inline(always)]
    fn select(m: bool, a: Self, b: Self) -> Self {
        if m {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    fn iterate<S: Carry<Self>>(n: u32, init: S, active: impl Fn(&S) -> bool, step: impl Fn(S) -> S) -> S {
        let mut s = init;
        for _ in 0..n {
            if !active(&s) {
                break;
            }
            s = step(s);
        }
        s
    }
    #[inline(always)]
    fn when<S: Carry<Self>>(cond: bool, state: S, body: impl FnOnce(S) -> S) -> S {
        if cond {
            body(state)
        } else {
            state
        }
    }
}

/// The membership leaf a family declares for `estimator`, if it is a fractal estimator.
fn membership_leaf(estimator: Leaf) -> Option<Leaf> {
    FRACTALS.iter().find_map(|family| family.membership.leaf_for(estimator))
}

impl CallLeaf for Member {
    #[inline(always)]
    fn leaf(leaf: Leaf, args: &[LeafArg<Self>]) -> LeafOut<Self> {
        match membership_leaf(leaf) {
            Some(member) => LeafOut::F(member.eval(args).distance()),
            None => leaf.eval(args),
        }
    }
    /// A formula written in the scene language answers its own membership test, its orbit alone.
    #[inline(always)]
    fn formula(ready: &Ready, nums: &[Self], p: V3<Self>, bailout: Self, _signed: bool) -> LeafOut<Self> {
        // Host code where it has been compiled ([`SceneMembership::new`] compiles it), else the formula's tree.
        let host = ready.host.as_ref().map(|h| {
            let run = |nums: &[f64]| Member(h.membership(nums, [p.x.0, p.y.0, p.z.0], bailout.0));
            let mut few = [0.0; 32];
            match few.get_mut(..nums.len()) {
                Some(few) => {
                    few.iter_mut().zip(nums).for_each(|(f, n)| *f = n.0);
                    run(few)
                }
                None => run(&nums.iter().map(|n| n.0).collect::<Vec<f64>>()),
            }
        });
        LeafOut::F(host.unwrap_or_else(|| user::membership(ready, nums, p, bailout)))
    }
}

/// A scene's membership, evaluated in f64 with every fractal decided by its own iteration.
pub struct SceneMembership {
    plan: Plan,
}

impl SceneMembership {
    pub fn new(scene: &Scene) -> SceneMembership {
        let mut plan = Plan::new(scene);
        plan.formula_calls_mut(&mut fractal_dsl::lower::tape::attach);
        SceneMembership { plan }
    }

    /// ≤ 0 inside the scene, > 0 outside; the exact distance where no fractal is involved, otherwise a sign only (a
    /// march over it cannot take distance-sized steps there). Union guards are off: they trust bounds.
    pub fn value(&self, p: [f64; 3], env: &Env<Member>) -> f64 {
        let walk = Walk { plan: &self.plan, guards: false };
        walk.distance(v3(Member(p[0]), Member(p[1]), Member(p[2])), env).0
    }
}
