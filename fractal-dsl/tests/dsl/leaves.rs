//! The leaf functions are written once and run everywhere: over the 8-lane packet type [`F32x8`] they give, lane by
//! lane, exactly the scalar results; traced, each becomes one
//! named function whose lowered code — run here by a small evaluator of the lowered form — gives exactly the direct
//! f64 results, and whose WGSL validates with naga.

use fractal_dsl::formula::leaf::{ArgKind, LeafArg, LeafOut};
use fractal_dsl::formula::Leaf;
use fractal_dsl::lower::code::{Body, CmpOp, LogicOp, MathFn, Op, Stmt, Ty, Val};
use fractal_dsl::lower::trace::trace_leaf;
use fractal_dsl::number::lanes::{F32x8, LANES};
use fractal_dsl::number::math::{v3, Num, V3};

// ---- arguments for every leaf ---------------------------------------------------------------------------------------

/// The reference orbit perturbed patterns are given: that of c = −0.75 + 0.1i, near the neck of the set, so it
/// stays bounded for the 8 iterations the patterns run.
static REFERENCE_ORBIT: std::sync::LazyLock<Vec<[f32; 2]>> =
    std::sync::LazyLock::new(|| fractal_dsl::formula::mandelbrot::reference_orbit(-0.75, 0.1, 8));

/// Arguments for `leaf` at the point `p`, in any precision, from a table of plausible values per parameter name.
fn args<F: Num>(leaf: Leaf, p: V3<F>, f: impl Fn(f64) -> F) -> Vec<LeafArg<'static, F>> {
    let vector = |v: [f64; 3]| LeafArg::V3(v3(f(v[0]), f(v[1]), f(v[2])));
    leaf.params()
        .iter()
        .map(|&(name, kind)| match (name, kind) {
            ("p", ArgKind::V3) => LeafArg::V3(p),
            (_, ArgKind::Orbit) => LeafArg::Orbit(&REFERENCE_ORBIT),
            // A perturbed pattern's offset from the reference: small, and moving with the point.
            ("dcx", _) => LeafArg::F(p.x * f(1e-3)),
            ("dcy", _) => LeafArg::F(p.y * f(1e-3)),
            (_, ArgKind::Count) => LeafArg::Count(F::count(if leaf == Leaf::DeMenger { 4 } else { 8 })),
            ("a", ArgKind::V3) => vector([0.0, -0.5, 0.1]),
            ("b", ArgKind::V3) => vector([0.5, 0.6, 0.7]),
            ("n", ArgKind::V3) => vector([0.0, 0.8, 0.6]),
            (_, ArgKind::V3) => vector([1.0, 0.5, 0.25]),
            ("power", _) => LeafArg::F(f(7.0)),
            ("bailout", _) => LeafArg::F(f(if leaf == Leaf::DeJulia { 4.0 } else { 2.0 })),
            ("cx", _) => LeafArg::F(f(-0.2)),
            ("cy", _) => LeafArg::F(f(0.6)),
            ("cz", _) => LeafArg::F(f(0.2)),
            ("cw", _) => LeafArg::F(f(0.0)),
            ("scale", _) => LeafArg::F(f(-1.5)),
            ("min_radius", _) => LeafArg::F(f(0.5)),
            ("fold_limit", _) => LeafArg::F(f(1.0)),
            ("k", _) => LeafArg::F(f(0.3)),
            ("h", _) => LeafArg::F(f(0.8)),
            ("r1", _) | ("major", _) => LeafArg::F(f(0.9)),
            ("r2", _) | ("minor", _) => LeafArg::F(f(0.25)),
            // The smooth blends' two distances: the point's x and y.
            ("a", _) => LeafArg::F(p.x),
            ("b", _) => LeafArg::F(p.y),
            (_, _) => LeafArg::F(f(0.7)),
        })
        .collect()
}

fn outputs<F: Copy>(out: LeafOut<F>) -> Vec<F> {
    match out {
        LeafOut::F(d) => vec![d],
        LeafOut::Pair([d, t]) => vec![d, t],
    }
}

/// Points near and on the shapes, the origin and the axes included (where the estimators have singular sets).
fn points() -> Vec<[f64; 3]> {
    let mut pts = vec![[0.0; 3], [0.0, 0.0, 0.7], [0.0, 0.9, 0.0], [1e-7, 0.0, 0.5], [0.5, 0.5, 0.5]];
    let mut rng = crate::common::Rng(0x9e37_79b9_7f4a_7c15);
    pts.extend((0..200).map(|_| [0, 1, 2].map(|_| (rng.unit() * 2.0 - 1.0) * 1.6)));
    pts
}

#[test]
fn every_leaf_gives_the_scalar_results_lane_by_lane() {
    for &leaf in Leaf::ALL {
        for chunk in points().chunks(LANES) {
            let mut lanes = [[0.0f32; 3]; LANES];
            for (i, p) in chunk.iter().enumerate() {
                lanes[i] = p.map(|v| v as f32);
            }
            let packet =
                v3(F32x8::from_fn(|i| lanes[i][0]), F32x8::from_fn(|i| lanes[i][1]), F32x8::from_fn(|i| lanes[i][2]));
            let got = outputs(leaf.eval::<F32x8>(&args(leaf, packet, F32x8::lit)));
            for (lane, p) in lanes.iter().enumerate().take(chunk.len()) {
                let want = outputs(leaf.eval::<f32>(&args(leaf, v3(p[0], p[1], p[2]), |v| v as f32)));
                for (g, w) in got.iter().zip(&want) {
                    assert!(
                        g.0[lane].to_bits() == w.to_bits() || (g.0[lane].is_nan() && w.is_nan()),
                        "{}: lane {lane} at {p:?} gives {} where the scalar gives {w}",
                        leaf.name(),
                        g.0[lane]
                    );
                }
            }
        }
    }
}

// ---- an evaluator of lowered code, to check tracing is faithful ---------------------------------------------------

#[derive(Clone, Copy, Debug)]
enum V {
    F(f64),
    V3([f64; 3]),
    Pair([f64; 2]),
    B(bool),
    I(u32),
}

impl V {
    fn f(self) -> f64 {
        match self {
            V::F(v) => v,
            other => panic!("expected a number, got {other:?}"),
        }
    }
    fn b(self) -> bool {
        match self {
            V::B(v) => v,
            other => panic!("expected a bool, got {other:?}"),
        }
    }
}

struct Run<'a> {
    body: &'a Body,
    args: &'a [(&'static str, V)],
    vals: Vec<Option<V>>,
}

enum Flow {
    Next,
    Break,
}

impl Run<'_> {
    fn get(&mut self, v: Val) -> V {
        match self.body.op(v) {
            Some(op) if fractal_dsl::lower::code::is_inline(op) => self.eval(op),
            _ => self.vals[v.0 as usize].expect("values are defined before use"),
        }
    }
    fn eval(&mut self, op: &Op) -> V {
        match op {
            Op::Lit(b) => V::F(f64::from_bits(b.0) as f32 as f64),
            Op::BoolLit(b) => V::B(*b),
            Op::IntLit(n) => V::I(*n),
            Op::Time | Op::Param(_) => panic!("leaf functions read no frame"),
            Op::Arg(name) => self.args.iter().find(|(n, _)| n == name).expect("every argument is given").1,
            Op::Orbit => panic!("leaf functions pass no orbit on"),
            Op::OrbitEntry(i) => {
                let last = REFERENCE_ORBIT.len() - 1;
                let e = REFERENCE_ORBIT[(self.get(*i).f() as usize).min(last)];
                V::Pair([e[0] as f64, e[1] as f64])
            }
            Op::OrbitLast => V::F((REFERENCE_ORBIT.len() - 1) as f64),
            Op::MakeV3(x, y, z) => V::V3([self.get(*x).f(), self.get(*y).f(), self.get(*z).f()]),
            Op::MakePair(d, t) => V::Pair([self.get(*d).f(), self.get(*t).f()]),
            Op::Comp(v, i) => match self.get(*v) {
                V::V3(c) => V::F(c[*i as usize]),
                V::Pair(c) => V::F(c[*i as usize]),
                other => panic!("no components in {other:?}"),
            },
            Op::Neg(v) => V::F(-self.get(*v).f()),
            Op::Bin(op, a, b) => V::F(op.apply(self.get(*a).f(), self.get(*b).f())),
            Op::Math(f, args) => {
                let a: Vec<f64> = args.iter().map(|v| self.get(*v).f()).collect();
                V::F(match f {
                    MathFn::Ln => a[0].ln(),
                    other => other.fold(&a),
                })
            }
            Op::Call(..) => panic!("leaf functions call no other leaf"),
            Op::Scene(..) | Op::Field(..) | Op::Frame(_) => panic!("leaf functions call no scene function"),
            Op::Cmp(op, a, b) => {
                let (a, b) = (self.get(*a).f(), self.get(*b).f());
                V::B(match op {
                    CmpOp::Lt => a < b,
                    CmpOp::Le => a <= b,
                })
            }
            Op::Logic(op, a, b) => {
                let (a, b) = (self.get(*a).b(), self.get(*b).b());
                V::B(match op {
                    LogicOp::And => a && b,
                    LogicOp::Or => a || b,
                })
            }
            Op::Not(v) => V::B(!self.get(*v).b()),
            Op::Select(c, a, b) => {
                if self.get(*c).b() {
                    self.get(*a)
                } else {
                    self.get(*b)
                }
            }
            Op::Load(var) => self.vals[var.0 as usize].expect("variables are declared before use"),
        }
    }
    fn stmts(&mut self, stmts: &[Stmt]) -> Flow {
        for s in stmts {
            match s {
                Stmt::Let { val, op, .. } => {
                    let v = self.eval(op);
                    self.vals[val.0 as usize] = Some(v);
                }
                Stmt::Var { var, init, .. } => {
                    let v = self.get(*init);
                    self.vals[var.0 as usize] = Some(v);
                }
                Stmt::Assign { var, value } => {
                    let v = self.get(*value);
                    self.vals[var.0 as usize] = Some(v);
                }
                Stmt::If { cond, body } => {
                    if self.get(*cond).b() {
                        if let Flow::Break = self.stmts(body) {
                            return Flow::Break;
                        }
                    }
                }
                Stmt::Loop { count, body } => {
                    let V::I(n) = self.get(*count) else { panic!("a loop count is an integer") };
                    for _ in 0..n {
                        if let Flow::Break = self.stmts(body) {
                            break;
                        }
                    }
                }
                Stmt::BreakIf { cond } => {
                    if self.get(*cond).b() {
                        return Flow::Break;
                    }
                }
            }
        }
        Flow::Next
    }
}

#[test]
fn every_leaf_traced_computes_what_the_formula_computes() {
    for &leaf in Leaf::ALL {
        let function = trace_leaf(leaf);
        assert_eq!(function.name(), leaf.name());
        for p in points() {
            // Arguments as the kernel would get them: f32 values, evaluated here in f64 on both sides.
            let direct_args = args(leaf, v3(p[0], p[1], p[2]).map(|v| v as f32 as f64), |v| v as f32 as f64);
            let want = outputs(leaf.eval::<f64>(&direct_args));
            let given: Vec<(&'static str, V)> = leaf
                .params()
                .iter()
                .zip(&direct_args)
                .map(|(&(name, _), a)| {
                    (
                        name,
                        match a {
                            LeafArg::F(x) => V::F(*x),
                            LeafArg::V3(v) => V::V3([v.x, v.y, v.z]),
                            LeafArg::Count(n) => V::I(*n),
                            // The body reads the orbit through `Op::OrbitEntry`, from the same table.
                            LeafArg::Orbit(_) => V::I(0),
                        },
                    )
                })
                .collect();
            let mut run = Run { body: &function.body, args: &given, vals: vec![None; 1 << 16] };
            run.stmts(&function.body.stmts);
            let got = match run.get(function.result) {
                V::F(d) => vec![d],
                V::Pair([d, t]) => vec![d, t],
                other => panic!("{} returns {other:?}", leaf.name()),
            };
            assert_eq!(function.returns, if want.len() == 1 { Ty::F } else { Ty::Pair });
            for (g, w) in got.iter().zip(&want) {
                // The traced constants are rounded to f32 as the kernels' are; the rest is the same arithmetic.
                let tolerance = 1e-6 * w.abs().max(1.0);
                assert!(
                    (g - w).abs() <= tolerance || (g.is_nan() && w.is_nan()),
                    "{} at {p:?}: traced {g}, direct {w}",
                    leaf.name()
                );
            }
        }
    }
}

#[test]
fn every_traced_leaf_validates_as_wgsl_and_guard_constants_arrive_as_literals() {
    let functions = fractal_dsl::back::wgsl::functions(&Leaf::ALL.iter().map(|&l| trace_leaf(l)).collect::<Vec<_>>());
    // The perturbed Mandelbrot pattern reads the reference orbit from the frame uniform, which a kernel declares.
    let frame = "struct Frame {\n    reference: vec4<f32>,\n    orbit: array<vec4<f32>, 5>,\n}\n\n\
                 @group(0) @binding(1) var<uniform> frame: Frame;\n\n";
    let module = format!("{frame}{functions}");
    let parsed = naga::front::wgsl::parse_str(&module).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&module)));
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
        .validate(&parsed)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&module)));
    for leaf in Leaf::ALL {
        assert!(module.contains(&format!("fn {}(", leaf.name())), "{} missing", leaf.name());
    }
    // DR_MAX and TINY are written once in formula/common.rs and reach the kernel as literals.
    assert!(module.contains("1e17"), "DR_MAX is not in the traced estimators");
    assert!(module.contains("1e-30"), "TINY is not in the traced functions");
}
