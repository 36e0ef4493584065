//! The CPU renderer against analytic answers: a unit sphere's hit mask and shading, and hard shadows of a sphere on a
//! plane, with small evaluators written here (the scene compiler generates such evaluators for real scenes).

use fractal_dsl::builder::{plane, scene, sphere, union, ShapeExt};
use fractal_dsl::eval::{Env, Evaluator, Sample};
use fractal_dsl::number::math::{length, v3, Real, V3};
use fractal_dsl::Scene;
use fractal_render::{render_scene, Backend, CpuRenderer, Frame, KernelSources, RenderError, RenderJob, Renderer};
use glam::DVec3;

/// The default surface material of every evaluator here.
fn default_sample<F: Real>(distance: F) -> Sample<F> {
    Sample {
        distance,
        albedo: v3(F::c(0.95), F::c(0.75), F::c(0.55)),
        ambient: F::c(0.15),
        diffuse: F::c(0.85),
        specular: F::zero(),
        shininess: F::c(32.0),
    }
}

/// A unit sphere at the origin.
struct UnitSphere;

impl<F: Real> Evaluator<F> for UnitSphere {
    fn distance(&self, p: V3<F>, _: &Env<F>) -> F {
        length(p) - F::one()
    }
    fn sample(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        default_sample(self.distance(p, env))
    }
}

/// Height of the ball's centre: its radius 0.5 plus a gap small enough for ambient occlusion to see.
const BALL_Y: f64 = 0.55;

/// A sphere of radius 0.5 at (0, [`BALL_Y`], 0) over the ground plane y = 0.
struct SphereOverPlane;

impl<F: Real> Evaluator<F> for SphereOverPlane {
    fn distance(&self, p: V3<F>, _: &Env<F>) -> F {
        let ball = length(p - v3(F::zero(), F::c(BALL_Y), F::zero())) - F::c(0.5);
        ball.min(p.y)
    }
    fn sample(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        default_sample(self.distance(p, env))
    }
}

/// Direction towards the key light of the sphere-over-plane scene (normalised by the frame packing).
const LIGHT: [f64; 3] = [1.0, 2.0, 0.5];

fn sphere_over_plane_scene() -> Scene {
    scene(union(sphere(0.5).translate([0.0, BALL_Y, 0.0]), plane([0.0, 1.0, 0.0], 0.0)))
        .camera(fractal_dsl::builder::camera([0.0, 3.0, -4.0], [0.0, 0.3, 0.0]))
        .light(fractal_dsl::builder::directional(LIGHT, fractal_dsl::builder::rgb(1.0, 1.0, 1.0)))
}

fn render_cpu(evaluator: &dyn Evaluator<f32>, s: &Scene, frame: &Frame) -> fractal_render::Image {
    CpuRenderer::new()
        .render(&RenderJob::new(KernelSources::default().with_cpu(evaluator, s), frame))
        .expect("CPU render")
}

/// The ray of pixel (x, y), spelled from the frame slots in f64 exactly as the render algorithm states it.
fn pixel_ray(frame: &Frame, x: u32, y: u32) -> (DVec3, DVec3) {
    let [o, r, u, f] = frame.camera().map(|c| DVec3::from_array(c.map(f64::from)));
    let (w, h) = (frame.width() as f64, frame.height() as f64);
    let pu = (2.0 * (x as f64 + 0.5) - w) / h;
    let pv = -(2.0 * (y as f64 + 0.5) - h) / h;
    (o, (f + r * pu + u * pv).normalize())
}

/// Distance from `centre` to the half-line from `origin` along the unit vector `dir`.
fn closest_approach(origin: DVec3, dir: DVec3, centre: DVec3) -> f64 {
    let along = (centre - origin).dot(dir).max(0.0);
    (origin + dir * along).distance(centre)
}

fn pack(c: DVec3) -> [u8; 4] {
    let ch = |v: f64| (v.clamp(0.0, 1.0).sqrt() * 255.0 + 0.5) as u8;
    [ch(c.x), ch(c.y), ch(c.z), 255]
}

#[test]
fn unit_sphere_hit_mask_and_shading_match_the_analytic_sphere() {
    let s = scene(sphere(1.0));
    let frame = Frame::default_view(&s, 0.0, 96, 96).expect("frame");
    let image = render_cpu(&UnitSphere, &s, &frame);
    let background = pack(DVec3::from_array(s.settings.background));
    let light = DVec3::new(0.6, 0.8, -0.4).normalize();
    let albedo = DVec3::new(0.95, 0.75, 0.55);

    let (mut checked, mut hits) = (0, 0);
    for y in 0..96 {
        for x in 0..96 {
            let (ro, rd) = pixel_ray(&frame, x, y);
            let b = ro.dot(rd);
            let closest = (ro.length_squared() - b * b).max(0.0).sqrt();
            // Rays grazing the silhouette may end either way within the hit epsilon and step budget.
            if (closest - 1.0).abs() < 0.01 {
                continue;
            }
            checked += 1;
            let got = image.rgba(x, y).unwrap();
            if closest < 1.0 {
                hits += 1;
                let t = -b - (1.0 - closest * closest).sqrt();
                let n = (ro + rd * t).normalize();
                let want = pack(albedo * (0.15 + 0.85 * n.dot(light).max(0.0)));
                let worst = got.iter().zip(want).map(|(g, w)| g.abs_diff(w)).max().unwrap();
                assert!(worst <= 2, "pixel ({x}, {y}): got {got:?}, analytic {want:?}");
            } else {
                assert_eq!(got, background, "pixel ({x}, {y}) should be background");
            }
        }
    }
    assert!(checked > 96 * 96 * 9 / 10, "only {checked} pixels away from the silhouette");
    assert!(hits > 96 * 96 / 10, "only {hits} sphere pixels: the camera does not see the sphere");
}

#[test]
fn f64_rendering_draws_the_same_sphere() {
    let s = scene(sphere(1.0));
    let frame = Frame::default_view(&s, 0.0, 48, 48).expect("frame");
    let single = render_cpu(&UnitSphere, &s, &frame);
    let double = render_scene::<f64, _>(&UnitSphere, &s, &frame).expect("f64 render");
    let differing = crate::common::fraction_different(&single, &double, 1);
    assert!(differing < 0.02, "{:.1} % of pixels differ between f32 and f64", differing * 100.0);
}

#[test]
fn hard_shadows_darken_exactly_the_shadowed_ground() {
    let lit_scene = sphere_over_plane_scene();
    let shadowed_scene = sphere_over_plane_scene().hard_shadows();
    let frame = Frame::default_view(&lit_scene, 0.0, 80, 60).expect("frame");
    let lit = render_cpu(&SphereOverPlane, &lit_scene, &frame);
    let shadowed = render_cpu(&SphereOverPlane, &shadowed_scene, &frame);

    let (mut in_shadow, mut in_light) = (0, 0);
    for y in 0..60 {
        for x in 0..80 {
            let (a, b) = (lit.rgba(x, y).unwrap(), shadowed.rgba(x, y).unwrap());
            assert!(b.iter().zip(a).all(|(s, l)| *s <= l), "shadows brightened pixel ({x}, {y})");
            let (ro, rd) = pixel_ray(&frame, x, y);
            if rd.y >= -1e-3 {
                continue;
            }
            // Where the ray meets the ground, unless the ball is in front of it.
            let ground = ro + rd * (-ro.y / rd.y);
            let ball = DVec3::Y * BALL_Y;
            if closest_approach(ro, rd, ball) < 0.55 {
                continue;
            }
            // Shadowed when the ray from the ground towards the light passes through the ball; skip the penumbra
            // band where the march's epsilons decide.
            let towards_light = DVec3::from_array(LIGHT).normalize();
            let miss = closest_approach(ground, towards_light, ball);
            if miss < 0.45 {
                in_shadow += 1;
                assert!(b[0] + 40 < a[0], "ground at {ground:?} should be in shadow: {b:?} vs lit {a:?}");
            } else if miss > 0.55 {
                in_light += 1;
                assert_eq!(a, b, "ground at {ground:?} should be lit");
            }
        }
    }
    assert!(in_shadow > 20 && in_light > 200, "shadow {in_shadow}, light {in_light}: the view misses the scene");
}

/// Pixels of `b` darker than `a` by more than 2 levels in some channel, and brighter likewise.
fn darker_and_brighter(a: &fractal_render::Image, b: &fractal_render::Image) -> (usize, usize) {
    let (mut darker, mut brighter) = (0, 0);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        let (p, q) = (p.to_le_bytes(), q.to_le_bytes());
        darker += p.iter().zip(q).any(|(x, y)| *x > y && x - y > 2) as usize;
        brighter += p.iter().zip(q).any(|(x, y)| y > *x && y - x > 2) as usize;
    }
    (darker, brighter)
}

#[test]
fn effects_change_the_picture_the_way_they_should() {
    use fractal_dsl::builder::rgb;
    let base = sphere_over_plane_scene();
    let frame = Frame::default_view(&base, 0.0, 80, 60).expect("frame");
    let plain = render_cpu(&SphereOverPlane, &base, &frame);
    let pixels = plain.pixels.len();
    let effect = |s: Scene| darker_and_brighter(&plain, &render_cpu(&SphereOverPlane, &s, &frame));

    let (darker, brighter) = effect(base.clone().soft_shadows(8.0));
    assert!(darker > pixels / 100 && brighter == 0, "soft shadows: {darker} darker, {brighter} brighter");
    // Occlusion only where the ball nearly touches the ground.
    let (darker, brighter) = effect(base.clone().ambient_occlusion(1.0));
    assert!(darker >= 10 && brighter == 0, "ambient occlusion: {darker} darker, {brighter} brighter");
    let (darker, brighter) = effect(base.clone().glow(rgb(0.2, 0.4, 1.0)));
    assert!(brighter > pixels / 100 && darker == 0, "glow: {darker} darker, {brighter} brighter");
    let (darker, brighter) = effect(base.clone().fog(rgb(1.0, 1.0, 1.0), 0.2));
    assert!(brighter > pixels / 2, "white fog: {darker} darker, {brighter} brighter");
    // Without the gamma curve every channel in (0, 1) gets darker.
    let (darker, brighter) = effect(base.clone().gamma(1.0));
    assert!(darker > pixels / 2 && brighter == 0, "gamma 1: {darker} darker, {brighter} brighter");
    // A one-pixel epsilon moves near hits by a fraction of a pixel; only grazing rays towards the horizon, which now
    // stop a pixel short of the ground, change.
    let (darker, brighter) = effect(base.clone().pixel_epsilon(1.0));
    assert!(darker + brighter < pixels / 10, "pixel epsilon: {darker} darker, {brighter} brighter");
}

#[test]
fn jobs_without_an_evaluator_or_with_another_scenes_frame_are_errors() {
    let s = scene(sphere(1.0));
    let frame = Frame::default_view(&s, 0.0, 8, 8).expect("frame");
    let mut r = CpuRenderer::new();
    assert_eq!(r.device().backend, Backend::Cpu);
    let err = r.render(&RenderJob::new(KernelSources::default().with_wgsl("x"), &frame)).unwrap_err();
    assert!(matches!(err, RenderError::MissingKernel { backend: Backend::Cpu, .. }), "{err}");
    let two_lights = sphere_over_plane_scene()
        .light(fractal_dsl::builder::directional([1.0, 0.0, 0.0], fractal_dsl::builder::rgb(1.0, 1.0, 1.0)));
    let err =
        r.render(&RenderJob::new(KernelSources::default().with_cpu(&UnitSphere, &two_lights), &frame)).unwrap_err();
    assert!(matches!(err, RenderError::Frame(_)), "{err}");
}

/// The CPU renderer marches primary rays in packets of eight where the evaluator has a packet instance; lane for
/// lane that is the scalar march, so every built-in scene's image equals the one-ray-at-a-time render's (here with
/// the interpreter, whose packet and scalar instances are the same walker).
#[test]
fn packet_marching_draws_the_scalar_renderers_image() {
    use fractal_dsl::eval::interp::Interpreter;
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let interp = Interpreter::new(scene).expect("a valid scene");
        // 61 columns: the last packet of each row is partly padding.
        let frame = Frame::default_view(scene, 0.0, 61, 20).expect("frame");
        let packets = Evaluator::<f32>::packets(&interp).expect("the interpreter has a packet instance");
        let packed = fractal_render::backend::cpu::render_packets(packets, scene, &frame).expect("render");
        let scalar = render_scene::<f32, _>(&interp, scene, &frame).expect("render");
        let differing = packed.pixels.iter().zip(&scalar.pixels).filter(|(a, b)| a != b).count();
        assert_eq!(differing, 0, "{name}: {differing} pixels differ between packet and scalar marching");
    }
}
