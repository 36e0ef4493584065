//! The viewer's UI used the way a person uses it, through egui's own input (a pointer pressing widgets, keys and
//! typed text), in a window under Xvfb (`ui_child`, run in its own process by the window test, twice: through
//! softbuffer, where the UI is rasterised on the host, and through the wgpu surface, where egui-wgpu draws it):
//!
//! - the panel shows: shown with O, it covers a block of the window's top-left corner and leaves the rest as it was;
//! - a slider moves the picture: pressing near the end of the `radius` slider's rail sets the parameter near its
//!   maximum, and the sphere on screen grows;
//! - a bookmark restores the view exactly (pose, time, values, picture), from its file beside the scene;
//! - F9 renders a still at the size and passes typed into the panel, beside the scene; R … R records a flight into a scene file with that
//!   `camera_path(..)` and a glTF camera;
//! - an error shows in place: typing a broken scene into the editor (F2) shows its `line:column` and leaves the last
//!   good picture outside the UI; typing a good one replaces the picture, and saving writes it to the file.

use std::path::Path;
use std::time::Duration;

use fractal_render::Image;
use fractal_runtime::viewer::{
    read_png, Action, Move, PresentMode, RenderScale, ScreenshotInfo, ScriptedStep, UiInput, ViewerOptions, ViewerScene,
};

use super::{spawn_child, test_display, STEP};

const WINDOW: (u32, u32) = (640, 400);
const SCENE: &str = "ui.fractal";
const SOURCE: &str = r#"scene(sphere(param("radius", 0.6, 0.3..1.2)).material(rgb(0.9, 0.4, 0.2)))
    .light(directional(vec3(0.6, 0.8, -0.4), rgb(1.0, 1.0, 1.0)))
    .camera(camera(vec3(0.0, 0.0, -3.2), vec3(0.0, 0.0, 0.0)).fov(50.0))
"#;
/// The broken edit: a sphere call missing its closing parenthesis on line 1.
const BROKEN: &str = "scene(sphere(0.5)\n";
/// The edit that compiles: a smaller, blue sphere.
const FIXED: &str = r#"scene(sphere(0.4).material(rgb(0.2, 0.4, 0.9)))
    .camera(camera(vec3(0.0, 0.0, -3.2), vec3(0.0, 0.0, 0.0)).fov(50.0))
"#;
/// Frames of the recorded flight (at the run's fixed step: a second and a half).
const FLIGHT_FRAMES: u32 = 45;
/// Longer than the editor's pause before it compiles an edit.
const PAUSE: Duration = Duration::from_millis(900);

fn press(widget: &str, at: (f32, f32)) -> ScriptedStep {
    ScriptedStep::Ui(UiInput::Press { widget: widget.to_string(), at })
}

/// A click: press, a frame, release, a frame for the change to apply.
fn click(widget: &str, at: (f32, f32)) -> Vec<ScriptedStep> {
    vec![press(widget, at), ScriptedStep::Frames(1), ScriptedStep::Ui(UiInput::Release), ScriptedStep::Frames(2)]
}

/// Replaces the editor's text with `text` (click into it, select all, type) and waits for it to compile.
fn retype(text: &str) -> Vec<ScriptedStep> {
    let mut steps = click("source", (0.5, 0.1));
    steps.extend([
        ScriptedStep::Ui(UiInput::Command('A')),
        ScriptedStep::Frames(1),
        ScriptedStep::Ui(UiInput::Type(text.to_string())),
        ScriptedStep::Frames(1),
        ScriptedStep::Idle(PAUSE),
        ScriptedStep::Frames(2),
    ]);
    steps
}

/// Pixels that differ between `a` and `b` outside the rectangles `skip` (x, y, width, height).
fn changed_outside(a: &Image, b: &Image, skip: &[Option<(u32, u32, u32, u32)>]) -> usize {
    let inside =
        |x: u32, y: u32| skip.iter().flatten().any(|&(sx, sy, w, h)| x >= sx && y >= sy && x < sx + w && y < sy + h);
    let pixels = (0..a.height).flat_map(|y| (0..a.width).map(move |x| (x, y)));
    pixels.filter(|&(x, y)| !inside(x, y) && a.rgba(x, y) != b.rgba(x, y)).count()
}

/// Views [`SOURCE`] and works its panel and editor.
pub(super) fn ui_child(dir: &Path, present: PresentMode) {
    let file = dir.join(SCENE);
    std::fs::write(&file, SOURCE).expect("write the scene");
    let shot = |name: &str| ScriptedStep::Screenshot(dir.join(name));
    let mut script = vec![ScriptedStep::Trigger(Action::TogglePause), ScriptedStep::Frames(3), shot("plain.png")];
    script.extend([ScriptedStep::Trigger(Action::TogglePanel), ScriptedStep::Frames(2), shot("panel.png")]);
    script.extend(click("param:radius", (0.95, 0.5)));
    script.push(shot("slider.png"));
    // Bookmarks: mark this view, turn away, go back by the panel's button.
    script.extend(click("bookmark", (0.5, 0.5)));
    script.push(shot("marked.png"));
    script.extend([ScriptedStep::Look { dx: 120.0, dy: -30.0 }, ScriptedStep::Frames(1), shot("turned.png")]);
    script.extend(click("bookmark:view 1", (0.5, 0.5)));
    script.push(shot("restored.png"));
    // A still from where we stand, its size and passes typed into the panel; a flight: R, forward 1.5 s, R.
    for (entry, value) in [("still width", "320"), ("still height", "180"), ("still passes", "4")] {
        script.extend(click(entry, (0.5, 0.5)));
        script.extend([ScriptedStep::Ui(UiInput::Command('A')), ScriptedStep::Ui(UiInput::Type(value.to_string()))]);
        script.extend([ScriptedStep::Ui(UiInput::Key("Enter".to_string())), ScriptedStep::Frames(2)]);
    }
    script.push(ScriptedStep::Trigger(Action::RenderStill));
    script.extend([ScriptedStep::Trigger(Action::RecordFlight), ScriptedStep::Press(Action::Move(Move::Forward))]);
    // Enter adds a key between the timed ones (at 0.5 s).
    script.extend([ScriptedStep::Frames(15), ScriptedStep::Trigger(Action::FlightKey)]);
    script.extend([ScriptedStep::Frames(FLIGHT_FRAMES - 15), ScriptedStep::Release(Action::Move(Move::Forward))]);
    script.extend([ScriptedStep::Trigger(Action::RecordFlight), ScriptedStep::Trigger(Action::FollowScenePath)]);
    script.push(ScriptedStep::Frames(1));
    script.extend([ScriptedStep::Trigger(Action::TogglePanel), ScriptedStep::Trigger(Action::ToggleEditor)]);
    script.extend([ScriptedStep::Frames(2), shot("editor.png")]);
    script.extend(retype(BROKEN));
    script.push(shot("broken.png"));
    script.extend(retype(FIXED));
    script.push(shot("fixed.png"));
    script.extend(click("save", (0.5, 0.5)));
    script.push(ScriptedStep::Frames(2));
    let options = ViewerOptions {
        present,
        window_size: WINDOW,
        render_scale: RenderScale::Fixed(0.5),
        fixed_time_step: Some(STEP),
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        accumulate: false,
        ..ViewerOptions::default()
    };
    let summary = fractal_runtime::viewer::run(ViewerScene::file(&file), options).expect("the viewer runs");
    let [plain, panel, slider, marked, turned, restored, editor, broken, fixed] = summary.screenshots.as_slice() else {
        panic!("expected nine screenshots, got {}", summary.screenshots.len());
    };
    let image = |s: &ScreenshotInfo| read_png(&s.path).expect("read a screenshot");
    let (plain_image, panel_image) = (image(plain), image(panel));

    let presenter = if present == PresentMode::Gpu { "wgpu surface" } else { "softbuffer" };
    assert!(summary.screenshots.iter().all(|s| s.presenter == presenter), "every picture through the {presenter}");

    // The panel shows: a block in the top-left corner, over an unchanged picture.
    assert_eq!(plain.ui_rect, None, "a scripted run starts with the panel hidden");
    let (x, y, w, h) = panel.ui_rect.expect("the panel was drawn");
    println!("panel at ({x}, {y}), {w}x{h}");
    assert!(x < 40 && y < 40 && w > 150 && h > 150, "the panel is a block in the top-left corner");
    assert_eq!(changed_outside(&plain_image, &panel_image, &[panel.ui_rect]), 0, "the panel changed only its pixels");
    let under_panel = changed_outside(&plain_image, &panel_image, &[]);
    assert!(under_panel > (w * h / 4) as usize, "the panel covers its block: {under_panel} pixels changed");

    // A slider moves the picture: the radius near its maximum, a bigger sphere outside the panel.
    let radius = slider.params.get("radius").expect("the radius param");
    assert!(radius > 1.1, "pressing near the end of the radius slider set {radius}");
    let grown = changed_outside(&panel_image, &image(slider), &[slider.ui_rect]);
    assert!(grown > 2000, "the bigger sphere changed only {grown} pixels");

    // A bookmark restores the view exactly: the same pose, time and values, the same picture outside the panel.
    assert_ne!(turned.pose, marked.pose, "the look moved the camera");
    assert_eq!((restored.pose, restored.time), (marked.pose, marked.time), "the bookmark's view");
    assert_eq!(restored.params.values(), marked.params.values());
    let (marked_image, restored_image) = (image(marked), image(restored));
    assert_eq!(changed_outside(&marked_image, &restored_image, &[marked.ui_rect, restored.ui_rect]), 0);
    assert!(changed_outside(&marked_image, &image(turned), &[marked.ui_rect, turned.ui_rect]) > 1000);
    let marks = std::fs::read_to_string(dir.join("ui.bookmarks.toml")).expect("the bookmark file beside the scene");
    assert!(marks.contains("name = \"view 1\"") && marks.contains("radius"), "{marks}");

    // The still: the panel's size, beside the scene; the flight: a scene file with its path, and a glTF camera.
    let [still] = summary.stills.as_slice() else { panic!("expected one still, got {:?}", summary.stills) };
    assert_eq!(still.parent(), Some(dir));
    let still_image = read_png(still).expect("read the still");
    assert_eq!((still_image.width, still_image.height), (320, 180), "the size typed into the panel");
    let [flight] = summary.flights.as_slice() else { panic!("expected one flight, got {:?}", summary.flights) };
    let flown = fractal_dsl::parse::parse_str(&std::fs::read_to_string(flight).expect("read the flight"))
        .expect("the flight is a scene file");
    let fractal_dsl::CameraPlacement::Path { keys, .. } = &flown.camera.placement else {
        panic!("the flight's camera is a path: {:?}", flown.camera.placement)
    };
    let seconds = FLIGHT_FRAMES as f64 * STEP;
    assert!(keys.len() >= 3 && (keys.last().unwrap().time - seconds).abs() < 2.0 * STEP, "{keys:?}");
    assert!(keys.iter().any(|k| (k.time - 0.5).abs() < 1.5 * STEP), "the key added with Enter: {keys:?}");
    let travelled = glam::DVec3::from(keys[0].position).distance(keys.last().unwrap().position.into());
    assert!(travelled > 0.5 * seconds, "the flight moved forward {travelled}");
    assert!(flight.with_extension("gltf").exists(), "the glTF camera beside it");

    // An error shows in place: its line:column, the last good scene and picture outside the UI.
    let error = broken.source_error.as_deref().expect("the broken edit is an error");
    assert!(error.starts_with("1:") || error.starts_with("2:"), "the error is located: {error}");
    assert_eq!(broken.scene, slider.scene, "a broken edit keeps the last good scene");
    assert!(broken.ui_rect.is_some() && editor.ui_rect.is_some(), "the editor (and the error line) are drawn");
    let (ex, ..) = editor.ui_rect.unwrap();
    assert!(ex > WINDOW.0 / 3, "the editor sits on the window's right, from x = {ex}");
    let kept = changed_outside(&image(editor), &image(broken), &[editor.ui_rect, broken.ui_rect]);
    assert_eq!(kept, 0, "outside the UI, the broken edit left the last good picture");
    assert!(
        changed_outside(&image(editor), &image(broken), &[editor.ui_rect]) > 100,
        "the error line shows over the picture"
    );

    // The fixed edit replaces the picture; saving writes it.
    assert_eq!(fixed.source_error, None, "the fixed text compiles");
    assert_ne!(fixed.scene, broken.scene, "the fixed text is on screen");
    assert_eq!(std::fs::read_to_string(&file).expect("read the saved scene"), FIXED, "saving wrote the editor's text");
}

/// The README's picture of the window: `amazing_box` with the panel and the editor open, written to
/// `docs/viewer.png`. Run by hand: `cargo test --test fractal viewer::ui::window_picture -- --ignored`.
#[test]
#[ignore = "draws the README's picture of the viewer; run by hand"]
fn window_picture() {
    let (display, _xvfb) = test_display().expect("a display (Xvfb) for the viewer");
    let dir = std::env::temp_dir().join(format!("fractal-viewer-picture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    let output = spawn_child("picture", &dir, &display).wait_with_output().expect("the viewer child");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/viewer.png");
    std::fs::copy(dir.join("window.png"), &docs).expect("copy the picture into docs/");
    println!("wrote {}", docs.display());
}

/// The child of [`window_picture`].
pub(super) fn picture_child(dir: &Path) {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/fractal/amazing_box.fractal");
    let script = vec![
        ScriptedStep::Trigger(Action::TogglePause),
        ScriptedStep::Trigger(Action::TogglePanel),
        ScriptedStep::Trigger(Action::ToggleEditor),
        ScriptedStep::Frames(40),
        ScriptedStep::Screenshot(dir.join("window.png")),
    ];
    let options = ViewerOptions {
        window_size: (1280, 720),
        render_scale: RenderScale::Fixed(1.0),
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        ..ViewerOptions::default()
    };
    fractal_runtime::viewer::run(ViewerScene::file(scene), options).expect("the viewer runs");
}
