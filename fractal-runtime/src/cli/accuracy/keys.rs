//! The camera path's other keys: a scene that flies a path is judged from each of its keys, not only from the time
//! the sweep was measured at (t = 0 unless `--time`), because a setting within budget at the first view can fail
//! further along (a close-up needs finer detail, an animated fractal has changed its shape).
//!
//! At each key the truth is computed again, at the iteration factor the sweep was judged against (the settling check
//! is not repeated), and the scene default is measured on the sweep's backend and on every `--also-on` backend. The
//! settings within budget at the sweep's time are then tried from the fastest down until one is within budget at
//! every key: the recommendation for the whole path.

use std::time::Instant;

use fractal_dsl::{CameraPlacement, Scene};
use fractal_render::device::Backend;
use fractal_render::frame::Frame;
use fractal_render::renderer::Renderer;
use fractal_render::{ParamValues, Pose};

use super::verdict::{capped, judged};
use crate::accuracy::sweep::{self, Budget, SweepPoint};
use crate::cli::error::CliError;
use crate::quality::Quality;
use crate::truth::{Truth, TruthSettings};

/// A backend of `--also-on`, opened once for all the frames it renders: the renderer, or why it did not open.
pub(super) type Opened = (Backend, Result<Box<dyn Renderer>, String>);

/// One key after t = 0: its time, the view from there, and the truth of that view.
struct KeyView {
    time: f64,
    position: [f64; 3],
    target: [f64; 3],
    frame: Frame,
    truth: Truth,
}

impl KeyView {
    fn name(&self) -> String {
        let p = |v: [f64; 3]| format!("({}, {}, {})", v[0], v[1], v[2]);
        format!("key t = {} s, {} → {}", self.time, p(self.position), p(self.target))
    }
}

/// The scene's path keys other than the one at `studied` (the sweep's time), or none when the camera is not a path
/// (or was overridden).
fn path_keys(scene: &Scene, studied: f64) -> Vec<(f64, [f64; 3], [f64; 3])> {
    match &scene.camera.placement {
        CameraPlacement::Path { keys, .. } => {
            keys.iter().filter(|k| k.time != studied).map(|k| (k.time, k.position, k.target)).collect()
        }
        CameraPlacement::LookAt { .. } => Vec::new(),
    }
}

/// Checks the scene default and the settings within budget at the sweep's time `studied` (`points`, judged against
/// the truth at `settings`) from every other key of the scene's camera path, telling `say` each key's truth, each key's
/// figures on each backend, then the verdicts on the default and on the fastest setting. Returns whether the scene has
/// such a key (nothing is said when not).
#[allow(clippy::too_many_arguments)]
pub(super) fn check(
    scene: &Scene,
    params: &ParamValues,
    size: (u32, u32),
    studied: f64,
    settings: TruthSettings,
    backend: Backend,
    mut renderer: Option<&mut Box<dyn Renderer>>,
    others: &mut [Opened],
    (points, own): (&[SweepPoint], &Quality),
    budget: &Budget,
    say: &mut dyn FnMut(String),
) -> Result<bool, CliError> {
    let keys = path_keys(scene, studied);
    if keys.is_empty() {
        return Ok(false);
    }
    let lookup = |p: &fractal_dsl::ParamDecl| params.lookup(p);
    let mut views = Vec::new();
    for (time, position, target) in keys {
        let pose = Pose::from_camera(&scene.camera, time, &lookup).map_err(|e| CliError::failure(e.to_string()))?;
        let frame =
            Frame::new(scene, &pose, time, size.0, size.1, params).map_err(|e| CliError::failure(e.to_string()))?;
        let start = Instant::now();
        let truth = Truth::compute(scene, &frame, settings)?;
        let hits = truth.pixels.iter().filter(|p| p.hit()).count();
        let view = KeyView { time, position, target, frame, truth };
        say(format!(
            "truth at {}: {:.2} % of pixels hit, at {}x the iterations{} ({:.1} s)",
            view.name(),
            100.0 * hits as f64 / view.truth.pixels.len().max(1) as f64,
            settings.iteration_factor,
            capped(scene, settings.iteration_factor),
            start.elapsed().as_secs_f64()
        ));
        views.push(view);
    }

    let mut default_fails = Vec::new();
    for view in &views {
        let point = measure(scene, view, backend, renderer.as_deref_mut(), own)?;
        let (line, violations) = judged(&point, budget);
        say(format!("{}: {} on {backend}: {line}", view.name(), point.quality));
        if !violations.is_empty() {
            default_fails.push(format!("{} ({})", view.name(), violations.join("; ")));
        }
        for (other, opened) in others.iter_mut() {
            let (setting, line) = match opened {
                Ok(r) => {
                    let point = measure(scene, view, *other, Some(r), own)?;
                    let (line, violations) = judged(&point, budget);
                    if !violations.is_empty() {
                        default_fails.push(format!("{} on {other} ({})", view.name(), violations.join("; ")));
                    }
                    (point.quality.to_string(), line)
                }
                Err(e) => ("scene default".to_string(), format!("not measured, the backend did not open ({e})")),
            };
            say(format!("{}: {setting} on {other}: {line}", view.name()));
        }
    }
    say(match (default_fails.is_empty(), views.len()) {
        (true, 1) => "the scene default is within budget at the path's other key too".to_string(),
        (true, n) => format!("the scene default is within budget at the path's {n} other keys too"),
        (false, _) => format!("the scene default is not within budget at {}", default_fails.join(", ")),
    });

    // The settings within budget at the sweep's time, fastest first: the first within budget at every key is the
    // path's.
    let mut candidates: Vec<&SweepPoint> = points.iter().filter(|p| budget.violations(&p.error).is_empty()).collect();
    candidates.sort_by(|a, b| a.time_ms.total_cmp(&b.time_ms));
    let mut rejected = Vec::new();
    let mut chosen = None;
    'candidates: for candidate in candidates {
        // The precision the setting was measured in at the sweep's time was that view's; each key's is its own
        // (unless `--precision` gave one).
        let setting = Quality { precision: own.precision, ..candidate.quality };
        for view in &views {
            let point = measure(scene, view, backend, renderer.as_deref_mut(), &setting)?;
            let violations = budget.violations(&point.error);
            if !violations.is_empty() {
                rejected.push(format!("{} fails at {} ({})", candidate.quality, view.name(), violations.join("; ")));
                continue 'candidates;
            }
        }
        chosen = Some(candidate);
        break;
    }
    let tried = |lead: &str| {
        if rejected.is_empty() {
            String::new()
        } else {
            format!("{lead}{}", rejected.join(", "))
        }
    };
    say(match chosen {
        Some(p) => format!(
            "fastest within budget at t = {studied} s and every other key: {} ({:.1} ms at t = {studied} s){}",
            p.quality,
            p.time_ms,
            tried(&format!("; faster at t = {studied} s but not within budget at every key: "))
        ),
        None => format!("no setting within budget at t = {studied} s is within it at every other key{}", tried(": ")),
    });
    Ok(true)
}

/// One setting rendered from `view` on `backend` against its truth.
fn measure(
    scene: &Scene,
    view: &KeyView,
    backend: Backend,
    renderer: Option<&mut Box<dyn Renderer>>,
    quality: &Quality,
) -> Result<SweepPoint, CliError> {
    let points =
        sweep::run(scene, &view.frame, &view.truth, backend, renderer, std::slice::from_ref(quality), &mut |_| {})?;
    Ok(points.into_iter().next().expect("one setting gives one point"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::*;

    /// A sphere seen whole from its first key and grazed from a close-up at its second: a step budget that is enough
    /// for the first view runs out at the second, so the path's recommendation is not the setting fastest at t = 0.
    #[test]
    fn a_setting_within_budget_at_t_0_that_fails_at_another_key_is_not_the_paths_recommendation() {
        let s = scene(sphere(1.0))
            .camera(camera_path([key(0.0, [0.0, 0.0, -6.0], [0.0; 3]), key(2.0, [0.0, 0.0, -1.05], [0.0, 0.9, 0.0])]));
        let params = ParamValues::defaults(&s);
        let size = (24, 16);
        let settings = TruthSettings { step_footprints: 0.05, iteration_factor: 1 };
        let frame = Frame::default_view(&s, 0.0, size.0, size.1).unwrap();
        let truth = Truth::compute(&s, &frame, settings).unwrap();
        let few_steps = Quality { max_steps: Some(12), ..Quality::default() };
        let mut points =
            sweep::run(&s, &frame, &truth, Backend::Cpu, None, &[Quality::default(), few_steps], &mut |_| {}).unwrap();
        let budget = Budget::default();
        assert!(points.iter().all(|p| budget.violations(&p.error).is_empty()), "both within budget at t = 0");
        // The timings of so small a frame are noise: the few steps made the faster.
        points[0].time_ms = 2.0;
        points[1].time_ms = 1.0;

        let mut lines = Vec::new();
        let mut say = |line| lines.push(line);
        let said = check(
            &s,
            &params,
            size,
            0.0,
            settings,
            Backend::Cpu,
            None,
            &mut [],
            (&points, &Quality::default()),
            &budget,
            &mut say,
        );
        assert!(said.unwrap());
        let text = lines.join("\n");
        assert!(text.contains("truth at key t = 2 s, (0, 0, -1.05) → (0, 0.9, 0)"), "{text}");
        assert!(text.contains("key t = 2 s, (0, 0, -1.05) → (0, 0.9, 0): scene default on cpu"), "{text}");
        assert!(text.contains("the scene default is within budget at the path's other key too"), "{text}");
        assert!(
            text.contains("faster at t = 0 s but not within budget at every key: steps 12 fails at key t = 2 s"),
            "{text}"
        );
        assert!(text.contains("out of steps"), "{text}");
        assert!(text.contains("fastest within budget at t = 0 s and every other key: scene default"), "{text}");

        // A camera that is not a path has no other key.
        let fixed = scene(sphere(1.0));
        let mut silent = |line: String| panic!("said {line}");
        let said = check(
            &fixed,
            &params,
            size,
            0.0,
            settings,
            Backend::Cpu,
            None,
            &mut [],
            (&points, &Quality::default()),
            &budget,
            &mut silent,
        );
        assert!(!said.unwrap());
    }
}
