//! Bounds are conservative or absent: no sampled point where a node's distance is negative lies outside the node's
//! bound (at any sampled time and parameter setting), fractal radii hold their rendered surfaces, union guards never
//! change a union's value where the analysis says they are exact and never change its sign anywhere, and the value
//! ranges bounds are built from contain every value an expression takes.

use fractal_dsl::analyse::bounds::{bound_info, sd_aabb, Aabb};
use fractal_dsl::analyse::interval::{range, Interval};
use fractal_dsl::analyse::{bound, fold::fold_node};
use fractal_dsl::builder::*;
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::Env;
use fractal_dsl::number::math::v3;
use fractal_dsl::vocab::radius::{julia_radius, mandelbox_half_extent, mandelbulb_radius};
use fractal_dsl::*;
use proptest::prelude::*;

use crate::common::{exact_bounded_primitive, unit_axis, vec3_in, Rng};

// ---- sampling -------------------------------------------------------------------------------------------------------

impl Rng {
    fn between(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
}

/// Points around a box: uniform in the box grown by `margin`, and points just outside each face.
fn points_around(b: &Aabb, margin: f64, n: usize, rng: &mut Rng) -> Vec<[f64; 3]> {
    let g = b.grow(margin);
    let mut out = Vec::with_capacity(2 * n);
    for _ in 0..n {
        out.push([0, 1, 2].map(|i| rng.between(g.min[i], g.max[i])));
        // On a random face, pushed out by up to 1% of the margin.
        let axis = (rng.next() % 3) as usize;
        let mut p = [0, 1, 2].map(|i| rng.between(b.min[i], b.max[i]));
        let out_by = rng.unit() * 0.01 * margin + 1e-9;
        p[axis] = if rng.next().is_multiple_of(2) { b.min[axis] - out_by } else { b.max[axis] + out_by };
        out.push(p);
    }
    out
}

fn param_values(interp: &Interpreter, rng: &mut Rng) -> Vec<f64> {
    interp.params().iter().map(|p| rng.between(p.min.min(p.max), p.max.max(p.min))).collect()
}

fn distance(interp: &Interpreter, p: [f64; 3], time: f64, params: &[f64]) -> f64 {
    interp.distance_in(v3(p[0], p[1], p[2]), &Env::new(time, params))
}

// ---- random trees -----------------------------------------------------------------------------------------------------

fn primitive() -> impl Strategy<Value = Node> {
    prop_oneof![
        // Every declared exact primitive, so a new one is checked without being listed here.
        exact_bounded_primitive(),
        (0.1..1.5f64).prop_map(sphere),
        Just(sphere(param("radius", 0.6, 0.2..1.4))),
        vec3_in(0.05, 1.2).prop_map(box3),
        (vec3_in(0.1, 1.2), 0.0..1.0f64).prop_map(|(h, f)| round_box(h, f * h[0].min(h[1]).min(h[2]))),
        (0.2..1.2f64, 0.05..0.5f64).prop_map(|(a, b)| torus(a, b)),
        (vec3_in(-1.0, 1.0), vec3_in(-1.0, 1.0), 0.05..0.6f64).prop_map(|(a, b, r)| capsule(a, b, r)),
        (0.1..1.0f64, 0.1..1.0f64).prop_map(|(r, h)| cylinder(r, h)),
        (0.1..1.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(h, a, b)| cone(h, a, b)),
        (0.1..1.5f64).prop_map(octahedron),
        vec3_in(0.1, 1.2).prop_map(ellipsoid),
        (unit_axis(), -1.0..1.0f64).prop_map(|(n, o)| plane(n, o)),
    ]
}

/// Fractals at iteration counts small enough for many samples.
fn fractal() -> impl Strategy<Value = Node> {
    prop_oneof![
        Just(Node::from(mandelbulb(8).iterations(4))),
        Just(Node::from(mandelbulb(param("power", 6.0, 3.0..9.0)).iterations(3))),
        (1u32..4).prop_map(|n| Node::from(menger(n))),
        (1u32..6).prop_map(|n| Node::from(sierpinski_tetrahedron(n))),
        Just(Node::from(julia([-0.2, 0.6, 0.2, 0.0]).iterations(6))),
        Just(Node::from(mandelbox(-1.5).iterations(5))),
        Just(mandelbox(2.0).iterations(5).scale(0.2)),
    ]
}

/// Unary operations, animated ones included (time and parameters).
fn wrap(inner: impl Strategy<Value = Node> + Clone + 'static) -> impl Strategy<Value = Node> {
    prop_oneof![
        (inner.clone(), vec3_in(-1.0, 1.0)).prop_map(|(a, v)| a.translate(v)),
        inner.clone().prop_map(|a| a.translate(vec3(sin(time()), 0.0, param("shift", 0.0, -0.5..0.5)))),
        (inner.clone(), -4.0..4.0f64).prop_map(|(a, t)| a.rotate_z(t)),
        inner.clone().prop_map(|a| a.rotate_y(time())),
        (inner.clone(), unit_axis(), -4.0..4.0f64).prop_map(|(a, k, t)| a.rotate(k, t)),
        inner.clone().prop_map(|a| a.rotate([1.0, 1.0, 0.0], time() * 0.7)),
        (inner.clone(), 0.3..2.0f64).prop_map(|(a, s)| a.scale(s)),
        inner.clone().prop_map(|a| a.scale(1.0 + 0.5 * sin(time()))),
        (inner.clone(), vec3_in(0.0, 1.5), 0u32..3).prop_map(|(a, per, n)| a.repeat_limited(per, [n, 0, n])),
        (inner.clone(), -1.5..1.5f64).prop_map(|(a, k)| a.twist(k)),
        (inner.clone(), -1.0..1.0f64).prop_map(|(a, k)| a.bend(k)),
        (inner.clone(), 0.0..0.4f64).prop_map(|(a, r)| a.round(r)),
        (inner.clone(), 0.0..0.3f64).prop_map(|(a, t)| a.onion(t)),
        (inner.clone(), vec3_in(0.0, 0.6)).prop_map(|(a, h)| a.elongate(h)),
        inner.prop_map(|a| a.material(rgb(0.3, 0.5, 0.7))),
    ]
}

fn tree() -> impl Strategy<Value = Node> {
    let leaf = prop_oneof![4 => primitive(), 1 => fractal()];
    leaf.prop_recursive(3, 16, 3, |inner| {
        prop_oneof![
            3 => wrap(inner.clone()),
            1 => (inner.clone(), inner.clone()).prop_map(|(a, b)| union(a, b)),
            1 => (inner.clone(), inner.clone()).prop_map(|(a, b)| intersect(a, b)),
            1 => (inner.clone(), inner.clone()).prop_map(|(a, b)| subtract(a, b)),
            1 => (prop::collection::vec(inner.clone(), 2..4), 0.0..1.0f64).prop_map(|(c, k)| smooth_union_all(c, k)),
            1 => (inner.clone(), inner.clone(), 0.0..1.0f64).prop_map(|(a, b, k)| smooth_intersect(a, b, k)),
            1 => (inner.clone(), inner, 0.0..1.0f64).prop_map(|(a, b, k)| smooth_subtract(a, b, k)),
        ]
    })
}

/// Every subtree of `n`, `n` first.
fn subtrees(n: &Node) -> Vec<&Node> {
    let mut out = vec![n];
    for c in n.children() {
        out.extend(subtrees(c));
    }
    out
}

const TIMES: [f64; 4] = [0.0, 0.37, 2.9, 12.0];

/// No point with a negative distance outside the bound; outside, the distance is at least `reach` × the distance to
/// the bound; and where the analysis says union guards are exact, the distance is never below the bound's signed
/// distance, inside or out.
fn check_node(node: &Node, points: usize, rng: &mut Rng) -> Result<(), TestCaseError> {
    let info = bound_info(node);
    let Some(b) = info.aabb else { return Ok(()) };
    let interp = Interpreter::new(&scene(node.clone())).unwrap();
    let margin = 0.5 * b.half_extents().iter().fold(0.0f64, |a, &h| a.max(h)) + 0.2;
    for &time in &TIMES {
        let params = param_values(&interp, rng);
        for p in points_around(&b, margin, points, rng) {
            let f = distance(&interp, p, time, &params);
            let to_box = sd_aabb(p, &b);
            let tol = 1e-9 * (1.0 + f.abs() + to_box.abs());
            prop_assert!(
                f.is_nan() || b.contains(p) || f >= 0.0,
                "f = {f} < 0 at {p:?} outside the bound {b:?} (t = {time}, params {params:?}) of {node:?}"
            );
            if to_box > 0.0 && !f.is_nan() {
                prop_assert!(
                    f >= info.reach * to_box - tol,
                    "f = {f} below reach {} × box distance {to_box} at {p:?} (t = {time}) of {node:?}",
                    info.reach
                );
            }
            if info.exact_guard && !f.is_nan() {
                prop_assert!(f >= to_box - tol, "f = {f} < sd_box = {to_box} at {p:?} (t = {time}) of {node:?}");
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn bounds_contain_their_shapes(root in tree(), seed in any::<u64>()) {
        let mut rng = Rng(seed | 1);
        let root = fold_node(&root);
        for node in subtrees(&root) {
            check_node(node, 40, &mut rng)?;
        }
    }

    #[test]
    fn unbounded_only_where_a_plane_infinite_repetition_or_unlimited_growth_is(root in tree()) {
        let root = fold_node(&root);
        let info = bound_info(&root);
        let has_plane = subtrees(&root).iter().any(|n| matches!(n, Node::Prim(p) if p.name() == "plane"));
        let grows_twist = subtrees(&root).iter().any(|n| n.op().is_some_and(|op| ["twist", "bend"].contains(&op.name())));
        if info.aabb.is_none() {
            prop_assert!(has_plane || grows_twist, "no reason for {root:?} to be unbounded");
        }
    }
}

// ---- union guards -------------------------------------------------------------------------------------------------------

/// Guarded children built only from what keeps guards exact: Menger sponges (their estimate is max(box, cuts)) and
/// exact primitives under rigid motion, scale, round, onion, elongate, subtraction, union and smooth union.
fn exact_guarded_child() -> impl Strategy<Value = Node> {
    let sponge = (1u32..4).prop_map(|n| Node::from(menger(n)));
    let body = prop_oneof![
        sponge.clone(),
        (sponge.clone(), exact_bounded_primitive()).prop_map(|(a, b)| union(a, b)),
        (sponge.clone(), exact_bounded_primitive(), 0.0..0.8f64).prop_map(|(a, b, k)| smooth_union(a, b, k)),
        (sponge, primitive()).prop_map(|(a, b)| subtract(a, b)),
    ];
    body.prop_recursive(2, 6, 1, |inner| {
        prop_oneof![
            (inner.clone(), vec3_in(-2.0, 2.0)).prop_map(|(a, v)| a.translate(v)),
            inner.clone().prop_map(|a| a.translate(vec3(sin(time()), 0.0, 0.0))),
            (inner.clone(), unit_axis(), -4.0..4.0f64).prop_map(|(a, k, t)| a.rotate(k, t)),
            inner.clone().prop_map(|a| a.rotate_y(time())),
            (inner.clone(), 0.3..2.0f64).prop_map(|(a, s)| a.scale(s)),
            (inner.clone(), 0.0..0.4f64).prop_map(|(a, r)| a.round(r)),
            (inner.clone(), 0.0..0.3f64).prop_map(|(a, t)| a.onion(t)),
            (inner.clone(), vec3_in(0.0, 0.6)).prop_map(|(a, h)| a.elongate(h)),
            (inner, vec3_in(0.5, 3.0), 0u32..2).prop_map(|(a, per, n)| a.repeat_limited(per, [n, n, 0])),
        ]
    })
}

/// Unions whose guarded children are any fractal subtree.
fn any_guarded_child() -> impl Strategy<Value = Node> {
    (fractal(), vec3_in(-2.0, 2.0), 0.3..1.5f64).prop_map(|(f, v, s)| f.scale(s).translate(v))
}

fn guarded_union(child: impl Strategy<Value = Node> + 'static) -> impl Strategy<Value = Node> {
    (prop::collection::vec(primitive(), 1..3), prop::collection::vec(child, 1..3), vec3_in(-1.0, 1.0))
        .prop_map(|(cheap, costly, v)| union_all(cheap.into_iter().chain(costly)).translate(v))
}

/// Bounded and unbounded evaluation of one scene at `p`.
fn both(guarded: &Interpreter, reference: &Interpreter, p: [f64; 3], time: f64) -> (f64, f64) {
    (distance(guarded, p, time, &[]), distance(reference, p, time, &[]))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn bounded_evaluation_never_exceeds_unbounded_evaluation(root in guarded_union(exact_guarded_child()), seed in any::<u64>()) {
        let folded = fold_node(&root);
        let union_node = match folded.op() {
            Some(op) if op.name() == "translate" => &op.shapes[0],
            _ => &folded,
        };
        if let Some(children) = union_node.op().filter(|op| op.name() == "union").map(|op| &op.shapes) {
            for (pos, _) in children.iter().enumerate() {
                if fractal_dsl::analyse::guarded_bound(children, pos).is_some() {
                    let child = &children[fractal_dsl::analyse::union_order(children)[pos]];
                    prop_assert!(bound_info(child).exact_guard, "{child:?} should keep guards exact");
                }
            }
        }
        let guarded = Interpreter::new(&scene(root.clone())).unwrap();
        let reference = Interpreter::new(&scene(root.clone())).unwrap().without_bound_guards();
        let mut rng = Rng(seed | 1);
        let region = bound(&folded).unwrap_or(Aabb::cube(3.0));
        for &time in &TIMES {
            for p in points_around(&region, 2.0, 150, &mut rng) {
                let (b, u) = both(&guarded, &reference, p, time);
                prop_assert!(b <= u + 1e-12 * (1.0 + u.abs()), "bounded {b} > unbounded {u} at {p:?}, t = {time}: {root:?}");
                prop_assert!(b >= u - 1e-12 * (1.0 + u.abs()), "bounded {b} < unbounded {u} at {p:?}, t = {time}: {root:?}");
            }
        }
    }

    /// Over estimators that fall short of the distance (escape-time fractals, Sierpinski, Mandelbox) a guard may skip
    /// a child whose estimate is below its box distance: the union's value then rises, but only up to the distance of
    /// a box that holds the child's surface, so it never crosses the surface: the sign is kept.
    #[test]
    fn guards_skip_only_children_whose_surface_is_no_nearer(root in guarded_union(any_guarded_child()), seed in any::<u64>()) {
        let guarded = Interpreter::new(&scene(root.clone())).unwrap();
        let reference = Interpreter::new(&scene(root.clone())).unwrap().without_bound_guards();
        let folded = fold_node(&root);
        let region = bound(&folded).unwrap_or(Aabb::cube(3.0));
        let mut rng = Rng(seed | 1);
        for &time in &TIMES {
            for p in points_around(&region, 2.0, 100, &mut rng) {
                let (b, u) = both(&guarded, &reference, p, time);
                prop_assert!(b >= u - 1e-12 * (1.0 + u.abs()), "a guard lowered the distance: {b} < {u} at {p:?}");
                prop_assert!(!(u < 0.0 && b > 0.0), "a guard moved {p:?} from inside ({u}) to outside ({b}): {root:?}");
            }
        }
    }
}

/// The guard is exact for the Menger sponge but not for the escape-time estimators: this measures by how much a guard
/// raises a union's value over a Mandelbulb next to a sphere (the raised value is still below the distance to the
/// Mandelbulb's box).
#[test]
fn guard_excess_over_an_escape_time_fractal_is_bounded_by_the_box_distance() {
    let root = union(sphere(0.5).translate([4.0, 0.0, 0.0]), mandelbulb(8));
    let guarded = Interpreter::new(&scene(root.clone())).unwrap();
    let reference = Interpreter::new(&scene(root.clone())).unwrap().without_bound_guards();
    let b = bound(&mandelbulb(8).into()).expect("bounded");
    let mut rng = Rng(99);
    let mut worst = 0.0f64;
    for p in points_around(&Aabb::cube(4.0), 2.0, 20000, &mut rng) {
        let (g, u) = both(&guarded, &reference, p, 0.0);
        if g > u {
            worst = worst.max(g - u);
            assert!(g <= sd_aabb(p, &b) + 1e-12, "raised past the box: {g} at {p:?}");
        }
    }
    eprintln!("largest rise of a guarded union over the unguarded value (mandelbulb + sphere): {worst:.4}");
}

// ---- fractal radii -------------------------------------------------------------------------------------------------

/// Points outside `b` within `margin`, where the scaled estimate must stay above `eps`: twice the default hit epsilon
/// for the escape-time fractals, whose radii carry a margin for the rendered surface, and 0 for the sponge and the
/// tetrahedron, which touch their cube.
fn assert_surface_inside(name: &str, fractal: Fractal, b: &Aabb, margin: f64, n: usize, eps: f64) {
    let interp = Interpreter::new(&scene(fractal)).unwrap();
    let mut rng = Rng(5);
    let mut nearest = f64::INFINITY;
    for p in points_around(b, margin, n, &mut rng) {
        if b.contains(p) {
            continue;
        }
        let f = distance(&interp, p, 0.0, &[]);
        assert!(f.is_finite(), "{name}: estimate {f} at {p:?}");
        nearest = nearest.min(f);
        assert!(f > eps, "{name}: surface (estimate {f}) at {p:?} outside the bound {b:?}");
    }
    assert!(nearest.is_finite(), "{name}: no point sampled outside");
}

#[test]
fn mandelbulb_radius_holds_the_rendered_surface_for_powers_2_to_32() {
    for power in [2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0, 12.0, 16.0, 24.0, 32.0] {
        let r = mandelbulb_radius(power).expect("finite");
        for iterations in 1..=16 {
            for bailout in [2.0, 256.0] {
                let f = mandelbulb(power).iterations(iterations).bailout(bailout);
                let b = bound(&f.clone().into()).expect("bounded");
                assert_eq!(b, Aabb::cube(r));
                let name = format!("mandelbulb {power} × {iterations}, bailout {bailout}");
                assert_surface_inside(&name, f, &b, 0.3, 250, 1e-3);
            }
        }
        eprintln!("mandelbulb power {power}: bound radius {r:.4}");
    }
    // An animated power is bounded by its lowest value.
    let animated = mandelbulb(param("power", 8.0, 3.0..12.0)).into();
    assert_eq!(bound(&animated), Some(Aabb::cube(mandelbulb_radius(3.0).expect("finite"))));
    let unbounded_power = mandelbulb(1.0 + time()).into();
    assert_eq!(bound(&unbounded_power), None, "powers down to 1 have no escape radius");
}

#[test]
fn menger_and_sierpinski_lie_in_the_unit_cube() {
    for levels in 1..=6 {
        for (name, f) in [("menger", menger(levels)), ("sierpinski", sierpinski_tetrahedron(levels))] {
            let b = bound(&f.clone().into()).expect("bounded");
            assert_eq!(b, Aabb::cube(1.0));
            assert_surface_inside(&format!("{name} {levels}"), f, &b, 0.5, 1500, 0.0);
        }
    }
}

#[test]
fn julia_escape_radius_holds_the_rendered_surface() {
    for c in [
        [-0.2, 0.6, 0.2, 0.0],
        [-0.4, 0.6, 0.0, 0.0],
        [-1.0, 0.2, 0.0, 0.0],
        [-2.0, 0.0, 0.0, 0.0],
        [0.3, 0.5, 0.1, -0.2],
    ] {
        let norm: f64 = c.iter().map(|v: &f64| v * v).sum::<f64>().sqrt();
        let r = julia_radius(norm).expect("finite");
        for (iterations, bailout) in [(1, 4.0), (4, 4.0), (11, 4.0), (11, 16.0), (20, 2.0)] {
            let f = julia(c).iterations(iterations).bailout(bailout);
            let b = bound(&f.clone().into()).expect("bounded");
            assert_eq!(b, Aabb::cube(r));
            assert_surface_inside(&format!("julia {c:?} × {iterations}"), f, &b, 0.3, 800, 1e-3);
        }
        eprintln!("julia |c| = {norm:.3}: bound radius {r:.4}");
    }
}

#[test]
fn mandelbox_extent_holds_the_rendered_surface_and_matches_the_known_value() {
    // The known half extent of the scale-2 Mandelbox with fold limit 1 is 6.
    let e = mandelbox_half_extent(Interval::point(2.0), 1.0).expect("finite");
    assert!((e - 6.0).abs() < 0.1 && e >= 6.0, "{e}");
    for (scale, min_radius, fold_limit) in [
        (2.0, 0.5, 1.0),
        (3.0, 0.5, 1.0),
        (1.5, 0.5, 1.0),
        (2.0, 0.25, 1.5),
        (2.0, 0.5, 0.5),
        (-1.5, 0.5, 1.0),
        (-2.0, 0.25, 1.0),
        (-3.0, 0.5, 2.0),
        (-1.2, 0.5, 1.0),
    ] {
        let f = mandelbox(scale).min_radius(min_radius).fold_limit(fold_limit);
        let b = bound(&f.clone().into()).expect("bounded");
        for iterations in [1, 2, 4, 12] {
            let name = format!("mandelbox {scale}, min radius {min_radius}, fold {fold_limit} × {iterations}");
            assert_surface_inside(&name, f.clone().iterations(iterations), &b, 0.3 * b.half_extents()[0], 800, 1e-3);
        }
        eprintln!("mandelbox scale {scale}, fold limit {fold_limit}: half extent {:.4}", b.half_extents()[0]);
    }
    assert_eq!(bound(&mandelbox(0.5).into()), None, "|scale| ≤ 1 never escapes");
    assert_eq!(bound(&mandelbox(param("s", 2.0, -2.0..3.0)).into()), None, "a scale range through ±1 is unbounded");
}

// ---- primitives and operations, exact cases ---------------------------------------------------------------------

#[test]
fn operation_bounds_follow_their_rules() {
    let unit = sphere(1.0);
    assert_eq!(bound(&unit), Some(Aabb::cube(1.0)));
    assert_eq!(bound(&plane([0.0, 1.0, 0.0], 0.0)), None);
    assert_eq!(bound(&union(unit.clone(), plane([0.0, 1.0, 0.0], 0.0))), None, "union with an unbounded child");
    assert_eq!(bound(&intersect(unit.clone(), plane([0.0, 1.0, 0.0], 0.0))), Some(Aabb::cube(1.0)));
    assert_eq!(bound(&subtract(unit.clone(), box3([5.0, 5.0, 5.0]))), Some(Aabb::cube(1.0)));
    assert_eq!(bound(&unit.clone().translate([1.0, 2.0, 3.0])), Some(Aabb::new([0.0, 1.0, 2.0], [2.0, 3.0, 4.0])));
    assert_eq!(bound(&unit.clone().scale(2.0)), Some(Aabb::cube(2.0)));
    assert_eq!(bound(&unit.clone().round(0.5)), Some(Aabb::cube(1.5)));
    assert_eq!(bound(&unit.clone().repeat([2.0, 0.0, 0.0])), None);
    assert_eq!(
        bound(&unit.clone().repeat_limited([3.0, 0.0, 0.0], [2, 0, 0])),
        Some(Aabb::new([-7.0, -1.0, -1.0], [7.0, 1.0, 1.0]))
    );
    assert_eq!(bound(&unit.clone().elongate([1.0, 0.0, 0.5])), Some(Aabb::new([-2.0, -1.0, -1.5], [2.0, 1.0, 1.5])));
    // Smooth union of three children: the fold can subtract k/4 twice.
    let three = smooth_union_all([sphere(1.0), sphere(1.0), sphere(1.0)], 0.8);
    assert_eq!(bound(&three), Some(Aabb::cube(1.4)));
    // A box turned 45° about y.
    let turned = bound(&box3([1.0, 1.0, 1.0]).rotate_y(std::f64::consts::FRAC_PI_4)).expect("bounded");
    assert!((turned.max[0] - 2f64.sqrt()).abs() < 1e-12 && (turned.max[1] - 1.0).abs() < 1e-12, "{turned:?}");
    // An animated angle about z sweeps the corners' radius in x and y and keeps z.
    let spun = bound(&box3([1.0, 0.5, 2.0]).translate([1.0, 0.0, 0.0]).rotate_z(time())).expect("bounded");
    let r = (2f64 * 2.0 + 0.25).sqrt();
    assert!((spun.max[0] - r).abs() < 1e-12 && (spun.max[2] - 2.0).abs() < 1e-12, "{spun:?}");
    // An animated translation sweeps its range; an unbounded one is unbounded.
    assert_eq!(
        bound(&unit.clone().translate(vec3(sin(time()), 0.0, 0.0))),
        Some(Aabb::new([-2.0, -1.0, -1.0], [2.0, 1.0, 1.0]))
    );
    assert_eq!(bound(&unit.clone().translate(vec3(time(), 0.0, 0.0))), None);
    // Twisting keeps the radius from the y axis; a rounded twist is unbounded (its estimate tends to a constant).
    let twisted = bound(&box3([1.0, 2.0, 1.0]).twist(1.0)).expect("bounded");
    assert!((twisted.max[0] - 2f64.sqrt()).abs() < 1e-12 && twisted.max[1] == 2.0, "{twisted:?}");
    assert_eq!(bound(&box3([1.0, 2.0, 1.0]).twist(1.0).round(0.1)), None);
}

#[test]
fn sd_aabb_is_the_box_distance() {
    let b = Aabb::new([-1.0, 0.0, 2.0], [1.0, 4.0, 3.0]);
    assert!((sd_aabb([3.0, 2.0, 2.5], &b) - 2.0).abs() < 1e-15);
    assert!((sd_aabb([0.0, 2.0, 2.5], &b) + 0.5).abs() < 1e-15);
    assert!((sd_aabb([2.0, 5.0, 2.5], &b) - 2f64.sqrt()).abs() < 1e-15);
}

// ---- value ranges --------------------------------------------------------------------------------------------------

fn expr() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![
        (-3.0..3.0f64).prop_map(Expr::Lit),
        Just(time()),
        Just(param("a", 0.5, -1.0..2.0)),
        Just(param("b", 1.0, 0.5..1.5)),
    ];
    leaf.prop_recursive(4, 24, 3, |inner| {
        prop_oneof![
            inner.clone().prop_map(|a| -a),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a + b),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a - b),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a * b),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| a / b),
            inner.clone().prop_map(sin),
            inner.clone().prop_map(cos),
            inner.clone().prop_map(abs),
            inner.clone().prop_map(sqrt),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| min(a, b)),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| max(a, b)),
            (inner.clone(), -3i32..4).prop_map(|(a, n)| pow(a, n as f64)),
            (inner.clone(), 0.0..2.5f64).prop_map(|(a, e)| pow(abs(a), e)),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| pow(abs(a) + 0.5, min(b, 3.0))),
            (inner.clone(), inner.clone(), inner.clone()).prop_map(|(a, b, c)| clamp(a, b, c)),
            (inner.clone(), inner.clone(), inner.clone()).prop_map(|(a, b, c)| mix(a, b, c)),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| noise2(a, b)),
            (inner.clone(), inner.clone(), 1u32..6).prop_map(|(a, b, n)| fbm3(a, b, 0.5, n)),
            (inner.clone(), inner).prop_map(|(a, b)| noise3(a, b.clone(), 0.25) + fbm2(b, 0.75, 3)),
        ]
    })
}

/// Whether `e` or any part of it satisfies `holds`.
fn any_part(e: &Expr, holds: &dyn Fn(&Expr) -> bool) -> bool {
    holds(e)
        || match e {
            Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => false,
            Expr::Neg(a) => any_part(a, holds),
            Expr::Bin(_, a, b) => any_part(a, holds) || any_part(b, holds),
            Expr::Call(_, args) => args.iter().any(|a| any_part(a, holds)),
        }
}

/// Whether evaluating `e` produces NaN anywhere along the way.
fn nan_inside(e: &Expr, t: f64, lookup: &dyn Fn(&ParamDecl) -> f64) -> bool {
    any_part(e, &|part| part.eval(t, lookup).is_nan())
}

/// Whether some part of `e` evaluates to ±∞ at an end its range leaves open: f64 overflow (0.5 to the power −13 000),
/// which an open end ("no limit known") admits, and past which no range promises anything (cos ∞ is NaN). Frames
/// never get there: the runtime refuses a frame at which a moving number of the scene's shape is not finite in f32.
fn overflow_at_open_end(e: &Expr, t: f64, lookup: &dyn Fn(&ParamDecl) -> f64) -> bool {
    any_part(e, &|part| {
        let (v, r) = (part.eval(t, lookup), range(part));
        (v == f64::INFINITY && r.hi == f64::INFINITY) || (v == f64::NEG_INFINITY && r.lo == f64::NEG_INFINITY)
    })
}

/// Whether `e` or any part of it has the range [`Interval::ENTIRE`].
fn any_unlimited(e: &Expr) -> bool {
    any_part(e, &|part| range(part) == Interval::ENTIRE)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4000, ..ProptestConfig::default() })]

    #[test]
    fn ranges_contain_every_value(e in expr(), t in prop_oneof![Just(0.0), 0.0..10.0f64, 0.0..1e4f64], a in -1.0..2.0f64, b in 0.5..1.5f64) {
        let r = range(&e);
        let lookup = |p: &ParamDecl| if p.name == "a" { a } else { b };
        let v = e.eval(t, &lookup);
        if nan_inside(&e, t, &lookup) {
            // NaN is no value (and min/max/clamp swallow it differently per language): such an expression is outside
            // what ranges promise, but the analysis must have seen it coming (some part's range has no limit, or a
            // part overflowed to an infinity its range left open).
            prop_assert!(
                any_unlimited(&e) || overflow_at_open_end(&e, t, &lookup),
                "NaN inside {:?} at t = {}, a = {}, b = {} unforeseen",
                e,
                t,
                a,
                b
            );
        } else {
            prop_assert!(r.contains(v), "{v} not in {r:?} for {e:?} at t = {t}, a = {a}, b = {b}");
        }
    }
}

#[test]
fn ranges_of_simple_expressions() {
    assert_eq!(range(&time()), Interval { lo: 0.0, hi: f64::INFINITY });
    assert_eq!(range(&param("r", 1.0, 0.5..2.0)), Interval { lo: 0.5, hi: 2.0 });
    assert_eq!(range(&(sin(time()) * 2.0)), Interval { lo: -2.0, hi: 2.0 });
    let narrow = range(&sin(param("x", 0.1, 0.0..0.5)));
    assert!(narrow.lo <= 0.0 && narrow.lo > -1e-14 && (narrow.hi - 0.5f64.sin()).abs() < 1e-14, "{narrow:?}");
    assert_eq!(range(&(Expr::Lit(1.0) / param("d", 1.0, -1.0..1.0))), Interval::ENTIRE);
    assert_eq!(range(&pow(param("x", 1.0, -2.0..1.0), 2.0)), Interval { lo: 0.0, hi: 4.0 });
    assert_eq!(range(&pow(param("x", 1.0, -2.0..1.0), 3.0)), Interval { lo: -8.0, hi: 1.0 });
    assert_eq!(range(&pow(param("x", 1.0, -2.0..1.0), 0.5)), Interval::ENTIRE, "non-integer power of a negative");
    assert_eq!(range(&(time() * 0.0)), Interval::point(0.0));
    let i = Interval { lo: -3.0, hi: 2.0 };
    assert!(i.max_abs() == 3.0 && i.min_abs() == 0.0 && i.is_finite() && !Interval::TIME.is_finite());
}
