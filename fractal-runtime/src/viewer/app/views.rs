//! Views the user keeps: bookmarks (saved with B, restored from the panel), stills (F9: the current view at the
//! panel's still size and passes, drawn in the view's precision, written as a PNG beside the scene without leaving
//! the viewer) and flights (R … R: the camera flown, written as a camera path).

use std::collections::BTreeMap;
use std::path::PathBuf;

use fractal_render::backend::cpu::CpuRenderer;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::Image;
use fractal_render::precision::Precision;
use fractal_render::progressive::Progressive;
use fractal_render::renderer::{RenderJob, Renderer};

use super::App;
use crate::viewer::bookmarks::{Bookmark, Bookmarks};
use crate::viewer::flight::{scene_with_flight, write_flight, Flight};
use crate::viewer::screenshot::{next_screenshot_path, write_png};
use crate::viewer::session::ViewerScene;

impl App {
    /// The folder and file stem of what the viewer writes beside the scene: the scene file's, or the screenshot
    /// folder and the scene's name for a built-in scene.
    pub(super) fn beside_scene(&self) -> (PathBuf, String) {
        match &self.source {
            ViewerScene::File(path) => (
                path.parent().map(PathBuf::from).unwrap_or_default(),
                path.file_stem().map_or(self.live.name.clone(), |s| s.to_string_lossy().into_owned()),
            ),
            _ => (self.options.screenshot_dir.clone(), self.live.name.clone()),
        }
    }

    /// The bookmarks beside the scene, read once.
    fn bookmarks(&mut self) -> Option<&mut Bookmarks> {
        if self.bookmarks.is_none() {
            let (folder, stem) = self.beside_scene();
            match Bookmarks::load(&Bookmarks::beside(&folder, &stem)) {
                Ok(marks) => self.bookmarks = Some(marks),
                Err(e) => self.report(format!("bookmarks: {e}")),
            }
        }
        self.bookmarks.as_mut()
    }

    /// The bookmarks' names, for the panel.
    pub(super) fn bookmark_names(&mut self) -> Vec<String> {
        self.bookmarks().map(|b| b.list.iter().map(|m| m.name.clone()).collect()).unwrap_or_default()
    }

    /// Saves the current view as the next `view N`.
    pub(super) fn save_bookmark(&mut self) {
        // The free camera from here on, so the view on screen is the one a restore gives back to the last bit.
        self.take_control();
        let Some(camera) = self.fly else {
            return println!("no view to bookmark yet");
        };
        let values = self.params.values();
        let params: BTreeMap<String, f64> = values.decls().iter().map(|d| (d.name.clone(), values.lookup(d))).collect();
        let time = self.time;
        let Some(marks) = self.bookmarks() else {
            return;
        };
        let name = marks.next_name();
        match marks.add(Bookmark::new(name.clone(), &camera, time, params)) {
            Ok(()) => println!("bookmarked \"{name}\" in {}", marks.path.display()),
            Err(e) => eprintln!("{e}"),
        }
    }

    /// Goes to the bookmark `name`: its camera (as the free camera), time and parameter values.
    pub(super) fn go_to_bookmark(&mut self, name: &str) {
        let Some(mark) = self.bookmarks().and_then(|b| b.get(name)).cloned() else {
            return println!("no bookmark \"{name}\"");
        };
        self.fly = Some(mark.camera());
        self.time = mark.time;
        for (param, value) in &mark.params {
            if let Err(e) = self.params.set(param, *value) {
                eprintln!("bookmark \"{name}\": {e}");
            }
        }
        println!("at bookmark \"{name}\"");
    }

    /// Renders the current view at the still size to the next `STEM-still-NNNN.png` beside the scene: the mean of
    /// the still's progressive passes (the box-filtered pixel, as standing still shows it), or with one pass the
    /// scene's usual frame.
    pub(super) fn render_still(&mut self) {
        let Some(pose) = self.last_pose.or_else(|| self.scene_pose().ok()) else {
            return println!("no view to render yet");
        };
        let ((width, height), passes) = (self.still_size, self.still_passes);
        let frame = match Frame::new(&self.live.scene, &pose, self.time, width, height, self.params.values()) {
            Ok(frame) => frame,
            Err(e) => return eprintln!("cannot render a still: {e}"),
        };
        let precision = self.frame_precision(&frame);
        let started = std::time::Instant::now();
        println!("rendering a still, {width}x{height}, {passes} passes, {precision} …");
        let image = if passes <= 1 {
            let job = RenderJob::new(self.live.kernels(), &frame).with_precision(precision);
            match self.engine.renderer().draws_in(&job) {
                true => self.engine.renderer().render(&job),
                false => CpuRenderer::new().render(&job),
            }
        } else {
            self.progressive_still(&frame, precision, passes)
        };
        let (folder, stem) = self.beside_scene();
        let path = next_screenshot_path(&folder, &format!("{stem}-still"));
        match image.map_err(|e| e.to_string()).and_then(|image| write_png(&image, &path)) {
            Ok(()) => {
                let seconds = started.elapsed().as_secs_f64();
                println!(
                    "rendered still {} ({width}x{height}, {passes} passes, {precision}, {seconds:.1} s)",
                    path.display()
                );
                self.summary.stills.push(path);
            }
            Err(e) => eprintln!("cannot render a still: {e}"),
        }
        // The still took a while: the next frame's time step should not count it.
        self.last_frame_at = None;
    }

    /// The mean of `passes` progressive passes of `frame`, each one sample a pixel.
    fn progressive_still(&mut self, frame: &Frame, precision: Precision, passes: u32) -> Result<Image, RenderError> {
        let one = self.live.one_sample()?;
        let mut progressive = Progressive::new(&one.scene, frame);
        let job = RenderJob::new(one.sources(&self.live), frame).with_precision(precision);
        let on_engine = self.engine.renderer().draws_in(&job);
        let mut cpu = CpuRenderer::new();
        for _ in 0..passes {
            let renderer: &mut dyn Renderer = if on_engine { self.engine.renderer() } else { &mut cpu };
            progressive.draw(renderer, &job)?;
        }
        Ok(progressive.image())
    }

    /// Starts recording a flight, or ends the one being recorded and writes it beside the scene.
    pub(super) fn toggle_flight(&mut self) {
        let Some(flight) = self.flight.take() else {
            self.take_control();
            let mut flight = Flight::default();
            if let Some(fly) = self.fly {
                flight.record(&fly.pose(), 0.0);
            }
            self.flight = Some(flight);
            return println!("recording a flight (R stops it)");
        };
        let fov = flight.fov_degrees();
        let keys = flight.finish();
        if keys.len() < 2 {
            return println!("flight not written: it needs two keys (fly for at least a second)");
        }
        let scene = scene_with_flight(self.live.authored(), keys, fov);
        let (folder, stem) = self.beside_scene();
        let (w, h) = self.render_size;
        match write_flight(&scene, &folder, &stem, w.max(1) as f64 / h.max(1) as f64) {
            Ok((fractal, gltf)) => {
                println!("flight written to {} and {}", fractal.display(), gltf.display());
                self.summary.flights.push(fractal);
            }
            Err(e) => eprintln!("{e}"),
        }
    }
}
