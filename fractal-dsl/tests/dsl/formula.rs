//! Formulas written in the scene language: the parser's errors point inside the formula, the printer's text reads
//! back as the same formula, the derived derivative is the derivative (against central differences in f64), a
//! formula of a built-in family's map draws that family (the estimate against the hand-written one), and hostile
//! formulas give finite, defined results.

use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::formula::dual::Dual;
use fractal_dsl::formula::user::{run_map, Ready};
use fractal_dsl::ir::formula::Formula;
use fractal_dsl::ir::{Expr, Node};
use fractal_dsl::number::math::v3;
use fractal_dsl::parse::parse_str;
use fractal_dsl::print::to_source;

use crate::common::{d64, Rng};

/// The power-8 Mandelbulb as the issue writes it.
const BULB: &str = "escape_time(|z, c| {
    let r = length(z);
    let theta = acos(z.z / r) * 8.0;
    let phi = atan2(z.y, z.x) * 8.0;
    pow(r, 8.0) * vec3(sin(theta) * cos(phi), sin(phi) * sin(theta), cos(theta)) + c
})
.iterations(8)
.bailout(2.0)";

fn formula_of(src: &str) -> Formula {
    let scene = parse_str(src).unwrap_or_else(|e| panic!("{src}\n{e}"));
    match &scene.root {
        Node::Fractal(f) => f.formula().cloned().expect("a formula"),
        other => panic!("not a fractal: {other:?}"),
    }
}

fn error_of(src: &str) -> String {
    match parse_str(src) {
        Ok(_) => panic!("accepted: {src}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn errors_point_inside_the_formula() {
    let cases = [
        ("escape_time(|z, c| z + w)", "1:24: unknown name `w`"),
        (
            "escape_time(|z, c| {\n    let r = length(z);\n    r * 2.0\n})",
            "3:5: the next z must be a vec3, found a number",
        ),
        ("escape_time(|z, c| z * vec2(1.0, 2.0))", "1:20: `*` applies to numbers and vectors of one size"),
        ("escape_time(|z, c| z.q + c)", "1:22: `q` is not a component of a vec3"),
        ("escape_time(|z, c| sphere(z))", "1:20: `sphere` is not a formula function"),
        ("escape_time(|z, c| lenght(z) * z + c)", "did you mean `length`?"),
        ("escape_time(|z, c| if z.x < 0.0 { z } )", "give it an `else`"),
        ("escape_time(|z, c| (z, 2.0))", "((z, scale) only in fold(..))"),
        ("escape_time(|z, c, d| z)", "found 3 parameters"),
        ("escape_time(|z, c| z == c)", "not == or !="),
        ("escape_time(|z, c| { let mut a = z; a })", "1:26: `mut` is a Rust keyword"),
        ("escape_time(z)", "a formula is a closure"),
        ("sphere(1.0).translate(|z| z)", "1:23: `|` is not part of the scene language"),
    ];
    for (src, expected) in cases {
        let message = error_of(src);
        assert!(message.contains(expected), "{src}\n  said:     {message}\n  expected: {expected}");
    }
}

#[test]
fn blocks_and_keywords_stay_out_of_the_rest_of_the_scene() {
    assert!(error_of("sphere({ 1.0 })").contains("`{` is not part of the scene language"));
    assert!(error_of("union(sphere(1.0), if t < 1.0 { sphere(2.0) } else { sphere(3.0) })").contains("keyword"));
}

#[test]
fn printed_formulas_read_back_the_same() {
    let sources = [
        BULB.to_string(),
        "hybrid(|z, c| z * z.x + c, |z| box_fold(z, 1.0) * -1.5)".into(),
        "fold(|z, c| { let z = sphere_fold(box_fold(z, 1.0), 0.5, 1.0); (z * 2.0 + c, 2.0) }).bailout(6.0)".into(),
        "escape_time(|z, c| { let q = qsqr(vec4(z, 0.0)); if q.x > param(\"k\", 0.1, -1.0..1.0) && !(q.y < -t) \
         { q.zyx + c } else { -q.wxy + c * 2.0 } })"
            .into(),
    ];
    for src in sources {
        let scene = parse_str(&src).unwrap_or_else(|e| panic!("{src}\n{e}"));
        let text = to_source(&scene);
        let again = parse_str(&text).unwrap_or_else(|e| panic!("{text}\n{e}"));
        assert_eq!(again, scene, "{text}");
        assert_eq!(to_source(&again), text);
    }
}

/// The formula ready to run with its literal numbers (these formulas have no `t` or `param`).
fn ready(formula: &Formula) -> (Ready, Vec<f64>) {
    let mut nums = Vec::new();
    let indexed = formula.map_nums(&mut |e: &Expr| {
        nums.push(e.as_lit().expect("a literal"));
        (nums.len() - 1) as u16
    });
    let literals = nums.iter().map(|&v| Some(v)).collect();
    (Ready { formula: indexed, literals, iterations: 1, host: None }, nums)
}

#[test]
fn the_derived_derivative_is_the_derivative() {
    let maps = [
        BULB.to_string(),
        "fold(|z, c| sphere_fold(box_fold(z, 1.0), 0.5, 1.0) * -1.5 + c)".into(),
        "escape_time(|z, c| { let q = qmul(vec4(z, 0.3), vec4(z.yzx, -0.2)); normalize(q.xyz) * exp(q.w) + c })".into(),
        "escape_time(|z, c| vec3(tan(z.x), asin(z.y * 0.5), atan(z.z)) * abs(z) + pow(abs(z), 2.5) * c)".into(),
    ];
    let mut rng = Rng(7);
    for src in maps {
        let (ready, nums) = ready(&formula_of(&src));
        let map = &ready.formula.maps[0];
        let duals: Vec<Dual<f64>> = nums.iter().map(|&n| Dual::constant(n)).collect();
        for _ in 0..200 {
            let p = [0, 1, 2].map(|_| rng.unit() * 2.4 - 1.2);
            let point = v3(Dual::variable(p[0], 0), Dual::variable(p[1], 1), Dual::variable(p[2], 2));
            let (next, _) = run_map(map, &duals, &ready.literals, point, point);
            let value = |q: [f64; 3]| {
                let v = v3(q[0], q[1], q[2]);
                let (n, _) = run_map(map, &nums, &ready.literals, v, v);
                [n.x, n.y, n.z]
            };
            let h = 1e-6;
            for axis in 0..3 {
                let (mut a, mut b) = (p, p);
                a[axis] += h;
                b[axis] -= h;
                let (fa, fb) = (value(a), value(b));
                for (i, component) in [next.x, next.y, next.z].iter().enumerate() {
                    let numeric = (fa[i] - fb[i]) / (2.0 * h);
                    let derived = component.d[axis];
                    let scale = 1.0 + numeric.abs().max(derived.abs());
                    // A fold is piecewise smooth: a point within h of a crease may differ; those are rare.
                    if (numeric - derived).abs() > 1e-4 * scale && !src.starts_with("fold") {
                        panic!("{src}\nd z{i} / d p{axis} at {p:?}: derived {derived}, numeric {numeric}");
                    }
                }
            }
        }
    }
}

/// The formula of the Mandelbulb's map draws the Mandelbulb: its estimate at most a little more than the hand-written
/// one (the derived one reads the gradient of the last length exactly; the hand-written one a running scalar, the
/// radial stretch alone), and the same set (membership by the orbit is the same orbit).
#[test]
fn the_bulb_formula_draws_the_bulb() {
    let formula = Interpreter::new(&parse_str(BULB).unwrap()).unwrap().without_bound_guards();
    let hand = Interpreter::new(&parse_str("mandelbulb(7.999).iterations(8)").unwrap()).unwrap().without_bound_guards();
    let (fs, hs) = (0.5, 0.65); // the step factors the two are scaled by
    let mut rng = Rng(11);
    let mut ratios = Vec::new();
    for _ in 0..2000 {
        let p = [0, 1, 2].map(|_| rng.unit() * 2.6 - 1.3);
        let (f, h) = (d64(&formula, p) / fs, d64(&hand, p) / hs);
        assert!(f.is_finite(), "{p:?}");
        if h > 1e-3 {
            ratios.push(f / h);
        }
    }
    ratios.sort_by(f64::total_cmp);
    let median = ratios[ratios.len() / 2];
    assert!((0.3..=1.05).contains(&median), "median estimate ratio formula / hand-written {median}");
}

#[test]
fn hostile_formulas_give_finite_defined_results() {
    let hostile = [
        // 0/0 and x/0 everywhere
        "escape_time(|z, c| z / (z.x - z.x) + c)",
        // never escapes
        "escape_time(|z, c| z * 0.5).iterations(64)",
        // grows past f32 in one step
        "escape_time(|z, c| z * 1e30 + c).bailout(1e6)",
        // logarithms and roots of negatives, acos past 1
        "escape_time(|z, c| vec3(ln(z.x), sqrt(z.y), acos(z.z * 10.0)) + c)",
        // a fold that blows up
        "fold(|z, c| z * 1e20 + c).iterations(64)",
        "fold(|z, c| { let k = 1.0 / dot(z, z); (z * k, k) })",
    ];
    let mut rng = Rng(3);
    for src in hostile {
        let interp = Interpreter::new(&parse_str(src).unwrap()).unwrap();
        for _ in 0..300 {
            let p = [0, 1, 2].map(|_| rng.unit() * 4.0 - 2.0);
            let d = d64(&interp, p);
            assert!(!d.is_nan(), "{src} at {p:?}: {d}");
        }
        assert!(!d64(&interp, [0.0; 3]).is_nan(), "{src} at the origin");
    }
    // A number beyond f32's range is infinite in the f32 kernels and finite in f64: refused, as in the rest of a scene.
    let src = "escape_time(|z, c| z * z + vec3(-0.2, 1e308, -0.1))";
    let refused = match parse_str(src) {
        Err(e) => e.to_string(),
        Ok(scene) => Interpreter::new(&scene).expect_err("refused").to_string(),
    };
    assert!(refused.contains("±3.4e38") && refused.contains("1e308"), "{refused}");
}

/// The built-in families written as formulas (`scenes/prelude/`) draw the built-in scenes' sets: wherever the
/// hand-written estimate puts a point clearly outside, the formula's does too, and the two estimates stay within a
/// small factor of each other (they differ in their derivative: derived against written by hand).
#[test]
fn the_prelude_formulas_draw_the_built_in_sets() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("scenes");
    let read = |path: std::path::PathBuf| {
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let scene = parse_str(&text).unwrap_or_else(|e| panic!("{}:{e}", path.display()));
        Interpreter::new(&scene).unwrap().without_bound_guards()
    };
    // (prelude file, built-in scene, half the sampled cube, the built-in estimate past which a point is clearly
    // outside: the Mandelbox's estimate is a small share of its distance everywhere)
    let pairs = [
        ("mandelbulb_bench", "mandelbulb_bench", 1.3, 0.065),
        ("julia", "julia", 1.3, 0.065),
        ("mandelbox", "mandelbox", 6.0, 0.01),
        ("menger", "sierpinski_cube", 1.3, 0.065),
        ("mandelbulb", "mandelbulb", 1.3, 0.065),
        ("juliabulb", "juliabulb", 1.3, 0.065),
        ("sierpinski", "sierpinski_tetrahedron", 1.9, 0.065),
        ("kifs", "kifs", 1.3, 0.065),
    ];
    let mut rng = Rng(5);
    for (prelude, built_in, half, outside) in pairs {
        let formula = read(root.join("prelude").join(format!("{prelude}.fractal")));
        // The built-in scene's fractal alone, without its floor or transforms.
        let hand = match built_in {
            "julia" => "julia(vec4(-0.2, 0.6, 0.2, 0.0)).iterations(11)",
            "mandelbox" => "mandelbox(2.0).iterations(14)",
            "sierpinski_cube" => "menger(5)",
            "mandelbulb" => "mandelbulb(8.0).iterations(8).bailout(2.0)",
            "juliabulb" => "juliabulb(vec3(0.45, 0.5, -0.15)).iterations(10).bailout(2.0)",
            "sierpinski_tetrahedron" => "sierpinski_tetrahedron(10)",
            "kifs" => "octahedral_kifs(2.0).iterations(12)",
            _ => "mandelbulb(8).iterations(8)",
        };
        let hand = Interpreter::new(&parse_str(hand).unwrap()).unwrap().without_bound_guards();
        let mut ratios = Vec::new();
        for _ in 0..3000 {
            let p = [0, 1, 2].map(|_| (rng.unit() * 2.0 - 1.0) * half);
            let (f, h) = (d64(&formula, p), d64(&hand, p));
            assert!(f.is_finite(), "{prelude} at {p:?}");
            if h > outside {
                assert!(f > 0.0, "{prelude} at {p:?}: the formula says inside ({f}), the built-in {h} away");
                ratios.push(f / h);
            }
        }
        assert!(
            !ratios.is_empty(),
            "{prelude}: no point clearly outside, e.g. {} at (1, 1, 1), {} at (5.5, 5.5, 5.5)",
            d64(&hand, [1.0; 3]),
            d64(&hand, [5.5; 3])
        );
        ratios.sort_by(f64::total_cmp);
        let median = ratios[ratios.len() / 2];
        // The Mandelbox's hand-written dr multiplies the steps' norms, which only bounds the norm of their product:
        // the derived Jacobian's norm is that norm, and its estimate about 3.7 times the hand-written one.
        assert!((0.1..=5.0).contains(&median), "{prelude}: median estimate ratio formula / built-in {median}");
    }
}

/// A formula compiled for the host ([`fractal_dsl::lower::tape`]) computes what walking its tree computes: the same
/// membership everywhere, and the same estimate to rounding (the traced code folds constants and drops identities
/// like x·1, which round alike or not at all in f64), on the gallery's formulas, the prelude and hostile formulas.
#[test]
fn host_code_computes_what_the_tree_computes() {
    use fractal_dsl::eval::plan::{FormulaCall, Plan};
    use fractal_dsl::eval::Env;
    use fractal_dsl::formula::user;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut sources: Vec<String> = ["fractal/quadratic_bulb", "fractal/kalibox", "fractal/menger_smooth"]
        .iter()
        .chain(&["fractal/bristorbrot", "fractal/quaternion_mandelbrot", "fractal/cosine_bulb"])
        .chain(&["fractal/amazing_surf", "prelude/mandelbox", "prelude/julia", "formulas/bulb_box_hybrid"])
        .chain(&["prelude/mandelbulb", "prelude/juliabulb", "prelude/sierpinski", "prelude/kifs"])
        .chain(&["fractal/makin_bulb", "formulas/lkmitch_bulb", "formulas/sym2_bulb", "formulas/riemann_bulb"])
        .map(|f| std::fs::read_to_string(root.join(format!("{f}.fractal"))).unwrap())
        .collect();
    sources.push(BULB.into());
    sources.push("escape_time(|z, c| vec3(ln(z.x), sqrt(z.y), acos(z.z * 10.0)) / (z.x - z.x) + c)".into());
    sources.push("fold(|z, c| { let k = 1.0 / dot(z, z); (z * k, k) }).iterations(30)".into());
    let mut rng = Rng(5);
    for src in &sources {
        let scene = parse_str(src).unwrap_or_else(|e| panic!("{src}\n{e}"));
        let mut calls: Vec<FormulaCall> = Vec::new();
        Plan::new(&scene).formula_calls_mut(&mut |c| calls.push(c.clone()));
        assert!(!calls.is_empty(), "{src}: no formula");
        let tree = Interpreter::new(&scene).unwrap().without_bound_guards();
        let host = fractal_dsl::lower::tape::interpreter(&scene).unwrap().without_bound_guards();
        for call in &mut calls {
            fractal_dsl::lower::tape::attach(call);
        }
        let env = Env::<f64>::still();
        for _ in 0..400 {
            let p = [0, 1, 2].map(|_| rng.unit() * 4.0 - 2.0);
            let (a, b) = (d64(&tree, p), d64(&host, p));
            let close = (a - b).abs() <= 1e-9 * (1.0 + a.abs()) || (a.is_nan() && b.is_nan());
            assert!(close, "{src}\nestimate at {p:?}: tree {a}, host code {b}");
            for call in &calls {
                let code = call.ready.host.as_ref().unwrap_or_else(|| panic!("{src}: no host code"));
                let nums: Vec<f64> = call.nums.iter().map(|t| t.eval(&env)).collect();
                let bailout = call.bailout.eval(&env);
                let walked = user::membership(&call.ready, &nums, v3(p[0], p[1], p[2]), bailout);
                let compiled = code.membership(&nums, p, bailout);
                assert_eq!(walked <= 0.0, compiled <= 0.0, "{src}\nmembership at {p:?}: {walked} against {compiled}");
            }
        }
    }
}

/// |zₙ| of the formula's one map from `q` after exactly `n` iterations, or — with `n` None — at the iteration its
/// orbit first passes `escape`, with that count (the iterations run out: None).
fn orbit_length(ready: &Ready, nums: &[f64], q: [f64; 3], n: Option<usize>, escape: f64) -> Option<(f64, usize)> {
    let c = v3(q[0], q[1], q[2]);
    let mut z = c;
    for k in 0..ready.iterations as usize {
        let r = (z.x * z.x + z.y * z.y + z.z * z.z).sqrt();
        if n == Some(k) || (n.is_none() && r > escape) {
            return Some((r, k));
        }
        z = run_map(&ready.formula.maps[0], nums, &ready.literals, z, c).0;
    }
    let r = (z.x * z.x + z.y * z.y + z.z * z.z).sqrt();
    (n == Some(ready.iterations as usize) || (n.is_none() && r > escape)).then_some((r, ready.iterations as usize))
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot = a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>();
    let len = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    (dot / (len(a) * len(b))).clamp(-1.0, 1.0).acos().to_degrees()
}

/// A scene with an escape-time formula is shaded by its gradient, the potential's direction: through a scale, a
/// translation and a union, the interpreter's normal at a point near the bulb is ∇|zₙ| with the orbit's escape count
/// n held (central differences in f64, 10⁻⁶ of the distance apart), and beside the sphere the sphere's normal. The
/// f32 and packet instances give the same normal as f64 up to f32's rounding of the orbit.
#[test]
fn a_formula_scene_is_shaded_by_the_potential_gradient() {
    use fractal_dsl::eval::{Env, Evaluator, PacketEvaluator};
    use fractal_dsl::number::lanes::F32x8;
    let (scale, shift, centre) = (0.8, [0.1, -0.2, 0.05], [2.0, 0.0, 0.0]);
    let src = format!(
        "union({BULB}.scale({scale}).translate(vec3({}, {}, {})), sphere(0.3).translate(vec3({}, {}, {})))",
        shift[0], shift[1], shift[2], centre[0], centre[1], centre[2]
    );
    let scene = Interpreter::new(&parse_str(&src).unwrap()).unwrap();
    let (ready, nums) = ready(&formula_of(BULB));
    let ready = Ready { iterations: 8, ..ready };
    let normal = |p: [f64; 3]| {
        let n = Evaluator::<f64>::normal(&scene, v3(p[0], p[1], p[2]), &Env::still()).expect("shaded by its gradient");
        [n.x, n.y, n.z]
    };
    let mut rng = Rng(5);
    let (mut checked, mut worst, mut worst_f32) = (0, 0.0f64, Vec::new());
    while checked < 300 {
        let p = [0, 1, 2].map(|i| shift[i] + (rng.unit() * 2.4 - 1.2) * scale);
        let q = [0, 1, 2].map(|i| (p[i] - shift[i]) / scale);
        let d = d64(&scene, p);
        let Some((_, n)) = orbit_length(&ready, &nums, q, None, 2.0) else { continue };
        if n < 2 || !(1e-4..0.05).contains(&d) {
            continue;
        }
        let h = 1e-6 * d;
        let along = |axis: usize, sign: f64| {
            let mut at = q;
            at[axis] += sign * h;
            orbit_length(&ready, &nums, at, Some(n), 2.0).unwrap().0
        };
        let potential = [0, 1, 2].map(|axis| along(axis, 1.0) - along(axis, -1.0));
        worst = worst.max(angle(normal(p), potential));
        let n32 = Evaluator::<f32>::normal(&scene, v3(p[0] as f32, p[1] as f32, p[2] as f32), &Env::still()).unwrap();
        let lanes = |x: f64| F32x8::splat(x as f32);
        let n8 = scene.normal_x8(v3(lanes(p[0]), lanes(p[1]), lanes(p[2])), &Env::still()).unwrap();
        let n32 = [n32.x, n32.y, n32.z];
        assert_eq!([n8.x.0[3], n8.y.0[3], n8.z.0[3]], n32, "packets at {p:?}");
        worst_f32.push(angle(normal(p), n32.map(f64::from)));
        checked += 1;
    }
    assert!(worst < 0.01, "the normal is {worst}° from the potential's gradient");
    worst_f32.sort_by(f64::total_cmp);
    let median = worst_f32[worst_f32.len() / 2];
    eprintln!("f32 normal against f64: median {median:.4}°, max {:.3}°", worst_f32[worst_f32.len() - 1]);
    assert!(median < 0.05, "the f32 normal is {median}° from the f64 one (median)");
    for _ in 0..50 {
        let u = [0, 1, 2].map(|_| rng.unit() - 0.5);
        let len = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
        let p = [0, 1, 2].map(|i| centre[i] + u[i] / len * 0.31);
        // 10⁻⁴°: acos near 1 reads the last bits of the dot product.
        assert!(angle(normal(p), u) < 1e-4, "beside the sphere at {p:?}: {:?}", normal(p));
    }
}
