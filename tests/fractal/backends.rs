//! Every built-in scene rendered at 96×96 by each backend — CPU (the native evaluator), wgpu (the WGSL kernel) and
//! OpenCL (the OpenCL C kernel, precise and fast-math) — must draw the same picture: hit masks agree on at least 99 %
//! of pixels and colours agree within a stated tolerance. This also proves every render kernel builds on each driver.
//! A scene with a camera path is also drawn at its last key (for `mandelbrot_zoom`, a view 1.04e-12 wide, where its
//! pattern is computed by perturbation). And every scene draws something at its own camera and time — at least 5 % of
//! its pixels hit — with no NaN or Inf anywhere in its CPU traces (colour before packing, depth, normal), which packing
//! to RGBA8 would hide. The GPU backends' trace kernels (the render kernel that also keeps each pixel's depth, normal
//! and steps, which the accuracy report reads) agree with the CPU's traces on a set of scenes chosen to cover the
//! render algorithm's paths. Each frame is drawn in the precision its view asks for: the dive's last key in f64, which
//! each GPU backend draws with its f64 kernel where the device computes in f64 (`SHADER_F64`, `cl_khr_fp64`), against
//! the CPU's f64 render, and leaves to the CPU otherwise.
//!
//! Tolerance: a pixel "agrees" when every channel is within 8/255 of the CPU image. The kernels run the same algorithm
//! in f32, but GPU built-ins (sqrt, pow, normalize, sin) may differ by a few ulps; near a silhouette or a shadow edge
//! that can flip a hit or a shadow sample, which changes the pixel completely — such flips are what the 1 % allows.

use fractal::render::choose_precision::decide;
use fractal::render::precision::PrecisionChoice;
use fractal::render::{CpuRenderer, Frame, Image, KernelSources, RenderJob, Renderer};
use fractal::scenes;
use fractal_render::device::backends_required;

const SIZE: u32 = 96;
const CHANNEL_TOLERANCE: u8 = 8;
/// Of pixels, the share allowed to differ in hit/miss, and the share allowed to differ in colour beyond tolerance.
const MASK_AGREEMENT: f64 = 0.99;
const COLOUR_AGREEMENT: f64 = 0.97;
/// The share of colours that must agree at the deepest key of `mandelbrot_zoom` (a view 1e-12 wide). About half of
/// its pixels have escape counts that change when c moves by a fiftieth of a pixel (measured with a double-double
/// iteration in `tests/mandelbrot_zoom.rs`), so two f32 renderers that round differently disagree on a part of them.
/// lavapipe rounds like the CPU and agrees on 100 %; pocl fuses multiply-adds (OpenCL's default `FP_CONTRACT`) and
/// agrees on 90 % (97 % with `#pragma OPENCL FP_CONTRACT OFF`, measured). The hit mask is held to the usual 99 %.
const DEEP_ZOOM_COLOUR_AGREEMENT: f64 = 0.85;

fn frame_of(scene: &fractal::dsl::Scene) -> Frame {
    frame_at(scene, 0.0)
}

fn frame_at(scene: &fractal::dsl::Scene, time: f64) -> Frame {
    Frame::default_view(scene, time, SIZE, SIZE).expect("built-in cameras are valid and 96x96 is a valid size")
}

/// The times a backend's picture is compared at: 0, and the last key of a camera path.
fn compared_times(scene: &fractal::dsl::Scene) -> Vec<f64> {
    match &scene.camera.placement {
        fractal::dsl::CameraPlacement::Path { keys, .. } => {
            vec![0.0, keys.iter().map(|k| k.time).fold(0.0, f64::max)]
        }
        _ => vec![0.0],
    }
}

fn background(scene: &fractal::dsl::Scene) -> [u8; 4] {
    let b = scene.settings.background;
    // The kernels' output transform: clamp, gamma 2 (sqrt) for every built-in scene, round.
    assert_eq!(scene.settings.gamma, 2.0);
    let c = |v: f64| (v.clamp(0.0, 1.0).sqrt() as f32 * 255.0 + 0.5) as u8;
    [c(b[0]), c(b[1]), c(b[2]), 255]
}

struct Comparison {
    mask: f64,
    colour: f64,
    hits: usize,
}

fn compare(reference: &Image, other: &Image, bg: [u8; 4]) -> Comparison {
    let (mut mask_same, mut colour_same, mut hits) = (0usize, 0usize, 0usize);
    let n = (reference.width * reference.height) as usize;
    for y in 0..reference.height {
        for x in 0..reference.width {
            let (a, b) = (reference.rgba(x, y).unwrap(), other.rgba(x, y).unwrap());
            let (hit_a, hit_b) = (a != bg, b != bg);
            hits += hit_a as usize;
            mask_same += (hit_a == hit_b) as usize;
            colour_same += a.iter().zip(b).all(|(p, q)| p.abs_diff(q) <= CHANNEL_TOLERANCE) as usize;
        }
    }
    Comparison { mask: mask_same as f64 / n as f64, colour: colour_same as f64 / n as f64, hits }
}

fn check_backend(label: &str, mut renderer: impl Renderer, kernels: impl Fn(&str) -> KernelSources<'static>) {
    let mut cpu = CpuRenderer::new();
    for (name, compiled) in scenes::ALL {
        let scene = compiled.scene();
        for time in compared_times(scene) {
            check_frame(label, &mut cpu, &mut renderer, &kernels, name, compiled, time);
        }
    }
}

fn check_frame(
    label: &str,
    cpu: &mut CpuRenderer,
    renderer: &mut impl Renderer,
    kernels: &impl Fn(&str) -> KernelSources<'static>,
    name: &str,
    compiled: &'static fractal::dsl::CompiledScene,
    time: f64,
) {
    let scene = compiled.scene();
    let frame = frame_at(scene, time);
    let native = compiled.native();
    // Each frame in the precision its view asks for. One in f64 that the backend does not compute in is drawn by the
    // CPU: in f32 both draw rounding noise there, which need not agree
    // (`tests/fractal/precision.rs` judges those frames).
    let chosen = decide(PrecisionChoice::Auto, scene, &frame, &native, &native).unwrap();
    let sources = kernels(name);
    let job = RenderJob::new(sources, &frame).with_precision(chosen.precision);
    if !renderer.draws_in(&job) {
        eprintln!("{name:>22} {label:>14} t = {time:>4}: not drawn by the kernels, {chosen}");
        return;
    }
    let cpu_sources = KernelSources::default().with_cpu(&native, scene).with_cpu_wide(&native);
    let reference = cpu
        .render(&RenderJob::new(cpu_sources, &frame).with_precision(chosen.precision))
        .expect("the CPU renderer renders every built-in scene");
    let image = renderer.render(&job).unwrap_or_else(|e| panic!("{label} failed on {name}: {e}"));
    let c = compare(&reference, &image, background(scene));
    eprintln!(
        "{name:>22} {label:>14} t = {time:>4} in {}: hit mask {:.2} %, colour within {CHANNEL_TOLERANCE}/255 {:.2} % \
         ({} hit pixels)",
        chosen.precision,
        100.0 * c.mask,
        100.0 * c.colour,
        c.hits
    );
    assert!(c.hits > 0, "{name}: the reference image hits nothing");
    assert!(
        c.mask >= MASK_AGREEMENT,
        "{name} on {label} at t = {time}: hit masks agree on {:.2} % only",
        100.0 * c.mask
    );
    let required = if name == "mandelbrot_zoom" && time > 0.0 { DEEP_ZOOM_COLOUR_AGREEMENT } else { COLOUR_AGREEMENT };
    assert!(c.colour >= required, "{name} on {label} at t = {time}: colours agree on {:.2} % only", 100.0 * c.colour);
}

/// Of pixels, the share that must hit geometry at each scene's own camera and time: a scene that renders (nearly)
/// empty is a bug in its camera or its bounds.
const MIN_HIT_SHARE: f64 = 0.05;

#[test]
fn every_scene_draws_something_and_no_pixel_is_nan() {
    for (name, compiled) in scenes::ALL {
        let scene = compiled.scene();
        let frame = frame_of(scene);
        let traces = fractal::render::backend::cpu::trace_scene::<f32, _>(&compiled.native(), scene, &frame)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let hits = traces.iter().filter(|p| p.hit).count() as f64 / traces.len() as f64;
        assert!(hits >= MIN_HIT_SHARE, "{name}: only {:.1} % of the pixels hit geometry", 100.0 * hits);
        for (i, p) in traces.iter().enumerate() {
            let normal = p.normal.unwrap_or([0.0; 3]);
            let finite = p.colour.iter().chain(&normal).all(|v| v.is_finite()) && (p.t.is_finite() || !p.hit);
            assert!(finite, "{name}: pixel {i} has a NaN or Inf: {p:?}");
        }
    }
}

fn compiled(name: &str) -> &'static fractal::dsl::CompiledScene {
    scenes::by_name(name).expect("a built-in scene")
}

#[test]
fn wgpu_draws_what_the_cpu_draws() {
    match fractal::render::WgpuRenderer::new() {
        Ok(r) => check_backend("wgpu", r, |name| {
            KernelSources::default().with_wgsl(compiled(name).wgsl()).with_wgsl_f64(compiled(name).wgsl_f64())
        }),
        Err(e) if !backends_required() => eprintln!("skipped: no wgpu adapter ({e})"),
        Err(e) => panic!("wgpu is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
    }
}

#[cfg(feature = "opencl")]
#[test]
fn opencl_draws_what_the_cpu_draws() {
    for precise in [true, false] {
        let label = if precise { "opencl precise" } else { "opencl fast" };
        match fractal::render::OpenClRenderer::new(precise) {
            Ok(r) => check_backend(label, r, |name| {
                KernelSources::default()
                    .with_opencl(compiled(name).opencl())
                    .with_opencl_f64(compiled(name).opencl_f64())
            }),
            Err(e) if !backends_required() => eprintln!("skipped: no OpenCL device ({e})"),
            Err(e) => panic!("OpenCL is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
        }
    }
}

/// Scenes whose traces are compared: primitives, a fractal, an over-relaxed fractal with glow, a displaced surface
/// refined by its sign, repetition, a formula (shaded by its gradient) and a fractal starved of steps (rays out of
/// steps).
fn traced_scenes() -> Vec<(String, fractal::dsl::Scene)> {
    let mut out: Vec<(String, fractal::dsl::Scene)> =
        ["sphere_box", "mandelbulb", "julia", "terrain", "infinite_spheres", "cosine_bulb"]
            .into_iter()
            .map(|name| (name.to_string(), compiled(name).scene().clone()))
            .collect();
    out.push(("mandelbulb, 12 steps".to_string(), compiled("mandelbulb").scene().clone().max_steps(12)));
    out
}
/// Of the pixels both hit, the share whose depth, normal and step count must agree with the CPU's trace: depth
/// within [`TRACE_DEPTH_TOLERANCE`] of t, normals within [`TRACE_NORMAL_TOLERANCE`] degrees, steps within
/// [`TRACE_STEP_TOLERANCE`]. The march is the same f32 algorithm; where a GPU built-in rounds another way a ray can
/// stop a step earlier or later, which moves it by up to an epsilon along the ray and changes its count by one
/// (measured on lavapipe and pocl: at least 99.6 % agree on each).
const TRACE_AGREEMENT: f64 = 0.97;
const TRACE_DEPTH_TOLERANCE: f64 = 1e-3;
const TRACE_NORMAL_TOLERANCE: f64 = 2.0;
const TRACE_STEP_TOLERANCE: u32 = 1;

/// The trace kernels (the render's march with each pixel's depth, normal and steps kept: what the accuracy report
/// measures a GPU backend by) agree with the CPU's traces of the same frame, and draw the render kernel's image.
fn check_traces(label: &str, renderer: &mut impl Renderer, sources: impl Fn(&fractal::dsl::Kernels) -> KernelSources) {
    let mut cpu = CpuRenderer::new();
    for (name, scene) in traced_scenes() {
        let frame = frame_of(&scene);
        let interpreter = fractal::dsl::eval::interp::Interpreter::new(&scene).expect("a built-in scene interprets");
        let reference = cpu
            .trace(&RenderJob::new(KernelSources::default().with_cpu(&interpreter, &scene), &frame))
            .expect("the CPU renderer traces every built-in scene");
        let kernels = fractal::dsl::compile(&scene).expect("a built-in scene compiles");
        let tracing = kernels.tracing();
        let traced = renderer
            .trace(&RenderJob::new(sources(&tracing), &frame))
            .unwrap_or_else(|e| panic!("{label} failed to trace {name}: {e}"));
        let rendered = renderer.render(&RenderJob::new(sources(&kernels), &frame)).expect("it traced, so it renders");
        assert!(traced.image.pixels == rendered.pixels, "{name} on {label}: the trace kernel draws another image");
        let pairs: Vec<_> = reference.pixels.iter().zip(&traced.pixels).collect();
        let n = pairs.len() as f64;
        let mask = pairs.iter().filter(|(a, b)| a.hit == b.hit).count() as f64 / n;
        let out_of_steps = pairs.iter().filter(|(a, b)| a.out_of_steps == b.out_of_steps).count() as f64 / n;
        let both: Vec<_> = pairs.iter().filter(|(a, b)| a.hit && b.hit).collect();
        let share = |ok: &dyn Fn(&fractal::render::PixelTrace, &fractal::render::PixelTrace) -> bool| {
            both.iter().filter(|(a, b)| ok(a, b)).count() as f64 / both.len().max(1) as f64
        };
        let depth = share(&|a, b| (a.t - b.t).abs() <= TRACE_DEPTH_TOLERANCE * a.t);
        let normal = share(&|a, b| {
            let (a, b) = (a.normal.unwrap_or_default(), b.normal.unwrap_or_default());
            let cos = a.iter().zip(&b).map(|(x, y)| x * y).sum::<f64>().clamp(-1.0, 1.0);
            cos.acos().to_degrees() <= TRACE_NORMAL_TOLERANCE
        });
        let steps = share(&|a, b| a.steps.abs_diff(b.steps) <= TRACE_STEP_TOLERANCE);
        eprintln!(
            "{name:>20} {label:>6}: hit mask {:.2} %, out of steps {:.2} % ({} rays); of {} both hit: depth {:.2} %, \
             normal {:.2} %, steps {:.2} %",
            100.0 * mask,
            100.0 * out_of_steps,
            traced.pixels.iter().filter(|p| p.out_of_steps).count(),
            both.len(),
            100.0 * depth,
            100.0 * normal,
            100.0 * steps,
        );
        for (what, agreed, required) in [
            ("hit masks", mask, MASK_AGREEMENT),
            ("out-of-steps flags", out_of_steps, MASK_AGREEMENT),
            ("depths", depth, TRACE_AGREEMENT),
            ("normals", normal, TRACE_AGREEMENT),
            ("step counts", steps, TRACE_AGREEMENT),
        ] {
            assert!(agreed >= required, "{name} on {label}: {what} agree on {:.2} % only", 100.0 * agreed);
        }
    }
}

#[test]
fn gpu_traces_match_the_cpu_traces() {
    match fractal::render::WgpuRenderer::new() {
        Ok(mut r) => check_traces("wgpu", &mut r, |k| KernelSources::default().with_wgsl(&k.wgsl)),
        Err(e) if !backends_required() => eprintln!("wgpu skipped: no adapter ({e})"),
        Err(e) => panic!("wgpu is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
    }
    #[cfg(feature = "opencl")]
    match fractal::render::OpenClRenderer::new(false) {
        Ok(mut r) => check_traces("opencl", &mut r, |k| KernelSources::default().with_opencl(&k.opencl)),
        Err(e) if !backends_required() => eprintln!("OpenCL skipped: no device ({e})"),
        Err(e) => panic!("OpenCL is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
    }
}

/// A job whose kernels have no `trace` entry (the render kernels handed to `trace`) is a clear error, not a panic.
#[test]
fn tracing_a_render_kernel_is_an_error() {
    let compiled = compiled("hello_world");
    let frame = frame_of(compiled.scene());
    let refuses = |label: &str, r: &mut dyn Renderer, sources: KernelSources| {
        let job = RenderJob::new(sources, &frame);
        let e = r.trace(&job).expect_err("the render kernel has no trace entry");
        eprintln!("{label}: {e}");
        assert!(matches!(e, fractal::render::RenderError::KernelRejected { .. }), "{e}");
        assert!(r.render(&job).is_ok(), "{label} still renders after the refusal");
    };
    match fractal::render::WgpuRenderer::new() {
        Ok(mut r) => refuses("wgpu", &mut r, KernelSources::default().with_wgsl(compiled.wgsl())),
        Err(e) if !backends_required() => eprintln!("wgpu skipped: no adapter ({e})"),
        Err(e) => panic!("wgpu is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
    }
    #[cfg(feature = "opencl")]
    match fractal::render::OpenClRenderer::new(false) {
        Ok(mut r) => refuses("opencl", &mut r, KernelSources::default().with_opencl(compiled.opencl())),
        Err(e) if !backends_required() => eprintln!("OpenCL skipped: no device ({e})"),
        Err(e) => panic!("OpenCL is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {e}"),
    }
}
