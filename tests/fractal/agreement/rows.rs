//! The agreement table: one row per vocabulary item (every primitive, fractal, CSG operation, transform, domain
//! operation, material rule and expression function), and the hard cases of evaluation. Each row is a `scene!`
//! invocation, so the native evaluator and both kernels exist for it; adding a vocabulary item is one row here.

use fractal::dsl::CompiledScene;

use super::harness::{Family, Row};

/// A row from the scene written once: `row!("name", Family, { scene tokens })`, then chained settings.
macro_rules! row {
    ($name:literal, $family:expr, { $($scene:tt)* }) => {
        Row::new($name, $family, {
            static SCENE: CompiledScene = fractal::scene! { $($scene)* };
            &SCENE
        })
    };
}

/// A 9 × 9 grid of points on the plane x = `x`, spaced 0.25.
fn grid_on_plane_x(x: f32) -> Vec<[f32; 3]> {
    (-4..=4).flat_map(|i| (-4..=4).map(move |j| [x, 0.25 * i as f32, 0.25 * j as f32])).collect()
}

/// Every vocabulary item.
pub fn vocabulary() -> Vec<Row> {
    use Family::*;
    vec![
        // ---- primitives
        row!("sphere", Exact, { sphere(1.0) }),
        row!("box3", Exact, { box3(vec3(1.0, 0.5, 0.75)) }),
        row!("round_box", Exact, { round_box(vec3(1.0, 0.5, 0.75), 0.25) }),
        row!("torus", Exact, { torus(1.0, 0.3) }),
        row!("capsule", Exact, { capsule(vec3(-0.6, -0.4, 0.1), vec3(0.5, 0.7, -0.2), 0.3) }),
        row!("cylinder", Exact, { cylinder(0.6, 0.9) }),
        row!("cone", Exact, { cone(0.8, 0.6, 0.2) }),
        row!("plane", Exact, { plane(vec3(0.3, 1.0, -0.2), 0.4) }),
        row!("octahedron", Exact, { octahedron(1.2) }),
        row!("hex_prism", Exact, { hex_prism(0.8, 0.5) }),
        row!("ellipsoid", Exact, { ellipsoid(vec3(1.0, 0.5, 0.75)) }),
        // ---- fractals
        row!("mandelbulb(8) trig-free", Mandelbulb, { mandelbulb(8) }).within(1.5),
        row!("mandelbulb(7.5) trig", Mandelbulb, { mandelbulb(7.5) }).within(1.5),
        row!("mandelbulb(3) stretched", Mandelbulb, { mandelbulb(3.0) }).within(1.5),
        row!("mandelbulb(2 + sin t) stretched, animated", Mandelbulb, { mandelbulb(2.5 + 0.5 * sin(t)) })
            .within(1.5)
            .at_time(0.75),
        row!("mandelbulb(8 + sin t) animated", Mandelbulb, { mandelbulb(8.0 + sin(t)) }).within(1.5).at_time(0.75),
        row!("mandelbulb iterations, bailout", Mandelbulb, { mandelbulb(8).iterations(5).bailout(4.0) }).within(1.5),
        row!("menger", Menger, { menger(4) }).within(1.5),
        row!("sierpinski_tetrahedron", Sierpinski, { sierpinski_tetrahedron(8) }).within(1.5),
        row!("julia", Julia, { julia(vec4(-0.2, 0.6, 0.2, 0.0)) }).within(1.5),
        row!("julia iterations, bailout", Julia, { julia(vec4(-0.8, 0.156, 0.0, 0.1)).iterations(8).bailout(3.0) })
            .within(1.5),
        row!("mandelbox", Mandelbox, { mandelbox(2.0) }).within(6.5),
        row!("mandelbox min_radius, fold_limit, negative scale", Mandelbox, {
            mandelbox(-1.5).iterations(10).min_radius(0.4).fold_limit(1.1)
        })
        .within(4.0),
        row!("juliabulb", Juliabulb, { juliabulb(vec3(0.4, 0.5, -0.1)) }).within(1.5),
        row!("juliabulb power, iterations, bailout, animated", Juliabulb, {
            juliabulb(vec3(-0.6, 0.2, 0.3 * sin(t))).power(5.0 + sin(t)).iterations(6).bailout(3.0)
        })
        .within(1.5)
        .at_time(0.5),
        row!("octahedral_kifs", Kifs, { octahedral_kifs(2.0) }).within(1.2),
        row!("icosahedral_kifs angle, iterations", Kifs, { icosahedral_kifs(2.618).angle(0.3).iterations(8) })
            .within(1.2),
        // ---- formulas written in the scene language (the estimate's derivative derived: `formula::user`). The bulb
        // formulas are compared off their pole axis: there sin(8θ) at θ = π is f32's rounding of 8π in f32 and 1e-15
        // in f64, and the formula as written (unlike the built-in leaf, `polar_trig_from_the_nearer_pole`) leaves
        // the axis in one precision only. The built-in Mandelbulb rows hold the pole-axis cases.
        row!("escape_time bulb (trig)", Mandelbulb, {
            escape_time(|z, c| {
                let r = length(z);
                let theta = acos(z.z / r) * 8.0;
                let phi = atan2(z.y, z.x) * 8.0;
                pow(r, 8.0) * vec3(sin(theta) * cos(phi), sin(phi) * sin(theta), cos(theta)) + c
            })
            .iterations(8)
        })
        .around([0.031, 0.047, 0.013], 1.2),
        row!("escape_time quaternion julia, param, time, if", Julia, {
            escape_time(|z, c| {
                let q = qsqr(vec4(z, 0.0)) + vec4(-0.2, 0.6 + 0.1 * sin(t), 0.2, 0.0);
                if q.w < param("w", 1.0, 0.0..2.0) {
                    q.xyz
                } else {
                    q.yxz
                }
            })
            .iterations(10)
            .bailout(4.0)
        })
        .within(1.5)
        .at_time(0.5),
        row!("fold mandelbox (derived derivative)", Mandelbox, {
            fold(|z, c| sphere_fold(box_fold(z, 1.0), 0.5, 1.0) * 2.0 + c).iterations(10).bailout(6.0)
        })
        .within(6.5),
        row!("fold kifs (own scale)", Kifs, {
            fold(|z| {
                let a = abs(z);
                let a = if a.x < a.y { a.yxz } else { a };
                let a = if a.x < a.z { a.zyx } else { a };
                let a = if a.y < a.z { a.xzy } else { a };
                (a * 2.0 - vec3(1.0, 0.0, 0.0), 2.0)
            })
            .iterations(10)
        })
        .within(1.2),
        row!("hybrid bulb and box fold", Hybrid, {
            hybrid(
                |z, c| {
                    let r = length(z);
                    let theta = atan2(length(z.xy), z.z) * 4.0;
                    let phi = atan2(z.y, z.x) * 4.0;
                    pow(r, 4.0) * vec3(sin(theta) * cos(phi), sin(phi) * sin(theta), cos(theta)) + c
                },
                |z, c| box_fold(z, 1.0) * 1.5 + c,
            )
            .iterations(8)
        })
        .around([0.031, 0.047, 0.013], 1.2),
        // ---- CSG (each child its own material, so the material rules are compared too)
        row!("union", Exact, {
            union(
                sphere(0.7).material(rgb(0.9, 0.2, 0.1)),
                box3(vec3(0.5, 0.4, 0.6)).translate(vec3(0.8, 0.3, 0.0)).material(rgb(0.1, 0.8, 0.3)),
                torus(0.8, 0.2).translate(vec3(-0.5, -0.4, 0.2)).material(rgb(0.2, 0.3, 0.9)),
            )
        }),
        row!("intersect", Exact, {
            intersect(
                sphere(1.0).material(rgb(0.9, 0.2, 0.1)),
                box3(vec3(0.8, 0.8, 0.8)).material(rgb(0.1, 0.8, 0.3)),
                cylinder(0.85, 0.7).material(rgb(0.2, 0.3, 0.9)),
            )
        }),
        row!("subtract", Exact, {
            subtract(box3(vec3(0.8, 0.8, 0.8)).material(rgb(0.9, 0.2, 0.1)), sphere(0.95).material(rgb(0.1, 0.8, 0.3)))
        }),
        row!("smooth_union", Exact, {
            smooth_union(
                sphere(0.6).material(rgb(0.9, 0.2, 0.1)),
                box3(vec3(0.45, 0.45, 0.45)).translate(vec3(0.6, 0.25, 0.0)).material(rgb(0.1, 0.8, 0.3)),
                0.3,
            )
        })
        .blends(0.3, 0.8),
        row!("smooth_intersect", Exact, {
            smooth_intersect(
                sphere(1.0).material(rgb(0.9, 0.2, 0.1)),
                box3(vec3(0.75, 0.75, 0.75)).material(rgb(0.1, 0.8, 0.3)),
                0.2,
            )
        })
        .blends(0.2, 0.8),
        row!("smooth_subtract", Exact, {
            smooth_subtract(
                box3(vec3(0.8, 0.8, 0.8)).material(rgb(0.9, 0.2, 0.1)),
                sphere(0.95).material(rgb(0.1, 0.8, 0.3)),
                0.25,
            )
        }),
        row!("union with a guarded fractal child", Mandelbulb, {
            union(
                sphere(0.4).translate(vec3(2.0, 0.0, 0.0)).material(rgb(0.9, 0.2, 0.1)),
                mandelbulb(8).material(rgb(0.1, 0.8, 0.3)),
            )
        })
        .within(3.0),
        // ---- transforms
        row!("translate", Exact, { box3(vec3(0.5, 0.4, 0.3)).translate(vec3(0.3, -0.2, 0.5)) }),
        row!("rotate_x", Exact, { box3(vec3(1.0, 0.5, 0.25)).rotate_x(0.6) }),
        row!("rotate_y (animated)", Trig, { box3(vec3(1.0, 0.5, 0.25)).rotate_y(0.5 * t) }).at_time(1.25),
        row!("rotate_z", Exact, { box3(vec3(1.0, 0.5, 0.25)).rotate_z(-0.9) }),
        row!("rotate(axis) (animated)", Trig, { box3(vec3(1.0, 0.5, 0.25)).rotate(vec3(1.0, 2.0, -0.5), 0.4 + t) })
            .at_time(0.75),
        row!("scale", Exact, { torus(1.0, 0.3).scale(1.75) }).within(3.0),
        // ---- domain operations
        row!("repeat", Exact, { sphere(0.3).repeat(vec3(1.0, 0.0, 1.5)) }).within(4.0),
        // A period slid to 0 at run time leaves its axis unrepeated, as a literal 0 does.
        row!("repeat (param period at 0)", Exact, {
            sphere(0.3).repeat(vec3(param("period", 1.0, 0.0..4.0), 0.0, param("depth", 1.5, 0.0..4.0)))
        })
        .with_params(&[0.0, 1.5])
        .within(4.0),
        row!("repeat_limited", Exact, { sphere(0.3).repeat_limited(vec3(1.0, 1.25, 0.0), vec3(2, 1, 0)) }).within(4.0),
        row!("twist", Trig, { box3(vec3(0.5, 1.0, 0.5)).twist(0.8) }),
        row!("bend", Trig, { box3(vec3(1.0, 0.2, 0.3)).bend(0.5) }),
        row!("round", Exact, { box3(vec3(0.6, 0.4, 0.5)).round(0.2) }),
        row!("onion", Exact, { sphere(1.0).onion(0.1) }),
        row!("elongate", Exact, { sphere(0.5).elongate(vec3(0.5, 0.0, 0.25)) }),
        row!("plane_fold", Exact, {
            box3(vec3(0.3, 0.4, 0.2)).translate(vec3(0.5, 0.2, 0.0)).plane_fold(vec3(1.0, 1.0, 0.0))
        }),
        row!("abs_fold", Exact, { sphere(0.4).translate(vec3(0.5, 0.3, -0.2)).abs_fold(vec3(1, 0, 1)) }),
        row!("box_fold", Exact, { torus(0.5, 0.15).translate(vec3(0.4, 0.0, 0.3)).box_fold(0.6) }).within(3.0),
        row!("sphere_fold", Exact, { box3(vec3(0.4, 0.3, 0.5)).translate(vec3(0.6, 0.0, 0.0)).sphere_fold(0.3, 0.9) }),
        row!("displace: noise3", Exact, { sphere(1.0).displace(0.15 * noise3(x * 3.0, y * 3.0, z * 3.0)) }),
        row!("displace: noise2 and fbm2 heightfield", Exact, {
            plane(vec3(0.0, 1.0, 0.0), 0.0).displace(0.4 * fbm2(x * 0.7, z * 0.7, 5) + 0.1 * noise2(x * 3.0, z * 3.0))
        })
        .within(3.0),
        row!("displace: fbm3 with t and a param", Exact, {
            sphere(1.0).displace(param("amp", 0.1, 0.0..0.3) * fbm3(x * 2.0 + t, y * 2.0, z * 2.0, 4))
        })
        .at_time(0.5),
        row!("material: mandelbrot pattern read at the point", Pattern, {
            plane(vec3(0.0, 1.0, 0.0), 0.0).material(rgb(mandelbrot(x, z, 128), 0.5 + 0.5 * noise2(x, z), y))
        })
        .within(2.0),
        row!("polar_repeat", Trig, { capsule(vec3(0.6, -0.3, 0.0), vec3(0.9, 0.4, 0.0), 0.15).polar_repeat(7) }),
        // ---- materials
        row!("material: default surface", Exact, { sphere(1.0) }),
        row!("material: rgb", Exact, { sphere(1.0).material(rgb(0.2, 0.4, 0.8)) }),
        row!("material: phong", Exact, { sphere(1.0).material(phong(rgb(0.3, 0.7, 0.35), 0.15, 0.85, 0.4, 32.0)) }),
        row!("material: ambient, diffuse, specular, shininess setters", Exact, {
            sphere(1.0).material(rgb(0.3, 0.7, 0.35).ambient(0.3).diffuse(0.6).specular(0.5).shininess(16.0))
        }),
        row!("material: orbit_trap on a fractal", Mandelbulb, {
            mandelbulb(8).material(orbit_trap(rgb(0.9, 0.6, 0.2), rgb(0.1, 0.3, 0.8)))
        })
        .within(1.5),
        row!("material: orbit_trap on a primitive takes its first colour", Exact, {
            sphere(1.0).material(orbit_trap(rgb(0.9, 0.6, 0.2), rgb(0.1, 0.3, 0.8)))
        }),
        row!("material: union picks the nearer child", Exact, {
            union(
                sphere(0.8).material(phong(rgb(0.9, 0.2, 0.1), 0.1, 0.9, 0.0, 8.0)),
                sphere(0.8).translate(vec3(0.9, 0.0, 0.0)).material(phong(rgb(0.1, 0.8, 0.3), 0.3, 0.6, 0.5, 64.0)),
            )
        })
        // On the bisector x = 0.45 (not an f32 number) the two distances differ by rounding only: either material.
        .with_points(&grid_on_plane_x(0.45)),
        row!("material: smooth_union blends every term", Exact, {
            smooth_union(
                sphere(0.8).material(phong(rgb(0.9, 0.2, 0.1), 0.1, 0.9, 0.0, 8.0)),
                sphere(0.8).translate(vec3(0.9, 0.0, 0.0)).material(phong(rgb(0.1, 0.8, 0.3), 0.3, 0.6, 0.5, 64.0)),
                0.5,
            )
        })
        .blends(0.5, 56.0),
        row!("material: the innermost wins", Exact, {
            union(sphere(0.8).material(rgb(0.9, 0.2, 0.1)), sphere(0.8).translate(vec3(0.9, 0.0, 0.0)))
                .material(rgb(0.1, 0.8, 0.3))
        }),
        row!("material: animated and parametric terms", Trig, {
            sphere(1.0)
                .material(rgb(0.5 + 0.5 * sin(t), abs(cos(t)), param("blue", 0.5, 0.0..1.0)).shininess(8.0 + 8.0 * t))
        })
        .at_time(1.25)
        .with_params(&[0.75]),
        // ---- expressions (each reads `t` or a param, so folding cannot remove it from the kernels)
        row!("expr: t", Exact, { sphere(1.0 + 0.25 * t) }).at_time(1.5),
        row!("expr: param", Exact, { sphere(param("radius", 1.0, 0.5..2.0)) }).with_params(&[1.25]),
        row!("expr: params in two uniform slots", Exact, {
            sphere(param("a", 0.5, 0.25..1.0) + param("b", 0.25, 0.0..1.0)).translate(vec3(
                param("c", 0.0, -1.0..1.0),
                param("d", 0.0, -1.0..1.0),
                param("e", 0.0, -1.0..1.0),
            ))
        })
        .with_params(&[0.625, 0.125, -0.25, 0.5, 0.375]),
        row!("expr: +", Exact, { sphere(0.5 + t) }).at_time(0.5),
        row!("expr: -", Exact, { sphere(1.0).translate(vec3(t - 1.0, 0.0, 0.0)) }).at_time(1.25),
        row!("expr: unary -", Exact, { sphere(1.0).translate(vec3(-t, 0.0, 0.0)) }).at_time(0.5),
        row!("expr: *", Exact, { sphere(0.5 + 0.75 * t) }).at_time(1.5),
        row!("expr: /", Exact, { sphere(0.5 + 1.0 / (1.0 + t)) }).at_time(1.25),
        row!("expr: sin", Trig, { sphere(1.0).translate(vec3(sin(t), 0.0, 0.0)) }).at_time(0.75),
        row!("expr: cos", Trig, { sphere(1.0).translate(vec3(0.0, cos(t), 0.0)) }).at_time(0.75),
        row!("expr: abs", Exact, { sphere(0.5 + abs(t - 2.0)) }).at_time(0.75),
        row!("expr: sqrt", Exact, { sphere(0.5 + sqrt(t)) }).at_time(1.5),
        row!("expr: min", Exact, { sphere(0.5 + min(t, 1.25)) }).at_time(0.75),
        row!("expr: max", Exact, { sphere(max(t, 1.25)) }).at_time(0.75),
        row!("expr: pow", Trig, { sphere(0.5 + pow(t, 1.5)) }).at_time(1.25),
        row!("expr: clamp", Exact, { sphere(clamp(t, 0.5, 0.875)) }).at_time(1.5),
        row!("expr: mix", Exact, { sphere(mix(0.5, 1.5, t)) }).at_time(0.25),
    ]
}

/// DESIGN.md's hard cases that concern evaluation, each through every evaluator. Hand-picked points come first in
/// each row; the random ones follow.
pub fn hard_cases() -> Vec<Row> {
    use Family::*;
    // The polar axis of the Mandelbulb here is z (θ = acos(z/r)): x = y = 0 is the pole, and 1e-7, 1e-30 off it. The
    // design notes' x = z = 0 (the y axis, on the equator here, where φ = atan2(y, 0)) gets the same offsets.
    let mut pole = Vec::new();
    let offsets = [(0.0, 0.0), (1e-7, 0.0), (0.0, 1e-7), (-1e-7, 1e-7), (1e-30, 0.0), (1e-30, 1e-30), (0.0, -1e-30)];
    for i in 0..=24 {
        let along = -1.5 + 0.125 * i as f32;
        for (a, b) in offsets {
            pole.push([a, b, along]);
            pole.push([a, along, b]);
        }
    }
    // p = 0 exactly, points whose orbits never escape (deep inside the bulb), and a point whose squared coordinates
    // (1e-40) are below f32's smallest normal number: denormal, and flushed to zero under fast math.
    let bounded = vec![
        [0.0, 0.0, 0.0],
        [-0.0, 0.0, -0.0],
        [0.1, 0.2, 0.3],
        [-0.3, 0.2, 0.1],
        [0.4, -0.1, 0.05],
        [0.0, 0.5, 0.0],
        [0.25, 0.25, -0.25],
        [1e-20, -1e-20, 1e-20],
    ];
    // Coordinates exactly on (the f32 roundings of) the k/3^j planes of the sponge, and points 100 units away.
    let mut planes = Vec::new();
    for j in 1..=4 {
        let s = 3f32.powi(j);
        for k in [-3i32, -2, -1, 0, 1, 2, 3] {
            let c = k as f32 / s;
            planes.push([c, 0.3, -0.7]);
            planes.push([0.45, c, c]);
            planes.push([c, c, c]);
            planes.push([1.0, c, 1.0 / s]);
        }
    }
    for p in [[100.0, 0.3, 0.2], [-70.0, 70.0, 10.0], [0.0, 0.0, 100.0], [1.0 / 3.0, 100.0, 1.0 / 9.0]] {
        planes.push(p);
    }
    // The plane x = 0.25 is exactly equidistant from two spheres centred at x = 0 and x = 0.5, in every precision:
    // the blend weight there is exactly ½ (and with k = 0 the step of the weight sits on it).
    let bisector = grid_on_plane_x(0.25);
    vec![
        row!("hard: mandelbulb(8) pole axis", Mandelbulb, { mandelbulb(8) }).within(1.5).with_points(&pole),
        // The same power through a parameter takes the trigonometric form; the range starts at 8 so the step factor
        // (which follows the lowest power an expression can take) is the literal's.
        row!("hard: mandelbulb(power 8 by param, trig path) pole axis", Mandelbulb, {
            mandelbulb(param("power", 8.0, 8.0..16.0))
        })
        .within(1.5)
        .with_params(&[8.0])
        .with_points(&pole),
        row!("hard: mandelbulb(8) at p = 0 and never-escaping points", Mandelbulb, { mandelbulb(8) })
            .within(0.5)
            .with_points(&bounded),
        row!("hard: mandelbulb(7.5) at p = 0 and never-escaping points", Mandelbulb, { mandelbulb(7.5) })
            .within(0.5)
            .with_points(&bounded),
        row!("hard: mandelbulb(8) bailout 256", Mandelbulb, { mandelbulb(8).bailout(256.0) })
            .within(1.5)
            .with_points(&bounded),
        row!("hard: mandelbulb(16) bailout 256", Mandelbulb, { mandelbulb(16).bailout(256.0) })
            .within(1.5)
            .with_points(&bounded),
        row!("hard: mandelbulb(32) bailout 256", Mandelbulb, { mandelbulb(32).bailout(256.0) })
            .within(1.5)
            .with_points(&bounded),
        // Formulas that are NaN or infinite somewhere, never escape, or overflow: each evaluator stops the orbit at
        // its last finite iterate alike.
        row!("hard: formula infinite or 0/0 at every point", Mandelbulb, { escape_time(|z, c| z / (z.x * 0.0) + c) })
            .within(1.5)
            .with_points(&pole),
        row!("hard: formula that never escapes", Mandelbulb, { escape_time(|z, c| z * 0.5).iterations(24) })
            .within(1.5)
            .with_points(&bounded),
        row!("hard: formula past f32 in one step", Mandelbulb, { escape_time(|z, c| z * 1e30 + c).bailout(1e6) })
            .within(1.5)
            .with_points(&bounded),
        row!("hard: menger(6) on k/3 planes and 100 away", Menger, { menger(6) }).within(1.5).with_points(&planes),
        row!("hard: smooth_union k = 0 (param)", Exact, {
            smooth_union(
                sphere(0.5).material(rgb(0.9, 0.2, 0.1)),
                sphere(0.5).translate(vec3(0.5, 0.0, 0.0)).material(rgb(0.1, 0.8, 0.3)),
                param("k", 0.5, 0.0..4.0),
            )
        })
        .with_params(&[0.0])
        .with_points(&bisector),
        row!("hard: smooth_union k = 0 (literal)", Exact, {
            smooth_union(
                sphere(0.5).material(rgb(0.9, 0.2, 0.1)),
                sphere(0.5).translate(vec3(0.5, 0.0, 0.0)).material(rgb(0.1, 0.8, 0.3)),
                0.0,
            )
        })
        .with_points(&bisector),
        row!("hard: smooth_union k larger than both shapes", Exact, {
            smooth_union(
                sphere(0.5).material(rgb(0.9, 0.2, 0.1)),
                sphere(0.5).translate(vec3(0.5, 0.0, 0.0)).material(rgb(0.1, 0.8, 0.3)),
                3.0,
            )
        })
        .blends(3.0, 0.8)
        .with_points(&bisector),
        row!("hard: unit sphere 1e5 away", Exact, { sphere(1.0).translate(vec3(100000.0, 0.0, 0.0)) })
            .around([100000.0, 0.0, 0.0], 2.0),
    ]
}
