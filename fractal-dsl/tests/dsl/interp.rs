//! The interpreter: exact primitives against closed-form distances, the evaluation rules of `eval` (union order,
//! materials, parameters, domain operations), f32 against f64, and the numerically hard cases of DESIGN.md that
//! concern the estimators.

use fractal_dsl::builder::*;
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::{Env, Evaluator, Sample};
use fractal_dsl::formula;
use fractal_dsl::number::math::{v3, V3};
use fractal_dsl::*;
use proptest::prelude::*;

use crate::common::{d64, exact_bounded_primitive, vec3_in};

fn d32(i: &Interpreter, p: [f64; 3]) -> f32 {
    i.distance_in(v3(p[0] as f32, p[1] as f32, p[2] as f32), &Env::<f32>::still())
}

fn sample64(i: &Interpreter, p: [f64; 3]) -> Sample<f64> {
    i.sample_in(v3(p[0], p[1], p[2]), &Env::<f64>::still())
}

fn len(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn albedo(s: &Sample<f64>) -> [f64; 3] {
    [s.albedo.x, s.albedo.y, s.albedo.z]
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    (0..3).all(|i| (a[i] - b[i]).abs() < 1e-12)
}

// ---- exact primitives against closed forms ---------------------------------------------------------------------------

/// Signed distance to the box [−h, h] computed by clamping (outside) and the nearest face (inside).
fn box_distance(p: [f64; 3], h: [f64; 3]) -> f64 {
    let outside = [0, 1, 2].map(|i| p[i] - p[i].clamp(-h[i], h[i]));
    let inside = (0..3).all(|i| p[i].abs() <= h[i]);
    if inside {
        -(0..3).map(|i| h[i] - p[i].abs()).fold(f64::INFINITY, f64::min)
    } else {
        len(outside)
    }
}

/// Signed distance to the rectangle [−a, a] × [−b, b] in the plane.
fn rect_distance(x: f64, y: f64, a: f64, b: f64) -> f64 {
    // An infinite z extent: a finite one would be the nearest face deep inside a rectangle wider than it.
    box_distance([x, y, 0.0], [a, b, f64::INFINITY])
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn exact_primitives_match_closed_forms(
        p in vec3_in(-3.0, 3.0),
        h in vec3_in(0.05, 1.5),
        r in 0.05..1.5f64,
        a in vec3_in(-1.0, 1.0),
        b in vec3_in(-1.0, 1.0),
        n in vec3_in(-1.0, 1.0),
        offset in -1.0..1.0f64,
    ) {
        let tol = 1e-12;
        let check = |node: Node, expected: f64| -> Result<(), TestCaseError> {
            let got = d64(&Interpreter::new(&scene(node.clone())).unwrap(), p);
            prop_assert!((got - expected).abs() <= tol * (1.0 + expected.abs()), "{node:?} at {p:?}: {got} vs {expected}");
            Ok(())
        };
        check(sphere(r), len(p) - r)?;
        check(box3(h), box_distance(p, h))?;
        let rr = r.min(h[0]).min(h[1]).min(h[2]);
        check(round_box(h, rr), box_distance(p, h.map(|v| v - rr)) - rr)?;
        let rho = (p[0] * p[0] + p[2] * p[2]).sqrt();
        check(torus(1.0, r * 0.5), ((rho - 1.0).powi(2) + p[1] * p[1]).sqrt() - r * 0.5)?;
        // Capsule: distance to the segment by projection.
        let ab = [0, 1, 2].map(|i| b[i] - a[i]);
        let ap = [0, 1, 2].map(|i| p[i] - a[i]);
        let t = ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]).max(1e-300)).clamp(0.0, 1.0);
        check(capsule(a, b, r), len([0, 1, 2].map(|i| p[i] - a[i] - ab[i] * t)) - r)?;
        check(cylinder(r, h[1]), rect_distance(rho, p[1], r, h[1]))?;
        // A cone with equal radii is the cylinder.
        check(cone(h[1], r, r), rect_distance(rho, p[1], r, h[1]))?;
        let nl = len(n);
        if nl > 0.1 {
            check(plane(n, offset), (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / nl + offset)?;
        }
        // Transforms of a sphere: the distance to a sphere of radius s·r centred at s·c + t, all exact.
        let s = 0.5 + r;
        check(sphere(r).translate(a).scale(s).translate(b), len([0, 1, 2].map(|i| p[i] - s * a[i] - b[i])) - s * r)?;
        // A box turned by 90° about z is the box with x and y half extents swapped.
        check(box3(h).rotate_z(std::f64::consts::FRAC_PI_2), box_distance(p, [h[1], h[0], h[2]]))?;
        check(box3(h).round(r), box_distance(p, h) - r)?;
        check(sphere(r).onion(0.1), (len(p) - r).abs() - 0.1)?;
        check(sphere(r).elongate([0.5, 0.0, 0.0]), len([p[0] - p[0].clamp(-0.5, 0.5), p[1], p[2]]) - r)?;
    }
}

// ---- evaluation rules ---------------------------------------------------------------------------------------------

const RED: [f64; 3] = [1.0, 0.0, 0.0];
const GREEN: [f64; 3] = [0.0, 1.0, 0.0];
const BLUE: [f64; 3] = [0.0, 0.0, 1.0];

fn colored(n: Node, c: [f64; 3]) -> Node {
    n.material(rgb(c[0], c[1], c[2]))
}

#[test]
fn union_takes_the_nearest_childs_material_and_the_first_on_ties() {
    let s = Interpreter::new(&scene(union(
        colored(sphere(1.0).translate([-2.0, 0.0, 0.0]), RED),
        colored(sphere(1.0).translate([2.0, 0.0, 0.0]), GREEN),
    )))
    .unwrap();
    assert!(close(albedo(&sample64(&s, [-1.5, 0.3, 0.0])), RED));
    assert!(close(albedo(&sample64(&s, [1.5, 0.3, 0.0])), GREEN));
    assert!(close(albedo(&sample64(&s, [0.0, 0.3, 0.0])), RED), "a tie keeps the first child");
    let d = sample64(&s, [0.0, 0.3, 0.0]).distance;
    assert!((d - (4.09f64.sqrt() - 1.0)).abs() < 1e-12);
    // Fractal children are evaluated after the others: at a tie the cheap child listed second wins.
    let tie = Interpreter::new(&scene(union(
        colored(Node::from(menger(1)).translate([-2.0, 0.0, 0.0]), RED),
        colored(box3([1.0, 1.0, 1.0]).translate([2.0, 0.0, 0.0]), GREEN),
    )))
    .unwrap();
    assert!(close(albedo(&sample64(&tie, [0.0, 0.0, 0.0])), GREEN));
}

#[test]
fn intersect_subtract_and_smooth_blends_choose_materials_by_the_rules() {
    let a = colored(sphere(1.0), RED);
    let b = colored(sphere(1.0).translate([1.0, 0.0, 0.0]), GREEN);
    // Intersection: the farther child's material.
    let i = Interpreter::new(&scene(intersect(a.clone(), b.clone()))).unwrap();
    assert!(close(albedo(&sample64(&i, [-0.5, 0.0, 0.0])), GREEN));
    assert!(close(albedo(&sample64(&i, [1.5, 0.0, 0.0])), RED));
    // Subtraction and smooth subtraction: always the left operand's.
    for n in [subtract(a.clone(), b.clone()), smooth_subtract(a.clone(), b.clone(), 0.3)] {
        let s = Interpreter::new(&scene(n)).unwrap();
        assert!(close(albedo(&sample64(&s, [0.9, 0.0, 0.0])), RED));
    }
    // Smooth union: mixed by the blend weight; halfway between equal spheres, half and half.
    let su = Interpreter::new(&scene(smooth_union(a.clone(), b.clone(), 0.5))).unwrap();
    let mid = sample64(&su, [0.5, 0.7, 0.0]);
    assert!(close(albedo(&mid), [0.5, 0.5, 0.0]), "{:?}", mid.albedo);
    let (da, db) = ((0.25f64 + 0.49).sqrt() - 1.0, (0.25f64 + 0.49).sqrt() - 1.0);
    assert!((mid.distance - formula::smooth_min(da, db, 0.5)).abs() < 1e-12);
    // Smooth intersection leans towards the farther child.
    let si = Interpreter::new(&scene(smooth_intersect(a, b, 0.5))).unwrap();
    let s = sample64(&si, [-0.3, 0.0, 0.0]);
    let (d_red, d_green) = (0.3 - 1.0, 1.3 - 1.0);
    let w = formula::blend_weight(d_green, d_red, 0.5);
    assert!(close(albedo(&s), [1.0 - w, w, 0.0]), "{:?} vs weight {w}", s.albedo);
}

#[test]
fn innermost_material_wins_and_bare_geometry_gets_the_default_surface() {
    let inner = Interpreter::new(&scene(colored(colored(sphere(1.0), RED), BLUE))).unwrap();
    assert!(close(albedo(&sample64(&inner, [2.0, 0.0, 0.0])), RED));
    let bare = Interpreter::new(&scene(sphere(1.0))).unwrap();
    let s = sample64(&bare, [2.0, 0.0, 0.0]);
    assert!(close(albedo(&s), [0.95, 0.75, 0.55]));
    assert_eq!((s.ambient, s.diffuse, s.specular, s.shininess), (0.15, 0.85, 0.0, 32.0));
    let phong_m = phong(rgb(0.1, 0.2, 0.3), 0.3, 0.6, 0.9, 64.0);
    let s = sample64(&Interpreter::new(&scene(sphere(1.0).material(phong_m))).unwrap(), [0.0, 2.0, 0.0]);
    assert_eq!((s.ambient, s.diffuse, s.specular, s.shininess), (0.3, 0.6, 0.9, 64.0));
}

#[test]
fn orbit_trap_mixes_by_the_fractals_trap_and_other_leaves_take_the_first_colour() {
    let trap = orbit_trap(rgb(1.0, 0.0, 0.0), rgb(0.0, 0.0, 1.0));
    let bulb = Interpreter::new(&scene(mandelbulb(8).material(trap.clone()))).unwrap();
    let p = [0.3, 0.5, 0.9];
    let t = formula::de_mandelbulb8(v3(p[0], p[1], p[2]), 8, 2.0)[1];
    assert!(close(albedo(&sample64(&bulb, p)), [1.0 - t, 0.0, t]), "trap {t}");
    let plain = Interpreter::new(&scene(sphere(1.0).material(trap))).unwrap();
    assert!(close(albedo(&sample64(&plain, p)), [1.0, 0.0, 0.0]));
}

#[test]
fn fractal_leaves_call_the_leaf_functions_times_the_step_factor() {
    let p = v3(0.4f32, -0.7, 0.55);
    let env = Env::<f32>::still();
    let cases: Vec<(Fractal, f32)> = vec![
        (mandelbulb(8), formula::de_mandelbulb8(p, 8, 2.0)[0]),
        (mandelbulb(7).iterations(5).bailout(4.0), formula::de_mandelbulb(p, 7.0, 5, 4.0)[0]),
        (menger(3), formula::de_menger(p, 3)[0]),
        (sierpinski_tetrahedron(5), formula::de_sierpinski(p, 5)[0]),
        (julia([-0.2, 0.6, 0.2, 0.0]), formula::de_julia(p, -0.2, 0.6, 0.2, 0.0, 11, 4.0)[0]),
        (mandelbox(-1.5).min_radius(0.4).fold_limit(1.2), formula::de_mandelbox(p, -1.5, 12, 0.4, 1.2)[0]),
        // A scene's own factor replaces the family's.
        (mandelbulb(8).step_factor(1.0), formula::de_mandelbulb8(p, 8, 2.0)[0]),
    ];
    for (f, raw) in cases {
        let step = f.step_factor_or_default() as f32;
        let i = Interpreter::new(&scene(f.clone())).unwrap();
        assert_eq!(i.distance_in(p, &env), raw * step, "{f:?}");
    }
    // A power that folds to 8 takes the polynomial form; a parameter power takes the trigonometric one.
    let folded = Interpreter::new(&scene(mandelbulb(Expr::Lit(4.0) * 2.0))).unwrap();
    assert_eq!(folded.distance_in(p, &env), formula::de_mandelbulb8(p, 8, 2.0)[0] * 0.75);
    // Its step factor is that of the lowest power it can take (2 here).
    let animated = Interpreter::new(&scene(mandelbulb(param("power", 8.0, 2.0..12.0)))).unwrap();
    assert_eq!(animated.distance_in(p, &Env::new(0.0, &[8.0])), formula::de_mandelbulb(p, 8.0, 8, 2.0)[0] * 0.35);
    // A power that stays below 4 takes the stretched estimate, at the factor 1.
    let low = Interpreter::new(&scene(mandelbulb(param("power", 3.0, 2.0..3.5)))).unwrap();
    assert_eq!(low.distance_in(p, &Env::new(0.0, &[3.0])), formula::de_mandelbulb_stretched(p, 3.0, 8, 2.0)[0]);
}

#[test]
fn parameters_are_read_by_slot_and_default_when_missing() {
    let s = scene(union(
        sphere(param("r", 1.0, 0.1..2.0)),
        sphere(0.5).translate(vec3(param("x", 3.0, 0.0..5.0) + time(), 0.0, 0.0)),
    ));
    let i = Interpreter::new(&s).unwrap();
    assert_eq!(i.params().iter().map(|p| p.name.as_str()).collect::<Vec<_>>(), ["r", "x"]);
    let at = |p: [f64; 3], time: f64, params: &[f64]| i.distance_in(v3(p[0], p[1], p[2]), &Env::new(time, params));
    assert!((at([0.0, 0.0, 0.0], 0.0, &[1.5, 3.0]) + 1.5).abs() < 1e-12);
    assert!((at([4.0, 0.0, 0.0], 1.0, &[0.1, 3.0]) + 0.5).abs() < 1e-12, "x + t = 4");
    assert!((at([0.0, 0.0, 0.0], 0.0, &[]) + 1.0).abs() < 1e-12, "missing slots read the defaults");
    assert_eq!(i.default_params::<f64>(), vec![1.0, 3.0]);
}

#[test]
fn domain_operations_follow_the_evaluation_rules() {
    let p = [0.7, -0.4, 1.3];
    let at = |n: Node| d64(&Interpreter::new(&scene(n)).unwrap(), p);
    // Rotation turns the shape by +angle: a box long in x turned 90° about z is long in y.
    let long = Interpreter::new(&scene(box3([2.0, 0.2, 0.2]).rotate_z(std::f64::consts::FRAC_PI_2))).unwrap();
    assert!(d64(&long, [0.0, 1.9, 0.0]) < 0.0 && d64(&long, [1.9, 0.0, 0.0]) > 0.0);
    // Any-axis rotation about z equals rotate_z.
    assert!(
        (at(box3([1.0, 0.5, 0.3]).rotate([0.0, 0.0, 2.0], 0.8)) - at(box3([1.0, 0.5, 0.3]).rotate_z(0.8))).abs()
            < 1e-12
    );
    // Repetition: p − period·floor(p/period + 0.5) on repeated axes; the limited form clamps the cell.
    let rep = Interpreter::new(&scene(sphere(0.3).repeat([2.0, 0.0, 0.0]))).unwrap();
    assert!((d64(&rep, [4.1, 0.2, 0.0]) - d64(&rep, [0.1, 0.2, 0.0])).abs() < 1e-12);
    let lim = Interpreter::new(&scene(sphere(0.3).repeat_limited([2.0, 0.0, 0.0], [1, 0, 0]))).unwrap();
    assert!((d64(&lim, [4.1, 0.0, 0.0]) - (2.1 - 0.3)).abs() < 1e-12);
    // Twist about y and bend in xy: the child at the turned point, divided by the stretch.
    let k = 0.9;
    let child = |q: [f64; 3]| box_distance(q, [0.5, 1.0, 0.3]);
    let a = k * p[1];
    let q = [a.cos() * p[0] - a.sin() * p[2], p[1], a.sin() * p[0] + a.cos() * p[2]];
    // The largest stretch of the map at radius ρ from the axis: (v + sqrt(v² + 4))/2 with v = |k|·ρ.
    let stretch = |rho: f64| (k * rho + ((k * rho).powi(2) + 4.0).sqrt()) / 2.0;
    let twist = child(q) / stretch(p[0].hypot(p[2]));
    assert!((at(box3([0.5, 1.0, 0.3]).twist(k)) - twist).abs() < 1e-12);
    let a = k * p[0];
    let q = [a.cos() * p[0] - a.sin() * p[1], a.sin() * p[0] + a.cos() * p[1], p[2]];
    let bend = child(q) / stretch(p[0].hypot(p[1]));
    assert!((at(box3([0.5, 1.0, 0.3]).bend(k)) - bend).abs() < 1e-12);
    // Scale divides the point and multiplies the distance back.
    assert!((at(box3([0.5, 1.0, 0.3]).scale(2.5)) - 2.5 * child(p.map(|v| v / 2.5))).abs() < 1e-12);
    // A union of nothing is refused, as by every other entry point.
    assert!(Interpreter::new(&scene(union_all([]))).is_err());
}

// ---- f32 against f64 ---------------------------------------------------------------------------------------------

/// The exact bounded primitives and the ellipsoid, each drawn with probability 1/7 (6 of 7 draws go to the six
/// shared ones).
fn primitive() -> impl Strategy<Value = Node> {
    prop_oneof![
        6 => exact_bounded_primitive(),
        1 => vec3_in(0.1, 1.2).prop_map(ellipsoid),
    ]
}

fn tree() -> impl Strategy<Value = Node> {
    primitive().prop_recursive(4, 20, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| union(a, b)),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| intersect(a, b)),
            (inner.clone(), inner.clone(), 0.0..1.0f64).prop_map(|(a, b, k)| smooth_union(a, b, k)),
            (inner.clone(), inner.clone(), 0.0..1.0f64).prop_map(|(a, b, k)| smooth_subtract(a, b, k)),
            (inner.clone(), vec3_in(-1.0, 1.0)).prop_map(|(a, v)| a.translate(v)),
            (inner.clone(), -4.0..4.0f64).prop_map(|(a, t)| a.rotate([1.0, 2.0, 0.5], t)),
            (inner.clone(), 0.3..3.0f64).prop_map(|(a, s)| a.scale(s)),
            (inner.clone(), -1.0..1.0f64).prop_map(|(a, k)| a.twist(k)),
            (inner.clone(), vec3_in(0.5, 2.0), 0u32..3).prop_map(|(a, per, n)| a.repeat_limited(per, [n, n, n])),
            (inner.clone(), 0.0..0.3f64).prop_map(|(a, r)| a.round(r).onion(0.05)),
            (inner, vec3_in(0.0, 0.5)).prop_map(|(a, h)| a.elongate(h)),
        ]
    })
}

/// f32 against f64 on trees of primitives, evaluated at the same (f32) point: each operation rounds to f32 relative to
/// the magnitudes it handles (coordinates up to 3, the distances), so the difference is a few f32 ulps of
/// 1 + |p| + |d|: measured at most 2e-7 of it over 3000 random trees; the tolerance is ten times that. Limited
/// repetition picks cell floor(p/period + 0.5), which can differ between precisions exactly on a cell boundary: such
/// points (within 1e-5 of one, in the tree's local coordinates) are skipped.
const F32_TOLERANCE: f64 = 2e-6;

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn f32_agrees_with_f64_on_primitive_trees(t in tree(), points in prop::collection::vec(vec3_in(-3.0, 3.0), 32)) {
        let i = Interpreter::new(&scene(t.clone())).unwrap();
        for p in points {
            let p32 = p.map(|v| v as f32 as f64);
            let (a, b) = (d32(&i, p32) as f64, d64(&i, p32));
            let scale = 1.0 + len(p32) + b.abs();
            if (a - b).abs() > F32_TOLERANCE * scale {
                prop_assert!(on_cell_boundary(&t, p32), "f32 {a} vs f64 {b} at {p32:?} for {t:?}");
            }
        }
    }
}

/// Whether some limited repetition in `n` sees `p` (carried through the transforms above it) within 1e-5 of a cell
/// boundary on a repeated axis.
fn on_cell_boundary(n: &Node, p: [f64; 3]) -> bool {
    let lit = |e: &Expr| e.as_lit().unwrap_or(0.0);
    let Some(op) = n.op() else {
        return n.children().iter().any(|c| on_cell_boundary(c, p));
    };
    let child = &op.shapes[0];
    let arg = |i: usize| op.args[i].exprs();
    match op.name() {
        "repeat_limited" => {
            (0..3).any(|i| {
                let per = lit(&arg(0)[i]);
                per != 0.0 && {
                    let x = p[i] / per + 0.5;
                    (x - x.round()).abs() < 1e-5
                }
            }) || on_cell_boundary(child, p)
        }
        "translate" => on_cell_boundary(child, [0, 1, 2].map(|i| p[i] - lit(&arg(0)[i]))),
        "scale" => on_cell_boundary(child, p.map(|v| v / lit(&arg(0)[0]))),
        // Below a rotation, twist or elongation the local point is not tracked here: any boundary counts.
        "rotate_x" | "rotate_y" | "rotate_z" | "rotate" | "twist" | "elongate" => contains_repeat(child),
        _ => n.children().iter().any(|c| on_cell_boundary(c, p)),
    }
}

fn contains_repeat(n: &Node) -> bool {
    n.op().is_some_and(|op| op.name() == "repeat_limited") || n.children().iter().any(contains_repeat)
}

/// Fractal estimators iterate a chaotic map: near the set, f32 rounding in the first iterations grows like the
/// derivative and the two precisions follow different orbits, so no tolerance holds there. Away from the surface (f64
/// estimate above 0.05) the orbits escape early and the two agree to a relative 2e-5 (measured at most 1.9e-6);
/// everywhere both stay finite.
#[test]
fn f32_agrees_with_f64_on_fractals_away_from_the_surface() {
    let fractals: Vec<(&str, Fractal, f64)> = vec![
        ("mandelbulb 8", mandelbulb(8), 1.5),
        ("mandelbulb 5.5", mandelbulb(5.5), 1.5),
        ("menger 4", menger(4), 1.5),
        ("sierpinski 8", sierpinski_tetrahedron(8), 1.5),
        ("julia", julia([-0.2, 0.6, 0.2, 0.0]), 2.0),
        ("mandelbox -1.5", mandelbox(-1.5), 3.0),
    ];
    let mut rng = 0x9e3779b97f4a7c15u64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    for (name, f, half) in fractals {
        let i = Interpreter::new(&scene(f)).unwrap();
        let mut worst = 0.0f64;
        for _ in 0..4000 {
            let p = [0, 1, 2].map(|_| ((next() * 2.0 - 1.0) * half) as f32 as f64);
            let (a, b) = (d32(&i, p) as f64, d64(&i, p));
            assert!(a.is_finite() && b.is_finite(), "{name} at {p:?}: f32 {a}, f64 {b}");
            if b > 0.05 {
                let rel = (a - b).abs() / b;
                worst = worst.max(rel);
                assert!(rel < 2e-5, "{name} at {p:?}: f32 {a} vs f64 {b}");
            }
        }
        eprintln!("{name}: largest relative f32/f64 difference away from the surface {worst:.2e}");
    }
}

// ---- hard cases (DESIGN.md) ----------------------------------------------------------------------------------------

/// Both Mandelbulb forms at power 8 in precision F.
fn bulb_forms<F: fractal_dsl::number::math::Real>(p: [f64; 3], iterations: u32) -> (F, F) {
    let q: V3<F> = v3(F::c(p[0]), F::c(p[1]), F::c(p[2]));
    (
        formula::de_mandelbulb8(q, iterations, F::c(2.0))[0],
        formula::de_mandelbulb(q, F::c(8.0), iterations, F::c(2.0))[0],
    )
}

/// Case 1: on the pole axis (x = y = 0; the polar axis is z) and 1e-7 and 1e-30 off it, both forms are finite and
/// agree, relative to 1 + |d|: in f64 to 5e-8, in f32 to 5e-6 (measured 6.8e-9 and 5.5e-7). They differ by more than
/// rounding of products because acos(z/r) is ill-conditioned next to the pole: z/r = ±(1 − ε) gives θ ≈ √(2ε), so an
/// ulp of z/r moves θ by ulp/√(2ε) (about 1e-9 at 1e-7 off the axis), which the trigonometric form then multiplies
/// by 8; the polynomial form never takes the angle.
#[test]
fn mandelbulb_on_and_near_the_pole_axis() {
    let mut worst = [0.0f64; 2];
    for k in -30..=30 {
        let z = k as f64 * 0.05;
        for off in [0.0, 1e-7, 1e-30] {
            // Our polar axis is z; the y axis (DESIGN.md's x = z = 0, a y-up convention) is checked as well.
            for p in [[off, 0.0, z], [0.0, off, z], [off, off, z], [off, z, 0.0], [0.0, z, off]] {
                for iterations in [1, 4, 8, 16] {
                    let (a, b) = bulb_forms::<f64>(p, iterations);
                    assert!(a.is_finite() && b.is_finite(), "f64 at {p:?}: {a}, {b}");
                    let e = (a - b).abs() / (1.0 + a.abs());
                    worst[0] = worst[0].max(e);
                    assert!(e < 5e-8, "f64 forms differ at {p:?} × {iterations}: {a} vs {b}");
                    let (a, b) = bulb_forms::<f32>(p, iterations);
                    assert!(a.is_finite() && b.is_finite(), "f32 at {p:?}: {a}, {b}");
                    let e = (a - b).abs() as f64 / (1.0 + a.abs() as f64);
                    worst[1] = worst[1].max(e);
                    assert!(e < 5e-6, "f32 forms differ at {p:?} × {iterations}: {a} vs {b}");
                }
            }
        }
    }
    eprintln!(
        "pole axis: largest difference between the two power-8 forms: f64 {:.1e}, f32 {:.1e}",
        worst[0], worst[1]
    );
}

/// Case 2: p = 0 exactly, and points whose orbit never escapes, give a finite estimate at or below 0.
#[test]
fn mandelbulb_at_the_origin_and_at_points_that_never_escape() {
    let bulbs = [
        Interpreter::new(&scene(mandelbulb(8))).unwrap(),
        Interpreter::new(&scene(mandelbulb(param("n", 8.0, 2.0..16.0)))).unwrap(),
    ];
    for i in &bulbs {
        for p in [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5], [0.1, -0.2, 0.15], [-0.3, 0.1, 0.2], [0.0, 0.4, -0.3]] {
            let (a, b) = (d32(i, p), d64(i, p));
            assert!(a.is_finite() && b.is_finite(), "{p:?}: {a}, {b}");
            assert!(a <= 0.0 && b <= 0.0, "{p:?} never escapes: {a}, {b}");
        }
    }
    for power in [2.0, 3.0, 8.0, 16.0, 32.0] {
        let [d, trap] = formula::de_mandelbulb(v3(0.0f32, 0.0, 0.0), power, 64, 256.0);
        assert!(d.is_finite() && d <= 0.0 && (0.0..=1.0).contains(&trap), "power {power}: {d}, {trap}");
    }
}

/// Random points, mostly near the set and one in ten up to 100 units away.
fn high_power_points(n: usize) -> Vec<[f64; 3]> {
    let mut rng = 12345u64;
    let mut next = move || {
        rng ^= rng << 13;
        rng ^= rng >> 7;
        rng ^= rng << 17;
        (rng >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|k| {
            let reach = if k % 10 == 0 { 100.0 } else { 1.2 };
            [0, 1, 2].map(|_| (next() * 2.0 - 1.0) * reach)
        })
        .collect()
}

/// Case 3: powers 16 and 32 with bailout 256, up to the iteration cap: no Inf or NaN in f64.
#[test]
fn high_power_mandelbulbs_stay_finite_in_f64() {
    for power in [16.0, 32.0] {
        for iterations in [8, 32, MAX_ITERATIONS] {
            let i = Interpreter::new(&scene(mandelbulb(power).bailout(256.0).iterations(iterations))).unwrap();
            for p in high_power_points(3000) {
                let d = d64(&i, p);
                assert!(d.is_finite(), "power {power} × {iterations} at {p:?}: {d}");
            }
        }
    }
}

/// Case 3 in f32. `formula::mandelbulb_escape` keeps |z|^power below 2^120, but `length` squares the new z, which
/// overflows f32 (2^128) once |z| passes 2^64: the estimate becomes +∞. With bailout 256, 15% of points within 1.5 of
/// the origin at power 16 and 3% at power 32 are affected (measured over 100 000 points).
#[test]
fn high_power_mandelbulbs_stay_finite_in_f32() {
    let d = formula::de_mandelbulb(v3(-0.73857415f32, -1.087467, 0.24681997), 16.0, 8, 256.0)[0];
    assert!(d.is_finite(), "power 16 × 8, bailout 256 at (-0.73857415, -1.087467, 0.24681997): {d}");
    for power in [16.0, 32.0] {
        for iterations in [8, 32, MAX_ITERATIONS] {
            let i = Interpreter::new(&scene(mandelbulb(power).bailout(256.0).iterations(iterations))).unwrap();
            for p in high_power_points(3000) {
                let d = d32(&i, p);
                assert!(d.is_finite(), "power {power} × {iterations} at {p:?}: {d}");
            }
        }
    }
}

/// Case 4: a 6-level Menger sponge at points exactly on the k/3^m planes of its holes, and 100 units away: finite,
/// f32 and f64 within 1e-5 (coordinates like 1/3 round in f32 by up to 3e-8; the estimate is 1-Lipschitz).
#[test]
fn menger_on_the_planes_of_its_holes() {
    let i = Interpreter::new(&scene(menger(6))).unwrap();
    let mut worst = 0.0f64;
    for m in 1..=6 {
        let step = 3f64.powi(-m);
        for k in -(3i32.pow(m as u32))..=3i32.pow(m as u32) {
            let c = k as f64 * step;
            for p in [[c, 0.0, 0.0], [c, c, 0.5], [1.0 / 3.0, c, -c], [c, 1.0, c], [c, c, c]] {
                let (a, b) = (d32(&i, p) as f64, d64(&i, p));
                assert!(a.is_finite() && b.is_finite(), "{p:?}: {a}, {b}");
                worst = worst.max((a - b).abs());
                assert!((a - b).abs() < 1e-5, "{p:?}: f32 {a} vs f64 {b}");
            }
        }
    }
    for p in [[100.0, 0.0, 0.0], [0.0, -100.0, 0.0], [57.7, 57.7, 57.7]] {
        let (a, b) = (d32(&i, p) as f64, d64(&i, p));
        assert!(a.is_finite() && (a - b).abs() < 1e-4 && b > 98.0, "{p:?}: {a} {b}");
    }
    eprintln!("menger 6 on k/3^m planes: largest f32/f64 difference {worst:.1e}");
}

/// Case 5: smooth union with k = 0 is the plain minimum (no division by zero, no NaN), also where both distances are
/// equal; with k larger than both shapes the blend is finite and within k/4 below the minimum.
#[test]
fn smooth_union_at_zero_and_huge_blend_radius() {
    let a = sphere(0.2).translate([-0.5, 0.0, 0.0]);
    let b = box3([0.1, 0.2, 0.3]).translate([0.5, 0.0, 0.0]);
    let plain = Interpreter::new(&scene(union(a.clone(), b.clone()))).unwrap();
    let zero = Interpreter::new(&scene(smooth_union(a.clone(), b.clone(), 0.0))).unwrap();
    let zero_param = Interpreter::new(&scene(smooth_union(a.clone(), b.clone(), param("k", 0.0, 0.0..1.0)))).unwrap();
    let huge = Interpreter::new(&scene(smooth_union(a.clone(), b.clone(), 5.0))).unwrap();
    for p in [[0.0, 0.0, 0.0], [0.0, 0.7, 0.1], [-0.5, 0.0, 0.0], [2.0, -1.0, 0.5], [0.3, 0.0, 0.0]] {
        let m = d64(&plain, p);
        assert_eq!(d64(&zero, p), m, "k = 0 at {p:?}");
        assert_eq!(d32(&zero_param, p), d32(&plain, p), "k = 0 (f32) at {p:?}");
        let s = sample64(&zero, p);
        assert!(s.albedo.x.is_finite() && s.ambient.is_finite());
        let h = d64(&huge, p);
        assert!(h.is_finite() && h <= m && h >= m - 5.0 / 4.0, "k = 5 at {p:?}: {h} vs min {m}");
        assert!(d32(&huge, p).is_finite());
    }
    // Equal distances with k = 0: h = 0 / TINY, not 0 / 0.
    assert_eq!(formula::smooth_min(0.25f32, 0.25, 0.0), 0.25);
    assert_eq!(formula::blend_weight(0.25f32, 0.25, 0.0), 0.5);
    let twins = Interpreter::new(&scene(smooth_union(sphere(1.0), sphere(1.0), 0.0))).unwrap();
    let s = sample64(&twins, [0.0, 2.0, 0.0]);
    assert!(s.distance == 1.0 && s.albedo.x.is_finite());
}

/// The quaternion Julia estimate at the critical point: z = 0 has a vanishing derivative, so the formula divides
/// 0 by 0 when c = 0 (NaN) and a positive log by 0 for escaping c (+∞). Kept as a record until `formula::de_julia`
/// guards the division.
#[test]
fn julia_at_its_critical_point_is_finite() {
    for c in [[0.0; 4], [0.3, 0.0, 0.0, 0.0]] {
        let d = formula::de_julia(v3(0.0f64, 0.0, 0.0), c[0], c[1], c[2], c[3], 11, 4.0)[0];
        assert!(d.is_finite(), "c = {c:?}: {d}");
    }
}

/// Evaluator trait objects dispatch to the same evaluation.
#[test]
fn evaluator_trait_matches_the_inherent_methods() {
    let i = Interpreter::new(&scene(union(sphere(1.0), Node::from(menger(2)).translate([3.0, 0.0, 0.0])))).unwrap();
    let e32: &dyn Evaluator<f32> = &i;
    let e64: &dyn Evaluator<f64> = &i;
    let p = v3(1.7f32, 0.2, -0.3);
    assert_eq!(e32.distance(p, &Env::still()), i.distance_in(p, &Env::still()));
    let q = v3(1.7f64, 0.2, -0.3);
    assert_eq!(e64.sample(q, &Env::still()), i.sample_in(q, &Env::still()));
}
