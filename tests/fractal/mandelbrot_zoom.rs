//! The deep zoom of the `mandelbrot_zoom` scene. At the deepest key of its camera path the view is 1e-12 wide, 10⁻¹⁴
//! per pixel here, where f32 numbers near 0.74 are 6·10⁻⁸ apart. The pattern there is computed by perturbation
//! (`fractal_dsl::formula::mandelbrot`): the frame's f64 reference orbit at the camera position, and per pixel the
//! hit's offset from the camera, rd·t, in f32.
//!
//! The check, at every pixel of a 96×54 render: the escape count the CPU renderer's perturbed pattern computes (f32,
//! the frame's orbit, the renderer's own t) against the count of a double-double (106-bit) iteration of the same
//! pixel's c = camera + rd·t. Near the set's boundary counts are chaotic below the pixel scale: moving c by a
//! fiftieth of a pixel changes the double-double count of about half of these pixels (a thousandth of a pixel: a
//! quarter of them). Such a pixel has no count at any precision an f64 renderer has — an f64 ulp of c is already a
//! hundredth of a pixel here, and a direct f64 iteration gets those pixels wrong as often as perturbation does. The
//! test measures them (their share is printed and bounded) and holds the perturbed counts to the others, the
//! *resolvable* pixels: those whose double-double count stays the same when c moves by a fiftieth of a pixel either
//! way. There the perturbed count must be exact on ≥ 99 % (measured 99.6 %; a direct f64 iteration: 99.8 %). The plain
//! f32 iteration, for contrast, must fail (< 50 %; measured 0 %), which shows the test can tell. The backends' renders
//! of this key are compared with the CPU's in `tests/backends.rs`.
//!
//! Counts are read from the smooth value ν = n + 1 − log₂(log₂|z|): escape means 16 < |z| < 16² + 2, so
//! log₂(log₂|z|) lies in (2, 3) and n = ⌊ν⌋ + 2.

use fractal::dsl::formula::mandelbrot::{inverse_count, mandelbrot, mandelbrot_perturbed};
use fractal::dsl::number::math::{normalize, v3, V3};
use fractal::render::backend::cpu::trace_scene;
use fractal::render::{Frame, ParamValues, Pose};
use fractal::scenes;

const ITERATIONS: u32 = 5000;
const WIDTH: u32 = 96;
const HEIGHT: u32 = 54;
/// Least share of resolvable pixels (measured: 0.51), so the check is not made on a handful.
const MIN_RESOLVABLE: f64 = 0.4;
/// The move of c, in pixels, a resolvable pixel's count must not notice: twice an f64 ulp of c at this depth.
const RESOLUTION_MOVE: f64 = 2e-2;

/// The escape count of a pattern value (0: never escaped).
fn count(value: f64) -> u32 {
    if value <= 0.0 {
        0
    } else {
        (value * f64::from(ITERATIONS)).floor() as u32 + 2
    }
}

#[test]
fn perturbation_counts_match_a_double_double_iteration_at_the_deepest_key() {
    let compiled = &scenes::MANDELBROT_ZOOM;
    let scene = compiled.scene();
    let fractal::dsl::CameraPlacement::Path { keys, .. } = &scene.camera.placement else {
        panic!("mandelbrot_zoom has a camera path");
    };
    let deepest = keys.iter().map(|k| k.time).fold(f64::MIN, f64::max);
    let pose = Pose::from_camera(&scene.camera, deepest, &|p| p.default).unwrap();
    let frame = Frame::new(scene, &pose, deepest, WIDTH, HEIGHT, &ParamValues::defaults(scene)).unwrap();
    let width = 2.0 * pose.position.y * (0.5 * pose.fov_degrees.to_radians()).tan() * WIDTH as f64 / HEIGHT as f64;
    assert!(width <= 1.01e-12, "the deepest key shows a view {width:e} wide");

    let native = compiled.native();
    let traces = trace_scene::<f32, _>(&native, scene, &frame).unwrap();
    let orbit = frame.reference_orbit();
    assert!(orbit.len() > 1, "the frame holds the reference orbit");
    let [origin, right, up, forward] = frame.camera().map(|c| v3(c[0], c[1], c[2]));
    let inverse = inverse_count(ITERATIONS);

    let (mut agree, mut f64_agree, mut plain_agree, mut resolvable) = (0, 0, 0, 0);
    for (i, trace) in traces.iter().enumerate() {
        assert!(trace.hit, "every pixel of the zoom sees the plane");
        // The ray as the renderer makes it (`fractal_dsl::ray::View::ray`), in f32.
        let (x, y) = ((i as u32 % WIDTH) as f32 + 0.5, (i as u32 / WIDTH) as f32 + 0.5);
        let (w, h) = (WIDTH as f32, HEIGHT as f32);
        let rd: V3<f32> = normalize(forward + right * ((2.0 * x - w) / h) + up * (-(2.0 * y - h) / h));
        let t = trace.t as f32;
        let offset = rd * t;

        // The pixel's c, exactly: the f64 camera position plus the f32 offset, in double-double.
        let (cx, cz) = (Dd::sum(pose.position.x, offset.x.into()), Dd::sum(pose.position.z, offset.z.into()));
        let truth = dd_count(cx, cz);
        let shift = RESOLUTION_MOVE * f64::from(frame.pixel_footprint()) * trace.t;
        let moved = [shift, -shift].map(|s| dd_count(cx.add(Dd(s, 0.0)), cz.add(Dd(-s, 0.0))));
        if moved.iter().any(|&m| m != truth) {
            continue;
        }
        resolvable += 1;

        let perturbed = mandelbrot_perturbed::<f32>(offset.x, offset.z, ITERATIONS, inverse as f32, &orbit);
        let direct = mandelbrot::<f64>(cx.0, cz.0, ITERATIONS, inverse);
        let plain = mandelbrot::<f32>(origin.x + offset.x, origin.z + offset.z, ITERATIONS, inverse as f32);
        agree += (count(f64::from(perturbed)) == truth) as usize;
        f64_agree += (count(direct) == truth) as usize;
        plain_agree += (count(f64::from(plain)) == truth) as usize;
    }
    let pixels = traces.len();
    let share = |n: usize| n as f64 / resolvable.max(1) as f64;
    eprintln!(
        "view {width:.3e} wide: {resolvable} of {pixels} pixels resolvable; on them the perturbed f32 counts are \
         exact on {:.2} %, a direct f64 iteration's on {:.2} %, a plain f32 iteration's on {:.2} %",
        100.0 * share(agree),
        100.0 * share(f64_agree),
        100.0 * share(plain_agree)
    );
    assert!(resolvable as f64 >= MIN_RESOLVABLE * pixels as f64, "only {resolvable} of {pixels} pixels are resolvable");
    assert!(share(agree) >= 0.99, "perturbed counts are exact on {:.2} % of pixels only", 100.0 * share(agree));
    assert!(
        share(plain_agree) < 0.5,
        "plain f32 is exact on {:.2} %: the test cannot tell",
        100.0 * share(plain_agree)
    );
}

/// A double-double number hi + lo (|lo| ≤ ½ ulp(hi)): about 106 bits, the reference's arithmetic.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Dd(f64, f64);

impl Dd {
    /// a + b exactly (Knuth's two-sum).
    fn sum(a: f64, b: f64) -> Dd {
        let s = a + b;
        let v = s - a;
        Dd(s, (a - (s - v)) + (b - v))
    }
    fn add(self, o: Dd) -> Dd {
        let s = Dd::sum(self.0, o.0);
        normalised(s.0, s.1 + self.1 + o.1)
    }
    fn mul(self, o: Dd) -> Dd {
        let p = self.0 * o.0;
        normalised(p, self.0.mul_add(o.0, -p) + self.0 * o.1 + self.1 * o.0)
    }
    fn neg(self) -> Dd {
        Dd(-self.0, -self.1)
    }
}

fn normalised(hi: f64, lo: f64) -> Dd {
    let s = hi + lo;
    Dd(s, lo - (s - hi))
}

/// The escape count of c in double-double: the step at which |z|² > 256 (the pattern's test), 0 within none.
fn dd_count(cx: Dd, cy: Dd) -> u32 {
    let (mut zx, mut zy) = (Dd(0.0, 0.0), Dd(0.0, 0.0));
    for n in 1..=ITERATIONS {
        let xy = zx.mul(zy);
        (zx, zy) = (zx.mul(zx).add(zy.mul(zy).neg()).add(cx), xy.add(xy).add(cy));
        if zx.0 * zx.0 + zy.0 * zy.0 > 256.0 {
            return n;
        }
    }
    0
}
