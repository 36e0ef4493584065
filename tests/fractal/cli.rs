//! The `fractal` program end to end, run as a user runs it: images, sequences that resume after an interruption,
//! shards, video, export, bench records, and every kind of bad input (a clear one-line error and the documented exit
//! status, never a panic). Sizes are tiny so the suite stays quick on CPU backends.
//!
//! GPU backends: the wgpu test skips with a note when no adapter opens, and fails instead when
//! FRACTAL_REQUIRE_GPU_BACKENDS=1 (CI, where lavapipe is installed).

use fractal_render::device::backends_required;
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::SystemTime;

use fractal_render::image::Image;
use fractal_runtime::output::read_png;

const FRACTAL: &str = env!("CARGO_BIN_EXE_fractal");

/// An empty scratch directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli").join(test);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fractal/cli").join(name).display().to_string()
}

/// Runs `fractal args` in `dir`.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(FRACTAL).args(args).current_dir(dir).output().expect("the fractal binary runs")
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[track_caller]
fn assert_ok(out: &Output) {
    assert!(out.status.success(), "exit {:?}\nstderr:\n{}", out.status.code(), stderr(out));
}

fn files_in(dir: &Path) -> BTreeSet<String> {
    fs::read_dir(dir)
        .map(|entries| entries.filter_map(|e| e.ok()).map(|e| e.file_name().to_string_lossy().into_owned()).collect())
        .unwrap_or_default()
}

/// The frames of a sequence directory: its files less the record of the settings they were drawn with.
fn frames_in(dir: &Path) -> BTreeSet<String> {
    files_in(dir).into_iter().filter(|f| !f.ends_with(".settings")).collect()
}

fn modified(path: &Path) -> SystemTime {
    fs::metadata(path).and_then(|m| m.modified()).expect("file exists")
}

/// Fraction of pixels that differ by more than `tolerance` levels in some channel.
fn fraction_unlike(a: &Image, b: &Image, tolerance: u8) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let unlike = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| p.to_le_bytes().iter().zip(q.to_le_bytes()).any(|(x, y)| x.abs_diff(y) > tolerance))
        .count();
    unlike as f64 / a.pixels.len() as f64
}

mod exports;
mod refusals;
mod sequences;

#[test]
fn help_lists_the_commands() {
    let out = run_in(&scratch("help"), &["--help"]);
    assert_ok(&out);
    let text = stdout(&out);
    for command in ["render", "bench", "accuracy", "export", "list"] {
        assert!(text.contains(command), "--help does not mention {command}:\n{text}");
    }
}

#[test]
fn list_names_every_builtin_with_its_description() {
    let out = run_in(&scratch("list"), &["list"]);
    assert_ok(&out);
    let text = stdout(&out);
    for name in scenes::names() {
        let line = text.lines().find(|l| l.starts_with(name)).unwrap_or_else(|| panic!("{name} missing:\n{text}"));
        assert!(line.len() > name.len() + 10, "{name} has no description: {line:?}");
    }
    assert!(text.contains("One lit sphere"), "{text}");
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let dir = scratch("render_png");
    let out = run_in(&dir, &["render", "hello_world", "--size", "48x32", "--backend", "cpu", "-o", "sphere.png"]);
    assert_ok(&out);
    assert!(stderr(&out).contains("using cpu"), "the device is not named:\n{}", stderr(&out));
    let image = read_png(&dir.join("sphere.png")).expect("a PNG");
    assert_eq!((image.width, image.height), (48, 32));
    assert!(!image.is_uniform(), "the image is one colour");
    assert!(!dir.join("sphere.png.partial").exists());
    // Without -o the file is named after the scene.
    assert_ok(&run_in(&dir, &["render", "hello_world", "--size", "8x8", "--backend", "cpu"]));
    assert!(dir.join("hello_world.png").is_file());
}

#[test]
fn a_file_scene_takes_parameters_and_time() {
    let dir = scratch("file_scene");
    let scene = fixture("sphere_param.fractal");
    let render = |name: &str, extra: &[&str]| {
        let mut args = vec!["render", scene.as_str(), "--size", "32x32", "--backend", "cpu", "-o", name];
        args.extend_from_slice(extra);
        assert_ok(&run_in(&dir, &args));
        read_png(&dir.join(name)).expect("a PNG")
    };
    let small = render("small.png", &[]);
    let large = render("large.png", &["--param", "radius=1.2"]);
    let background = small.rgba(0, 0).expect("corner");
    let covered = |img: &Image| img.count_unlike(background, 2);
    assert!(
        covered(&large) > 2 * covered(&small),
        "radius 1.2 covers {} pixels, 0.5 covers {}",
        covered(&large),
        covered(&small)
    );
    // --time advances the scene: the moving sphere is elsewhere at t = 2.
    let moving = fixture("moving_sphere.fractal");
    for (name, time) in [("t0.png", "0"), ("t2.png", "2")] {
        assert_ok(&run_in(
            &dir,
            &["render", &moving, "--size", "32x32", "--backend", "cpu", "--time", time, "-o", name],
        ));
    }
    let (t0, t2) = (read_png(&dir.join("t0.png")).unwrap(), read_png(&dir.join("t2.png")).unwrap());
    assert!(fraction_unlike(&t0, &t2, 2) > 0.05, "the sphere did not move between t = 0 and t = 2");
}

#[test]
fn view_without_a_display_says_how_to_render_instead() {
    let dir = scratch("view");
    let view = |scene: &str| {
        Command::new(FRACTAL)
            .args(["view", scene])
            .current_dir(&dir)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap()
    };
    let out = view("hello_world");
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("no display") && stderr(&out).contains("fractal render hello_world"),
        "{}",
        stderr(&out)
    );
    let out = view("no_such_scene");
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}

/// `fractal view --headless` runs the viewer's frames with no display, says what they cost, and saves the last one
/// as a window would show it: with time paused, the frame `fractal render` draws at the same time and size.
#[test]
fn view_headless_draws_frames_and_says_what_they_cost() {
    let dir = scratch("view-headless");
    let view = |args: &[&str]| {
        Command::new(FRACTAL)
            .args(["view", "hello_world"])
            .args(args)
            .current_dir(&dir)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap()
    };
    let args = ["--headless", "--frames", "4", "--size", "96x64", "--backend", "cpu", "--paused", "--no-accumulate"];
    let out = view(&[&args[..], &["--screenshot", "last.png"]].concat());
    assert_ok(&out);
    let report = stdout(&out);
    assert!(report.contains("4 frames at 96x64 (rendered at 96x64)"), "{report}");
    assert!(report.contains("3 kernel frames") && report.contains("host memory"), "{report}");
    let shown = read_png(&dir.join("last.png")).expect("the last frame was saved");
    assert_ok(&run_in(&dir, &["render", "hello_world", "--size", "96x64", "--backend", "cpu", "-o", "render.png"]));
    let rendered = read_png(&dir.join("render.png")).unwrap();
    assert_eq!(fraction_unlike(&shown, &rendered, 0), 0.0, "the headless viewer shows what render draws");

    // A count of frames or a screenshot means nothing with a window; a scale outside 0.05..=1 is refused.
    let out = view(&["--frames", "4"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let out = view(&["--headless", "--scale", "2"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("0.05..=1"), "{}", stderr(&out));
}

/// `--samples` draws a built-in with more rays a pixel on a backend that runs its kernels (compiled again for it)
/// and on the CPU alike: the silhouette's pixels change, little else does.
#[test]
fn samples_from_the_command_line_smooth_the_edges_on_every_backend() {
    let dir = scratch("samples");
    let args = |backend: &'static str, samples: &'static str, name: &'static str| {
        ["render", "hello_world", "--size", "48x32", "--backend", backend, "--samples", samples, "-o", name]
    };
    assert_ok(&run_in(&dir, &args("cpu", "1", "one.png")));
    assert_ok(&run_in(&dir, &args("cpu", "16", "cpu.png")));
    let (one, cpu) = (read_png(&dir.join("one.png")).unwrap(), read_png(&dir.join("cpu.png")).unwrap());
    let changed = fraction_unlike(&one, &cpu, 8);
    assert!(changed > 0.005 && changed < 0.2, "{:.1} % of pixels changed by more than 8 levels", changed * 100.0);
    // A progressive still: passes of one ray a pixel for a fifth of a second, at least one.
    let out = run_in(&dir, &["render", "hello_world", "--size", "48x32", "--backend", "cpu", "--progressive", "0.2"]);
    assert_ok(&out);
    assert!(stderr(&out).contains(" passes, "), "{}", stderr(&out));
    let refined = read_png(&dir.join("hello_world.png")).unwrap();
    assert!(fraction_unlike(&refined, &cpu, 16) < 0.05, "the progressive still is not the supersampled one");
    let gpu = run_in(&dir, &args("wgpu", "16", "gpu.png"));
    if gpu.status.success() {
        let unlike = fraction_unlike(&read_png(&dir.join("gpu.png")).unwrap(), &cpu, 3);
        assert!(unlike < 0.02, "{:.1} % of pixels differ by more than 3 levels", unlike * 100.0);
    } else {
        assert!(!backends_required(), "wgpu is required but failed:\n{}", stderr(&gpu));
    }
}

#[test]
fn wgpu_renders_what_the_cpu_renders() {
    let dir = scratch("wgpu");
    let args = |backend: &'static str, name: &'static str| {
        ["render", "mandelbulb_bench", "--size", "40x32", "--backend", backend, "-o", name]
    };
    let gpu = run_in(&dir, &args("wgpu", "gpu.png"));
    if !gpu.status.success() {
        let message = stderr(&gpu);
        assert!(!backends_required(), "wgpu is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but failed:\n{message}");
        assert!(message.contains("no wgpu device"), "wgpu failed for another reason than a missing device:\n{message}");
        eprintln!("note: skipping the wgpu render, no adapter: {message}");
        return;
    }
    assert!(stderr(&gpu).contains("using wgpu on"), "{}", stderr(&gpu));
    assert_ok(&run_in(&dir, &args("cpu", "cpu.png")));
    let (a, b) = (read_png(&dir.join("gpu.png")).unwrap(), read_png(&dir.join("cpu.png")).unwrap());
    assert!(!a.is_uniform());
    let unlike = fraction_unlike(&a, &b, 8);
    assert!(unlike < 0.03, "{:.1} % of pixels differ by more than 8 levels", unlike * 100.0);
}

/// `fractal bench --baseline` on a GPU backend: device timings of both kernels, their ratio, and both error figures.
fn bench_against_the_baseline(backend: &str) {
    let dir = scratch(&format!("bench_baseline_{backend}"));
    let args = [
        "bench",
        "mandelbulb_bench",
        "--size",
        "48x27",
        "--frames",
        "2",
        "--backend",
        backend,
        "--baseline",
        "--json",
        "b.json",
    ];
    let out = run_in(&dir, &args);
    if !out.status.success() {
        let message = stderr(&out);
        assert!(!backends_required(), "{backend} is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but failed:\n{message}");
        assert!(message.contains(&format!("no {backend} device")), "{backend} failed for another reason:\n{message}");
        eprintln!("note: skipping the {backend} bench, no device: {message}");
        return;
    }
    let report = stdout(&out);
    for word in
        [&format!("device:  {backend} on"), "baseline kernel", "generated/baseline (median)", "baseline error vs f64"]
    {
        assert!(report.contains(word), "no `{word}` in the report:\n{report}");
    }
    // The true error of the timed march comes from the same backend's trace kernel: depths and normals too.
    for word in ["true error (vs ground truth", "depth error (footprints)", "normal error"] {
        assert!(report.contains(word), "no `{word}` in the report:\n{report}");
    }
    assert!(report.contains("device time"), "{backend} kernel times do not come from the device:\n{report}");
    let json = fs::read_to_string(dir.join("b.json")).unwrap();
    assert!(json.contains("\"kernel_ratio\":") && json.contains("\"camera\":\"static\""), "{json}");
}

#[test]
fn wgpu_bench_runs_the_baseline_on_the_same_device() {
    bench_against_the_baseline("wgpu");
}

#[cfg(feature = "opencl")]
#[test]
fn opencl_bench_runs_the_baseline_on_the_same_device() {
    bench_against_the_baseline("opencl");
}

#[test]
fn bench_appends_a_csv_row_and_a_json_line() {
    let dir = scratch("bench");
    let args = [
        "bench",
        "hello_world",
        "--size",
        "32x32",
        "--frames",
        "2",
        "--backend",
        "cpu",
        "--csv",
        "b.csv",
        "--json",
        "b.json",
        "--image-error",
    ];
    for _ in 0..2 {
        let out = run_in(&dir, &args);
        assert_ok(&out);
        let report = stdout(&out);
        for word in [
            "median",
            "FPS",
            "precision (vs f64 interpreter",
            "hit/miss differs",
            "true error (vs ground truth",
            "depth error",
            "image error (vs the truth of the image",
        ] {
            assert!(report.contains(word), "no `{word}` in the report:\n{report}");
        }
    }
    let csv = fs::read_to_string(dir.join("b.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert_eq!(rows.len(), 3, "one header and two rows:\n{csv}");
    assert!(rows[0].starts_with("timestamp,scene,width,height,backend"), "{}", rows[0]);
    let header: Vec<&str> = rows[0].split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap_or_else(|| panic!("no column {name}"));
    for row in &rows[1..] {
        // Device names hold commas inside quotes; the columns before them are plain.
        let cells: Vec<&str> = row.split(',').collect();
        assert_eq!(cells[column("scene")], "hello_world");
        assert_eq!(cells[column("width")], "32");
        assert_eq!(cells[column("backend")], "cpu");
        // Columns after the device's are counted from the end.
        let psnr: f64 = cells[cells.len() - (header.len() - column("image_psnr_db"))].parse().expect("a PSNR");
        assert!(psnr > 20.0, "{psnr} dB");
    }
    let json = fs::read_to_string(dir.join("b.json")).unwrap();
    let lines: Vec<&str> = json.lines().collect();
    assert_eq!(lines.len(), 2, "{json}");
    for line in lines {
        assert!(line.starts_with('{') && line.ends_with('}'), "{line}");
        for field in [
            "\"scene\":\"hello_world\"",
            "\"backend\":\"cpu\"",
            "\"frames\":2",
            "\"max_steps\":",
            "\"hit_mismatch\":",
            "\"false_hits\":",
            "\"image_error\":{\"psnr\":",
        ] {
            assert!(line.contains(field), "no {field} in {line}");
        }
    }
}

#[test]
fn gallery_renders_every_scene_and_a_labelled_contact_sheet() {
    let dir = scratch("gallery");
    let out = run_in(&dir, &["gallery", "--backend", "cpu", "--size", "64x36", "--columns", "5", "-o", "g"]);
    assert_ok(&out);
    let count = scenes::ALL.len() as u32;
    for name in scenes::names() {
        let image = read_png(&dir.join(format!("g/{name}.png"))).unwrap();
        assert_eq!((image.width, image.height), (64, 36), "{name}");
        assert!(!image.is_uniform(), "{name} drew nothing");
        assert!(stderr(&out).contains(name), "{}", stderr(&out));
    }
    let sheet = read_png(&dir.join("g/gallery.png")).unwrap();
    // Five 64-pixel columns with 6-pixel gaps; a row per five scenes, each 36 pixels and a 24-pixel label band.
    assert_eq!(sheet.width, 6 + 5 * (64 + 6));
    assert_eq!(sheet.height, 6 + count.div_ceil(5) * (36 + 24 + 6));
}

#[test]
fn accuracy_sweeps_settings_against_the_truth_and_writes_a_report() {
    let dir = scratch("accuracy");
    let out =
        run_in(&dir, &["accuracy", "mandelbulb_bench", "--size", "24x14", "--truth-step", "0.05", "--csv", "a.csv"]);
    assert_ok(&out);
    let text = stdout(&out);
    for word in ["truth at 1x the iterations", "truth at 2x the iterations", "scene default against", "steps 512"] {
        assert!(text.contains(word), "no `{word}` in\n{text}");
    }
    assert!(text.contains("fastest within budget") || text.contains("no setting tried"), "{text}");
    // Too few steps leave rays out of steps: the budget says so.
    let starved = text.lines().find(|l| l.trim_start().starts_with("steps 32")).expect("a 32-step row");
    assert!(starved.contains("out of steps"), "{starved}");
    let csv = fs::read_to_string(dir.join("a.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert!(rows[0].starts_with("scene,backend,size,setting,ms"), "{}", rows[0]);
    assert!(rows.len() > 15 && rows[1..].iter().all(|r| r.starts_with("mandelbulb_bench,cpu,24x14,")), "{csv}");
    // The scene's own setting alone: its figures and verdict, no sweep.
    let out = run_in(
        &dir,
        &[
            "accuracy",
            "hello_world",
            "--size",
            "24x14",
            "--truth-step",
            "0.05",
            "--default-only",
            "--time",
            "0.5",
            "--normals-csv",
            "n.csv",
        ],
    );
    assert_ok(&out);
    let text = stdout(&out);
    assert!(text.starts_with("accuracy of hello_world at t = 0.5 s at 24x14 on cpu"), "{text}");
    let rows = text.lines().filter(|l| l.starts_with("scene default ")).count();
    assert_eq!(rows, 1, "{text}");
    assert!(!text.contains("steps 32") && text.contains("the scene default is"), "{text}");
    // Every pixel whose normal was judged, one CSV row each.
    let normals = fs::read_to_string(dir.join("n.csv")).unwrap();
    let count = normals.lines().count() - 1;
    assert!(normals.starts_with("x,y,centre_deg,cone_deg,ox,oy,oz,dx,dy,dz,t_render,t_truth,"), "{normals}");
    assert!(count > 0 && text.contains(&format!("wrote the {count} measured normals")), "{text}\n{normals}");
    // The truth's own normals given back are judged 0° off; a malformed file is said before any truth is computed.
    let given: String = normals
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            format!("{},{},{}\n", f[0], f[1], f[16..19].join(","))
        })
        .collect();
    fs::write(dir.join("g.csv"), given).unwrap();
    fs::write(dir.join("bad.csv"), "1,2,0.5\n").unwrap();
    let judge = |file: &str| {
        let args = ["accuracy", "hello_world", "--size", "24x14", "--truth-step", "0.05", "--default-only"];
        run_in(&dir, &[&args[..], &["--time", "0.5", "--judge-normals", file]].concat())
    };
    let text = stdout(&judge("g.csv"));
    assert!(text.contains("the normals of g.csv: median 0.00°"), "{text}");
    assert!(text.contains(&format!("0.00° cone-consistent ({count} judged)")), "{text}");
    let out = judge("bad.csv");
    assert!(!out.status.success() && stderr(&out).contains("bad.csv:1: expected x,y,nx,ny,nz"), "{}", stderr(&out));
    // A named truth instead of the settling one.
    let out = run_in(
        &dir,
        &[
            "accuracy",
            "mandelbulb_bench",
            "--size",
            "24x14",
            "--truth-step",
            "0.05",
            "--default-only",
            "--truth-factor",
            "4",
        ],
    );
    assert_ok(&out);
    let text = stdout(&out);
    assert!(text.contains("truth at 4x the iterations") && !text.contains("truth at 1x"), "{text}");
    assert!(!text.contains("truth at 8x") && text.contains("the scene default is"), "{text}");
    let report_args =
        ["--report", "--size", "16x9", "--truth-step", "0.05", "--estimator-samples", "4", "--out", "r.md"];
    let out = run_in(&dir, &[&["accuracy"][..], &report_args].concat());
    assert_ok(&out);
    let report = fs::read_to_string(dir.join("r.md")).unwrap();
    for name in scenes::names() {
        assert!(report.contains(&format!("## {name}")), "no section for {name}:\n{report}");
        // Each section shows its time-against-error plot, written beside the report.
        assert!(report.contains(&format!("](r/{name}.svg)")), "no plot linked for {name}:\n{report}");
        let svg = fs::read_to_string(dir.join(format!("r/{name}.svg"))).unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("hit mismatch"), "{name}: {svg}");
    }
    // A scene that flies a camera path is judged from its other keys too: the Mandelbulb's close-up at t = 25 s.
    let path_section = &report[report.find("## mandelbulb\n").unwrap()..report.find("## mandelbulb_bench").unwrap()];
    for line in [
        "- truth at key t = 25 s, (0.75, 0.7, -0.75)",
        "key t = 25 s, (0.75, 0.7, -0.75) → (0.3, 0.45, -0.3): scene default on cpu",
    ] {
        assert!(path_section.contains(line), "no `{line}` in\n{path_section}");
    }
    assert!(path_section.contains("every other key"), "{path_section}");
    let fixed_camera =
        &report[report.find("## mandelbulb_bench").unwrap()..report.find("## mandelbulb_powers").unwrap()];
    assert!(!fixed_camera.contains("truth at key"), "{fixed_camera}");
    assert!(report.contains("## Distance estimators against the true distance"), "{report}");
    assert!(report.contains("| mandelbulb(8) | near coordinate axes | 0.75 |"), "{report}");

    // The defaults alone at another size: a section and one row per scene, no sweep, plots or estimator study.
    let out = run_in(
        &dir,
        &["accuracy", "--report", "--default-only", "--size", "16x9", "--truth-step", "0.05", "--out", "d.md"],
    );
    assert_ok(&out);
    let defaults = fs::read_to_string(dir.join("d.md")).unwrap();
    assert!(defaults.starts_with("# Accuracy of the scene defaults at 16×9"), "{defaults}");
    assert!(defaults.contains("`fractal accuracy --report --size 16x9 --backend cpu --default-only"), "{defaults}");
    for name in scenes::names() {
        assert!(defaults.contains(&format!("## {name}\n")), "no section for {name}:\n{defaults}");
    }
    assert_eq!(defaults.matches("\n| scene default |").count(), scenes::names().count(), "{defaults}");
    assert!(!defaults.contains("steps 32") && !defaults.contains(".svg") && !dir.join("d").exists(), "{defaults}");
    assert!(!defaults.contains("## Distance estimators"), "{defaults}");
}

/// `--camera-pos`, `--camera-target` and `--fov` replace the scene's camera (or camera path) for one render.
#[test]
fn the_camera_can_be_placed_from_the_command_line() {
    let dir = scratch("camera_override");
    let render = |extra: &[&str], out: &str| {
        let args = [&["render", "hello_world", "--backend", "cpu", "--size", "32x32", "-o", out][..], extra].concat();
        let result = run_in(&dir, &args);
        assert_ok(&result);
        read_png(&dir.join(out)).unwrap()
    };
    let own = render(&[], "own.png");
    let moved = render(&["--camera-pos", "-3,1,-3", "--camera-target", "0,0,0"], "moved.png");
    let narrow = render(&["--camera-pos=-3,1,-3", "--camera-target", "0,0,0", "--fov", "20"], "narrow.png");
    assert!(fraction_unlike(&own, &moved, 8) > 0.05, "the camera did not move");
    assert!(fraction_unlike(&moved, &narrow, 8) > 0.05, "the field of view did not change");

    for (args, message) in [
        (&["--camera-pos", "1,2,3"][..], "--camera-target"),
        (&["--camera-pos", "1,2", "--camera-target", "0,0,0"], "is not a point: write X,Y,Z"),
        (&["--camera-pos", "1,nan,3", "--camera-target", "0,0,0"], "`nan` in `1,nan,3` is not a finite coordinate"),
        (&["--fov", "180"], "field of view `180` must be a number of degrees in (0, 180)"),
    ] {
        let out = run_in(&dir, &[&["render", "hello_world", "-o", "bad.png"][..], args].concat());
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(stderr(&out).contains(message), "{args:?}: expected `{message}` in {}", stderr(&out));
        assert!(!dir.join("bad.png").exists());
    }
}
