//! The interactive viewer end to end.
//!
//! - Under Xvfb (started here on a free display number when `DISPLAY` is unset), the viewer opens `sphere_box`, plays
//!   a scripted camera move (forward for ten frames, a turn of the mouse), toggles shadows and takes screenshots of
//!   what it presented. Each screenshot must equal an offline render of the same pose, time and settings on the same
//!   backend, upscaled to the window the way the viewer upscales; and the X server's own copy of the window
//!   (`xwd -root`) must equal the last screenshot. Runs twice: the default backend with its default presenter (a wgpu
//!   surface on lavapipe), and the CPU backend through softbuffer.
//! - Hot reload: the viewer shows a `.fractal` file; a broken save is reported as `file:line:column` and leaves the
//!   last good picture on screen, a fixed save replaces it (and matches its offline render).
//! - Standing still: with time paused the viewer shows the mean of progressive passes, one more each frame; a
//!   screenshot must equal the same number of passes drawn offline (and be within 40 dB of as many samples a pixel
//!   drawn at once, closer than the one-sample frame), and a turn of the camera must show the usual frame again. On
//!   the default backend (wgpu on lavapipe, through its surface) and on the CPU through softbuffer.
//! - Without a display, an example binary says so in one line and writes its PNG instead.
//!
//! Each viewer run is a child process (this test binary, re-run with [`CHILD_ENV`] set), because a process may create
//! only one window-system event loop. Without Xvfb the window test is skipped with a note, or fails when
//! `FRACTAL_REQUIRE_GPU_BACKENDS=1`.

mod headless;
mod precision;
mod still;
mod ui;

use fractal_render::device::backends_required;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use fractal_render::{
    select, Backend, BackendChoice, Frame, Image, KernelSources, RenderJob, Renderer, RendererOptions, WgpuRenderer,
};
use fractal_runtime::viewer::{
    read_png, Action, Move, PresentMode, RenderScale, ScreenshotInfo, ScriptedStep, ViewerOptions, ViewerScene,
    ViewerSummary,
};

/// Set in the child process: the folder for its screenshots. Unset, the child test does nothing.
const CHILD_ENV: &str = "FRACTAL_VIEWER_TEST_DIR";
/// Set in the child process: `auto` (default backend and presenter) or `cpu-softbuffer`.
const MODE_ENV: &str = "FRACTAL_VIEWER_TEST_MODE";
const WINDOW: (u32, u32) = (320, 240);
/// Seconds per frame of the scripted run; the camera moves at [`SPEED`] for [`MOVE_FRAMES`] frames.
const STEP: f64 = 1.0 / 30.0;
const SPEED: f64 = 1.5;
const MOVE_FRAMES: u32 = 10;
const TURN_PIXELS: f64 = 40.0;
const SENSITIVITY: f64 = 0.003;
/// The screenshot after which the X server's copy of the window is taken.
const LAST_SHOT: &str = "no_shadows.png";
/// How long the viewer stays open after its last screenshot, for `xwd`.
const LINGER: Duration = Duration::from_secs(6);

/// Per channel, the largest difference allowed between a presented pixel and the offline render. Both images come
/// from the same kernel with the same uniforms on the same device, so the renders are identical; presenting converts
/// 8-bit values to floats and back, which is exact for 8-bit unorm targets and within one step for sRGB targets.
const TOLERANCE: u8 = 1;

fn require_backends() -> bool {
    backends_required()
}

fn on_path(program: &str) -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path).map(|dir| dir.join(program)).find(|p| p.is_file())
}

/// A private X server, killed when dropped.
struct Xvfb {
    child: Child,
    display: String,
}

impl Xvfb {
    /// Starts Xvfb on the first free display number from :99.
    fn start(program: &Path) -> Result<Xvfb, String> {
        for number in 99..160 {
            let socket = PathBuf::from(format!("/tmp/.X11-unix/X{number}"));
            if display_in_use(number) {
                continue;
            }
            let display = format!(":{number}");
            let mut child = Command::new(program)
                .args([display.as_str(), "-screen", "0", "800x600x24", "-nolisten", "tcp"])
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .spawn()
                .map_err(|e| format!("cannot start Xvfb: {e}"))?;
            let deadline = Instant::now() + Duration::from_secs(15);
            while Instant::now() < deadline {
                if socket.exists() {
                    return Ok(Xvfb { child, display });
                }
                if let Ok(Some(_)) = child.try_wait() {
                    break; // Lost a race for this number: try the next.
                }
                std::thread::sleep(Duration::from_millis(50));
            }
            let _ = child.kill();
            let _ = child.wait();
        }
        Err("no free X display number between :99 and :159".to_string())
    }
}

/// Whether an X server holds display `number`: its lock file names a live process. A lock left by a server that
/// died is stale (Xvfb replaces it), so that number is free.
fn display_in_use(number: u32) -> bool {
    match std::fs::read_to_string(format!("/tmp/.X{number}-lock")) {
        Ok(text) => match text.trim().parse::<u32>() {
            Ok(pid) => Path::new(&format!("/proc/{pid}")).exists(),
            Err(_) => true,
        },
        // No lock: free unless something else listens on the socket.
        Err(_) => Path::new(&format!("/tmp/.X11-unix/X{number}")).exists(),
    }
}

impl Drop for Xvfb {
    /// Stops the server with SIGTERM, so it removes its lock file and socket; SIGKILL only if it does not stop.
    fn drop(&mut self) {
        let terminated = Command::new("kill").args(["-TERM", &self.child.id().to_string()]).status();
        if terminated.is_ok_and(|s| s.success()) {
            let deadline = Instant::now() + Duration::from_secs(5);
            while Instant::now() < deadline {
                if let Ok(Some(_)) = self.child.try_wait() {
                    return;
                }
                std::thread::sleep(Duration::from_millis(20));
            }
        }
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The display to test on: the caller's, or a fresh Xvfb. `Err` says why there is none.
fn test_display() -> Result<(String, Option<Xvfb>), String> {
    if let Some(display) = std::env::var_os("DISPLAY").filter(|d| !d.is_empty()) {
        return Ok((display.to_string_lossy().into_owned(), None));
    }
    let program = on_path("Xvfb").ok_or("DISPLAY is unset and Xvfb is not installed (Debian: xvfb xauth)")?;
    let xvfb = Xvfb::start(&program)?;
    Ok((xvfb.display.clone(), Some(xvfb)))
}

fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("fractal-viewer-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create a scratch folder");
    dir
}

#[test]
fn the_window_shows_the_offline_render_of_the_scripted_pose() {
    let (display, xvfb) = match test_display() {
        Ok(found) => found,
        Err(reason) if require_backends() => {
            panic!("FRACTAL_REQUIRE_GPU_BACKENDS=1 but no display to test on: {reason}")
        }
        Err(reason) => {
            eprintln!("skipping the viewer window test: {reason}");
            return;
        }
    };
    // The root window is only ours to read on our own Xvfb (the window sits at its top-left corner).
    let xwd = on_path("xwd").filter(|_| xvfb.is_some());
    if xwd.is_none() {
        eprintln!("note: not comparing the X server's copy of the window (needs our own Xvfb and xwd)");
    }
    for mode in ["auto", "cpu-softbuffer", "hot-reload", "animated", "still-auto", "still-cpu", "deep", "ui", "ui-gpu"]
    {
        let dir = scratch_dir(mode);
        let mut child = spawn_child(mode, &dir, &display);
        let last_shot = dir.join(LAST_SHOT);
        let root = dir.join("root.xwd");
        let deadline = Instant::now() + Duration::from_secs(300);
        let mut captured = false;
        let status = loop {
            if let Some(status) = child.try_wait().expect("poll the child") {
                break status;
            }
            if !captured && last_shot.exists() {
                captured = true;
                if let Some(xwd) = &xwd {
                    let out = Command::new(xwd)
                        .args(["-root", "-silent", "-display", display.as_str(), "-out"])
                        .arg(&root)
                        .output()
                        .expect("run xwd");
                    assert!(out.status.success(), "xwd failed: {}", String::from_utf8_lossy(&out.stderr));
                }
            }
            if Instant::now() > deadline {
                let _ = child.kill();
                panic!("the viewer ({mode}) did not exit by itself within 300 s");
            }
            std::thread::sleep(Duration::from_millis(25));
        };
        let output = child.wait_with_output().expect("child output");
        let stdout = String::from_utf8_lossy(&output.stdout);
        let stderr = String::from_utf8_lossy(&output.stderr);
        eprintln!("--- viewer run `{mode}` ---\n{stdout}{stderr}");
        assert!(status.success(), "the viewer run `{mode}` failed ({status})");
        assert!(stdout.contains("1 passed"), "the child ran no test: {stdout}");
        if mode == "hot-reload" {
            // The broken save is reported as file:line:column (the bad call is on line 2).
            let file = dir.join(RELOAD_FILE);
            assert!(stderr.contains(&format!("{}:2:", file.display())), "no located error in: {stderr}");
            assert!(stdout.contains(&format!("reloaded {}", file.display())), "{stdout}");
            let _ = std::fs::remove_dir_all(&dir);
            continue;
        }
        if mode == "animated" {
            assert!(stdout.contains("param radius = 0.9140"), "the param key was reported: {stdout}");
            let _ = std::fs::remove_dir_all(&dir);
            continue;
        }
        if mode == "deep" {
            assert!(stderr.contains("precision f64"), "the viewer did not say the frame's precision: {stderr}");
            let _ = std::fs::remove_dir_all(&dir);
            continue;
        }
        if mode.starts_with("still") || mode.starts_with("ui") {
            let _ = std::fs::remove_dir_all(&dir);
            continue;
        }
        assert!(stdout.contains(&format!("saved screenshot {}", last_shot.display())), "{stdout}");
        if xwd.is_some() {
            assert!(captured, "the last screenshot never appeared while the viewer ran");
            let screen = read_xwd(&root).expect("read the xwd dump");
            let window = crop(&screen, WINDOW.0, WINDOW.1);
            let shot = read_png(&last_shot).expect("read the last screenshot");
            let (worst, _) = compare(&window, &shot);
            assert!(
                worst <= TOLERANCE,
                "{mode}: the X server shows something else than the screenshot (max diff {worst})"
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    drop(xvfb);
}

/// Starts [`viewer_child_process`] in a new process of this test binary, in `mode`, with its files in `dir`.
fn spawn_child(mode: &str, dir: &Path, display: &str) -> Child {
    // The child test by its full name in this binary (`viewer::viewer_child_process`), so `--exact` finds it.
    let child_test = format!("{}::viewer_child_process", module_path!().split_once("::").map_or("", |(_, m)| m));
    let exe = std::env::current_exe().expect("the test binary's path");
    Command::new(exe)
        .args(["--exact", &child_test, "--ignored", "--nocapture", "--test-threads=1"])
        .env(CHILD_ENV, dir)
        .env(MODE_ENV, mode)
        .env("DISPLAY", display)
        .env_remove("WAYLAND_DISPLAY")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the viewer child process")
}

/// The viewer run itself, in a child process started by the test above.
#[test]
#[ignore = "run by the_window_shows_the_offline_render_of_the_scripted_pose in its own process"]
fn viewer_child_process() {
    let Some(dir) = std::env::var_os(CHILD_ENV).map(PathBuf::from) else {
        return;
    };
    let mode = std::env::var(MODE_ENV).unwrap_or_else(|_| "auto".to_string());
    match mode.as_str() {
        "hot-reload" => return hot_reload_child(&dir),
        "animated" => return animated_child(&dir),
        "still-auto" => return still::still_child(&dir, false),
        "still-cpu" => return still::still_child(&dir, true),
        "still-figures" => return still::figures_child(&dir),
        "deep" => return precision::deep_child(&dir),
        "ui" => return ui::ui_child(&dir, PresentMode::Softbuffer),
        "ui-gpu" => return ui::ui_child(&dir, PresentMode::Gpu),
        "picture" => return ui::picture_child(&dir),
        _ => {}
    }
    let (backend, present, presenter) = match mode.as_str() {
        "cpu-softbuffer" => (BackendChoice::Only(Backend::Cpu), PresentMode::Softbuffer, "softbuffer"),
        // On the device whatever the adapter, so the surface path is tested on lavapipe too.
        _ => (BackendChoice::Auto, PresentMode::Gpu, "wgpu surface"),
    };
    let mut script = scripted_steps(&dir);
    script.push(ScriptedStep::Idle(LINGER));
    let options = ViewerOptions { window_position: Some((0, 0)), ..scripted_options(&dir, (backend, present), script) };
    let summary = fractal_runtime::viewer::run(ViewerScene::compiled("sphere_box", &scenes::SPHERE_BOX), options)
        .expect("the viewer runs");
    check_scripted_run(&summary, presenter);
}

/// The scripted session of the window test and of the headless run (module `headless`): frames at the scene's
/// camera, ten frames forward, a turn of the mouse, the panel shown and hidden, shadows toggled and time paused, with
/// four screenshots on the way.
fn scripted_steps(dir: &Path) -> Vec<ScriptedStep> {
    let forward = Action::Move(Move::Forward);
    vec![
        ScriptedStep::Frames(3),
        ScriptedStep::Screenshot(dir.join("start.png")),
        ScriptedStep::Press(forward),
        ScriptedStep::Frames(MOVE_FRAMES),
        ScriptedStep::Release(forward),
        ScriptedStep::Look { dx: TURN_PIXELS, dy: 0.0 },
        ScriptedStep::Screenshot(dir.join("moved.png")),
        ScriptedStep::Trigger(Action::TogglePanel),
        // egui lays a new window out unseen on its first frame (to size it), and shows it from the next.
        ScriptedStep::Frames(2),
        ScriptedStep::Screenshot(dir.join("panel.png")),
        ScriptedStep::Trigger(Action::TogglePanel),
        ScriptedStep::Trigger(Action::CycleShadows),
        ScriptedStep::Trigger(Action::TogglePause),
        ScriptedStep::Frames(2),
        ScriptedStep::Screenshot(dir.join(LAST_SHOT)),
    ]
}

/// The options of a scripted run of `script` on `backend` through `present`, with its screenshots in `dir`.
fn scripted_options(
    dir: &Path,
    (backend, present): (BackendChoice, PresentMode),
    script: Vec<ScriptedStep>,
) -> ViewerOptions {
    ViewerOptions {
        backend,
        present,
        window_size: WINDOW,
        // Half size, so the comparison also checks the upscaling.
        render_scale: RenderScale::Fixed(0.5),
        fixed_time_step: Some(STEP),
        move_speed: SPEED,
        mouse_sensitivity: SENSITIVITY,
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        // These runs compare frames drawn as usual; `still_child` tests the passes.
        accumulate: false,
        ..ViewerOptions::default()
    }
}

/// Checks a run of [`scripted_steps`]: the poses the script asked for, and each screenshot equal to an offline
/// render of its pose upscaled as the viewer upscales; `presenter` is the one expected for wgpu frames (or for
/// every frame, on the CPU).
fn check_scripted_run(summary: &ViewerSummary, presenter: &str) {
    let [start, moved, panel, no_shadows] = summary.screenshots.as_slice() else {
        panic!("expected four screenshots, got {}", summary.screenshots.len());
    };
    println!("device: {}, presenter: {}", start.device, start.presenter);
    if start.device.backend == Backend::Cpu {
        assert_eq!(start.presenter, presenter);
    } else if start.device.backend == Backend::Wgpu && require_backends() {
        assert_eq!(start.presenter, presenter, "wgpu frames should reach the window without a host round trip");
    }

    // The scripted move: 10 frames forward at 1.5 units/s with 1/30 s steps, then a turn to the right.
    let scene = scenes::SPHERE_BOX.scene();
    let initial = fractal_render::Pose::from_camera(&scene.camera, start.time, &|p| p.default).unwrap();
    assert!(start.pose.position.distance(initial.position) < 1e-12, "the first screenshot is the scene's camera");
    let travelled = SPEED * STEP * MOVE_FRAMES as f64;
    let expected = start.pose.position + start.pose.forward * travelled;
    assert!(moved.pose.position.distance(expected) < 1e-9, "moved to {:?}, expected {expected:?}", moved.pose.position);
    // Yaw about the world's up axis (0 along +z, positive towards +x) and pitch above the horizon.
    let angles = |f: glam::DVec3| (f.x.atan2(f.z), f.y.asin());
    let ((yaw0, pitch0), (yaw1, pitch1)) = (angles(start.pose.forward), angles(moved.pose.forward));
    let turn = yaw1 - yaw0;
    assert!((turn - TURN_PIXELS * SENSITIVITY).abs() < 1e-9, "moving the mouse right turns right: yaw changed {turn}");
    assert!((pitch1 - pitch0).abs() < 1e-9, "a horizontal mouse move keeps the pitch");
    assert_ne!(no_shadows.scene.settings.shadows, scene.settings.shadows, "the shadow toggle recompiled the scene");

    let mut images = Vec::new();
    for shot in [start, moved, no_shadows] {
        let presented = read_png(&shot.path).expect("read the screenshot");
        assert_eq!((presented.width, presented.height), WINDOW);
        assert_eq!(shot.render_size, (WINDOW.0 / 2, WINDOW.1 / 2));
        let offline = upscale(&render_offline(shot), WINDOW.0, WINDOW.1);
        let (worst, mean) = compare(&presented, &offline);
        println!("{}: max channel difference {worst}, mean {mean:.4}", shot.path.display());
        assert!(worst <= TOLERANCE, "{}: the window differs from the offline render by {worst}", shot.path.display());
        images.push(presented);
    }
    let changed = |a: &Image, b: &Image| a.pixels.iter().zip(&b.pixels).filter(|(x, y)| x != y).count();
    // The panel (O) is drawn over the same frame in the window's top-left corner, and nowhere else.
    let with_panel = read_png(&panel.path).expect("read the panel screenshot");
    assert_eq!(panel.pose.position, moved.pose.position);
    let (px, py, pw, ph) = panel.ui_rect.expect("the panel was drawn");
    assert!(px < 40 && py < 40, "the panel sits in the top-left corner, at ({px}, {py})");
    let mut inside = 0;
    for y in 0..WINDOW.1 {
        for x in 0..WINDOW.0 {
            if with_panel.rgba(x, y) != images[1].rgba(x, y) {
                assert!(x >= px && y >= py && x < px + pw && y < py + ph, "the panel reaches ({x}, {y})");
                inside += 1;
            }
        }
    }
    assert!(inside > 2000, "the panel changed only {inside} pixels");
    assert!(changed(&images[0], &images[1]) > images[0].pixels.len() / 20, "the camera move changed the picture");
    assert!(changed(&images[1], &images[2]) > 100, "turning the shadows off changed the picture");
}

/// The scene file the hot-reload run edits.
const RELOAD_FILE: &str = "reload.fractal";

/// Waits until `path` exists (a screenshot was saved).
fn wait_for(path: &Path) -> bool {
    let deadline = Instant::now() + Duration::from_secs(120);
    while !path.exists() {
        if Instant::now() > deadline {
            return false;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    true
}

/// Views a `.fractal` file while another thread saves a broken version (the last good scene must stay on screen)
/// and then a recoloured one (which must replace it).
fn hot_reload_child(dir: &Path) {
    let file = dir.join(RELOAD_FILE);
    let original = scenes::source_file("hello_world").expect("hello_world source");
    let colour = "rgb(0.9, 0.2, 0.1)";
    assert!(original.lines().nth(1).is_some_and(|l| l.contains(colour)), "the colour is on line 2");
    let broken = original.replacen(colour, "rgb(0.9, 0.2)", 1);
    let recoloured = original.replacen(colour, "rgb(0.1, 0.3, 0.9)", 1);
    std::fs::write(&file, original).expect("write the scene file");
    let shots = [dir.join("before.png"), dir.join("broken.png"), dir.join("after.png")];
    let settle = Duration::from_secs(2);
    let script = vec![
        ScriptedStep::Trigger(Action::TogglePause),
        ScriptedStep::Frames(2),
        ScriptedStep::Screenshot(shots[0].clone()),
        ScriptedStep::Idle(settle),
        ScriptedStep::Screenshot(shots[1].clone()),
        ScriptedStep::Idle(settle),
        ScriptedStep::Screenshot(shots[2].clone()),
    ];
    let editor = {
        let (file, shots) = (file.clone(), shots.clone());
        std::thread::spawn(move || {
            assert!(wait_for(&shots[0]), "the first screenshot never came");
            std::fs::write(&file, broken).expect("save the broken scene");
            assert!(wait_for(&shots[1]), "the second screenshot never came");
            std::fs::write(&file, recoloured).expect("save the recoloured scene");
        })
    };
    let options = ViewerOptions {
        window_size: (160, 120),
        render_scale: RenderScale::Fixed(1.0),
        fixed_time_step: Some(STEP),
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        // These runs compare frames drawn as usual; `still_child` tests the passes.
        accumulate: false,
        ..ViewerOptions::default()
    };
    let summary = fractal_runtime::viewer::run(ViewerScene::file(&file), options).expect("the viewer runs");
    editor.join().expect("the editor thread");
    let [before, broken, after] = summary.screenshots.as_slice() else {
        panic!("expected three screenshots, got {}", summary.screenshots.len());
    };
    let images: Vec<Image> = [before, broken, after].iter().map(|s| read_png(&s.path).expect("screenshot")).collect();
    assert_eq!(broken.scene, before.scene, "a broken save keeps the last good scene");
    assert_eq!(images[1], images[0], "a broken save keeps the last good picture");
    assert_ne!(after.scene, before.scene, "the fixed save was loaded");
    assert!(images[2] != images[1], "the recoloured scene is on screen");
    let offline = upscale(&render_file_scene(after), 160, 120);
    let (worst, _) = compare(&images[2], &offline);
    assert!(worst <= TOLERANCE, "the reloaded scene differs from its offline render by {worst}");
}

/// Views a scene whose geometry and light move with `t`, starting with a `param(..)` set by option and stepping it with
/// its key: both frames must match offline renders at their own times and values, without recompiling.
fn animated_child(dir: &Path) {
    use fractal_dsl::builder::{camera, cos, param, point_light, rgb, scene, sin, sphere, time, vec3, ShapeExt};
    let moving = scene(
        sphere(param("radius", 0.8, 0.5..1.2))
            .translate(vec3(sin(time()) * 0.6, 0.0, 0.0))
            .material(rgb(0.9, 0.6, 0.2)),
    )
    .light(point_light(vec3(cos(time()) * 3.0, 2.0, -2.0), rgb(1.0, 1.0, 1.0)).intensity(12.0))
    .camera(camera([0.0, 0.5, -4.0], [0.0, 0.0, 0.0]));
    let script = vec![
        ScriptedStep::Frames(2),
        ScriptedStep::Screenshot(dir.join("early.png")),
        ScriptedStep::Frames(20),
        ScriptedStep::Trigger(Action::IncreaseParam),
        ScriptedStep::Screenshot(dir.join("late.png")),
    ];
    let options = ViewerOptions {
        window_size: (160, 120),
        render_scale: RenderScale::Fixed(1.0),
        fixed_time_step: Some(STEP),
        params: vec![("radius".to_string(), 0.9)],
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        // These runs compare frames drawn as usual; `still_child` tests the passes.
        accumulate: false,
        ..ViewerOptions::default()
    };
    let summary =
        fractal_runtime::viewer::run(ViewerScene::built("moving", moving).unwrap(), options).expect("the viewer runs");
    let [early, late] = summary.screenshots.as_slice() else {
        panic!("expected two screenshots, got {}", summary.screenshots.len());
    };
    assert_eq!(early.params.get("radius"), Some(0.9), "the start value from the options");
    let expected = 0.9 + (1.2 - 0.5) / 50.0;
    assert!((late.params.get("radius").unwrap() - expected).abs() < 1e-12, "one step up the range");
    assert_eq!(late.scene, early.scene, "a parameter change does not change (or recompile) the scene");
    assert!((late.time - early.time - 21.0 * STEP).abs() < 1e-9, "t advanced one step per frame");
    let images: Vec<Image> = [early, late].iter().map(|s| read_png(&s.path).expect("screenshot")).collect();
    assert!(images[0] != images[1], "the scene moved");
    for (shot, image) in [early, late].iter().zip(&images) {
        let (worst, _) = compare(image, &render_file_scene(shot));
        assert!(worst <= TOLERANCE, "{}: differs from its offline render by {worst}", shot.path.display());
    }
}

/// Renders a screenshot of a runtime-loaded scene offline: its compiled kernels, or the interpreter on the CPU.
fn render_file_scene(shot: &ScreenshotInfo) -> Image {
    let kernels = fractal_dsl::compile(&shot.scene).unwrap();
    let interpreter = fractal_dsl::eval::interp::Interpreter::new(&shot.scene).unwrap();
    let sources = KernelSources::compiled(&kernels).with_cpu(&interpreter, &shot.scene);
    let (w, h) = shot.render_size;
    let frame = Frame::new(&shot.scene, &shot.pose, shot.time, w, h, &shot.params).expect("pack the frame");
    let mut renderer: Box<dyn Renderer> = match shot.device.backend {
        Backend::Wgpu => Box::new(WgpuRenderer::new().expect("open wgpu")),
        other => select::open(other, &RendererOptions::default()).expect("open the backend"),
    };
    renderer.render(&RenderJob::new(sources, &frame)).expect("offline render")
}

/// Renders what `shot` shows with a fresh renderer of the same backend and the kernels `fractal render` would use.
fn render_offline(shot: &ScreenshotInfo) -> Image {
    let compiled = &scenes::SPHERE_BOX;
    let recompiled = fractal_dsl::compile(&shot.scene).unwrap();
    let unchanged = shot.scene.settings == compiled.scene().settings;
    let (wgsl, opencl) = if unchanged {
        (compiled.wgsl(), compiled.opencl())
    } else {
        (recompiled.wgsl.as_str(), recompiled.opencl.as_str())
    };
    let native = compiled.native();
    let kernels = KernelSources::default().with_wgsl(wgsl).with_opencl(opencl).with_cpu(&native, &shot.scene);
    let (w, h) = shot.render_size;
    let frame = Frame::new(&shot.scene, &shot.pose, shot.time, w, h, &shot.params).expect("pack the frame");
    let mut renderer: Box<dyn Renderer> = match shot.device.backend {
        Backend::Wgpu => Box::new(WgpuRenderer::new().expect("open wgpu")),
        other => select::open(other, &RendererOptions::default()).expect("open the backend"),
    };
    assert_eq!(renderer.device().name, shot.device.name, "the offline render runs on the viewer's device");
    renderer.render(&RenderJob::new(kernels, &frame)).expect("offline render")
}

/// Nearest-pixel upscaling: window pixel d shows source pixel ((2d + 1)·src) / (2·dst), the one under its centre.
fn upscale(image: &Image, width: u32, height: u32) -> Image {
    let at = |d: u32, dst: u32, src: u32| (((2 * d + 1) * src) / (2 * dst)).min(src - 1);
    let mut pixels = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        for x in 0..width {
            let (sx, sy) = (at(x, width, image.width), at(y, height, image.height));
            pixels.push(image.pixels[(sy * image.width + sx) as usize]);
        }
    }
    Image { width, height, pixels }
}

/// Largest and mean per-channel difference of the RGB channels (alpha is not shown in a window).
fn compare(a: &Image, b: &Image) -> (u8, f64) {
    assert_eq!((a.width, a.height), (b.width, b.height), "image sizes differ");
    let mut worst = 0u8;
    let mut total = 0u64;
    for (&p, &q) in a.pixels.iter().zip(&b.pixels) {
        for c in 0..3 {
            let d = p.to_le_bytes()[c].abs_diff(q.to_le_bytes()[c]);
            worst = worst.max(d);
            total += d as u64;
        }
    }
    (worst, total as f64 / (a.pixels.len() * 3) as f64)
}

fn crop(image: &Image, width: u32, height: u32) -> Image {
    assert!(image.width >= width && image.height >= height, "the screen is smaller than the window");
    let pixels =
        (0..height).flat_map(|y| (0..width).map(move |x| image.pixels[(y * image.width + x) as usize])).collect();
    Image { width, height, pixels }
}

/// Reads an X window dump (ZPixmap, 24 or 32 bits per pixel, as Xvfb's 24-bit screen writes it).
fn read_xwd(path: &Path) -> Result<Image, String> {
    let data = std::fs::read(path).map_err(|e| e.to_string())?;
    let field = |i: usize| -> Result<u32, String> {
        let b = data.get(4 * i..4 * i + 4).ok_or("truncated xwd header")?;
        Ok(u32::from_be_bytes([b[0], b[1], b[2], b[3]]))
    };
    let (header_size, format, width, height) = (field(0)?, field(2)?, field(4)?, field(5)?);
    let (byte_order, bits_per_pixel, bytes_per_line) = (field(7)?, field(11)?, field(12)?);
    let masks = [field(14)?, field(15)?, field(16)?];
    let colours = field(19)?;
    if format != 2 || !(bits_per_pixel == 32 || bits_per_pixel == 24) {
        return Err(format!("unsupported xwd: format {format}, {bits_per_pixel} bits per pixel"));
    }
    let start = header_size as usize + colours as usize * 12;
    let bytes = (bits_per_pixel / 8) as usize;
    let mut pixels = Vec::with_capacity((width * height) as usize);
    for y in 0..height as usize {
        for x in 0..width as usize {
            let at = start + y * bytes_per_line as usize + x * bytes;
            let raw = data.get(at..at + bytes).ok_or("truncated xwd pixels")?;
            let mut word = [0u8; 4];
            word[..bytes].copy_from_slice(raw);
            let value =
                if byte_order == 0 { u32::from_le_bytes(word) } else { u32::from_be_bytes(word) >> (8 * (4 - bytes)) };
            let channel = |mask: u32| ((value & mask) >> mask.trailing_zeros()) as u8;
            pixels.push(u32::from_le_bytes([channel(masks[0]), channel(masks[1]), channel(masks[2]), 255]));
        }
    }
    Ok(Image { width, height, pixels })
}

/// The path of an example binary built with this test's profile, building it when it is missing.
fn example_binary(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    // target/<profile>/deps/viewer-<hash> → target/<profile>/examples/<name>
    let profile_dir = exe.parent().and_then(Path::parent).expect("target/<profile>");
    let binary = profile_dir.join("examples").join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    if !binary.is_file() {
        let mut cargo = Command::new(env!("CARGO"));
        cargo.args(["build", "--example", name]).current_dir(env!("CARGO_MANIFEST_DIR"));
        if profile_dir.file_name() == Some(&OsString::from("release")) {
            cargo.arg("--release");
        }
        let status = cargo.status().expect("run cargo build");
        assert!(status.success(), "cargo build --example {name} failed");
    }
    binary
}

#[test]
fn without_a_display_an_example_renders_a_png() {
    let binary = example_binary("hello_world");
    let dir = scratch_dir("headless");
    let output = Command::new(&binary)
        .current_dir(&dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run the example");
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(output.status.success(), "exit {}: {stdout}{stderr}", output.status);
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 1, "one line: {stdout}");
    assert!(lines[0].starts_with("no display") && lines[0].contains("hello_world.png"), "{stdout}");
    let image = read_png(&dir.join("hello_world.png")).expect("the PNG was written");
    assert_eq!((image.width, image.height), ViewerOptions::default().window_size);
    assert!(!image.is_uniform(), "the PNG shows the scene");
    let _ = std::fs::remove_dir_all(&dir);
}
