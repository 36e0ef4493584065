//! The rule that picks a frame's precision from the view.
//!
//! f32 is enough while its rounding stays small beside what the ray program resolves at each hit: the hit epsilon
//! (the hit test compares the distance with it) and the normal's taps (the normal is a difference of distances that
//! far apart). A camera close to a fractal's surface makes both tiny — a tenth of a footprint 1e-4 from the
//! Mandelbulb is 1e-7, about one f32 step of coordinates near 1 — and a scene far from the origin makes the f32 step
//! of its coordinates large. [`choose`] measures it on the frame itself: it marches a [`PROBE`] grid of the frame's
//! rays in f64, and at each hit compares what f32 computes there with f64 ([`Probe`]): the hit point and the camera
//! position as f32 stores them, against the pixel's footprint; the distance, against the hit epsilon; the normal the
//! render shades with (tetrahedral, or a formula scene's gradient), computed as the f32 render computes it, against
//! f64's. A frame whose distance and normal figures stay within [`Limits`] (at [`QUANTILE`] of the probe's hits) is
//! drawn in f32; otherwise in f64. The figures say why. The rounding of the hit points is reported, not judged: a perturbed Mandelbrot zoom
//! ([`fractal_dsl::formula::mandelbrot`](mod@fractal_dsl::formula::mandelbrot)) reads its pattern from the ray's offset, not from the rounded point, and
//! is right in f32 where its points are rounded by millions of footprints; a distance or a normal that rounding
//! spoils shows in their own figures.
//!
//! f64 runs on the CPU renderer (its f64 instance, with the camera position the frame keeps to 48 bits). The wgpu
//! and OpenCL kernels compute in f32 and refuse a job in f64; double-single kernels are not built yet.

use fractal_dsl::analyse::{bound, fold::fold_node};
use fractal_dsl::eval::Evaluator;
use fractal_dsl::number::math::{dot, length, v3, V3};
use fractal_dsl::ray::SceneFns;
use fractal_dsl::Scene;

use crate::backend::cpu::View;
use crate::error::RenderError;
use crate::frame::Frame;
use crate::precision::{Chosen, Limits, Precision, PrecisionChoice, Probe, PROBE, QUANTILE};

/// The precision `choice` gives for `scene` seen through `frame`: the given one, or [`choose`]'s.
pub fn decide(
    choice: PrecisionChoice,
    scene: &Scene,
    frame: &Frame,
    evaluator: &dyn Evaluator<f32>,
    wide: &dyn Evaluator<f64>,
) -> Result<Chosen, RenderError> {
    match choice {
        PrecisionChoice::Only(precision) => {
            Ok(Chosen { precision, probe: None, reason: "as asked (--precision)".to_string() })
        }
        PrecisionChoice::Auto => choose(scene, frame, evaluator, wide, Limits::default()),
    }
}

/// Probes `frame` and picks the cheapest precision within `limits` (see the module notes).
pub fn choose(
    scene: &Scene,
    frame: &Frame,
    evaluator: &dyn Evaluator<f32>,
    wide: &dyn Evaluator<f64>,
    limits: Limits,
) -> Result<Chosen, RenderError> {
    let probe = probe(scene, frame, evaluator, wide)?;
    let over: Vec<String> = [
        (probe.distance, limits.distance, "its distances are", "hit epsilons"),
        (probe.normal_degrees, limits.normal_degrees, "its normals are", "°"),
    ]
    .into_iter()
    .filter(|(v, limit, _, _)| v.is_nan() || v > limit)
    .map(|(v, limit, what, unit)| format!("{what} {} {unit} off f64's (limit {limit})", show(v)))
    .collect();
    let at = format!("at the {:.0}th percentile of {} probe hits", 100.0 * QUANTILE, probe.hits);
    let (precision, reason) = if probe.hits == 0 {
        (Precision::F32, "no probe ray hits the scene".to_string())
    } else if over.is_empty() {
        let figures = format!(
            "distances {} hit epsilons and normals {}° off f64's, hit points rounded by {} footprints",
            show(probe.distance),
            show(probe.normal_degrees),
            show(probe.position)
        );
        (Precision::F32, format!("f32 is enough: {figures} ({at})"))
    } else {
        (Precision::F64, format!("in f32 {} ({at})", over.join(", ")))
    };
    Ok(Chosen { precision, probe: Some(probe), reason })
}

fn show(v: f64) -> String {
    if v.is_finite() && v != 0.0 && !(1e-3..1e4).contains(&v.abs()) {
        format!("{v:.1e}")
    } else {
        format!("{v:.3}")
    }
}

/// How far rounding `p` to f32 moves it.
fn f32_rounding(p: V3<f64>) -> f64 {
    length(v3(p.x - f64::from(p.x as f32), p.y - f64::from(p.y as f32), p.z - f64::from(p.z as f32)))
}

/// Marches the probe grid in f64 and measures f32 against it at each hit.
pub fn probe(
    scene: &Scene,
    frame: &Frame,
    evaluator: &dyn Evaluator<f32>,
    wide: &dyn Evaluator<f64>,
) -> Result<Probe, RenderError> {
    let scene_bound = bound(&fold_node(&scene.root));
    let view = View::<f64>::new(scene, frame, scene_bound)?;
    let narrow = View::<f32>::new(scene, frame, scene_bound)?;
    let (on, on32) = (view.on(wide), narrow.on(evaluator));
    let [ox, oy, oz] = frame.camera_origin();
    let origin_rounding = f32_rounding(v3(ox, oy, oz));
    let (w, h) = (frame.width() as f64, frame.height() as f64);
    let mut figures = Vec::new();
    for j in 0..PROBE.1 {
        for i in 0..PROBE.0 {
            let px = (i as f64 + 0.5) * w / PROBE.0 as f64;
            let py = (j as f64 + 0.5) * h / PROBE.1 as f64;
            let Some((p, t, eps, tap)) = view.probe_hit(&on, px, py) else { continue };
            let footprint = view.footprint() * t;
            let narrow_p = v3(p.x as f32, p.y as f32, p.z as f32);
            let position = (f32_rounding(p) + origin_rounding) / footprint;
            let d64 = on.distance(p);
            let d32 = f64::from(on32.distance(narrow_p));
            let distance = (d32 - d64).abs() / eps;
            // The normal each render shades with: the tetrahedral one, or a formula scene's gradient.
            let n64 = on.normal(p, tap);
            let n32 = on32.normal(narrow_p, tap as f32);
            let n32 = v3(f64::from(n32.x), f64::from(n32.y), f64::from(n32.z));
            let normal = (dot(n64, n32) / (length(n64) * length(n32))).clamp(-1.0, 1.0).acos().to_degrees();
            figures.push([position, distance, if normal.is_nan() { 180.0 } else { normal }]);
        }
    }
    let at = |k: usize| {
        let mut v: Vec<f64> = figures.iter().map(|f| f[k]).collect();
        v.sort_by(f64::total_cmp);
        v.get(((v.len().max(1) - 1) as f64 * QUANTILE).round() as usize).copied().unwrap_or(0.0)
    };
    Ok(Probe { hits: figures.len(), position: at(0), distance: at(1), normal_degrees: at(2) })
}
