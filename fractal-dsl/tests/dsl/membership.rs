//! Each fractal family's membership test (declared in `vocab/fractals.rs`, formulas `in_*` in `formula/membership.rs`):
//! it pairs every estimator leaf with a membership leaf of the same arguments, it agrees with points whose membership
//! is known from the set's definition, it never puts a point outside the family's declared bound, and where the
//! estimate says the surface is well away it says outside.

use fractal_dsl::builder::*;
use fractal_dsl::formula::leaf::{LeafArg, LeafOut};
use fractal_dsl::formula::Leaf;
use fractal_dsl::ir::fractal::CallArg;
use fractal_dsl::ir::Fractal;
use fractal_dsl::number::math::v3;
use fractal_dsl::vocab::fractals::families::FRACTALS;

use crate::common::Rng;

/// One fractal of every family, and the other leaf forms a family's call can take (the Mandelbulb of a power other
/// than 8).
fn samples() -> Vec<Fractal> {
    vec![
        mandelbulb(8),
        mandelbulb(7),
        menger(3),
        sierpinski_tetrahedron(6),
        julia([-0.2, 0.6, 0.2, 0.0]),
        mandelbox(2.0),
        mandelbox(-1.5),
    ]
}

/// The fractal's leaf arguments (after the point), folded to numbers.
fn call_args(f: &Fractal) -> (Leaf, Vec<LeafArg<'static, f64>>) {
    let (leaf, args) = f.call().expect("a built-in family");
    let args = args
        .into_iter()
        .map(|a| match a {
            CallArg::Num(e) => LeafArg::F(e.as_lit().expect("literal arguments")),
            CallArg::Count(n) => LeafArg::Count(n),
        })
        .collect();
    (leaf, args)
}

fn with_point<'a>(p: [f64; 3], args: &[LeafArg<'a, f64>]) -> Vec<LeafArg<'a, f64>> {
    std::iter::once(LeafArg::V3(v3(p[0], p[1], p[2]))).chain(args.iter().copied()).collect()
}

/// The fractal's membership value at `p` by its declared membership leaf: −1 inside, outside a lower bound on the
/// distance to the set (or a tiny positive number).
fn value(f: &Fractal, p: [f64; 3]) -> f64 {
    let (estimator, args) = call_args(f);
    let leaf = f.decl().membership.leaf_for(estimator).expect("a membership leaf");
    match leaf.eval::<f64>(&with_point(p, &args)) {
        LeafOut::F(v) => v,
        LeafOut::Pair(_) => panic!("{} returns a pair", leaf.name()),
    }
}

fn inside(f: &Fractal, p: [f64; 3]) -> bool {
    value(f, p) < 0.0
}

/// The raw estimate (without the step factor).
fn estimate(f: &Fractal, p: [f64; 3]) -> f64 {
    let (leaf, args) = call_args(f);
    leaf.eval::<f64>(&with_point(p, &args)).distance()
}

#[test]
fn every_estimator_leaf_has_a_membership_leaf_of_the_same_arguments() {
    for f in samples() {
        let (estimator, _) = f.call().expect("a built-in family");
        let member = f.decl().membership.leaf_for(estimator);
        assert!(member.is_some(), "{}: no membership leaf for {}", f.name(), estimator.name());
    }
    // Formulas written in the scene language answer membership by their own orbit (`formula::user::membership`).
    for decl in FRACTALS.iter().filter(|d| d.arg.shape != fractal_dsl::ir::fractal::FractalArgShape::Formula) {
        assert!(!decl.membership.leaves.is_empty(), "{} declares no membership", decl.name);
        for &(estimator, member) in decl.membership.leaves {
            assert_eq!(
                estimator.params(),
                member.params(),
                "{}: {} and {}",
                decl.name,
                estimator.name(),
                member.name()
            );
        }
    }
}

/// A fractal with points inside and points outside it.
type Known = (Fractal, Vec<[f64; 3]>, Vec<[f64; 3]>);

#[test]
fn known_points_are_where_the_definitions_put_them() {
    let cases: Vec<Known> = vec![
        // z = 0 is a fixed point; on the negative z axis the power-8 map sends (0, 0, −1) to (0, 0, 1) − 1 = 0.
        (mandelbulb(8), vec![[0.0; 3], [0.0, 0.0, -1.0], [0.3, -0.2, 0.1]], vec![[1.5, 0.0, 0.0], [0.0, 0.0, 0.9]]),
        (mandelbulb(7), vec![[0.0; 3], [0.2, 0.2, 0.1]], vec![[1.5, 0.0, 0.0], [0.0, 1.3, 0.0]]),
        // The centre and the middle of each face are cut away at the first level; corners and edges stay.
        (
            menger(3),
            vec![[0.95, 0.95, 0.95], [1.0, -1.0, 0.0], [0.99, 0.0, 0.99]],
            vec![[0.0; 3], [0.0, 0.0, 0.9], [1.1, 0.0, 0.0], [0.9, 0.1, -0.1]],
        ),
        // Vertices and edges stay at every level; the centre is the octahedron removed first.
        (
            sierpinski_tetrahedron(6),
            vec![[1.0, 1.0, 1.0], [0.0, 0.0, 1.0], [0.5, 0.5, 1.0], [-1.0, 1.0, -1.0]],
            vec![[0.0; 3], [1.1, 1.1, 1.1], [0.9, 0.9, 0.9], [0.0, 0.0, -0.5]],
        ),
        (julia([-0.2, 0.6, 0.2, 0.0]), vec![[0.0; 3]], vec![[3.0, 0.0, 0.0], [0.0, 1.5, 1.5]]),
        (mandelbox(2.0), vec![[0.0; 3], [0.5, 0.5, 0.5]], vec![[10.0, 10.0, 10.0], [6.5, 0.0, 0.0]]),
    ];
    for (f, ins, outs) in cases {
        for p in ins {
            assert!(inside(&f, p), "{}: {p:?} should be inside", f.name());
        }
        for p in outs {
            assert!(!inside(&f, p), "{}: {p:?} should be outside", f.name());
        }
    }
}

#[test]
fn membership_stays_in_the_bound_and_outside_where_the_estimate_is_far() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for f in samples() {
        let bound = (f.decl().bound)(&f).expect("a bound").aabb;
        let (lo, hi) = (bound.min, bound.max);
        let (mut hits, mut far) = (0, 0);
        let mut members = Vec::new();
        let mut apart = Vec::new();
        for _ in 0..20_000 {
            // Points in the bound grown by half its size on every side.
            let p = [0, 1, 2].map(|i| {
                let span = hi[i] - lo[i];
                lo[i] - 0.5 * span + rng.unit() * 2.0 * span
            });
            let member = inside(&f, p);
            let in_bound = (0..3).all(|i| p[i] >= lo[i] && p[i] <= hi[i]);
            assert!(!member || in_bound, "{}: {p:?} is inside the set but outside its bound", f.name());
            hits += member as u32;
            if member {
                members.push(p);
            } else if value(&f, p) > 1e-20 {
                apart.push((p, value(&f, p)));
            }
            // The estimate times the step factor is a lower bound on the distance to the surface.
            if estimate(&f, p) * f.step_factor_or_default() > 0.05 * (hi[0] - lo[0]) {
                far += 1;
                assert!(!member, "{}: {p:?} is inside the set where the estimate is {}", f.name(), estimate(&f, p));
            }
        }
        assert!(hits > 10, "{}: only {hits} of 20000 points inside", f.name());
        // Outside, the value is a lower bound on the distance to the set: no member is nearer.
        for (p, v) in apart {
            for q in &members {
                let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                assert!(d >= v, "{}: {q:?} is a member {d} from {p:?}, where the value says {v}", f.name());
            }
        }
        assert!(far > 1000, "{}: only {far} points far from the surface", f.name());
    }
}
