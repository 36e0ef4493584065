//! The `fractal` program end to end, run as a user runs it: images, sequences that resume after an interruption,
//! shards, video, export, bench records, and every kind of bad input (a clear one-line error and the documented exit
//! status, never a panic). Sizes are tiny so the suite stays quick on CPU backends.
//!
//! GPU backends: the wgpu test skips with a note when no adapter opens, and fails instead when
//! FRACTAL_REQUIRE_GPU_BACKENDS=1 (CI, where lavapipe is installed).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::SystemTime;

use fractal_render::image::Image;
use fractal_runtime::output::read_png;

#[path = "cli/refused.rs"]
mod refused;

const FRACTAL: &str = env!("CARGO_BIN_EXE_fractal");

/// An empty scratch directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli").join(test);
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/cli").join(name).display().to_string()
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

fn backends_required() -> bool {
    std::env::var("FRACTAL_REQUIRE_GPU_BACKENDS").is_ok_and(|v| v == "1")
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
fn an_interrupted_sequence_resumes_without_losing_or_rewriting_frames() {
    let dir = scratch("resume");
    let scene = fixture("moving_sphere.fractal");
    let args = ["render", &scene, "--size", "32x32", "--backend", "cpu", "--frames", "0..6", "--fps", "3", "-o"];
    let run = || run_in(&dir, &[&args[..], &["out/%05d.png"]].concat());
    assert_ok(&run());
    let all: BTreeSet<String> = (0..6).map(|f| format!("{f:05}.png")).collect();
    assert_eq!(frames_in(&dir.join("out")), all);
    assert!(dir.join("out/sequence.png.settings").exists(), "the sequence's settings are not recorded");
    let frame = |f: u32| dir.join(format!("out/{f:05}.png"));
    let first: Vec<Image> = (0..6).map(|f| read_png(&frame(f)).unwrap()).collect();
    assert!(first[0] != first[5], "time does not advance the scene");

    // A crashed run: frames 2 and 4 never finished, one of them left its partial file, and a stray partial of a
    // finished frame (3) is lying around too.
    fs::remove_file(frame(2)).unwrap();
    fs::remove_file(frame(4)).unwrap();
    fs::write(dir.join("out/00004.png.partial"), b"half a PNG").unwrap();
    fs::write(dir.join("out/00003.png.partial"), b"stale").unwrap();
    let kept = [0, 1, 3, 5].map(|f| (f, modified(&frame(f))));
    std::thread::sleep(std::time::Duration::from_millis(20));

    let out = run();
    assert_ok(&out);
    assert!(stderr(&out).contains("resuming: 4 of 6"), "{}", stderr(&out));
    assert_eq!(frames_in(&dir.join("out")), all, "missing frames or leftover partial files");
    for (f, time) in kept {
        assert_eq!(modified(&frame(f)), time, "complete frame {f} was rewritten");
    }
    for f in 0..6 {
        assert!(read_png(&frame(f)).unwrap() == first[f as usize], "frame {f} differs after the resume");
    }
    // A third run has nothing left to do.
    let out = run();
    assert_ok(&out);
    assert!(stderr(&out).contains("nothing to do"), "{}", stderr(&out));
}

#[test]
fn shards_cover_every_frame_exactly_once() {
    let dir = scratch("shards");
    let shard = |i: &str, out: &str| {
        let args = [
            "render",
            "hello_world",
            "--size",
            "16x16",
            "--backend",
            "cpu",
            "--frames",
            "3..10",
            "--shard",
            i,
            "-o",
            out,
        ];
        assert_ok(&run_in(&dir, &args));
    };
    shard("0/2", "a/%d.png");
    shard("1/2", "b/%d.png");
    let (a, b) = (frames_in(&dir.join("a")), frames_in(&dir.join("b")));
    assert!(a.is_disjoint(&b), "{a:?} and {b:?} overlap");
    let all: BTreeSet<String> = (3..10).map(|f| format!("{f}.png")).collect();
    assert_eq!(a.union(&b).cloned().collect::<BTreeSet<_>>(), all);
    assert_eq!(a, ["3.png", "5.png", "7.png", "9.png"].map(String::from).into());
    // Shards may share one directory.
    shard("1/2", "both/%d.png");
    shard("0/2", "both/%d.png");
    assert_eq!(frames_in(&dir.join("both")), all);
}

#[test]
fn video_goes_through_ffmpeg() {
    let has_ffmpeg = Command::new("ffmpeg").arg("-version").output().is_ok_and(|o| o.status.success());
    if !has_ffmpeg {
        // The test command installs ffmpeg and asks for every external tool; elsewhere the video path is optional.
        assert!(
            !std::env::var("FRACTAL_REQUIRE_GPU_BACKENDS").is_ok_and(|v| v == "1"),
            "ffmpeg is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but not installed"
        );
        eprintln!("note: skipping, ffmpeg is not installed");
        return;
    }
    let dir = scratch("video");
    let out = run_in(
        &dir,
        &["render", "hello_world", "--size", "32x32", "--backend", "cpu", "--frames", "0..4", "-o", "clip.mp4"],
    );
    assert_ok(&out);
    assert!(fs::metadata(dir.join("clip.mp4")).unwrap().len() > 100);
    assert_eq!(files_in(&dir), ["clip.mp4".to_string()].into());
}

#[test]
fn export_writes_every_target() {
    let dir = scratch("export");
    for target in ["opencl", "wgsl-kernel", "glsl-kernel", "hlsl-kernel", "msl", "spirv"] {
        let file = format!("kernel.{target}");
        assert_ok(&run_in(&dir, &["export", "sphere_box", "--target", target, "-o", &file]));
        let bytes = fs::read(dir.join(&file)).unwrap();
        assert!(bytes.len() > 200, "{target}: only {} bytes", bytes.len());
        if target == "spirv" {
            assert_eq!(bytes[..4], 0x0723_0203u32.to_le_bytes(), "not a SPIR-V module");
        } else {
            let text = String::from_utf8(bytes).expect("text");
            assert!(text.contains("render") || text.contains("main"), "{target} has no entry point");
        }
    }
    // Text to standard output when there is no -o; file scenes export too.
    let out = run_in(&dir, &["export", &fixture("sphere_param.fractal"), "--target", "wgsl-kernel"]);
    assert_ok(&out);
    assert!(stdout(&out).contains("fn render"), "{}", stdout(&out));
}

/// Engine packages go into the directory -o names; a one-file package (Shadertoy) goes to standard output without
/// it. The packages' contents are checked by `fractal-runtime/tests/tools/engines.rs`.
#[test]
fn export_writes_engine_packages() {
    let dir = scratch("export_engines");
    let expected: [(&str, &[&str]); 8] = [
        ("bevy", &["README.md", "sphere_box.wgsl", "sphere_box_material.wgsl"]),
        ("godot", &["README.md", "sphere_box.gdshader", "sphere_box.gdshaderinc"]),
        ("unity", &["README.md", "sphere_box.hlsl", "sphere_box.shader"]),
        ("unreal", &["README.md", "sphere_box.ush", "sphere_box_custom_node.hlsl"]),
        ("shadertoy", &["sphere_box.glsl"]),
        ("glsl", &["README.md", "sphere_box.glsl"]),
        ("hlsl", &["README.md", "sphere_box.hlsl"]),
        ("wgsl", &["README.md", "sphere_box.wgsl"]),
    ];
    for (engine, files) in expected {
        let out = run_in(&dir, &["export", "sphere_box", "--target", engine, "-o", engine]);
        assert_ok(&out);
        let written: Vec<String> = files_in(&dir.join(engine)).into_iter().collect();
        assert_eq!(written, files.iter().map(|f| f.to_string()).collect::<Vec<_>>(), "{engine}");
    }
    let out = run_in(&dir, &["export", "sphere_box", "--target", "shadertoy"]);
    assert_ok(&out);
    assert!(stdout(&out).contains("void mainImage("), "{}", stdout(&out));
}

/// `--camera-path` writes a glTF 2.0 file that the `gltf` crate imports (buffers included): one perspective camera
/// with the scene's field of view, and an animation sampled at every key and every 1/fps second, whose first and last
/// translations are the path's first and last positions with z mirrored (glTF is right-handed).
#[test]
fn export_writes_the_camera_path_as_gltf() {
    let dir = scratch("export_camera");
    assert_ok(&run_in(&dir, &["export", "mandelbrot_zoom", "--camera-path", "--fps", "2", "-o", "camera.gltf"]));
    let (document, buffers, _) = gltf::import(dir.join("camera.gltf")).expect("the export imports as glTF");
    let camera = document.cameras().next().expect("a camera");
    let gltf::camera::Projection::Perspective(perspective) = camera.projection() else { panic!("not perspective") };
    assert!((perspective.yfov() - 55f32.to_radians()).abs() < 1e-6);
    assert!((perspective.aspect_ratio().unwrap() - 16.0 / 9.0).abs() < 1e-6);

    let animation = document.animations().next().expect("an animation");
    assert_eq!(animation.channels().count(), 2);
    let mut translations = Vec::new();
    for channel in animation.channels() {
        let reader = channel.reader(|b| Some(&buffers[b.index()]));
        let times: Vec<f32> = reader.read_inputs().expect("times").collect();
        // Keys every 5 s from 0 to 90, frames every 0.5 s: 181 samples, in order.
        assert_eq!(times.len(), 181);
        assert!(times.windows(2).all(|w| w[0] < w[1]) && times[0] == 0.0 && times[180] == 90.0);
        match reader.read_outputs().expect("values") {
            gltf::animation::util::ReadOutputs::Translations(t) => translations = t.collect(),
            gltf::animation::util::ReadOutputs::Rotations(r) => {
                let unit = |q: [f32; 4]| (q.iter().map(|c| c * c).sum::<f32>() - 1.0).abs() < 1e-5;
                assert!(r.into_f32().all(unit), "rotations are unit quaternions");
            }
            _ => panic!("only translation and rotation are animated"),
        }
    }
    assert_eq!(translations.first(), Some(&[-0.7, 2.4, 0.048]));
    let last = translations.last().unwrap();
    assert!((last[1] - 5.4e-13).abs() < 1e-18 && (last[0] + 0.743_643_9).abs() < 1e-6, "{last:?}");

    // A still camera: the node's transform, no animation.
    assert_ok(&run_in(&dir, &["export", "hello_world", "--camera-path", "-o", "still.gltf"]));
    let (still, _, _) = gltf::import(dir.join("still.gltf")).expect("the export imports as glTF");
    assert_eq!((still.cameras().count(), still.animations().count()), (1, 0));
}

/// `fractal mesh` writes every format; the .glb imports with the `gltf` crate and holds positions, normals, colours
/// and indices of a closed mesh.
#[test]
fn mesh_writes_every_format() {
    let dir = scratch("mesh");
    for ext in ["glb", "ply", "stl", "obj"] {
        let file = format!("sphere.{ext}");
        let out = run_in(&dir, &["mesh", "hello_world", "--resolution", "24", "-o", &file]);
        assert_ok(&out);
        assert!(stderr(&out).contains("closed"), "{}", stderr(&out));
        assert!(fs::metadata(dir.join(&file)).unwrap().len() > 1000, "{ext}: too small");
    }
    let (document, buffers, _) = gltf::import(dir.join("sphere.glb")).expect("the mesh imports as glTF");
    let primitive = document.meshes().next().unwrap().primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let positions: Vec<[f32; 3]> = reader.read_positions().expect("positions").collect();
    let indices: Vec<u32> = reader.read_indices().expect("indices").into_u32().collect();
    assert_eq!(reader.read_normals().expect("normals").count(), positions.len());
    assert_eq!(reader.read_colors(0).expect("colours").into_rgb_f32().count(), positions.len());
    assert!(indices.len() % 3 == 0 && indices.iter().all(|&i| (i as usize) < positions.len()));
    // hello_world's sphere of radius 1 at the origin: every vertex within a cell (2/24 of a side) of it.
    let cell = 2.0 / 24.0;
    assert!(positions.iter().all(|p| ((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - 1.0).abs() < cell));
    let stl = fs::read(dir.join("sphere.stl")).unwrap();
    assert_eq!(stl.len(), 84 + 50 * indices.len() / 3, "STL: one 50-byte record per triangle");

    // A sequence: one file per frame, each of the scene at its own time (julia's constant drifts with t).
    let out = run_in(
        &dir,
        &["mesh", "julia", "--resolution", "16", "--frames", "0..2", "--fps", "0.5", "-o", "seq/%03d.ply"],
    );
    assert_ok(&out);
    assert_eq!(files_in(&dir.join("seq")), ["000.ply".to_string(), "001.ply".to_string()].into());
    assert_ne!(fs::read(dir.join("seq/000.ply")).unwrap(), fs::read(dir.join("seq/001.ply")).unwrap());
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
        &["accuracy", "hello_world", "--size", "24x14", "--truth-step", "0.05", "--default-only", "--time", "0.5"],
    );
    assert_ok(&out);
    let text = stdout(&out);
    assert!(text.starts_with("accuracy of hello_world at t = 0.5 s at 24x14 on cpu"), "{text}");
    let rows = text.lines().filter(|l| l.starts_with("scene default ")).count();
    assert_eq!(rows, 1, "{text}");
    assert!(!text.contains("steps 32") && text.contains("the scene default is"), "{text}");
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

/// A finished sequence rerun with other settings is refused, not reported as done with the old frames kept.
#[test]
fn a_sequence_resumed_with_other_settings_is_refused() {
    let dir = scratch("sequence_settings");
    let render = |size: &str| {
        run_in(
            &dir,
            &["render", "hello_world", "--backend", "cpu", "--size", size, "--frames", "0..2", "-o", "f/%02d.png"],
        )
    };
    assert_ok(&render("16x8"));
    let first = fs::read(dir.join("f/00.png")).unwrap();
    assert_ok(&render("16x8"));
    let out = render("8x8");
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("2 frames of f/%02d.png were rendered with other settings"), "{}", stderr(&out));
    assert!(stderr(&out).contains("size 16x8"), "{}", stderr(&out));
    assert_eq!(fs::read(dir.join("f/00.png")).unwrap(), first);
}

/// The channels of an OpenEXR file, by name, as f32.
fn exr_channels(path: &Path) -> BTreeMap<String, Vec<f32>> {
    let image =
        exr::prelude::read_all_flat_layers_from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let layer = &image.layer_data[0];
    layer.channel_data.list.iter().map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect())).collect()
}

/// `--aov` writes depth (+inf on misses), unit normals (0 on misses) and steps beside the PNG, and they describe the
/// same pixels: a pixel has a depth exactly where it has a normal, and where the PNG is not the background. The CPU
/// writes them from its traces, wgpu from its trace kernel; both describe the same frame.
#[test]
fn aovs_are_written_beside_the_image_and_agree_with_it() {
    let dir = scratch("aov");
    let size = (40u32, 24u32);
    let mut depths = Vec::new();
    for backend in ["cpu", "wgpu"] {
        let out = run_in(
            &dir,
            &[
                "render",
                "hello_world",
                "--backend",
                backend,
                "--size",
                "40x24",
                "--aov",
                "depth,normal,steps",
                "-o",
                &format!("{backend}.png"),
            ],
        );
        if backend == "wgpu" && !out.status.success() {
            let message = stderr(&out);
            assert!(!backends_required(), "wgpu is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but failed:\n{message}");
            assert!(
                message.contains("no wgpu device"),
                "wgpu failed for another reason than a missing device:\n{message}"
            );
            eprintln!("note: skipping the wgpu AOVs, no adapter: {message}");
            break;
        }
        assert_ok(&out);
        let png = read_png(&dir.join(format!("{backend}.png"))).unwrap();
        let depth = exr_channels(&dir.join(format!("{backend}.depth.exr")));
        let normal = exr_channels(&dir.join(format!("{backend}.normal.exr")));
        let steps = exr_channels(&dir.join(format!("{backend}.steps.exr")));
        assert_eq!(depth.keys().collect::<Vec<_>>(), ["Z"]);
        assert_eq!(normal.keys().collect::<Vec<_>>(), ["B", "G", "R"]);
        assert_eq!(steps.keys().collect::<Vec<_>>(), ["Y"]);
        let z = &depth["Z"];
        assert_eq!(z.len(), (size.0 * size.1) as usize);
        let background = png.rgba(0, 0).unwrap();
        let mut hits = 0;
        for (i, &t) in z.iter().enumerate() {
            let n = [normal["R"][i], normal["G"][i], normal["B"][i]];
            let length = n.iter().map(|c| c * c).sum::<f32>().sqrt();
            let (x, y) = (i as u32 % size.0, i as u32 / size.0);
            if t.is_finite() {
                hits += 1;
                assert!(t > 0.0 && (length - 1.0).abs() < 1e-3, "{backend} pixel {i}: depth {t}, normal {n:?}");
                assert!(steps["Y"][i] >= 1.0, "{backend} pixel {i} hit in {} steps", steps["Y"][i]);
                assert_ne!(png.rgba(x, y).unwrap(), background, "{backend} pixel {i} hit but shows the background");
            } else {
                assert_eq!((t, length), (f32::INFINITY, 0.0), "{backend} pixel {i}");
                assert_eq!(png.rgba(x, y).unwrap(), background, "{backend} pixel {i} missed but is not the background");
            }
        }
        assert!(hits > 0 && hits < z.len(), "{backend}: {hits} of {} pixels hit", z.len());
        depths.push(z.clone());
    }
    if let [cpu, gpu] = &depths[..] {
        let same = cpu.iter().zip(gpu).filter(|(a, b)| a == b || (*a - *b).abs() <= 1e-3 * a.abs()).count();
        assert!(same as f64 >= 0.99 * cpu.len() as f64, "depths agree on {same} of {} pixels", cpu.len());
    }
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
