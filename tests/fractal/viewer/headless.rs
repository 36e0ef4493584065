//! The viewer without a window (`fractal view --headless`): the window test's script played in this process (no
//! event loop is made, so no child process is needed), its screenshots checked the same way against offline renders
//! — on wgpu through the texture that stands in for the surface, with every frame timed by the device where it has
//! timestamps; on wgpu with the presenter `auto` picks for the adapter; and on the CPU through host memory.

use fractal_render::{Backend, BackendChoice};
use fractal_runtime::viewer::{run_headless, FrameKind, PresentMode, ViewerScene};

use super::{check_scripted_run, require_backends, scratch_dir, scripted_options, scripted_steps, MOVE_FRAMES};

#[test]
fn the_headless_viewer_shows_the_offline_render_of_the_scripted_pose() {
    let runs = [
        (Backend::Wgpu, PresentMode::Gpu, "wgpu texture"),
        // `auto` reads frames back on a software rasteriser, and draws them on the device on a GPU.
        (Backend::Wgpu, PresentMode::Auto, ""),
        (Backend::Cpu, PresentMode::Auto, "host memory"),
    ];
    for (backend, present, presenter) in runs {
        let dir = scratch_dir(&format!("headless-{backend}-{present:?}"));
        let options = scripted_options(&dir, (BackendChoice::Only(backend), present), scripted_steps(&dir));
        let scene = ViewerScene::compiled("sphere_box", &scenes::SPHERE_BOX);
        // More frames than the script takes: the run ends with the script.
        let run = match run_headless(scene, options, 1000, None) {
            Ok(run) => run,
            Err(e) if backend == Backend::Wgpu && !require_backends() => {
                eprintln!("skipping the headless wgpu run: {e}");
                continue;
            }
            Err(e) => panic!("the headless viewer on {backend} failed: {e}"),
        };
        let presenter = match (presenter, run.summary.device.as_ref().map(|d| d.device_type.as_str())) {
            ("", Some("Cpu")) => "host memory",
            ("", _) => "wgpu texture",
            (given, _) => given,
        };
        assert_eq!(run.summary.presenter, Some(presenter));
        check_scripted_run(&run.summary, presenter);
        let scripted = 3 + MOVE_FRAMES as usize + 2;
        assert!(run.frames.len() >= scripted, "{} frames drawn, the script has {scripted}", run.frames.len());
        assert!(run.frames.iter().all(|(kind, ms)| *kind == FrameKind::Kernel && *ms > 0.0), "{:?}", run.frames);
        assert_eq!(run.summary.frames, run.frames.len() as u64);
        // Where the device has timestamps, each frame's kernel and blit were timed, in order.
        if presenter != "wgpu texture" {
            assert!(run.device_times.is_empty(), "only frames drawn to a wgpu texture are timed by the device");
        } else if !run.device_times.is_empty() {
            assert_eq!(run.device_times.len(), run.frames.len(), "one device time per frame");
            for times in &run.device_times {
                assert!(times.kernel_ms.is_some_and(|ms| ms > 0.0) && times.blit_ms > 0.0, "{times:?}");
            }
        } else {
            eprintln!("note: {backend}'s device wrote no timestamps");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
