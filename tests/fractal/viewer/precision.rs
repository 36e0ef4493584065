//! The viewer 1e-9 from the Mandelbulb's pole (`mandelbulb_dive` at its last key, paused), on the default backend:
//! the view asks for f64, so the window shows an f64 frame of the same pose (the backend's f64 kernel where its device
//! has f64, lavapipe's included; the CPU renderer's otherwise), and that is not the f32 frame, which is rounding noise
//! there.

use std::path::Path;

use fractal_render::precision::Precision;
use fractal_render::{CpuRenderer, Frame, KernelSources, RenderJob, Renderer};
use fractal_runtime::viewer::{read_png, RenderScale, ScriptedStep, ViewerOptions, ViewerScene};

use fractal::scenes;

use super::{compare, STEP, TOLERANCE};

/// The dive's last key: 1e-9 from the surface.
const DEEP: f64 = 27.0;

pub(super) fn deep_child(dir: &Path) {
    let script = vec![ScriptedStep::Frames(2), ScriptedStep::Screenshot(dir.join("deep.png"))];
    let options = ViewerOptions {
        window_size: (96, 54),
        render_scale: RenderScale::Fixed(1.0),
        fixed_time_step: Some(STEP),
        start_time: DEEP,
        paused: true,
        screenshot_dir: dir.to_path_buf(),
        script: Some(script),
        print_help: false,
        accumulate: false,
        ..ViewerOptions::default()
    };
    let compiled = &scenes::MANDELBULB_DIVE;
    let summary = fractal_runtime::viewer::run(ViewerScene::compiled("mandelbulb_dive", compiled), options)
        .expect("the viewer runs");
    let [shot] = summary.screenshots.as_slice() else {
        panic!("expected one screenshot, got {}", summary.screenshots.len());
    };
    let shown = read_png(&shot.path).expect("read the screenshot");
    let (w, h) = shot.render_size;
    let frame = Frame::new(&shot.scene, &shot.pose, shot.time, w, h, &shot.params).expect("pack the frame");
    let native = compiled.native();
    let sources = KernelSources::default().with_cpu(&native, &shot.scene).with_cpu_wide(&native);
    let draw = |p: Precision| CpuRenderer::new().render(&RenderJob::new(sources, &frame).with_precision(p)).unwrap();
    let (wide, narrow) = (draw(Precision::F64), draw(Precision::F32));
    let (worst, _) = compare(&shown, &wide);
    assert!(worst <= TOLERANCE, "the window is not the f64 frame (max diff {worst})");
    let (_, mean) = compare(&shown, &narrow);
    assert!(mean > 4.0, "the window is as close to the f32 frame as to the f64 one (mean diff {mean})");
    println!("deep frame shown in f64 on {}, {} presenter", shot.device, shot.presenter);
}
