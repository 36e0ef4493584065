//! Without a display: whether there is a window system to open a window on, and the fallback that renders the scene's
//! first frame (at the window size, from the scene's camera or the camera path file, in the precision the view asks
//! for) to a PNG.

use std::path::Path;

use fractal_render::backend::cpu::CpuRenderer;
use fractal_render::camera::Pose;
use fractal_render::choose_precision::decide;
use fractal_render::device::DeviceInfo;
use fractal_render::frame::{Frame, ParamValues};
use fractal_render::renderer::{RenderJob, Renderer};

use super::engine::EngineChain;
use super::live_scene::LiveScene;
use super::path_file::load_camera_path;
use super::screenshot::write_png;
use super::session::{ViewerError, ViewerOptions, ViewerScene};

/// `Ok` when an X11 or Wayland display is named in the environment (on other systems the window system is always
/// there); otherwise why not.
pub fn display_available() -> Result<(), String> {
    if !cfg!(all(unix, not(target_os = "macos"), not(target_os = "android"))) {
        return Ok(());
    }
    let set = |name: &str| std::env::var_os(name).is_some_and(|v| !v.is_empty());
    if set("DISPLAY") || set("WAYLAND_DISPLAY") {
        Ok(())
    } else {
        Err("DISPLAY and WAYLAND_DISPLAY are unset".to_string())
    }
}

/// Renders the first frame the viewer would show to `png` (no window); returns the device that drew it.
pub fn render_png(scene: &ViewerScene, options: &ViewerOptions, png: &Path) -> Result<DeviceInfo, ViewerError> {
    let overrides = super::effects::EffectOverrides::default().with_samples(options.samples);
    let live = LiveScene::load(scene).and_then(|l| l.with_overrides(&overrides)).map_err(ViewerError::Scene)?;
    let mut params = ParamValues::defaults(&live.scene);
    for (name, value) in &options.params {
        params.set(name, *value)?;
    }
    let time = options.start_time;
    let pose = match &options.camera_path {
        Some(file) => {
            let path = load_camera_path(file).map_err(ViewerError::CameraPath)?;
            path.path.pose(time, path.fov_degrees.unwrap_or(live.scene.camera.fov_degrees))
        }
        None => Pose::from_camera(&live.scene.camera, time, &|d| params.lookup(d))
            .map_err(|e| ViewerError::Frame(e.into()))?,
    };
    let (width, height) = options.window_size;
    let frame = Frame::new(&live.scene, &pose, time, width, height, &params)?;
    let chosen = decide(options.precision, &live.scene, &frame, live.evaluator(), live.evaluator_wide())?;
    eprintln!("precision {chosen}");
    let job = RenderJob::new(live.kernels(), &frame).with_precision(chosen.precision);
    let mut chain = EngineChain::new(options.backend, options.renderer);
    let mut notes = Vec::new();
    loop {
        let mut engine = chain.next(&mut notes)?;
        if !engine.renderer().draws_in(&job) {
            // The backend does not compute in the view's precision (wgpu in f64): the CPU draws the frame.
            let image = CpuRenderer::new().render(&job)?;
            write_png(&image, png).map_err(|message| ViewerError::Output { path: png.to_path_buf(), message })?;
            return Ok(CpuRenderer::new().device());
        }
        match engine.renderer().render(&job) {
            Ok(image) => {
                write_png(&image, png).map_err(|message| ViewerError::Output { path: png.to_path_buf(), message })?;
                return Ok(engine.device());
            }
            Err(e) if e.is_backend_specific() && chain.has_more() => {
                notes.push(format!("{} failed, falling back: {e}", engine.device().backend));
            }
            Err(e) => return Err(e.into()),
        }
    }
}
