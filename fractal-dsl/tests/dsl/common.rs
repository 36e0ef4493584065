//! Helpers shared by the integration tests: a deterministic point generator, the random-tree building blocks
//! (coordinate boxes, unit axes, exact bounded primitives) and distance evaluation at rest.

use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::Env;
use fractal_dsl::geom::Interval;
use fractal_dsl::ir::arg::{ArgDecl, ArgRange, ArgShape, Rule};
use fractal_dsl::number::math::v3;
use fractal_dsl::vocab::prims::decl::PRIMS;
use fractal_dsl::*;
use proptest::prelude::*;

/// A small deterministic xorshift generator for dense point sets, so measured figures are reproducible run to run
/// (proptest drives the shapes). Test files add the samplers they need in their own `impl Rng` blocks.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in [0, 1) from the top 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The f64 distance at `p` at time 0 with every parameter at its default.
pub fn d64(i: &Interpreter, p: [f64; 3]) -> f64 {
    i.distance_in(v3(p[0], p[1], p[2]), &Env::<f64>::still())
}

pub fn vec3_in(lo: f64, hi: f64) -> impl Strategy<Value = [f64; 3]> {
    [lo..hi, lo..hi, lo..hi]
}

pub fn unit_axis() -> impl Strategy<Value = [f64; 3]> {
    vec3_in(-1.0, 1.0).prop_filter_map("a usable axis", |a| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        (l > 0.2).then(|| a.map(|c| c / l))
    })
}

/// Whether a declared primitive is bounded with an exact distance (reach 1): not the plane (unbounded, so a child
/// holding it is unguarded) nor the ellipsoid (a lower bound). Judged by the declaration's own bound, at unequal
/// argument values (an ellipsoid with equal radii is a sphere, and exact).
fn exactly_bounded(decl: &PrimDecl) -> bool {
    let ranges: Vec<ArgRange> = decl
        .args
        .iter()
        .enumerate()
        .map(|(i, a)| match a.shape {
            ArgShape::Number => ArgRange::Num(Interval::point(0.5 + 0.1 * i as f64)),
            _ => ArgRange::Vec3([0.5, 0.75, 1.0].map(Interval::point)),
        })
        .collect();
    matches!((decl.bound)(&ranges), Some(b) if b.reach >= 1.0)
}

/// Valid constant arguments for declared arguments (a primitive's or an operator's), drawn by the rule the
/// declaration gives each one.
pub fn declared_args(decls: &'static [ArgDecl]) -> BoxedStrategy<Vec<ArgValue>> {
    let draws: Vec<BoxedStrategy<[f64; 3]>> = decls
        .iter()
        .map(|a| match a.rule {
            Rule::Positive => vec3_in(0.05, 1.2).boxed(),
            Rule::NonNegative => vec3_in(0.0, 1.0).boxed(),
            Rule::Finite => vec3_in(-1.0, 1.0).boxed(),
            Rule::Direction => unit_axis().boxed(),
            // A fraction of the smallest extent it rounds, scaled below.
            Rule::RoundingOf(_) => vec3_in(0.0, 1.0).boxed(),
            Rule::Period => vec3_in(0.5, 3.0).boxed(),
            Rule::AtMost(most) => {
                let most = most.min(3);
                [0..=most, 0..=most, 0..=most].prop_map(|n| n.map(f64::from)).boxed()
            }
            Rule::CountUpTo(most) => (1..=most.min(8)).prop_map(|n| [f64::from(n); 3]).boxed(),
            // A constant displacement (the point-dependent ones have rows of their own).
            Rule::Displacement => vec3_in(0.0, 0.3).boxed(),
        })
        .collect();
    draws
        .prop_map(move |draws| {
            decls
                .iter()
                .zip(&draws)
                .map(|(a, v)| {
                    let v = match a.rule {
                        Rule::RoundingOf(of) => [v[0] * draws[of].iter().copied().fold(f64::INFINITY, f64::min); 3],
                        _ => *v,
                    };
                    match a.shape {
                        ArgShape::Number => ArgValue::Num(Expr::Lit(v[0])),
                        _ => ArgValue::Vec3(v.into()),
                    }
                })
                .collect()
        })
        .boxed()
}

/// Every declared primitive whose distance is exact and bounded (`fractal_dsl::vocab::prims`), with valid constant
/// arguments: a new primitive is in every test that draws from here without being listed.
pub fn exact_bounded_primitive() -> impl Strategy<Value = Node> {
    let kinds: Vec<PrimKind> = PRIMS.iter().copied().filter(|d| exactly_bounded(d)).map(PrimKind).collect();
    prop::sample::select(kinds).prop_flat_map(|k| declared_args(k.0.args).prop_map(move |args| k.0.node(args)))
}
