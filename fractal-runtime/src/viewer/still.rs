//! Standing still: while nothing that changes the picture changes, the viewer refines it. Each frame draws one
//! progressive pass ([`Progressive`]: every pixel's next sample of the pixel program, drawn by the scene's one-sample
//! trace kernels on whichever backend draws) and the window shows the passes' mean, the box-filtered pixel; any change
//! starts over. This module owns what counts as standing still and the passes; the game loop draws and presents.
//!
//! - What the picture depends on is a frame's [`StillKey`]: the frame uniforms the kernels read (camera pose and field
//!   of view, lights, parameters, render size; the time only when the scene's shapes or materials read `t`, since
//!   lights and a camera that move with time change their own uniforms), the scene as rendered (with the effect and
//!   quality overrides: a toggle, a step or epsilon change and a reload change it), the window size, the backend and
//!   the presenter. A paused animation, or a playing scene in which nothing moves, stands still; a playing animation
//!   does not.
//! - A frame whose key differs from the last frame's is drawn as usual, with the scene's own samples, and drops the
//!   passes. The next frame with the same key draws pass 1 (every pixel's centre ray: the usual one-sample frame),
//!   each frame after it one more, up to [`PASS_CAP`]; then the viewer rests: it shows the same picture again a few
//!   times a second and renders nothing until something changes.
//! - A scene with `.samples(n)`, n > 1, draws its usual frame with up to n adaptive samples a pixel (one, or where
//!   it differs from a neighbour five, then more while they disagree). The passes take the same sequence of samples
//!   at every pixel, so from n passes on every pixel has at least the samples the usual frame gave it, and until then
//!   the window keeps the usual frame: standing still never makes the picture worse. Past 16 that wait would hide the
//!   refinement for long, and a pixel the adaptive rule stopped early was already within its threshold, so the passes
//!   show from min(n, 16) on ([`SHOW_FROM_MAX`]).
//! - The render scale holds while standing still (the game loop stops feeding the scale controller), so the passes
//!   keep the size they started at.

use fractal_dsl::Scene;
use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::Image;
use fractal_render::precision::Precision;
use fractal_render::progressive::Progressive;
use fractal_render::renderer::{RenderJob, Renderer};

use super::live_scene::{LiveScene, OneSample};

/// The most passes of one still view: as many samples as `--samples` allows.
pub const PASS_CAP: u32 = 256;
/// The most passes a scene with `.samples(n)` waits for before the window shows them.
pub const SHOW_FROM_MAX: u32 = 16;

/// Everything a frame's picture depends on: two frames with equal keys draw the same image.
#[derive(Clone, Debug, PartialEq)]
pub struct StillKey {
    frame: Frame,
    scene: Scene,
    window: (u32, u32),
    backend: Backend,
    presenter: &'static str,
}

impl StillKey {
    /// The key of `frame` of `scene` (as rendered) in a window of `window` pixels, drawn by `backend` and shown by
    /// `presenter`.
    pub fn new(
        scene: &Scene,
        frame: &Frame,
        window: (u32, u32),
        backend: Backend,
        presenter: &'static str,
    ) -> StillKey {
        let frame = if scene.uses_time() { frame.clone() } else { frame.with_time(0.0) };
        StillKey { frame, scene: scene.clone(), window, backend, presenter }
    }
}

/// What a frame draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Plan {
    /// The frame as usual: something changed (or accumulating is off).
    Frame,
    /// The next progressive pass.
    Pass,
    /// Nothing: the passes are done, the window shows their picture again.
    Rest,
}

/// The passes of the view standing still, and the key they are of.
pub struct Accumulator {
    enabled: bool,
    key: Option<StillKey>,
    plan: Plan,
    passes: Option<Progressive>,
    /// Passes before the window shows them (the scene's samples, at most [`SHOW_FROM_MAX`]).
    show_from: u32,
    /// The one-sample form of the scene it was compiled from.
    one_sample: Option<(Scene, OneSample)>,
}

impl Accumulator {
    /// No passes yet; `enabled: false` draws every frame as usual.
    pub fn new(enabled: bool) -> Accumulator {
        Accumulator { enabled, key: None, plan: Plan::Frame, passes: None, show_from: 1, one_sample: None }
    }

    /// What the frame with `key` draws; a key unlike the last frame's drops the passes.
    pub fn plan(&mut self, key: StillKey) -> Plan {
        self.plan = if !self.enabled {
            Plan::Frame
        } else if self.key.as_ref() != Some(&key) {
            self.key = Some(key);
            self.passes = None;
            Plan::Frame
        } else if self.passes() >= PASS_CAP {
            Plan::Rest
        } else {
            Plan::Pass
        };
        self.plan
    }

    /// Forgets the view (after a failed frame): the next frame is drawn as usual.
    pub fn reset(&mut self) {
        self.key = None;
        self.passes = None;
        self.plan = Plan::Frame;
    }

    /// Whether the last frame stood still (drew a pass or rested).
    pub fn still(&self) -> bool {
        self.plan != Plan::Frame
    }

    /// Whether the last frame rested: nothing to render until something changes.
    pub fn resting(&self) -> bool {
        self.plan == Plan::Rest
    }

    /// Passes drawn of the view standing still.
    pub fn passes(&self) -> u32 {
        self.passes.as_ref().map_or(0, Progressive::passes)
    }

    /// Passes in the picture the window shows: 0 while it shows the usual frame.
    pub fn shown(&self) -> u32 {
        let n = self.passes();
        if self.still() && n >= self.show_from {
            n
        } else {
            0
        }
    }

    /// Draws the next pass of `frame` of `live`'s scene with `renderer` in `precision`; the picture to show, or `None`
    /// while the window keeps the usual frame.
    pub fn pass(
        &mut self,
        renderer: &mut dyn Renderer,
        live: &LiveScene,
        (frame, precision): (&Frame, Precision),
    ) -> Result<Option<Image>, RenderError> {
        if self.one_sample.as_ref().is_none_or(|(scene, _)| *scene != live.scene) {
            self.one_sample = Some((live.scene.clone(), live.one_sample()?));
        }
        let Some((_, one)) = &self.one_sample else {
            return Ok(None);
        };
        self.show_from = show_from(live.scene.settings.samples);
        let passes = self.passes.get_or_insert_with(|| Progressive::new(&one.scene, frame));
        passes.draw(renderer, &RenderJob::new(one.sources(live), frame).with_precision(precision))?;
        Ok((passes.passes() >= self.show_from).then(|| passes.image()))
    }

    /// The passes as the title and panel show them: `None` while moving.
    pub fn describe(&self) -> Option<String> {
        if !self.still() {
            return None;
        }
        let n = self.passes();
        Some(match self.plan {
            Plan::Rest => format!("{n} passes, done"),
            _ if self.shown() == 0 => format!("{n}/{} passes", self.show_from),
            _ => format!("{n} passes"),
        })
    }
}

/// Passes before the window shows them, for a scene of `samples` a pixel.
fn show_from(samples: u32) -> u32 {
    samples.clamp(1, SHOW_FROM_MAX)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::{camera, point_light, rgb, scene, sin, sphere, time, vec3, ShapeExt};
    use fractal_render::camera::Pose;
    use fractal_render::frame::ParamValues;

    fn frame(s: &Scene, pose: &Pose, t: f64, size: (u32, u32)) -> Frame {
        Frame::new(s, pose, t, size.0, size.1, &ParamValues::defaults(s)).unwrap()
    }

    fn key(s: &Scene, f: &Frame) -> StillKey {
        StillKey::new(s, f, (64, 48), Backend::Cpu, "softbuffer")
    }

    #[test]
    fn the_key_changes_with_what_the_picture_depends_on() {
        let still = scene(sphere(1.0)).camera(camera([0.0, 0.0, -3.0], [0.0, 0.0, 0.0]));
        let pose = Pose::from_camera(&still.camera, 0.0, &|p| p.default).unwrap();
        let base = key(&still, &frame(&still, &pose, 0.0, (32, 24)));
        assert_eq!(base, key(&still, &frame(&still, &pose, 0.0, (32, 24))), "the same view");
        assert_eq!(base, key(&still, &frame(&still, &pose, 5.0, (32, 24))), "time moves nothing in this scene");
        let mut moved = pose;
        moved.position.x += 1e-3;
        assert_ne!(base, key(&still, &frame(&still, &moved, 0.0, (32, 24))), "the camera moved");
        let mut zoomed = pose;
        zoomed.fov_degrees += 1.0;
        assert_ne!(base, key(&still, &frame(&still, &zoomed, 0.0, (32, 24))), "the field of view changed");
        assert_ne!(base, key(&still, &frame(&still, &pose, 0.0, (16, 12))), "the render scale changed");
        let f = frame(&still, &pose, 0.0, (32, 24));
        assert_ne!(base, StillKey::new(&still, &f, (65, 48), Backend::Cpu, "softbuffer"), "the window changed");
        assert_ne!(base, StillKey::new(&still, &f, (64, 48), Backend::Wgpu, "softbuffer"), "the backend changed");
        assert_ne!(base, StillKey::new(&still, &f, (64, 48), Backend::Cpu, "wgpu surface"), "the presenter changed");
        let shadowed = still.clone().hard_shadows();
        assert_ne!(base, key(&shadowed, &frame(&shadowed, &pose, 0.0, (32, 24))), "an effect changed");

        // Time counts where the shapes read it, and where a light moves with it (through the light's uniforms).
        let moving = scene(sphere(1.0).translate(vec3(sin(time()), 0.0, 0.0)));
        assert_ne!(
            key(&moving, &frame(&moving, &pose, 0.0, (32, 24))),
            key(&moving, &frame(&moving, &pose, 1.0, (32, 24)))
        );
        let lit = scene(sphere(1.0)).light(point_light(vec3(sin(time()), 2.0, 0.0), rgb(1.0, 1.0, 1.0)));
        assert_ne!(key(&lit, &frame(&lit, &pose, 0.0, (32, 24))), key(&lit, &frame(&lit, &pose, 1.0, (32, 24))));

        // Parameters are uniforms.
        let sized = scene(sphere(fractal_dsl::builder::param("r", 1.0, 0.5..2.0)));
        let at = |r: f64| {
            let mut values = ParamValues::defaults(&sized);
            values.set("r", r).unwrap();
            key(&sized, &Frame::new(&sized, &pose, 0.0, 32, 24, &values).unwrap())
        };
        assert_eq!(at(1.0), at(1.0));
        assert_ne!(at(1.0), at(1.5), "a parameter changed");
    }

    #[test]
    fn passes_start_on_the_second_still_frame_and_stop_at_the_cap() {
        let s = scene(sphere(1.0));
        let pose = Pose::from_camera(&s.camera, 0.0, &|p| p.default).unwrap();
        let a = key(&s, &frame(&s, &pose, 0.0, (8, 6)));
        let mut moved = pose;
        moved.position.y += 0.5;
        let b = key(&s, &frame(&s, &moved, 0.0, (8, 6)));
        let mut acc = Accumulator::new(true);
        assert_eq!(acc.plan(a.clone()), Plan::Frame, "the first frame");
        assert_eq!(acc.describe(), None);
        assert_eq!(acc.plan(a.clone()), Plan::Pass, "standing still");
        assert!(acc.still() && !acc.resting());
        assert_eq!(acc.plan(b.clone()), Plan::Frame, "a move resets");
        assert!(!acc.still());
        assert_eq!(acc.plan(b.clone()), Plan::Pass);
        acc.reset();
        assert_eq!(acc.plan(b), Plan::Frame, "a reset forgets the view");
        let mut off = Accumulator::new(false);
        for _ in 0..3 {
            assert_eq!(off.plan(a.clone()), Plan::Frame, "turned off");
        }
    }

    /// Stands still on `s` for `frames` frames with the CPU renderer: what each frame drew, and the last picture.
    fn stand_still(s: Scene, frames: u32) -> (Accumulator, Vec<(Plan, bool)>, Option<Image>) {
        let live = LiveScene::load(&crate::viewer::ViewerScene::built("s", s).unwrap()).unwrap();
        let pose = Pose::from_camera(&live.scene.camera, 0.0, &|p| p.default).unwrap();
        let f = frame(&live.scene, &pose, 0.0, (6, 4));
        let mut renderer = fractal_render::CpuRenderer::new();
        let mut acc = Accumulator::new(true);
        let (mut drawn, mut last) = (Vec::new(), None);
        for _ in 0..frames {
            let plan = acc.plan(key(&live.scene, &f));
            let mut shown = false;
            if plan == Plan::Pass {
                let picture = acc.pass(&mut renderer, &live, (&f, Precision::F32)).unwrap();
                shown = picture.is_some();
                last = picture.or(last);
            }
            drawn.push((plan, shown));
        }
        (acc, drawn, last)
    }

    #[test]
    fn passes_rest_at_the_cap() {
        let (acc, drawn, last) = stand_still(scene(sphere(1.0)), PASS_CAP + 3);
        assert_eq!(drawn[0], (Plan::Frame, false));
        assert!(drawn[1..=PASS_CAP as usize].iter().all(|&d| d == (Plan::Pass, true)), "one pass a frame, each shown");
        assert_eq!(drawn[PASS_CAP as usize + 1..], [(Plan::Rest, false), (Plan::Rest, false)]);
        assert_eq!((acc.passes(), acc.shown()), (PASS_CAP, PASS_CAP));
        assert!(acc.resting());
        assert_eq!(acc.describe().as_deref(), Some("256 passes, done"));
        assert_eq!(last.map(|i| (i.width, i.height)), Some((6, 4)));
    }

    #[test]
    fn scenes_with_samples_show_passes_once_they_are_as_good() {
        assert_eq!((show_from(1), show_from(4), show_from(16), show_from(256)), (1, 4, 16, SHOW_FROM_MAX));
        assert_eq!(show_from(0), 1);
        let (acc, drawn, _) = stand_still(scene(sphere(1.0)).samples(4), 6);
        let shown: Vec<bool> = drawn.iter().map(|d| d.1).collect();
        assert_eq!(shown, [false, false, false, false, true, true], "from the fourth pass on");
        assert_eq!(acc.describe().as_deref(), Some("5 passes"));
        let (acc, _, _) = stand_still(scene(sphere(1.0)).samples(4), 3);
        assert_eq!((acc.shown(), acc.describe().as_deref()), (0, Some("2/4 passes")));
    }
}
