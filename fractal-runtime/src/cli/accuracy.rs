//! `fractal accuracy`: sweeps quality settings of a scene on one backend against the ground truth
//! ([`crate::truth`]), prints the table and the fastest setting within the error budget, appends CSV rows, and with
//! `--report` does it for every built-in scene and writes the Markdown report; with `--image`, the scene default's
//! image against the truth of the image instead ([`image`]).

use std::fmt::Write as _;
use std::io::Write as _;
use std::time::Instant;

use fractal_render::device::Backend;
use fractal_render::frame::Frame;
use fractal_render::select::{BackendChoice, RendererOptions};
use fractal_render::Pose;

use crate::accuracy::sweep::{self, Budget};
use crate::accuracy::{metrics, plot, table};
use crate::cli::args::AccuracyArgs;
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary};
use crate::output::png::prepare_output;
use crate::quality::Quality;
use crate::truth::{self, Truth, TruthSettings};

mod files;
pub mod image;
mod keys;
mod verdict;

use files::{plot_dir, report_path, write_plot};

use verdict::{capped, judged};

/// Factor on the iteration count of the escape-time sets the estimator study measures against.
pub const CONVERGED_FACTOR: u32 = 2;
/// The truth of an escape-time fractal has converged when doubling its iterations moves less than this share of the
/// hit mask.
pub const CONVERGED_MASK: f64 = 0.001;
/// Largest factor on the iterations the truth goes to.
pub const MAX_TRUTH_FACTOR: u32 = 8;

pub fn accuracy(args: &AccuracyArgs, library: &SceneLibrary) -> Result<(), CliError> {
    let backend = match args.backend {
        BackendChoice::Only(b) => b,
        BackendChoice::Auto => {
            return Err(CliError::usage("accuracy needs one backend: --backend cpu, wgpu or opencl"))
        }
    };
    if args.image {
        return image::run(args, library, backend);
    }
    if let Some(path) = &args.csv {
        prepare_output(path)?;
    }
    let out = report_path(args);
    if args.report {
        prepare_output(&out)?;
    }
    if args.estimators {
        match &args.scene {
            Some(name) => scene_estimator_study(name, library, args.estimator_samples as usize)?,
            None => drop(estimator_study(args.estimator_samples as usize)),
        }
        return Ok(());
    }
    let names: Vec<String> = match (&args.scene, args.report) {
        (Some(name), false) => vec![name.clone()],
        (Some(_), true) => return Err(CliError::usage("--report studies every built-in scene: give no scene with it")),
        (None, true) if args.time != 0.0 => {
            return Err(CliError::usage(
                "--report studies each scene at t = 0 and its camera path's keys: give no --time with it",
            ))
        }
        (None, _) => library.scenes.iter().map(|(n, _)| n.to_string()).collect(),
    };
    let budget = Budget::default();
    let mut report = String::new();
    for name in &names {
        let mut loaded = LoadedScene::load(name, library)?;
        args.camera.apply(&mut loaded.scene.camera);
        if args.samples.len() > 1 {
            return Err(CliError::usage("a list of --samples is for --image; the sweep takes one count"));
        }
        loaded.set_samples(args.samples.first().copied())?;
        let section = study(&loaded, args, backend, &budget)?;
        report += &section;
    }
    if args.report {
        // The estimators do not depend on the image's size: a report of the defaults at another size leaves them
        // to the full report.
        if !args.default_only {
            report += &estimator_study(args.estimator_samples as usize);
        }
        let text = report_text(args, backend, &budget, &report);
        std::fs::write(&out, text).map_err(|e| CliError::failure(format!("cannot write {}: {e}", out.display())))?;
        eprintln!("wrote {}", out.display());
    }
    Ok(())
}

/// One scene: truths, sweep, table, CSV; returns its Markdown section.
fn study(loaded: &LoadedScene, args: &AccuracyArgs, backend: Backend, budget: &Budget) -> Result<String, CliError> {
    let scene = &loaded.scene;
    // Read before the truth, so a malformed file is said at once.
    let given_normals = args.judge_normals.as_deref().map(read_normals).transpose()?;
    let params = loaded.params(&[])?;
    let lookup = |p: &fractal_dsl::ParamDecl| params.lookup(p);
    let pose = Pose::from_camera(&scene.camera, args.time, &lookup).map_err(|e| CliError::failure(e.to_string()))?;
    let (w, h) = args.size;
    let frame = Frame::new(scene, &pose, args.time, w, h, &params).map_err(|e| CliError::failure(e.to_string()))?;
    let out = &mut std::io::stdout().lock();
    let mut md = format!("## {}\n\n", loaded.name);
    let at = if args.time == 0.0 { String::new() } else { format!(" at t = {} s", args.time) };
    let _ = writeln!(out, "accuracy of {}{at} at {w}x{h} on {backend}", loaded.name);

    let mut renderer = match backend {
        Backend::Cpu => None,
        other => Some(fractal_render::select::open(other, &RendererOptions { precise: args.precise })?),
    };
    // The truth at the scene's iteration count, and for escape-time fractals at doubled counts until neither the hit
    // mask nor the scene default's judged figures move: the converged truth, judged against (`--truth-factor` names
    // the one instead). The default against each truth is on record.
    let escape_time = sweep::escape_time_iterations(scene).is_some();
    // With the default's render against each truth, where more truths may follow (the sweep renders it for the one).
    let mut truths: Vec<(u32, Truth, Option<sweep::SweepPoint>)> = Vec::new();
    let mut factor = if escape_time { args.truth_factor.unwrap_or(1) } else { 1 };
    loop {
        let start = Instant::now();
        let settings = TruthSettings { step_footprints: args.truth_step, iteration_factor: factor };
        let truth = Truth::compute(scene, &frame, settings)?;
        let took = start.elapsed().as_secs_f64();
        let hits = truth.pixels.iter().filter(|p| p.hit()).count();
        let default = if escape_time {
            let defaults = sweep::run(scene, &frame, &truth, backend, renderer.as_mut(), &[own(args)], &mut |_| {})?;
            defaults.into_iter().next()
        } else {
            None
        };
        let previous = truths.last();
        let moved = previous.map(|(_, p, _)| mask_moved(p.pixels.iter().map(|p| p.hit()), &truth));
        let figures = match (previous.and_then(|p| p.2.as_ref()), &default) {
            (Some(before), Some(after)) => Some(budget.moved(&before.error, &after.error)),
            _ => None,
        };
        let figures_said = match &figures {
            Some(f) if f.is_empty() => ", the scene default's judged figures by under a quarter of their limits".into(),
            Some(f) => format!(", the scene default's {}", f.join(", ")),
            None => String::new(),
        };
        let line = format!(
            "truth at {factor}x the iterations{}: {:.2} % of pixels hit{}, step {:.4} footprint, {took:.1} s",
            capped(scene, factor),
            100.0 * hits as f64 / truth.pixels.len() as f64,
            moved.map_or(String::new(), |m| format!(
                " ({:.2} % of the mask moved from {}x{figures_said})",
                100.0 * m,
                factor / 2
            )),
            args.truth_step,
        );
        let _ = writeln!(out, "  {line}");
        let _ = writeln!(md, "- {line}");
        if let Some(default) = &default {
            let line = format!("scene default against the {factor}x truth: {}", default.error.describe());
            let _ = writeln!(out, "  {line}");
            let _ = writeln!(md, "- {line}");
        }
        truths.push((factor, truth, default));
        let settled = moved.is_some_and(|m| m < CONVERGED_MASK) && figures.is_some_and(|f| f.is_empty());
        if !escape_time || settled || factor >= MAX_TRUTH_FACTOR || args.truth_factor.is_some() {
            break;
        }
        factor *= 2;
    }
    let references: Vec<(u32, &Truth)> = truths.iter().map(|(f, t, _)| (*f, t)).collect();
    let judged_index = settled_in_step(scene, &frame, args.truth_step, budget, &references, &mut |line| {
        let _ = writeln!(out, "  {line}");
        let _ = writeln!(md, "- {line}");
    })?;
    let (judged_factor, judged) = references[judged_index];

    let qualities =
        if args.default_only { vec![Quality::default()] } else { sweep::grid(scene, backend, args.precise) };
    let qualities: Vec<Quality> =
        qualities.into_iter().map(|q| Quality { precision: own(args).precision, ..q }).collect();
    let _ = writeln!(md);
    // The default was measured against every truth of an escape-time scene already: its point against the judged one
    // is kept, not rendered again.
    let known = truths[judged_index].2.clone();
    let pending: Vec<Quality> = qualities.into_iter().filter(|q| known.is_none() || !q.is_default()).collect();
    let mut points: Vec<sweep::SweepPoint> = known.into_iter().collect();
    points.extend(sweep::run(scene, &frame, judged, backend, renderer.as_mut(), &pending, &mut |p| {
        eprintln!("  measured {} ({:.1} ms)", p.quality, p.time_ms);
    })?);
    let _ = write!(out, "{}", table::text(&points, budget));
    if let Some(dir) = plot_dir(args) {
        let path = dir.join(format!("{}.svg", loaded.name));
        write_plot(&path, plot::svg(&loaded.name, &points, budget))?;
        let _ = writeln!(out, "  wrote {}", path.display());
        if args.report {
            let folder = dir.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            md += &format!("![{0}: time against true error]({folder}/{0}.svg)\n\n", loaded.name);
        }
    }
    md += &table::markdown(&points, budget);
    let verdict = match sweep::recommended(&points, budget) {
        Some(p) => format!("fastest within budget: {} ({:.1} ms)", p.quality, p.time_ms),
        None => "no setting tried is within budget".to_string(),
    };
    let default_line = match points.iter().find(|p| p.quality.is_default()) {
        Some(p) => format!("the scene default is {}", budget.verdict(&p.error).sentence()),
        None => String::new(),
    };
    let _ = writeln!(out, "  {verdict}; {default_line}\n");
    let _ = writeln!(md, "\n**{verdict}**; {default_line}.\n");
    let mut others: Vec<keys::Opened> = args
        .also_on
        .iter()
        .filter(|&&b| b != backend)
        .map(|&b| {
            (b, fractal_render::select::open(b, &RendererOptions { precise: args.precise }).map_err(|e| e.to_string()))
        })
        .collect();
    for (other, opened) in &mut others {
        let line = default_on(scene, (&frame, judged), *other, opened, budget, &own(args))?;
        let _ = writeln!(out, "  {line}");
        let _ = writeln!(md, "- {line}");
    }
    if !args.also_on.is_empty() {
        let _ = writeln!(md);
    }
    let settings = TruthSettings { step_footprints: args.truth_step, iteration_factor: judged_factor };
    let has_keys = keys::check(
        scene,
        &params,
        args.size,
        args.time,
        settings,
        backend,
        renderer.as_mut(),
        &mut others,
        (&points, &own(args)),
        budget,
        &mut |line| {
            let _ = writeln!(out, "  {line}");
            let _ = writeln!(md, "- {line}");
        },
    )?;
    if has_keys {
        let _ = writeln!(md);
    }
    if let Some(path) = &args.csv {
        append_csv(path, &table::csv_rows(&loaded.name, &backend.to_string(), args.size, &points, budget))?;
    }
    if let (Some(path), Some(normals)) = (&args.judge_normals, &given_normals) {
        let (centre, cone) = metrics::judge_normals(judged, normals);
        let _ = writeln!(
            out,
            "  the normals of {}: median {:.2}°, p99 {:.2}° at the centre / {:.2}° cone-consistent ({} judged)",
            path.display(),
            centre.median,
            centre.p99,
            cone.p99,
            cone.count
        );
    }
    if let Some(path) = &args.normals_csv {
        let default = Quality { precision: own(args).precision, ..Quality::default() };
        let traces =
            sweep::trace_cpu(&default.apply(scene), &default, &frame).map_err(|e| CliError::failure(e.to_string()))?;
        let samples = metrics::normal_samples(judged, &traces);
        std::fs::write(path, metrics::normal_samples_csv(&samples))
            .map_err(|e| CliError::failure(format!("cannot write {}: {e}", path.display())))?;
        let _ = writeln!(
            out,
            "  wrote the {} measured normals of the default's CPU render to {}",
            samples.len(),
            path.display()
        );
    }
    Ok(md)
}

/// The scene's own setting rendered on `backend` against `truth`: one line with its time, the figures its image
/// holds and the budget's verdict on them, or why the backend did not open.
fn default_on(
    scene: &fractal_dsl::Scene,
    (frame, truth): (&Frame, &Truth),
    backend: Backend,
    opened: &mut Result<Box<dyn fractal_render::renderer::Renderer>, String>,
    budget: &Budget,
    own: &Quality,
) -> Result<String, CliError> {
    let renderer = match opened {
        Ok(r) => r,
        Err(e) => return Ok(format!("scene default on {backend}: not measured, the backend did not open ({e})")),
    };
    let point = &sweep::run(scene, frame, truth, backend, Some(renderer), std::slice::from_ref(own), &mut |_| {})?[0];
    Ok(format!("scene default on {backend}: {}", judged(point, budget).0))
}

/// Which of `truths` (in rising iterations) the sweep is judged against: the one of most iterations that has settled
/// in its `step`, checked against a truth at twice the step from the most iterations down (the first when none has).
/// A truth has settled when that moves less of its hit mask than the budget's hit mismatch (a truth less certain
/// than that cannot judge it); one that has not (walls thinner than the step, which a finer step keeps finding) is
/// no ground truth, however many iterations it has. Measured at 192x108, 1/64 footprint: the Mandelbulb's truths
/// move 0.20–0.26 %, the Mandelbox's 0.41 % at its own iterations and 2–3 % at more. Each check is reported
/// through `say`.
fn settled_in_step(
    scene: &fractal_dsl::Scene,
    frame: &Frame,
    step: f64,
    budget: &Budget,
    truths: &[(u32, &Truth)],
    say: &mut dyn FnMut(String),
) -> Result<usize, CliError> {
    for (i, (factor, truth)) in truths.iter().enumerate().rev() {
        let start = Instant::now();
        let settings = TruthSettings { step_footprints: 2.0 * step, iteration_factor: *factor };
        let coarse = Truth::hit_mask(scene, frame, settings)?;
        let moved = mask_moved(coarse, truth);
        let settled = moved < budget.hit_mismatch;
        let verdict = match (settled, i) {
            (true, _) => "settled: judged against",
            (false, 0) => "not settled, and no truth of fewer iterations: judged against all the same",
            (false, _) => "not settled: not judged against",
        };
        say(format!(
            "truth at {factor}x the iterations against twice its step: {:.2} % of the mask moved, {verdict} ({:.1} s)",
            100.0 * moved,
            start.elapsed().as_secs_f64()
        ));
        if settled || i == 0 {
            return Ok(i);
        }
    }
    Ok(0)
}

/// Share of the pixels whose hit or miss differs between hit mask `a` and truth `b` of one frame.
/// The scene's own setting in the precision `--precision` asks for (`auto`: the one each view asks for).
fn own(args: &AccuracyArgs) -> Quality {
    let precision = match args.precision {
        fractal_render::precision::PrecisionChoice::Auto => None,
        fractal_render::precision::PrecisionChoice::Only(p) => Some(p),
    };
    Quality { precision, ..Quality::default() }
}

fn mask_moved(a: impl IntoIterator<Item = bool>, b: &Truth) -> f64 {
    let moved = a.into_iter().zip(&b.pixels).filter(|(hit, q)| *hit != q.hit()).count();
    moved as f64 / b.pixels.len().max(1) as f64
}

/// Every studied fractal's estimate against its true distance: printed, and returned as a Markdown section.
/// The estimator study of the fractals of one scene: the table, and for each formula written in the scene language
/// the step factor its ratios ask for, recorded for later loads of the formula ([`crate::step_factors`]).
fn scene_estimator_study(name: &str, library: &SceneLibrary, samples: usize) -> Result<(), CliError> {
    let loaded = LoadedScene::load(name, library)?;
    let mut fractals = Vec::new();
    collect_fractals(&loaded.scene.root, &mut fractals);
    if fractals.is_empty() {
        return Err(CliError::usage(format!("{name} has no fractal to study")));
    }
    let many = fractals.len() > 1;
    let named: Vec<(String, fractal_dsl::Fractal)> = fractals
        .into_iter()
        .enumerate()
        .map(|(i, f)| {
            let number = if many { format!(" #{}", i + 1) } else { String::new() };
            (format!("{}{number}: {}", loaded.name, f.name()), f)
        })
        .collect();
    // The factor follows the points anywhere near the set, which rays meet; the planes' and axes' own tails (where a
    // formula is often singular) are in the table, with the largest estimate a march steps through them from.
    let mut worst: Vec<(usize, f64)> = Vec::new();
    let _ = estimator_table(&named, samples, &mut |i, row| {
        if row.region == truth::estimate::Region::Anywhere.name() {
            worst.push((i, row.p999))
        }
    });
    let out = &mut std::io::stdout().lock();
    for (i, (short, fractal)) in named.iter().enumerate() {
        let measured = crate::step_factors::from_ratios(worst.iter().filter(|(j, _)| *j == i).map(|(_, r)| *r));
        let Some(factor) = measured else {
            let _ = writeln!(out, "{short}: no point near the set was found; no step factor measured");
            continue;
        };
        let _ = writeln!(
            out,
            "{short}: measured step factor {factor} (1 / the p99.9 ratio anywhere near the set, rounded down to 0.05, at most 1)"
        );
        if let Some(formula) = fractal.formula() {
            match crate::step_factors::record(formula, factor) {
                Ok(path) => {
                    let _ = writeln!(
                        out,
                        "  recorded in {}: loads of this formula without .step_factor(k) use it",
                        path.display()
                    );
                }
                Err(e) => eprintln!("fractal: {e}"),
            }
        }
    }
    Ok(())
}

/// The fractals of a tree, each as written (its own step factor, none of the transforms above it).
fn collect_fractals(node: &fractal_dsl::Node, out: &mut Vec<fractal_dsl::Fractal>) {
    if let fractal_dsl::Node::Fractal(f) = node {
        out.push((**f).clone());
    }
    for c in node.children() {
        collect_fractals(c, out);
    }
}

fn estimator_study(samples: usize) -> String {
    estimator_table(&truth::estimate::studied(), samples, &mut |_, _| {})
}

/// Studies each fractal and prints the table; returns it as Markdown. `each` sees every row with its fractal's index.
fn estimator_table(
    fractals: &[(String, fractal_dsl::Fractal)],
    samples: usize,
    each: &mut dyn FnMut(usize, &truth::estimate::RatioStudy),
) -> String {
    let started = Instant::now();
    let out = &mut std::io::stdout().lock();
    let mut md = format!(
        "## Distance estimators against the true distance\n\n\
         Written by `fractal accuracy --estimators --estimator-samples {samples}`: per fractal and region, {samples} \
         points outside the set and near it, escape-time sets at {CONVERGED_FACTOR}x their iterations; ratio = raw \
         estimate (the kernel's estimate divided by the family's step \
         factor) / true distance, the true distance searched from membership alone \
         (`fractal-runtime/src/truth/estimate.rs`). A march is safe where step factor × ratio ≤ 1: *unsafe* is the \
         share of points where it is not. A march stops where the scene's estimate (step factor × raw) falls below \
         its hit epsilon, so it never steps from a point whose estimate is smaller: *unsafe below* is the largest \
         scene estimate at an unsafe point (scene units), and a hit epsilon above it keeps every sampled point safe. \
         The Mandelbox's tail lies there: on an orbit that stays within the escape radius R its estimate |z|/|dr| \
         never falls below R/|scale|^N, while the true distance goes to 0 at the boundary of the set at twice the \
         iterations.\n\n\
         | fractal | region | step factor | points | median | p99.9 | max | ratio > 1 % | unsafe % | unsafe below |\n\
         |---|---|---|---|---|---|---|---|---|---|\n"
    );
    let _ = writeln!(
        out,
        "estimate / true distance ({samples} points per fractal and region, escape-time sets at {CONVERGED_FACTOR}x \
         their iterations)"
    );
    // The terminal table's columns, right-aligned to these widths.
    let aligned = |cells: &[&str]| -> String {
        const WIDTHS: [usize; 10] = [28, 24, 6, 6, 7, 7, 7, 8, 8, 12];
        cells.iter().zip(WIDTHS).map(|(c, w)| format!("{c:>w$}")).collect::<Vec<_>>().join(" ")
    };
    let headers =
        ["fractal", "region", "factor", "points", "median", "p99.9", "max", ">1 %", "unsafe %", "unsafe below"];
    let _ = writeln!(out, "{}", aligned(&headers));
    for (i, (name, fractal)) in fractals.iter().enumerate() {
        for row in truth::estimate::study(name, fractal.clone(), samples, CONVERGED_FACTOR, 0x5eed) {
            each(i, &row);
            let cells = [
                format!("{:.2}", row.step_factor),
                row.samples.to_string(),
                format!("{:.3}", row.median),
                format!("{:.3}", row.p999),
                format!("{:.3}", row.max),
                format!("{:.2}", 100.0 * row.above_one),
                format!("{:.2}", 100.0 * row.unsafe_stepped),
                if row.unsafe_below > 0.0 { format!("{:.1e}", row.unsafe_below) } else { "–".to_string() },
            ];
            let line: Vec<&str> =
                [row.fractal.as_str(), row.region].into_iter().chain(cells.iter().map(String::as_str)).collect();
            let _ = writeln!(out, "{}", aligned(&line));
            md += &format!("| {} | {} | {} |\n", row.fractal, row.region, cells.join(" | "));
        }
    }
    let _ = writeln!(out, "  ({:.1} s)", started.elapsed().as_secs_f64());
    md + "\n"
}

/// The `--judge-normals` file: x,y,nx,ny,nz per line.
fn read_normals(path: &std::path::Path) -> Result<Vec<(u32, u32, [f64; 3])>, CliError> {
    let text =
        std::fs::read_to_string(path).map_err(|e| CliError::failure(format!("cannot read {}: {e}", path.display())))?;
    let bad = |line: usize| CliError::usage(format!("{}:{line}: expected x,y,nx,ny,nz", path.display()));
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            let f: Vec<&str> = l.split(',').map(str::trim).collect();
            if f.len() != 5 {
                return Err(bad(i + 1));
            }
            let n: Result<Vec<f64>, _> = f[2..].iter().map(|v| v.parse::<f64>()).collect();
            match (f[0].parse::<u32>(), f[1].parse::<u32>(), n) {
                // A normal needs a direction: finite and not zero.
                (Ok(x), Ok(y), Ok(n)) if n.iter().all(|v| v.is_finite()) && n.iter().any(|&v| v != 0.0) => {
                    Ok((x, y, [n[0], n[1], n[2]]))
                }
                _ => Err(bad(i + 1)),
            }
        })
        .collect()
}

fn append_csv(path: &std::path::Path, rows: &str) -> Result<(), CliError> {
    let fail = |e: std::io::Error| CliError::failure(format!("cannot write {}: {e}", path.display()));
    let new = std::fs::metadata(path).map(|m| m.len() == 0).unwrap_or(true);
    let mut file = std::fs::OpenOptions::new().create(true).append(true).open(path).map_err(fail)?;
    if new {
        file.write_all(table::csv_header().as_bytes()).map_err(fail)?;
    }
    file.write_all(rows.as_bytes()).map_err(fail)
}

fn report_text(args: &AccuracyArgs, backend: Backend, budget: &Budget, sections: &str) -> String {
    let (w, h) = args.size;
    let mut command = format!("fractal accuracy --report --size {w}x{h} --backend {backend}");
    if args.default_only {
        command += " --default-only";
    }
    if args.truth_step != truth::DEFAULT_STEP_FOOTPRINTS {
        command += &format!(" --truth-step {}", args.truth_step);
    }
    if let Some(factor) = args.truth_factor {
        command += &format!(" --truth-factor {factor}");
    }
    if !args.also_on.is_empty() {
        let list: Vec<String> = args.also_on.iter().map(|b| b.to_string()).collect();
        command += &format!(" --also-on {}", list.join(","));
    }
    let (title, rendered) = if args.default_only {
        (
            format!("Accuracy of the scene defaults at {w}×{h}"),
            "Every built-in scene is rendered with its own setting (the scene default) from its own camera at t = 0, \
             then from each other key of a camera path (the lines after its table), and measured against a ground \
             truth that never reads a distance estimate. The settings a default was chosen from are swept in \
             `docs/accuracy.md`, at the size the sweep could afford; this report judges the defaults again at this \
             size, where a pixel covers less of the scene and detail that fell between pixels there is measured.",
        )
    } else {
        (
            "Accuracy: speed against true error".to_string(),
            "Every built-in scene is rendered from its own camera at t = 0 with each quality setting (a scene with a \
             camera path, then with its default and the settings within budget from each other key: the lines after \
             its table) and measured against a ground truth that never reads a distance estimate.",
        )
    };
    format!(
        "# {title}\n\n\
         Written by `{command}`. {rendered} The truth decides each fractal by its own iteration (escape time or IFS \
         levels) and exact primitives by their exact f64 distance, and finds the first crossing along each ray with \
         steps of {:.4} pixel footprints, bisected (`fractal-runtime/src/truth.rs`). Escape-time fractals get a truth \
         at the scene's iteration count and at doubled counts until doubling moves less than {:.1} % of the hit mask \
         and none of the scene default's judged figures by more than {:.0} % of its limit (at most \
         {MAX_TRUTH_FACTOR}x; the default's figures against each are listed); renders are judged against the one of \
         most iterations that has also settled in its step: a truth at twice the step moves less than {:.1} % of its mask. \
         This report judges geometry at each pixel; the colour each pixel should have, and what anti-aliasing buys \
         against it, is `docs/image-accuracy.md`'s (`fractal accuracy --image --report`).\n\n\
         Columns: time of the render (median of {}), distance evaluations per pixel, false hits and misses (% of \
         pixels; a false hit is *thin-ray* where the ray through the pixel's centre misses, *cone-consistent* where \
         no ray of the pixel's cone meets the scene either, and the budget counts the latter), rays out of steps, \
         depth error in pixel footprints (median and p99, thin-ray and pixel-cone consistent; *interior*: truth hits \
         whose 8 neighbours hit too), overshoot (rays that passed more than a \
         footprint through the true surface: thin-ray, and cone-consistent where every ray of the pixel's cone meets \
         the scene that far in front, which the budget counts), normal error in degrees (median and p99 against the \
         true normal at the pixel's centre, and p99 cone-consistent: against the nearest of the true normals across \
         the pixel's footprint, which the budget counts), colour PSNR, NaN/Inf pixels. Definitions: \
         `fractal-runtime/src/accuracy/metrics.rs`.\n\n\
         Normals are compared where render and truth stand on the same surface and the true surface has one normal \
         at the pixel's scale: no edge, rim, silhouette, hole or detail below the pixel within half a pixel of its \
         centre (*normals measured*: their share of the pixels both hit). A scene default's line on another backend \
         times its render kernel and reads every figure but the evaluation count from its trace kernel, the render \
         kernel that also writes each pixel's depth, normal and steps.\n\n\
         Budget: hit mismatch ≤ {:.1} %, overshoot ≤ {:.1} %, normal p99 ≤ {}° (cone-consistent; judged over at \
         least {} measured normals: the p99 of fewer is their maximum, and a verdict names them unjudged), no ray out of steps, no \
         NaN/Inf, interior depth p99 ≤ {} footprint (cone-consistent), and thin-ray depth median ≤ {} footprint \
         where the true surface is smooth at the pixel's scale (over at least as many such pixels).\n\n{sections}",
        args.truth_step,
        100.0 * CONVERGED_MASK,
        100.0 * sweep::SETTLED_SHARE,
        100.0 * budget.hit_mismatch,
        sweep::TIMING_RUNS,
        100.0 * budget.hit_mismatch,
        100.0 * budget.overshoot,
        budget.normal_p99,
        sweep::MIN_NORMALS,
        budget.depth_p99_interior,
        budget.depth_median_smooth,
    )
}
