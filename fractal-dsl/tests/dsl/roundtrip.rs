//! Round trip: a scene written by the printer and read back by the parser is the same scene, and the printed text is
//! canonical (printing the parsed scene gives the same text). Random scenes are built with the builder API; those
//! that break a validation rule must be refused by the parser too.

use fractal_dsl::builder::*;
use fractal_dsl::ir::arg::{ArgDecl, ArgShape, Rule};
use fractal_dsl::ir::op::Operands;
use fractal_dsl::ir::*;
use fractal_dsl::parse::parse_str;
use fractal_dsl::print::to_source;
use fractal_dsl::validate::validate;
use fractal_dsl::vocab::ops::decl::OPS;
use fractal_dsl::vocab::prims::decl::PRIMS;
use glam::DVec3;
use proptest::prelude::*;

fn round_trip(s: &Scene) -> Scene {
    let src = to_source(s);
    parse_str(&src).unwrap_or_else(|e| panic!("{src}\n{e}"))
}

#[test]
fn canonical_text_of_a_small_scene() {
    let s = scene(union(
        mandelbulb(8).iterations(10),
        sphere(1.0).translate(vec3(1.5, 0.0, -0.5)).material(rgb(0.9, 0.2, 0.1).specular(0.5)),
    ))
    .light(directional(vec3(1.0, 1.0, -1.0), rgb(1.0, 1.0, 1.0)).intensity(2.0))
    .max_steps(200)
    .soft_shadows(16.0);
    let expected = "\
scene(
    union(
        mandelbulb(8.0).iterations(10),
        sphere(1.0).translate(vec3(1.5, 0.0, -0.5)).material(rgb(0.9, 0.2, 0.1).specular(0.5)),
    ),
)
    .light(directional(vec3(1.0, 1.0, -1.0), rgb(1.0, 1.0, 1.0)).intensity(2.0))
    .max_steps(200)
    .soft_shadows(16.0)
";
    assert_eq!(to_source(&s), expected);
    assert_eq!(round_trip(&s), s);
    assert_eq!(to_source(&scene(sphere(1.0))), "scene(sphere(1.0))\n");
}

#[test]
fn numbers_keep_their_exact_value_and_form() {
    let values = [
        -1.0,
        -0.0,
        0.1 + 0.2,
        1e-300,
        -5e-324,
        f64::MAX,
        f64::MIN_POSITIVE,
        1.5f32 as f64,
        0.1f32 as f64,
        1.0 / 3.0,
        1e21,
    ];
    for v in values {
        let forms = [
            Expr::Lit(v),
            -Expr::Lit(v),
            -(-Expr::Lit(v)),
            Expr::Lit(v) - Expr::Lit(v),
            Expr::Lit(v) * -Expr::Lit(v),
            (time() - Expr::Lit(v)) * (time() + Expr::Lit(v)),
            time() - (time() - Expr::Lit(v)),
            time() / (time() * Expr::Lit(v)),
            -(time() + Expr::Lit(v)),
        ];
        for e in forms {
            let s = scene(sphere(1.0).translate(vec3(e.clone(), sin(e.clone()), clamp(e, -time(), time()))));
            match validate(&s) {
                Ok(()) => assert_eq!(round_trip(&s), s, "{}", to_source(&s)),
                // f64::MAX · −f64::MAX is −inf: refused as text too.
                Err(_) => assert!(parse_str(&to_source(&s)).is_err(), "{}", to_source(&s)),
            }
        }
    }
}

#[test]
fn normalised_plane_normals_and_rotation_axes_read_back_exactly() {
    // The builder normalises both; normalising a unit vector again can round differently, so the printer writes a
    // neighbour that normalises to exactly the stored vector.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for _ in 0..5000 {
        let v = DVec3::new(next(), next(), next());
        let s = scene(union(plane(vec3(v.x, v.y, v.z), 0.5), sphere(1.0).rotate(v, 0.3)));
        if validate(&s).is_ok() {
            assert_eq!(round_trip(&s), s, "{}", to_source(&s));
        }
    }
}

#[test]
fn invalid_values_still_print_as_text_that_parses_to_an_error() {
    for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let s = scene(sphere(v).translate(vec3(v, 0.0, 0.0))).max_distance(v);
        let err = parse_str(&to_source(&s)).unwrap_err();
        assert!(!err.message.contains("internal error"), "{err}");
    }
}

// ---- random scenes --------------------------------------------------------------------------------------------------

fn finite() -> impl Strategy<Value = f64> {
    prop_oneof![
        6 => -10.0..10.0f64,
        1 => Just(0.0),
        1 => Just(-0.0),
        1 => any::<f64>().prop_filter("finite", |v| v.is_finite()),
    ]
}

/// Parameters declared consistently across a scene, plus two that break a rule.
fn param_pool() -> impl Strategy<Value = Expr> {
    prop_oneof![
        4 => Just(param("a", 0.0, -1.0..1.0)),
        4 => Just(param("r", 1.0, 0.5..2.0)),
        2 => Just(param("power", 8.0, 2.0..16.0)),
        1 => Just(param("a", 0.5, -1.0..1.0)),
        1 => Just(param("bad", 5.0, 0.0..1.0)),
    ]
}

/// An expression where any finite value is allowed.
fn free() -> impl Strategy<Value = Expr> {
    let leaf = prop_oneof![4 => finite().prop_map(Expr::Lit), 1 => Just(time()), 1 => param_pool()];
    leaf.prop_recursive(3, 12, 3, |inner| {
        prop_oneof![
            inner.clone().prop_map(|e| -e),
            (inner.clone(), inner.clone(), 0..4usize).prop_map(|(a, b, op)| match op {
                0 => a + b,
                1 => a - b,
                2 => a * b,
                _ => a / b,
            }),
            (prop::sample::select(Func::ALL.to_vec()), prop::collection::vec(inner, Func::MAX_ARITY)).prop_map(
                |(f, mut args)| {
                    args.truncate(f.arity());
                    if f.takes_count() {
                        // An octave count is a whole-number literal in source.
                        *args.last_mut().expect("fbm takes arguments") = Expr::Lit(3.0);
                    }
                    Expr::Call(f, args)
                }
            ),
        ]
    })
}

/// A value for a slot that must be > 0: mostly valid, sometimes not.
fn positive() -> impl Strategy<Value = Expr> {
    prop_oneof![
        8 => (0.01..10.0f64).prop_map(Expr::Lit),
        2 => Just(param("r", 1.0, 0.5..2.0)),
        1 => Just(Expr::Lit(1.0) + time()),
        1 => Just(0.5 + 0.25 * sin(time())),
        1 => Just(Expr::Lit(-1.0)),
        1 => free(),
    ]
}

fn non_negative() -> impl Strategy<Value = Expr> {
    prop_oneof![6 => positive(), 1 => Just(Expr::Lit(0.0))]
}

fn free_vec3() -> impl Strategy<Value = Vec3Expr> {
    (free(), free(), free()).prop_map(|(x, y, z)| vec3(x, y, z))
}

fn positive_vec3() -> impl Strategy<Value = Vec3Expr> {
    (positive(), positive(), positive()).prop_map(|(x, y, z)| vec3(x, y, z))
}

fn non_negative_vec3() -> impl Strategy<Value = Vec3Expr> {
    (non_negative(), non_negative(), non_negative()).prop_map(|(x, y, z)| vec3(x, y, z))
}

fn color() -> impl Strategy<Value = Color> {
    prop_oneof![
        4 => (0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(r, g, b)| rgb(r, g, b)),
        1 => free_vec3().prop_map(Color),
    ]
}

fn material() -> impl Strategy<Value = Material> {
    let terms = (
        prop::option::of(non_negative()),
        prop::option::of(non_negative()),
        prop::option::of(non_negative()),
        prop::option::of(non_negative()),
    );
    let base = prop_oneof![
        3 => color().prop_map(Material::from),
        1 => (color(), color()).prop_map(|(a, b)| orbit_trap(a, b)),
        1 => (color(), non_negative(), non_negative(), non_negative(), positive())
            .prop_map(|(c, a, d, s, n)| phong(c, a, d, s, n)),
    ];
    (base, terms).prop_map(|(mut m, (a, d, s, n))| {
        if let Some(a) = a {
            m = m.ambient(a);
        }
        if let Some(d) = d {
            m = m.diffuse(d);
        }
        if let Some(s) = s {
            m = m.specular(s);
        }
        if let Some(n) = n {
            m = m.shininess(n);
        }
        m
    })
}

/// A value for a declared argument, drawn by its shape and rule: mostly valid, sometimes not, sometimes animated.
fn arg_value(a: &ArgDecl) -> BoxedStrategy<ArgValue> {
    let constant = |lo: f64, hi: f64| (lo..hi, lo..hi, lo..hi).prop_map(|(x, y, z)| vec3(x, y, z));
    match (a.shape, a.rule) {
        (ArgShape::Number, Rule::Positive) => positive().prop_map(ArgValue::Num).boxed(),
        (ArgShape::Number, Rule::NonNegative | Rule::RoundingOf(_)) => non_negative().prop_map(ArgValue::Num).boxed(),
        (ArgShape::Number, _) => free().prop_map(ArgValue::Num).boxed(),
        (ArgShape::Counts, _) => {
            [0..4u32, 0..4u32, 0..4u32].prop_map(|n| ArgValue::Vec3(n.map(f64::from).into())).boxed()
        }
        (_, Rule::Direction) => constant(-1.0, 1.0).prop_map(ArgValue::Vec3).boxed(),
        (_, Rule::Positive) => positive_vec3().prop_map(ArgValue::Vec3).boxed(),
        (_, Rule::NonNegative | Rule::Period) => non_negative_vec3().prop_map(ArgValue::Vec3).boxed(),
        (_, _) => free_vec3().prop_map(ArgValue::Vec3).boxed(),
    }
}

fn args(decls: &[ArgDecl]) -> Vec<BoxedStrategy<ArgValue>> {
    decls.iter().map(arg_value).collect()
}

/// Every declared primitive (`fractal_dsl::vocab::prims`): a new one is drawn here without being listed.
fn primitive() -> impl Strategy<Value = Node> {
    let kinds: Vec<PrimKind> = PRIMS.iter().copied().map(PrimKind).collect();
    prop::sample::select(kinds).prop_flat_map(|k| args(k.0.args).prop_map(move |a| k.0.node(a)))
}

/// Every declared operator (`fractal_dsl::vocab::ops`) over shapes drawn from `inner`.
fn operator(inner: BoxedStrategy<Node>) -> impl Strategy<Value = Node> {
    let kinds: Vec<OpKind> = OPS.iter().copied().map(OpKind).collect();
    prop::sample::select(kinds).prop_flat_map(move |OpKind(d)| {
        let shapes = match d.operands {
            Operands::Many => prop::collection::vec(inner.clone(), 1..4),
            Operands::Two => prop::collection::vec(inner.clone(), 2),
            Operands::Receiver => prop::collection::vec(inner.clone(), 1),
        };
        (shapes, args(d.args)).prop_map(move |(s, a)| d.node(s, a))
    })
}

fn fractal() -> impl Strategy<Value = Fractal> {
    let power = prop_oneof![
        4 => (2.0..64.0f64).prop_map(Expr::Lit),
        2 => Just(Expr::Lit(8.0)),
        1 => Just(param("power", 8.0, 2.0..16.0)),
        1 => Just(Expr::Lit(1.5)),
    ];
    let iterations = prop::option::of(prop_oneof![9 => 1..=64u32, 1 => Just(0u32)]);
    let scale = prop_oneof![(1.05..8.0f64), (-8.0..-1.05f64), Just(1.0)];
    prop_oneof![
        (power, iterations.clone(), prop::option::of(positive())).prop_map(|(p, n, b)| with(
            mandelbulb(p),
            n,
            b,
            None,
            None
        )),
        (0..=9u32).prop_map(menger),
        (0..=25u32).prop_map(sierpinski_tetrahedron),
        ((free(), free(), free(), free()), iterations.clone(), prop::option::of(positive()))
            .prop_map(|((x, y, z, w), n, b)| with(julia(vec4(x, y, z, w)), n, b, None, None)),
        (scale, iterations, prop::option::of((0.01..0.99f64).prop_map(Expr::Lit)), prop::option::of(positive()))
            .prop_map(|(s, n, r, f)| with(mandelbox(s), n, None, r, f)),
    ]
}

fn with(
    mut f: Fractal,
    n: Option<u32>,
    bailout: Option<Expr>,
    min_radius: Option<Expr>,
    fold: Option<Expr>,
) -> Fractal {
    if let Some(n) = n {
        f = f.iterations(n);
    }
    if let Some(b) = bailout {
        f = f.bailout(b);
    }
    if let Some(r) = min_radius {
        f = f.min_radius(r);
    }
    if let Some(l) = fold {
        f = f.fold_limit(l);
    }
    f
}

fn shape() -> impl Strategy<Value = Node> {
    let stepped = (fractal(), prop::option::of(0.1..2.0f64)).prop_map(|(f, k)| {
        Node::from(match k {
            Some(k) => f.step_factor(k),
            None => f,
        })
    });
    let leaf = prop_oneof![3 => primitive(), 1 => stepped];
    leaf.prop_recursive(5, 48, 4, |inner| {
        prop_oneof![
            6 => operator(inner.clone().boxed()),
            1 => (inner, material()).prop_map(|(n, m)| n.material(m)),
        ]
    })
}

fn light() -> impl Strategy<Value = Light> {
    let kind = prop_oneof![
        (free_vec3(), color()).prop_map(|(d, c)| directional(d, c)),
        (free_vec3(), color()).prop_map(|(p, c)| point_light(p, c)),
    ];
    (kind, prop::option::of(non_negative())).prop_map(|(l, i)| match i {
        Some(i) => l.intensity(i),
        None => l,
    })
}

fn point() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn camera_strategy() -> impl Strategy<Value = Camera> {
    let fov = prop::option::of(prop_oneof![4 => 1.0..179.0f64, 1 => Just(180.0)]);
    let placement = prop_oneof![
        1 => Just(Camera::default()),
        2 => (free_vec3(), free_vec3()).prop_map(|(p, t)| camera(p, t)),
        2 => (prop::collection::vec((0.01..5.0f64, point(), point()), 1..5), any::<bool>(), any::<bool>()).prop_map(
            |(steps, linear, looped)| {
                let mut time = 0.0;
                let keys = steps.into_iter().map(|(dt, p, t)| {
                    time += dt;
                    key(time, p, t)
                });
                let mut c = camera_path(keys.collect::<Vec<_>>());
                if linear {
                    c = c.linear();
                }
                if looped {
                    c = c.looped();
                }
                c
            }
        ),
    ];
    (placement, fov).prop_map(|(c, f)| match f {
        Some(f) => c.fov(f),
        None => c,
    })
}

fn rgb_strategy() -> impl Strategy<Value = Color> {
    (0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(r, g, b)| rgb(r, g, b))
}

fn scene_strategy() -> impl Strategy<Value = Scene> {
    let settings = (
        prop::option::of(prop_oneof![9 => 1..=10_000u32, 1 => Just(0u32)]),
        prop::option::of(0.1..100.0f64),
        prop::option::of((any::<bool>(), 1e-5..2.0f64)),
        0..4usize,
        prop::option::of(prop_oneof![9 => 0.01..10.0f64, 1 => Just(0.0)]),
        prop::option::of(rgb_strategy()),
        prop::option::of((rgb_strategy(), 0.001..1.0f64)),
        prop::option::of(rgb_strategy()),
        prop::option::of(0.5..3.0f64),
        prop::option::of(1.0..=2.0f64),
        prop::option::of(0.05..4.0f64),
        prop::bool::weighted(0.2),
    );
    (shape(), prop::collection::vec(light(), 0..3), camera_strategy(), settings).prop_map(
        |(root, lights, cam, (steps, dist, eps, shadows, ao, glow, fog, bg, gamma, relax, normal, membership))| {
            let mut s = scene(root).camera(cam);
            for l in lights {
                s = s.light(l);
            }
            if let Some(n) = steps {
                s = s.max_steps(n);
            }
            if let Some(d) = dist {
                s = s.max_distance(d);
            }
            if let Some((pixel, e)) = eps {
                s = if pixel { s.pixel_epsilon(e) } else { s.epsilon(e) };
            }
            if let Some(w) = relax {
                s = s.over_relaxation(w);
            }
            if let Some(k) = normal {
                s = s.normal_pixel_epsilon(k);
            }
            if membership {
                s = s.membership_hits();
            }
            s = match shadows {
                0 => s,
                1 => s.no_shadows(),
                2 => s.hard_shadows(),
                _ => s.soft_shadows(8.0),
            };
            if let Some(a) = ao {
                s = s.ambient_occlusion(a);
            }
            if let Some(c) = glow {
                s = s.glow(c);
            }
            if let Some((c, d)) = fog {
                s = s.fog(c, d);
            }
            if let Some(c) = bg {
                s = s.background(c);
            }
            if let Some(g) = gamma {
                s = s.gamma(g);
            }
            s
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// Valid scenes read back equal (and print the same text again); invalid ones are refused by the parser too.
    #[test]
    fn printed_scenes_read_back_equal(s in scene_strategy()) {
        let src = to_source(&s);
        let parsed = parse_str(&src);
        match validate(&s) {
            Ok(()) => {
                let parsed = parsed.map_err(|e| TestCaseError::fail(format!("{src}\n{e}")))?;
                prop_assert_eq!(&parsed, &s, "{}", src);
                prop_assert_eq!(to_source(&parsed), src);
            }
            Err(errors) => {
                prop_assert!(parsed.is_err(), "{}\nvalidation: {:?}\nbut the parser accepted it", src, errors);
                let message = parsed.unwrap_err().message;
                let known = errors.iter().any(|e| e.message == message);
                prop_assert!(known, "{}\nparser: {}\nvalidation: {:?}", src, message, errors);
            }
        }
    }
}
