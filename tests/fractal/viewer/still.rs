//! Standing still in the viewer: progressive passes on screen, against the same passes drawn offline.
//!
//! - `still_child` views `sphere_box` (whose own `.samples(16)` draws its usual frame) with time paused: before 16
//!   passes the window keeps the usual frame; from then on a screenshot equals as many passes drawn offline on the same
//!   backend (and lies within 40 dB of as many samples a pixel drawn at once, closer than one sample a pixel); a turn
//!   of the camera shows the usual frame again, and standing still after it starts over.
//! - `standing_still_figures` (ignored: it measures, `docs/performance.md` has the command) stands still on
//!   `mandelbulb_bench` at 480×270 for two seconds on the default backend and prints the passes drawn and the PSNR of
//!   the picture against 256 passes.

use std::path::Path;
use std::time::Duration;

use fractal_render::progressive::Progressive;
use fractal_render::{
    select, Backend, BackendChoice, CpuRenderer, Frame, Image, KernelSources, RenderJob, Renderer, RendererOptions,
    WgpuRenderer,
};
use fractal_runtime::viewer::{
    read_png, write_png, Action, PresentMode, RenderScale, ScreenshotInfo, ScriptedStep, ViewerOptions, ViewerScene,
};

use fractal_runtime::truth::image::{ImageTruth, ImageTruthSettings};
use fractal_runtime::truth::TruthSettings;

use super::{compare, render_offline, spawn_child, test_display, upscale, SENSITIVITY, STEP, TOLERANCE, TURN_PIXELS};

/// Passes the still screenshots show: more than `sphere_box`'s 16 samples, from which the passes are shown.
const STILL_PASSES: u32 = 20;
/// Passes before the early screenshot: fewer than 16, so the window still shows the usual frame.
const EARLY_PASSES: u32 = 8;

/// Views `sphere_box` with time paused: standing still, turning, standing still again.
pub(super) fn still_child(dir: &Path, cpu: bool) {
    let (backend, present) = match cpu {
        true => (BackendChoice::Only(Backend::Cpu), PresentMode::Softbuffer),
        false => (BackendChoice::Auto, PresentMode::Gpu),
    };
    // The first frame is drawn as usual; each later one of the same view adds a pass, a screenshot's frame too.
    let script = vec![
        ScriptedStep::Trigger(Action::TogglePause),
        ScriptedStep::Frames(EARLY_PASSES),
        ScriptedStep::Screenshot(dir.join("early.png")),
        ScriptedStep::Frames(STILL_PASSES - EARLY_PASSES - 1),
        ScriptedStep::Screenshot(dir.join("still.png")),
        ScriptedStep::Look { dx: TURN_PIXELS, dy: 0.0 },
        ScriptedStep::Screenshot(dir.join("moved.png")),
        ScriptedStep::Frames(STILL_PASSES - 1),
        ScriptedStep::Screenshot(dir.join("still_again.png")),
    ];
    let window = (160, 120);
    let options = ViewerOptions {
        backend,
        present,
        window_size: window,
        render_scale: RenderScale::Fixed(0.5),
        fixed_time_step: Some(STEP),
        mouse_sensitivity: SENSITIVITY,
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        ..ViewerOptions::default()
    };
    let summary = fractal_runtime::viewer::run(ViewerScene::compiled("sphere_box", &scenes::SPHERE_BOX), options)
        .expect("the viewer runs");
    let [early, still, moved, again] = summary.screenshots.as_slice() else {
        panic!("expected four screenshots, got {}", summary.screenshots.len());
    };
    println!("device: {}, presenter: {}", still.device, still.presenter);
    assert_eq!(still.scene.settings.samples, 16, "the scene takes up to 16 samples a pixel");
    assert_eq!((early.passes, still.passes, moved.passes, again.passes), (0, STILL_PASSES, 0, STILL_PASSES));
    assert_eq!(early.pose, still.pose, "standing still");
    assert_ne!(moved.pose.forward, still.pose.forward, "the turn moved the camera");
    let presented = |shot: &ScreenshotInfo| read_png(&shot.path).expect("read the screenshot");
    let stretch = |image: &Image| upscale(image, window.0, window.1);

    for (shot, what) in [(early, "before 16 passes the window keeps"), (moved, "a move shows")] {
        let (worst, _) = compare(&presented(shot), &stretch(&render_offline(shot)));
        assert!(worst <= TOLERANCE, "{what} the usual frame: it differs from it by {worst}");
    }
    for shot in [still, again] {
        let image = presented(shot);
        let (passes, direct, one) = progressive_offline(shot);
        let name = shot.path.display();
        let (worst, mean) = compare(&image, &stretch(&passes));
        println!("{name}: {} passes, max channel difference {worst}, mean {mean:.4}", shot.passes);
        assert!(worst <= TOLERANCE, "{name}: differs from {} passes drawn offline by {worst}", shot.passes);
        let (refined, plain) = (psnr(&image, &stretch(&direct)), psnr(&stretch(&one), &stretch(&direct)));
        println!("  {refined:.1} dB from {} samples a pixel at once; one sample a pixel {plain:.1} dB", shot.passes);
        assert!(refined > 40.0 && refined > plain + 3.0, "{name}: {refined:.1} dB, one sample {plain:.1} dB");
    }
}

/// The scene's one-sample form and its trace kernels, as `fractal render --progressive` draws passes.
fn one_sample(scene: &fractal_dsl::Scene) -> (fractal_dsl::Scene, fractal_dsl::Kernels) {
    let one = scene.clone().samples(1);
    let kernels = fractal_dsl::compile(&one).expect("compile").tracing();
    (one, kernels)
}

/// A fresh renderer of the screenshot's backend.
fn renderer_of(shot: &ScreenshotInfo) -> Box<dyn Renderer> {
    match shot.device.backend {
        Backend::Wgpu => Box::new(WgpuRenderer::new().expect("open wgpu")),
        other => select::open(other, &RendererOptions::default()).expect("open the backend"),
    }
}

fn frame_of(shot: &ScreenshotInfo) -> Frame {
    let (w, h) = shot.render_size;
    Frame::new(&shot.scene, &shot.pose, shot.time, w, h, &shot.params).expect("pack the frame")
}

/// What a still screenshot of `sphere_box` shows, drawn offline: its passes on a fresh renderer of its backend; as
/// many samples a pixel drawn at once on the CPU, with no adaptive stop (`fractal render --samples N`); and one sample
/// a pixel.
fn progressive_offline(shot: &ScreenshotInfo) -> (Image, Image, Image) {
    let (one, kernels) = one_sample(&shot.scene);
    let native = scenes::SPHERE_BOX.native();
    let sources = KernelSources::compiled(&kernels).with_cpu(&native, &one);
    let frame = frame_of(shot);
    let mut renderer = renderer_of(shot);
    let mut passes = Progressive::new(&one, &frame);
    for _ in 0..shot.passes {
        passes.draw(renderer.as_mut(), &RenderJob::new(sources, &frame)).expect("a pass");
    }
    let cpu = |scene: &fractal_dsl::Scene| {
        let job = RenderJob::new(KernelSources::default().with_cpu(&native, scene), &frame);
        CpuRenderer::new().render(&job).expect("a CPU render")
    };
    let many = shot.scene.clone().samples(shot.passes).sample_threshold(0.0);
    (passes.image(), cpu(&many), cpu(&one))
}

/// PSNR of `a` against `b` over RGB, in dB.
fn psnr(a: &Image, b: &Image) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height), "image sizes differ");
    let mut sum = 0.0;
    for (&p, &q) in a.pixels.iter().zip(&b.pixels) {
        for c in 0..3 {
            sum += (f64::from(p.to_le_bytes()[c]) - f64::from(q.to_le_bytes()[c])).powi(2);
        }
    }
    10.0 * (255.0f64 * 255.0 / (sum / (a.pixels.len() * 3) as f64)).log10()
}

/// The figures run's window, rendered at full size.
const FIGURES_SIZE: (u32, u32) = (480, 270);
/// How long the figures run stands still.
const FIGURES_STILL: Duration = Duration::from_secs(2);
/// Passes of the converged picture the figures compare with.
const CONVERGED: u32 = 256;
/// Set: the figures also compare the first still view with the image truth (`docs/image-truth.md`), marched at
/// [`TRUTH_STEP`] footprints.
const TRUTH_ENV: &str = "FRACTAL_FIGURES_TRUTH";
const TRUTH_STEP: f64 = 1.0 / 64.0;

/// Measures standing still on `mandelbulb_bench`: passes in [`FIGURES_STILL`] and the picture's PSNR against
/// [`CONVERGED`] passes. Prints the figures; asserts nothing about time.
#[test]
#[ignore = "measures; run by hand (docs/performance.md)"]
fn standing_still_figures() {
    let (display, _xvfb) = test_display().expect("a display (DISPLAY, or Xvfb installed)");
    let dir = std::env::temp_dir().join(format!("fractal-viewer-figures-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create a scratch folder");
    let output = spawn_child("still-figures", &dir, &display).wait_with_output().expect("the child's output");
    print!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    assert!(output.status.success(), "the figures run failed");
}

pub(super) fn figures_child(dir: &Path) {
    // Twice: the first time the one-sample kernels are compiled when the view first stands still; the second time
    // (after a small turn) they are ready.
    let script = vec![
        ScriptedStep::Trigger(Action::TogglePause),
        ScriptedStep::Frames(1),
        ScriptedStep::Idle(FIGURES_STILL),
        ScriptedStep::Screenshot(dir.join("first.png")),
        ScriptedStep::Look { dx: 10.0, dy: 0.0 },
        ScriptedStep::Frames(1),
        ScriptedStep::Idle(FIGURES_STILL),
        ScriptedStep::Screenshot(dir.join("second.png")),
    ];
    let options = ViewerOptions {
        window_size: FIGURES_SIZE,
        render_scale: RenderScale::Fixed(1.0),
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        ..ViewerOptions::default()
    };
    let compiled = &scenes::MANDELBULB_BENCH;
    let summary =
        fractal_runtime::viewer::run(ViewerScene::compiled("mandelbulb_bench", compiled), options).expect("the viewer");
    let native = compiled.native();
    for (shot, what) in summary.screenshots.iter().zip(["first still view (kernels compiled)", "second still view"]) {
        let shown = read_png(&shot.path).expect("read the screenshot");
        let (one, kernels) = one_sample(&shot.scene);
        let sources = KernelSources::compiled(&kernels).with_cpu(&native, &one);
        let frame = frame_of(shot);
        let mut renderer = renderer_of(shot);
        let mut passes = Progressive::new(&one, &frame);
        let (mut first, mut same) = (None, None);
        for _ in 0..CONVERGED {
            passes.draw(renderer.as_mut(), &RenderJob::new(sources, &frame)).expect("a pass");
            first = first.or_else(|| Some(passes.image()));
            if passes.passes() == shot.passes {
                same = Some(passes.image());
            }
        }
        let converged = passes.image();
        let reference = shot.path.with_extension("converged.png");
        write_png(&converged, &reference).expect("write the reference");
        println!("{what}: {} on {}, {}x{}", shot.device, shot.presenter, shot.render_size.0, shot.render_size.1);
        println!(
            "  {} passes on screen after {:.1} s standing still (the screenshot frame's own pass included)",
            shot.passes,
            FIGURES_STILL.as_secs_f64()
        );
        if let Some(same) = same {
            println!("  against its passes drawn offline: max channel difference {}", compare(&shown, &same).0);
        }
        let first_image = first.expect("one pass");
        let (one_pass, picture) = (psnr(&first_image, &converged), psnr(&shown, &converged));
        println!("  PSNR against {CONVERGED} passes: one pass {one_pass:.1} dB, the picture {picture:.1} dB");
        println!("  screenshot {}, reference {}", shot.path.display(), reference.display());
        if std::env::var_os(TRUTH_ENV).is_some() && shot.path.ends_with("first.png") {
            let start = std::time::Instant::now();
            let settings = ImageTruthSettings {
                truth: TruthSettings { step_footprints: TRUTH_STEP, ..TruthSettings::default() },
                ..ImageTruthSettings::default()
            };
            let truth = ImageTruth::compute(&shot.scene, &frame, settings).expect("the image truth").image();
            println!(
                "  PSNR against the image truth ({:.0} s): one pass {:.1} dB, the picture {:.1} dB, {CONVERGED} passes \
                 {:.1} dB",
                start.elapsed().as_secs_f64(),
                psnr(&first_image, &truth),
                psnr(&shown, &truth),
                psnr(&converged, &truth)
            );
        }
    }
}
