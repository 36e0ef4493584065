//! Precision chosen by the view: close to a fractal's surface (the Mandelbulb's pole, an edge of the Menger sponge) f32
//! fails the accuracy budget and the rule picks f64, which passes it; far from the origin the same scene draws the
//! image it draws at the origin. Judged against the f64 truth (membership, never the estimate), at a small size and a
//! truth step of 1/32 footprint so the test stays short; on the CPU, and on the GPU backends with their f64 kernels
//! where the device computes in f64.

use fractal::dsl::builder::*;
use fractal::dsl::eval::interp::Interpreter;
use fractal::dsl::eval::Evaluator;
use fractal::dsl::{CompiledScene, Scene};
use fractal::render::backend::cpu::trace_scene;
use fractal::render::choose_precision::{choose, decide};
use fractal::render::precision::{Limits, Precision, PrecisionChoice};
use fractal::render::{CpuRenderer, Frame, Image, KernelSources, ParamValues, Pose, RenderJob, Renderer};
use fractal::runtime::accuracy::{measure, Budget, Observed};
use fractal::runtime::truth::{Truth, TruthSettings};
use fractal::scenes;
use glam::DVec3;

const SIZE: (u32, u32) = (32, 18);

/// The dive's frame at `time`: a key every 3 s, 10^-(k-1) from the south pole at 3k s (27 s: 1e-9).
fn dive_frame(time: f64) -> (&'static Scene, Frame) {
    let scene = scenes::MANDELBULB_DIVE.scene();
    (scene, Frame::default_view(scene, time, SIZE.0, SIZE.1).unwrap())
}

/// The budget's violations of the CPU render of `frame` of `compiled` in `precision`, against `truth`.
fn violations(compiled: &CompiledScene, frame: &Frame, truth: &Truth, precision: Precision) -> Vec<String> {
    violations_of(&compiled.native(), compiled.scene(), (frame, truth), precision)
}

/// The budget's violations of the CPU render of `frame` of `scene` by `evaluator` in `precision`, against `truth`.
fn violations_of<E: Evaluator<f32> + Evaluator<f64>>(
    evaluator: &E,
    scene: &Scene,
    (frame, truth): (&Frame, &Truth),
    precision: Precision,
) -> Vec<String> {
    let traces = match precision {
        Precision::F32 => trace_scene::<f32, _>(evaluator, scene, frame).unwrap(),
        Precision::F64 => trace_scene::<f64, _>(evaluator, scene, frame).unwrap(),
    };
    Budget::default().verdict(&measure(scene, truth, Observed::Traced(&traces))).violations
}

fn truth(scene: &Scene, frame: &Frame) -> Truth {
    Truth::compute(scene, frame, TruthSettings { step_footprints: 1.0 / 32.0, iteration_factor: 1 }).unwrap()
}

/// The view the precision issue was filed with: the showcase `mandelbulb` at t = 0 from 3e-4 before the set's first
/// crossing of the line from (1.2, 1, −2.2) to the origin. Its f32 render passed the budget of old (whose truth
/// stepped near the camera as if it stood 0.1 away); against a truth stepped at the surface's footprints it fails.
#[test]
fn the_showcase_3e_4_from_its_surface_fails_the_budget_in_f32() {
    let compiled = &scenes::MANDELBULB;
    let scene = compiled.scene();
    let at = DVec3::new(0.413_507_549_962_055_1, 0.344_589_624_968_379_2, -0.758_097_174_930_434_4);
    let pose = Pose::look_at(at, DVec3::ZERO, scene.camera.fov_degrees).unwrap();
    let frame = Frame::new(scene, &pose, 0.0, SIZE.0, SIZE.1, &ParamValues::defaults(scene)).unwrap();
    let fails = violations(compiled, &frame, &truth(scene, &frame), Precision::F32);
    assert!(!fails.is_empty(), "the 3e-4 view is within budget in f32");
}

#[test]
fn the_dive_1e9_from_the_pole_asks_for_f64_which_is_within_budget_where_f32_is_not() {
    let (scene, frame) = dive_frame(27.0);
    let native = scenes::MANDELBULB_DIVE.native();
    let chosen = decide(PrecisionChoice::Auto, scene, &frame, &native, &native).unwrap();
    assert_eq!(chosen.precision, Precision::F64, "{chosen}");
    let truth = truth(scene, &frame);
    let f32_fails = violations(&scenes::MANDELBULB_DIVE, &frame, &truth, Precision::F32);
    assert!(!f32_fails.is_empty(), "f32 1e-9 from the surface is within budget");
    let f64_fails = violations(&scenes::MANDELBULB_DIVE, &frame, &truth, Precision::F64);
    assert!(f64_fails.is_empty(), "f64 1e-9 from the surface: {f64_fails:?}");
}

#[test]
fn the_whole_bulb_and_every_built_in_scene_stay_in_f32() {
    let (scene, frame) = dive_frame(0.0);
    let native = scenes::MANDELBULB_DIVE.native();
    assert_eq!(choose(scene, &frame, &native, &native, Limits::default()).unwrap().precision, Precision::F32);
    for (name, compiled) in scenes::ALL.iter().filter(|(n, _)| *n != "mandelbulb_dive") {
        let scene = compiled.scene();
        let frame = Frame::default_view(scene, 0.0, 48, 27).unwrap();
        let native = compiled.native();
        let chosen = choose(scene, &frame, &native, &native, Limits::default()).unwrap();
        assert_eq!(chosen.precision, Precision::F32, "{name}: {chosen}");
    }
}

/// The Menger sponge (5 levels) `distance` from the concave edge where its face z = −1 meets the wall of its central
/// tunnel, x = −1/3, looking at the edge. Its surface is planes at every level, so the truth's is the estimate's however
/// close the camera goes.
fn menger_edge(distance: f64) -> (Scene, Frame) {
    let edge = DVec3::new(-1.0 / 3.0, 0.0, -1.0);
    let s = scene(menger(5)).light(directional([-0.5, 0.8, -0.45], rgb(1.0, 0.96, 0.88))).pixel_epsilon(0.05);
    let at = edge + DVec3::new(1.0, 0.25, -1.0).normalize() * distance;
    let pose = Pose::look_at(at, edge, 50.0).unwrap();
    let frame = Frame::new(&s, &pose, 0.0, SIZE.0, SIZE.1, &ParamValues::defaults(&s)).unwrap();
    (s, frame)
}

#[test]
fn the_menger_sponge_1e9_from_an_edge_asks_for_f64_which_is_within_budget_on_every_backend_that_has_it() {
    let (s, frame) = menger_edge(1e-9);
    let interp = Interpreter::new(&s).unwrap();
    let chosen = decide(PrecisionChoice::Auto, &s, &frame, &interp, &interp).unwrap();
    assert_eq!(chosen.precision, Precision::F64, "{chosen}");
    let truth = truth(&s, &frame);
    let f64_fails = violations_of(&interp, &s, (&frame, &truth), Precision::F64);
    assert!(f64_fails.is_empty(), "f64 1e-9 from the sponge's edge: {f64_fails:?}");
    assert!(!violations_of(&interp, &s, (&frame, &truth), Precision::F32).is_empty(), "f32 there is within budget");
    let tracing = fractal::dsl::compile(&s).unwrap().tracing();
    for (label, mut gpu) in gpus_with_f64() {
        let job = RenderJob::new(KernelSources::compiled(&tracing), &frame).with_precision(Precision::F64);
        let traced = gpu.trace(&job).unwrap();
        let fails = Budget::default().verdict(&measure(&s, &truth, Observed::Traced(&traced.pixels))).violations;
        assert!(fails.is_empty(), "{label} in f64 1e-9 from the sponge's edge: {fails:?}");
    }
}

/// A unit sphere and a small box, moved by `offset`, seen from a camera moved likewise.
fn far_scene(offset: f64) -> (Scene, Pose) {
    let at = |x: f64, y: f64, z: f64| [x + offset, y, z];
    let s = scene(union(sphere(1.0).translate(at(0.0, 0.0, 0.0)), box3([0.3, 0.3, 0.3]).translate(at(1.2, 0.6, 0.0))))
        .light(directional([0.5, 0.8, -0.4], rgb(1.0, 1.0, 1.0)));
    let pose = Pose::look_at(DVec3::from(at(0.5, 1.0, -3.5)), DVec3::from(at(0.3, 0.0, 0.0)), 50.0).unwrap();
    (s, pose)
}

fn render_cpu(scene: &Scene, pose: &Pose, precision: PrecisionChoice) -> (Precision, Image) {
    let frame = Frame::new(scene, pose, 0.0, 160, 90, &ParamValues::defaults(scene)).unwrap();
    let interp = Interpreter::new(scene).unwrap();
    let chosen = decide(precision, scene, &frame, &interp, &interp).unwrap();
    let sources = KernelSources::default().with_cpu(&interp, scene).with_cpu_wide(&interp);
    let image = CpuRenderer::new().render(&RenderJob::new(sources, &frame).with_precision(chosen.precision)).unwrap();
    (chosen.precision, image)
}

/// Share of pixels whose channels differ by more than `levels`.
fn differing(a: &Image, b: &Image, levels: u8) -> f64 {
    let off = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| p.to_le_bytes().iter().zip(q.to_le_bytes()).take(3).any(|(x, y)| x.abs_diff(y) > levels));
    off.count() as f64 / a.pixels.len() as f64
}

#[test]
fn a_scene_a_million_units_out_draws_the_image_it_draws_at_the_origin() {
    let (here, pose_here) = far_scene(0.0);
    let (far, pose_far) = far_scene(1e6);
    let (p_here, at_origin) = render_cpu(&here, &pose_here, PrecisionChoice::Auto);
    assert_eq!(p_here, Precision::F32);
    // The frame is anchored at the camera: the scene's translation cancels against the anchor before the point
    // relative to it is added, so f32 keeps the precision it has at the origin and the rule sees no need for f64.
    let (p_far, far_away) = render_cpu(&far, &pose_far, PrecisionChoice::Auto);
    assert_eq!(p_far, Precision::F32, "the view 1e6 out asks for f32");
    let (_, far_f64) = render_cpu(&far, &pose_far, PrecisionChoice::Only(Precision::F64));
    let (f32_off, f64_off) = (differing(&at_origin, &far_away, 2), differing(&at_origin, &far_f64, 2));
    eprintln!(
        "1e6 out against the origin: f32 {:.3} %, f64 {:.3} % of pixels off by > 2 levels",
        100.0 * f32_off,
        100.0 * f64_off
    );
    assert!(f32_off < 0.002, "f32 1e6 out differs on {:.2} % of pixels", 100.0 * f32_off);
    assert!(f64_off < 0.002, "f64 1e6 out differs on {:.2} % of pixels", 100.0 * f64_off);
}

/// The GPU renderers, by name: wgpu and OpenCL (fast math, as the commands open it). A required backend that cannot be
/// opened fails; one that is not required is skipped with a note.
fn gpus() -> Vec<(&'static str, Box<dyn Renderer>)> {
    gpus_where(false)
}

/// The GPU renderers whose devices compute in f64: wgpu where the adapter offers `SHADER_F64` (lavapipe does), OpenCL
/// where the device has `cl_khr_fp64` (pocl's CPU device does); one without f64 is skipped with a note.
fn gpus_with_f64() -> Vec<(&'static str, Box<dyn Renderer>)> {
    gpus_where(true)
}

fn gpus_where(f64_only: bool) -> Vec<(&'static str, Box<dyn Renderer>)> {
    let required = fractal_render::device::backends_required();
    let mut out: Vec<(&'static str, Box<dyn Renderer>)> = Vec::new();
    match fractal::render::WgpuRenderer::new() {
        Ok(r) if r.has_fp64() || !f64_only => out.push(("wgpu", Box::new(r))),
        Ok(r) => eprintln!("wgpu skipped: {} has no SHADER_F64", r.device()),
        Err(e) if !required => eprintln!("wgpu skipped: no adapter ({e})"),
        Err(e) => panic!("wgpu is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
    }
    #[cfg(feature = "opencl")]
    match fractal::render::OpenClRenderer::new(false) {
        Ok(r) if r.has_fp64() || !f64_only => out.push(("opencl", Box::new(r))),
        Ok(r) => eprintln!("OpenCL skipped: {} has no cl_khr_fp64", r.device()),
        Err(e) if !required => eprintln!("OpenCL skipped: no device ({e})"),
        Err(e) => panic!("OpenCL is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
    }
    out
}

#[test]
fn on_the_gpus_the_dive_1e9_from_the_pole_is_within_budget_in_f64_and_not_in_f32() {
    let (scene, frame) = dive_frame(27.0);
    let tracing = fractal::dsl::compile(scene).unwrap().tracing();
    let truth = truth(scene, &frame);
    for (label, mut gpu) in gpus_with_f64() {
        let mut judged = |precision| {
            let job = RenderJob::new(KernelSources::compiled(&tracing), &frame).with_precision(precision);
            assert!(gpu.draws_in(&job), "{label}: a device with f64 draws in {precision}");
            let traced = gpu.trace(&job).unwrap();
            Budget::default().verdict(&measure(scene, &truth, Observed::Traced(&traced.pixels))).violations
        };
        let f64_fails = judged(Precision::F64);
        assert!(f64_fails.is_empty(), "{label} in f64 1e-9 from the surface: {f64_fails:?}");
        assert!(!judged(Precision::F32).is_empty(), "{label} in f32 1e-9 from the surface is within budget");
    }
}

#[test]
fn on_the_gpus_a_scene_a_million_units_out_draws_the_image_at_the_origin() {
    let (here, pose_here) = far_scene(0.0);
    let (_, at_origin) = render_cpu(&here, &pose_here, PrecisionChoice::Auto);
    let (far, pose_far) = far_scene(1e6);
    let frame = Frame::new(&far, &pose_far, 0.0, 160, 90, &ParamValues::defaults(&far)).unwrap();
    let kernels = fractal::dsl::compile(&far).unwrap();
    for (label, mut gpu) in gpus() {
        let mut draw = |precision| {
            let job = RenderJob::new(KernelSources::compiled(&kernels), &frame).with_precision(precision);
            gpu.draws_in(&job).then(|| gpu.render(&job).unwrap())
        };
        for precision in [Precision::F32, Precision::F64] {
            let Some(image) = draw(precision) else { continue };
            let off = differing(&at_origin, &image, 8);
            eprintln!(
                "{label} in {precision} 1e6 out against the CPU at the origin: {:.3} % of pixels off by > 8 levels",
                100.0 * off
            );
            // The backends' agreement tolerance (`tests/fractal/backends.rs`): 97 % of colours within 8 levels.
            assert!(off < 0.03, "{label} in {precision} 1e6 out differs on {:.2} % of pixels", 100.0 * off);
        }
    }
}
