//! A sweep of quality settings on one backend: each setting rendered, timed and measured against the truth, and the
//! error budget the recommended setting must meet.
//!
//! The CPU backend renders with the f32 interpreter of the scene with the setting applied (the same evaluator for
//! every setting, so times compare) and gives every figure; wgpu and OpenCL time the render kernels compiled for the
//! setting and measure the same march through its trace kernels (every figure but the count of distance
//! evaluations), and cannot scale the step factor. OpenCL also sweeps its
//! math: the kernels built with and without `-cl-fast-relaxed-math`.

use std::time::Instant;

use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::{HitEpsilon, Node, Scene};

use crate::accuracy::metrics::{measure, Observed, TrueError};
use crate::quality::{Quality, StepScaled};
use crate::truth::Truth;
use fractal_dsl::analyse::{bound, fold::fold_node};
use fractal_dsl::validate::check_membership_hits;
use fractal_render::backend::cpu::{trace_scene_with, MarchLevers, PixelTrace};
use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::precision::Precision;
use fractal_render::renderer::{KernelSources, RenderJob, Renderer};
use fractal_render::select::RendererOptions;

/// Renders per timing; the median is reported.
pub const TIMING_RUNS: usize = 3;

/// Fewest measured normals whose p99 the budget judges: the p99 of fewer is their maximum. A fractal seen small is
/// rough at the pixel's scale almost everywhere, so few of its normals can be measured at all.
pub const MIN_NORMALS: usize = 100;

/// A truth has settled in what the budget judges when doubling its iterations moves none of the scene default's
/// judged figures by more than this share of the figure's limit (a truth less certain than that cannot judge it).
pub const SETTLED_SHARE: f64 = 0.25;

/// The error a recommended setting may have.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Budget {
    /// Fraction of pixels.
    pub hit_mismatch: f64,
    /// Fraction of pixels, cone-consistent.
    pub overshoot: f64,
    /// Degrees.
    pub normal_p99: f64,
    /// Footprints, cone-consistent, over interior pixels.
    pub depth_p99_interior: f64,
    /// Footprints, thin-ray, median over the pixels where the true surface is smooth at the pixel's scale (judged
    /// over at least [`MIN_NORMALS`] of them).
    pub depth_median_smooth: f64,
}

impl Default for Budget {
    fn default() -> Self {
        Budget {
            hit_mismatch: 0.005,
            overshoot: 0.001,
            normal_p99: 5.0,
            depth_p99_interior: 1.0,
            depth_median_smooth: 1.0,
        }
    }
}

impl Budget {
    /// The ways `e` exceeds the budget (empty: within it). Rays out of steps and NaN/Inf pixels allow none.
    pub fn violations(&self, e: &TrueError) -> Vec<String> {
        let mut out: Vec<String> = self
            .against_truth(e)
            .into_iter()
            .filter_map(|f| f.value.filter(|&v| v > f.limit).map(f.violation))
            .collect();
        if let Some(t) = &e.traced {
            if t.out_of_steps > 0.0 {
                out.push(format!("{:.2} % out of steps", 100.0 * t.out_of_steps));
            }
            if t.non_finite > 0 {
                out.push(format!("{} NaN/Inf", t.non_finite));
            }
        }
        out
    }

    /// The figures of `e` the budget judges against the truth. Rays out of steps and NaN/Inf pixels read no truth.
    fn against_truth(&self, e: &TrueError) -> [JudgedFigure; 5] {
        let t = e.traced.as_ref();
        [
            JudgedFigure {
                name: "hit mismatch %",
                value: Some(100.0 * e.hit_mismatch()),
                limit: 100.0 * self.hit_mismatch,
                violation: |v| format!("hit mismatch {v:.2} %"),
            },
            JudgedFigure {
                name: "overshoot %",
                value: t.map(|t| 100.0 * t.overshoot_cone),
                limit: 100.0 * self.overshoot,
                violation: |v| format!("overshoot {v:.2} %"),
            },
            JudgedFigure {
                name: "normal p99°",
                value: t.filter(|t| t.normal_cone.count >= MIN_NORMALS).map(|t| t.normal_cone.p99),
                limit: self.normal_p99,
                violation: |v| format!("normal p99 {v:.1}°"),
            },
            JudgedFigure {
                name: "depth p99",
                value: t.map(|t| t.depth_cone_interior.p99),
                limit: self.depth_p99_interior,
                violation: |v| format!("depth p99 {v:.2}"),
            },
            JudgedFigure {
                name: "depth p50 smooth",
                value: t.filter(|t| t.depth_smooth.count >= MIN_NORMALS).map(|t| t.depth_smooth.median),
                limit: self.depth_median_smooth,
                violation: |v| {
                    format!("thin-ray depth median {v:.2} footprints on surfaces smooth at the pixel's scale")
                },
            },
        ]
    }

    /// The judged figures of one render that moved by more than [`SETTLED_SHARE`] of their limit from its error
    /// `before` (against a truth) to `after` (against the truth at twice the iterations), as "depth p99 1.89 → 3.38";
    /// empty when the truth has settled in them. A figure measured against one of the truths only has not settled.
    pub fn moved(&self, before: &TrueError, after: &TrueError) -> Vec<String> {
        let show = |v: Option<f64>| v.map_or("unmeasured".to_string(), |v| format!("{v:.2}"));
        self.against_truth(before)
            .into_iter()
            .zip(self.against_truth(after))
            .filter(|(a, b)| match (a.value, b.value) {
                (Some(x), Some(y)) if x.is_nan() || y.is_nan() => x.is_nan() != y.is_nan(),
                (Some(x), Some(y)) => (y - x).abs() > SETTLED_SHARE * a.limit,
                (None, None) => false,
                _ => true,
            })
            .map(|(a, b)| format!("{} {} → {}", a.name, show(a.value), show(b.value)))
            .collect()
    }

    /// The budget's verdict on `e`: its violations and what it left unjudged (a normal p99 over fewer than
    /// [`MIN_NORMALS`] measured normals).
    pub fn verdict(&self, e: &TrueError) -> Verdict {
        let unjudged = e
            .traced
            .as_ref()
            .filter(|t| t.normal_cone.count < MIN_NORMALS)
            .map(|t| format!("normals unjudged, {} measured", t.normal_cone.count));
        Verdict { violations: self.violations(e), unjudged }
    }
}

/// One figure the budget judges against the truth: its name, its value (`None` where not measured: an image's traced
/// figures, a normal p99 over fewer than [`MIN_NORMALS`]), its limit and how a value over it is said.
struct JudgedFigure {
    name: &'static str,
    value: Option<f64>,
    limit: f64,
    violation: fn(f64) -> String,
}

/// A verdict of the [`Budget`], written so it never reads as a pass on what it did not measure: "within budget" or
/// the violations, then what was left unjudged in brackets.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// The ways the error exceeds the budget (empty: within it).
    pub violations: Vec<String>,
    /// What the budget did not judge.
    pub unjudged: Option<String>,
}

impl Verdict {
    /// The verdict as a sentence's end: "within budget …" or "not within budget: …".
    pub fn sentence(&self) -> String {
        if self.violations.is_empty() {
            self.to_string()
        } else {
            format!("not within budget: {self}")
        }
    }
}

impl std::fmt::Display for Verdict {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.violations.is_empty() {
            f.write_str("within budget")?;
        } else {
            f.write_str(&self.violations.join("; "))?;
        }
        match &self.unjudged {
            Some(unjudged) => write!(f, " ({unjudged})"),
            None => Ok(()),
        }
    }
}

/// One measured setting.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepPoint {
    pub quality: Quality,
    /// Median render time in milliseconds.
    pub time_ms: f64,
    pub error: TrueError,
}

/// The settings a sweep tries on `scene` with `backend` (one at a time around its own, then a few combinations), the
/// scene's own first. The step factor and the bound are only varied on the CPU, the math only on OpenCL, where
/// `precise` is the sweep's own choice.
pub fn grid(scene: &Scene, backend: Backend, precise: bool) -> Vec<Quality> {
    let on_cpu = backend == Backend::Cpu;
    let own = &scene.settings;
    let mut out = vec![Quality::default()];
    for n in [32, 64, 96, 192, 256, 512] {
        if n != own.max_steps {
            out.push(Quality { max_steps: Some(n), ..Quality::default() });
        }
    }
    let fixed = match own.epsilon {
        HitEpsilon::Fixed(e) => e,
        HitEpsilon::Pixel(_) => 0.0005,
    };
    for e in [fixed * 0.25, fixed * 4.0, 0.002] {
        out.push(Quality { epsilon: Some(HitEpsilon::Fixed(e)), ..Quality::default() });
    }
    for k in [0.05, 0.1, 0.25, 0.5, 1.0, 2.0] {
        out.push(Quality { epsilon: Some(HitEpsilon::Pixel(k)), ..Quality::default() });
    }
    if let Some(n) = escape_time_iterations(scene) {
        for m in [n.saturating_sub(2).max(1), n + 2, n + 4] {
            out.push(Quality { iterations: Some(m), ..Quality::default() });
        }
    }
    if on_cpu && bound(&fold_node(&scene.root)).is_some() {
        out.push(Quality { bounds: Some(false), ..Quality::default() });
    }
    for w in [1.0, 1.2, 1.3, 1.4, 1.5] {
        if w != own.over_relaxation {
            out.push(Quality { over_relaxation: Some(w), ..Quality::default() });
        }
    }
    if backend == Backend::OpenCl {
        out.push(Quality { precise: Some(!precise), ..Quality::default() });
    }
    // The normal at the pixel's scale, apart from the hit epsilon.
    for k in [0.1, 0.25, 0.5, 1.0] {
        if own.normal_epsilon != Some(k) {
            out.push(Quality { normal: Some(k), ..Quality::default() });
        }
    }
    // A finer pixel epsilon with the steps to reach it, plain and over-relaxed, and for an escape-time set with the
    // iterations to come near its limit: the combinations that can keep a pixel epsilon's fattening of the surface,
    // and the fatter set of few iterations, within budget.
    for k in [0.025, 0.05, 0.1] {
        let finer = Quality { epsilon: Some(HitEpsilon::Pixel(k)), max_steps: Some(256), ..Quality::default() };
        out.push(finer);
        out.push(Quality { over_relaxation: Some(1.3), ..finer });
        // A fine epsilon takes the normal from detail far below the pixel: the same hits with it at the pixel's scale.
        out.push(Quality { normal: Some(0.5), ..finer });
        if let Some(n) = escape_time_iterations(scene) {
            out.push(Quality { over_relaxation: Some(1.3), iterations: Some(n + 4), ..finer });
        }
    }
    // Hits on the escape-time sets themselves, where the estimate may stop rays far in front of them, with the
    // iterations that bring the drawn set near its limit.
    if check_membership_hits(&scene.root).is_empty() {
        let flipped = Quality { membership: Some(!own.membership_hits), ..Quality::default() };
        out.push(flipped);
        if let (false, Some(n)) = (own.membership_hits, escape_time_iterations(scene)) {
            out.extend([2, 4].map(|f| Quality { iterations: Some(n * f), ..flipped }));
        }
    }
    if on_cpu {
        for s in [0.8, 1.2, 4.0 / 3.0] {
            out.push(Quality { step_scale: Some(s), ..Quality::default() });
        }
        // A longer step with the budget to finish, and the same with a pixel epsilon.
        out.push(Quality { step_scale: Some(4.0 / 3.0), max_steps: Some(256), ..Quality::default() });
        out.push(Quality {
            step_scale: Some(4.0 / 3.0),
            max_steps: Some(256),
            epsilon: Some(HitEpsilon::Pixel(0.5)),
            ..Quality::default()
        });
    }
    out.dedup();
    out
}

/// The iteration count of the scene's first escape-time fractal, if it has one.
pub fn escape_time_iterations(scene: &Scene) -> Option<u32> {
    fn find(node: &Node) -> Option<u32> {
        match node {
            Node::Fractal(f) if f.decl().membership.approaches_limit => Some(f.iterations_or_default()),
            _ => node.children().iter().find_map(find),
        }
    }
    find(&scene.root)
}

/// Renders `quality` on the CPU with per-pixel traces, `TIMING_RUNS` times.
fn run_cpu(scene: &Scene, quality: &Quality, frame: &Frame, truth: &Truth) -> Result<SweepPoint, RenderError> {
    let applied = quality.apply(scene);
    let mut times = Vec::new();
    let mut traces = Vec::new();
    for _ in 0..TIMING_RUNS {
        let start = Instant::now();
        traces = trace_cpu(&applied, quality, frame)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    let error = measure(&applied, truth, Observed::Traced(&traces));
    Ok(SweepPoint { quality: *quality, time_ms: median(times), error })
}

/// One CPU render of `applied` (a scene with `quality` applied) with per-pixel traces, as a sweep times it.
pub fn trace_cpu(applied: &Scene, quality: &Quality, frame: &Frame) -> Result<Vec<PixelTrace>, RenderError> {
    let interpreter = Interpreter::new(applied)?;
    let scaled = StepScaled { inner: &interpreter, scale: quality.step_scale() as f32 };
    let levers = MarchLevers {
        bound: match quality.bounds {
            Some(false) => None,
            _ => bound(&fold_node(&applied.root)),
        },
    };
    let wide = StepScaled { inner: &interpreter, scale: quality.step_scale() };
    match quality.precision {
        Some(Precision::F64) => trace_scene_with::<f64, _>(&wide, applied, frame, levers),
        _ => trace_scene_with::<f32, _>(&scaled, applied, frame, levers),
    }
}

/// Renders `quality` with the kernels compiled for it on a GPU backend.
fn run_kernels(
    renderer: &mut dyn Renderer,
    scene: &Scene,
    quality: &Quality,
    frame: &Frame,
    truth: &Truth,
) -> Result<SweepPoint, RenderError> {
    let applied = quality.apply(scene);
    let kernels = fractal_dsl::compile(&applied)?;
    let precision = quality.precision.unwrap_or_default();
    let job = RenderJob::new(KernelSources::compiled(&kernels), frame).with_precision(precision);
    // The first render builds the kernel; it is not timed.
    renderer.render(&job)?;
    let mut times = Vec::new();
    for _ in 0..TIMING_RUNS {
        let start = Instant::now();
        renderer.render(&job)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    // The render kernel's march, read back by its trace kernel: the same steps, with depth, normal and steps kept.
    let tracing = kernels.tracing();
    let traced = renderer.trace(&RenderJob::new(KernelSources::compiled(&tracing), frame).with_precision(precision))?;
    let error = measure(&applied, truth, Observed::Traced(&traced.pixels));
    Ok(SweepPoint { quality: *quality, time_ms: median(times), error })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// `quality` with its precision decided: as given, or the one the view asks for with the setting applied
/// ([`fractal_render::choose_precision`], through the interpreter).
pub fn with_precision(scene: &Scene, quality: &Quality, frame: &Frame) -> Result<Quality, RenderError> {
    if quality.precision.is_some() {
        return Ok(*quality);
    }
    let applied = quality.apply(scene);
    let interpreter = Interpreter::new(&applied)?;
    let chosen = fractal_render::choose_precision::decide(
        fractal_render::precision::PrecisionChoice::Auto,
        &applied,
        frame,
        &interpreter,
        &interpreter,
    )?;
    Ok(Quality { precision: Some(chosen.precision), ..*quality })
}

/// Measures every setting of `qualities` on `backend` against `truth`. `renderer` is the opened GPU renderer (unused
/// for the CPU). A setting in f64 the backend does not compute in (a device without f64) is measured on
/// the CPU, as the auto renderer would draw it. `progress` is told each finished point.
pub fn run(
    scene: &Scene,
    frame: &Frame,
    truth: &Truth,
    backend: Backend,
    mut renderer: Option<&mut Box<dyn Renderer>>,
    qualities: &[Quality],
    progress: &mut dyn FnMut(&SweepPoint),
) -> Result<Vec<SweepPoint>, RenderError> {
    let mut out = Vec::new();
    for q in qualities {
        let q = &with_precision(scene, q, frame)?;
        let drawn = match (backend, renderer.as_mut(), q.precise) {
            (Backend::Cpu, _, _) | (_, None, _) => run_cpu(scene, q, frame, truth),
            // The other math is another build of the program: a renderer of its own.
            (_, Some(_), Some(precise)) => {
                let mut other = fractal_render::select::open(backend, &RendererOptions { precise })?;
                run_kernels(other.as_mut(), scene, q, frame, truth)
            }
            (_, Some(r), None) => run_kernels(r.as_mut(), scene, q, frame, truth),
        };
        let point = match drawn {
            Err(RenderError::Precision { .. }) => run_cpu(scene, q, frame, truth)?,
            drawn => drawn?,
        };
        progress(&point);
        out.push(point);
    }
    Ok(out)
}

/// The points no other point beats on both `time` and `error` (lower is better for both), by increasing time.
pub fn pareto<T>(points: &[T], time: impl Fn(&T) -> f64, error: impl Fn(&T) -> f64) -> Vec<&T> {
    let mut sorted: Vec<&T> = points.iter().collect();
    sorted.sort_by(|a, b| time(a).total_cmp(&time(b)).then(error(a).total_cmp(&error(b))));
    let mut front = Vec::new();
    let mut best = f64::INFINITY;
    for p in sorted {
        if error(p) < best {
            best = error(p);
            front.push(p);
        }
    }
    front
}

/// The fastest point within the budget.
pub fn recommended<'a>(points: &'a [SweepPoint], budget: &Budget) -> Option<&'a SweepPoint> {
    points.iter().filter(|p| budget.violations(&p.error).is_empty()).min_by(|a, b| a.time_ms.total_cmp(&b.time_ms))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::truth::TruthSettings;
    use fractal_dsl::builder::*;

    /// A verdict names what it did not judge: a normal p99 over too few normals passes, and says so.
    #[test]
    fn a_verdict_names_the_normals_it_did_not_judge() {
        use crate::accuracy::metrics::{Spread, TracedError};
        let budget = Budget::default();
        let error = |count, p99| TrueError {
            traced: Some(TracedError {
                normal_cone: Spread { count, median: 1.0, p99, max: p99 },
                ..TracedError::default()
            }),
            ..TrueError::default()
        };
        assert_eq!(budget.verdict(&error(MIN_NORMALS, 1.0)).to_string(), "within budget");
        assert_eq!(budget.verdict(&error(12, 40.0)).to_string(), "within budget (normals unjudged, 12 measured)");
        assert_eq!(budget.verdict(&error(MIN_NORMALS, 40.0)).to_string(), "normal p99 40.0°");
    }

    /// A truth has settled in what the budget judges when doubling its iterations moves no judged figure of the
    /// scene default by more than a quarter of its limit; a figure measured against one truth only has not settled.
    #[test]
    fn a_truth_settles_when_the_defaults_judged_figures_stop_moving() {
        use crate::accuracy::metrics::{Spread, TracedError};
        let budget = Budget::default();
        let error = |depth_p99, normals| TrueError {
            traced: Some(TracedError {
                depth_cone_interior: Spread { count: 500, median: 0.2, p99: depth_p99, max: depth_p99 },
                normal_cone: Spread { count: normals, median: 1.0, p99: 4.0, max: 4.0 },
                ..TracedError::default()
            }),
            ..TrueError::default()
        };
        assert!(budget.moved(&error(0.5, 200), &error(0.7, 200)).is_empty());
        assert_eq!(budget.moved(&error(1.89, 200), &error(3.38, 200)), ["depth p99 1.89 → 3.38"]);
        assert_eq!(budget.moved(&error(0.5, 200), &error(0.5, 80)), ["normal p99° 4.00 → unmeasured"]);
        // Under MIN_NORMALS against both truths, the normals are judged against neither.
        assert!(budget.moved(&error(0.5, 12), &error(0.5, 80)).is_empty());
    }

    /// Clipping to the bound is a lever the CPU sweep turns off where the scene has a bound; off, the march covers
    /// the whole ray and must find the same surface, only with more evaluations.
    #[test]
    fn the_bound_is_a_lever_of_bounded_scenes_on_the_cpu() {
        let bounded = scene(sphere(1.0)).camera(camera([0.0, 0.5, -3.0], [0.0; 3]));
        let open = scene(union(sphere(1.0), plane(vec3(0.0, 1.0, 0.0), 1.0)));
        let off = |s: &Scene, b| grid(s, b, false).iter().any(|q| q.bounds == Some(false));
        assert!(off(&bounded, Backend::Cpu) && !off(&bounded, Backend::Wgpu) && !off(&open, Backend::Cpu));
        // The math is a lever of OpenCL alone: the other build than the sweep's own.
        let math = |b, precise| grid(&bounded, b, precise).iter().filter_map(|q| q.precise).collect::<Vec<_>>();
        assert_eq!(math(Backend::OpenCl, false), [true]);
        assert_eq!(math(Backend::OpenCl, true), [false]);
        assert!(math(Backend::Cpu, false).is_empty() && math(Backend::Wgpu, false).is_empty());

        let frame = Frame::default_view(&bounded, 0.0, 24, 16).unwrap();
        let truth = Truth::compute(&bounded, &frame, TruthSettings::default()).unwrap();
        let clipped = run_cpu(&bounded, &Quality::default(), &frame, &truth).unwrap();
        let unclipped =
            run_cpu(&bounded, &Quality { bounds: Some(false), ..Quality::default() }, &frame, &truth).unwrap();
        assert_eq!(unclipped.quality.to_string(), "no bounds");
        assert_eq!(clipped.error.hit_mismatch(), 0.0);
        assert_eq!(unclipped.error.hit_mismatch(), 0.0);
        let evaluations = |p: &SweepPoint| p.error.traced.as_ref().unwrap().evaluations_per_pixel.unwrap();
        assert!(
            evaluations(&unclipped) > evaluations(&clipped),
            "{} vs {}",
            evaluations(&unclipped),
            evaluations(&clipped)
        );
    }

    /// A kernel render is judged on its trace kernel's march: every figure but the evaluation count, and its hit mask
    /// even where glow tints the misses of its image.
    #[test]
    fn a_kernel_render_is_judged_on_its_traced_march() {
        let glowing = scene(sphere(1.0)).camera(camera([0.0, 0.0, -3.0], [0.0; 3])).glow(rgb(0.2, 0.4, 1.0));
        let frame = Frame::default_view(&glowing, 0.0, 24, 16).unwrap();
        let truth = Truth::compute(&glowing, &frame, TruthSettings::default()).unwrap();
        let mut renderer = match fractal_render::select::open(Backend::Wgpu, &RendererOptions::default()) {
            Ok(r) => r,
            Err(e) if fractal_render::device::backends_required() => {
                panic!("wgpu required but unavailable: {e}")
            }
            Err(e) => return eprintln!("wgpu skipped: {e}"),
        };
        let point = run_kernels(renderer.as_mut(), &glowing, &Quality::default(), &frame, &truth).unwrap();
        assert!(point.error.psnr.is_finite() && point.error.hit_mismatch() < 0.01, "{}", point.error.describe());
        let traced = point.error.traced.as_ref().expect("the trace kernel's figures");
        assert!(traced.normal.count > 0 && traced.normal.p99 < 5.0, "{}", point.error.describe());
        assert!(traced.depth_thin.p99 < 1.0 && traced.evaluations_per_pixel.is_none(), "{}", point.error.describe());
        let blunt = Quality { epsilon: Some(HitEpsilon::Pixel(4.0)), ..Quality::default() };
        let point = run_kernels(renderer.as_mut(), &glowing, &blunt, &frame, &truth).unwrap();
        assert!(point.error.false_hits > 0.01, "{}", point.error.describe());
    }

    /// Over-relaxation with its fallback finds the same surface in fewer steps; a factor of 2 would step through
    /// thin walls without the fallback, so it is the test of the fallback too.
    #[test]
    fn over_relaxation_keeps_the_surface_and_saves_evaluations() {
        // A floor the rays graze (long marches) and a thin wall.
        let thin = scene(union_all([
            box3(vec3(1.0, 1.0, 0.02)),
            sphere(0.5).translate(vec3(0.0, 0.0, 2.0)),
            plane(vec3(0.0, 1.0, 0.0), 1.0),
        ]))
        .camera(camera([0.4, -0.7, -4.0], [0.0, -0.9, 0.0]))
        .max_steps(400);
        let frame = Frame::default_view(&thin, 0.0, 32, 24).unwrap();
        let truth = Truth::compute(&thin, &frame, TruthSettings::default()).unwrap();
        let plain = run_cpu(&thin, &Quality::default(), &frame, &truth).unwrap();
        let evaluations = |p: &SweepPoint| p.error.traced.as_ref().unwrap().evaluations_per_pixel.unwrap();
        for omega in [1.2, 2.0] {
            let relaxed =
                run_cpu(&thin, &Quality { over_relaxation: Some(omega), ..Quality::default() }, &frame, &truth)
                    .unwrap();
            assert_eq!(relaxed.quality.to_string(), format!("relax {omega}"));
            assert_eq!(relaxed.error.hit_mismatch(), plain.error.hit_mismatch(), "ω = {omega}");
            assert_eq!(relaxed.error.traced.as_ref().unwrap().overshoot, 0.0, "ω = {omega}");
            assert!(
                evaluations(&relaxed) < evaluations(&plain),
                "ω = {omega}: {} vs {}",
                evaluations(&relaxed),
                evaluations(&plain)
            );
        }
    }
}
