//! Host-side packing of the frame uniforms every kernel reads ([`FrameLayout`]): camera, time, image size, lights
//! and parameter values, evaluated on the host for one time and one set of parameter values.
//!
//! Lights are expressions of `t` and `param(..)`; they are evaluated here (in f64, then rounded to f32), so a kernel
//! only reads numbers and a moving light never recompiles anything.
//!
//! A scene with perturbed Mandelbrot patterns
//! ([`fractal_dsl::formula::mandelbrot`](mod@fractal_dsl::formula::mandelbrot)) also gets the reference orbit of the
//! camera position's pattern coordinates, computed here in f64 from the f64 pose: that is what lets a zoom go past what
//! the kernels' f32 can resolve.

use fractal_dsl::analyse::ReferenceSpec;
use fractal_dsl::back::{FrameLayout, Scalar};
use fractal_dsl::{LightKind, ParamDecl, Scene};
use glam::DVec3;

use crate::camera::Pose;
use crate::error::FrameError;
pub use crate::limits::{MAX_IMAGE_SIDE, MAX_TIME};

/// Values of a scene's parameters, in [`Scene::params`] order (the uniform order).
#[derive(Clone, Debug, PartialEq)]
pub struct ParamValues {
    decls: Vec<ParamDecl>,
    values: Vec<f64>,
}

impl ParamValues {
    /// Every parameter of `scene` at its default.
    pub fn defaults(scene: &Scene) -> ParamValues {
        let decls = scene.params();
        let values = decls.iter().map(|p| p.default).collect();
        ParamValues { decls, values }
    }

    /// The given values, one per parameter of `scene` in order; each must lie within its declared range.
    pub fn from_values(scene: &Scene, values: &[f64]) -> Result<ParamValues, FrameError> {
        let decls = scene.params();
        if decls.len() != values.len() {
            return Err(FrameError::ParamCount { expected: decls.len(), got: values.len() });
        }
        let mut out = ParamValues::defaults(scene);
        for (decl, &value) in decls.iter().zip(values) {
            out.set(&decl.name, value)?;
        }
        Ok(out)
    }

    /// Sets one parameter by name; refuses unknown names and values outside the declared range.
    pub fn set(&mut self, name: &str, value: f64) -> Result<(), FrameError> {
        let index =
            self.decls.iter().position(|p| p.name == name).ok_or_else(|| FrameError::UnknownParam(name.to_string()))?;
        let decl = &self.decls[index];
        if !(value.is_finite() && value >= decl.min && value <= decl.max) {
            return Err(FrameError::ParamOutOfRange { name: name.to_string(), value, min: decl.min, max: decl.max });
        }
        self.values[index] = value;
        Ok(())
    }

    pub fn get(&self, name: &str) -> Option<f64> {
        self.decls.iter().position(|p| p.name == name).map(|i| self.values[i])
    }

    /// The declarations, in uniform order.
    pub fn decls(&self) -> &[ParamDecl] {
        &self.decls
    }

    /// The values, in uniform order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The value of `decl` (by name), or its default when these values do not name it.
    pub fn lookup(&self, decl: &ParamDecl) -> f64 {
        self.get(&decl.name).unwrap_or(decl.default)
    }

    fn check_matches(&self, scene_params: &[ParamDecl]) -> Result<(), FrameError> {
        if self.decls.len() != scene_params.len() {
            return Err(FrameError::ParamCount { expected: scene_params.len(), got: self.decls.len() });
        }
        for (want, have) in scene_params.iter().zip(&self.decls) {
            if want.name != have.name {
                return Err(FrameError::ParamMismatch { expected: want.name.clone(), found: have.name.clone() });
            }
        }
        Ok(())
    }
}

/// The frame uniforms of one image: [`FrameLayout`] slots of four f32 each, plus the image size they were packed
/// for.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    layout: FrameLayout,
    width: u32,
    height: u32,
    slots: Vec<[f32; 4]>,
    /// What the camera position lost when rounded to the f32 of slot 0: the position is slot 0 plus this, to about
    /// 48 bits. Host-side only: the f32 kernels do not read it, the CPU renderer's f64 instance and the truth do.
    origin_low: [f32; 3],
}

/// One light as a kernel reads it from its two slots.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSlot {
    /// Unit direction towards the light, and colour · intensity.
    Directional { direction: [f32; 3], radiance: [f32; 3] },
    /// Position, and colour · intensity (falls off with the squared distance).
    Point { position: [f32; 3], radiance: [f32; 3] },
}

/// Checks a scene time against [`MAX_TIME`] (NaN fails too).
pub fn check_time(time: f64) -> Result<(), FrameError> {
    if time.abs() <= MAX_TIME {
        Ok(())
    } else {
        Err(FrameError::Time(time))
    }
}

/// Checks that every number of the distance tree that moves (reads `t` or a `param`) is finite in f32 at this time
/// and with these parameter values. Validation cannot see `sqrt(t - 5)` go bad at t < 5 or a `param` divide by 0;
/// the kernels would draw NaN geometry (nothing, or something else on each backend), so the frame is refused instead.
/// An expression that reads the point (a displacement, a pattern) has no one value per frame and is not checked here.
fn check_shape_values(scene: &Scene, time: f64, lookup: &dyn Fn(&ParamDecl) -> f64) -> Result<(), FrameError> {
    let mut bad = None;
    fractal_dsl::visit::visit_node_exprs(&scene.root, &mut |e| {
        if bad.is_none() && !fractal_dsl::validate::is_constant(e) && !e.uses_point() {
            let v = e.eval(time, lookup);
            if !(v.is_finite() && v.abs() <= f64::from(f32::MAX)) {
                bad = Some(FrameError::NonFiniteValue { expr: fractal_dsl::print::expr(e), value: v, time });
            }
        }
    });
    bad.map_or(Ok(()), Err)
}

/// Checks an image size against [`MAX_IMAGE_SIDE`].
pub fn check_image_size(width: u32, height: u32) -> Result<(), FrameError> {
    if width == 0 || height == 0 || width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE {
        return Err(FrameError::ImageSize { width, height, max: MAX_IMAGE_SIDE });
    }
    Ok(())
}

/// The slots of a scene with this many lights and parameters and the perturbation reference `reference`.
fn layout(lights: usize, params: usize, reference: Option<ReferenceSpec>) -> FrameLayout {
    FrameLayout { lights, params, orbit: reference.map_or(0, |r| r.entries()) }
}

fn finite3(v: [f64; 3]) -> bool {
    v.iter().all(|c| c.is_finite())
}

fn f32x3(v: DVec3) -> [f32; 3] {
    v.as_vec3().to_array()
}

/// How far from the origin (on some axis) a camera may stand with the frame anchored at the origin; beyond, the
/// frame of a scene whose kernels read the anchor ([`fractal_dsl::lower::reads_anchor`]) is anchored at the camera
/// ([`Frame::anchor`]). Nearer cameras keep the origin so that a scene's own view
/// computes what it computed before anchors existed; out there f32's spacing is 7.6e-6.
pub const ANCHOR_BEYOND: f64 = 64.0;

/// The anchor of a frame seen from `position`: the origin, or the camera's position rounded to f32.
fn anchor_of(position: DVec3) -> DVec3 {
    if position.abs().max_element() <= ANCHOR_BEYOND {
        return DVec3::ZERO;
    }
    DVec3::from_array(f32x3(position).map(f64::from))
}

/// `v` as a high f32 part and the low f32 part the rounding left: their sum holds about 48 bits of each coordinate.
fn split(v: DVec3) -> ([f32; 3], [f32; 3]) {
    let high = f32x3(v);
    (high, f32x3(v - DVec3::from_array(high.map(f64::from))))
}

impl Frame {
    /// Packs the uniforms of `scene` seen from `pose` at `time` for a `width`×`height` image.
    pub fn new(
        scene: &Scene,
        pose: &Pose,
        time: f64,
        width: u32,
        height: u32,
        params: &ParamValues,
    ) -> Result<Frame, FrameError> {
        check_image_size(width, height)?;
        check_time(time)?;
        let scene_params = scene.params();
        params.check_matches(&scene_params)?;
        let lights = scene.effective_lights();
        let reference = fractal_dsl::analyse::scene_reference(scene);
        let layout = layout(lights.len(), scene_params.len(), reference);

        let fov = pose.fov_degrees;
        if !(fov.is_finite() && fov > 0.0 && fov < 180.0) {
            return Err(crate::error::CameraError::FieldOfView(fov).into());
        }
        if !pose.position.is_finite() || !pose.forward.is_finite() || !pose.up.is_finite() {
            return Err(crate::error::CameraError::NonFinite { time }.into());
        }
        let (right, up, forward) = pose.basis();
        let tan_half = (0.5 * fov.to_radians()).tan();
        let (w, h) = (width as f32, height as f32);

        let mut slots = vec![[0.0f32; 4]; layout.slots()];
        let anchor = if fractal_dsl::lower::reads_anchor(scene) { anchor_of(pose.position) } else { DVec3::ZERO };
        let (p, origin_low) = split(pose.position - anchor);
        slots[0] = [p[0], p[1], p[2], time as f32];
        let a = f32x3(anchor);
        slots[4] = [a[0], a[1], a[2], 0.0];
        let r = f32x3(right * tan_half);
        slots[1] = [r[0], r[1], r[2], w];
        let u = f32x3(up * tan_half);
        slots[2] = [u[0], u[1], u[2], h];
        let f = f32x3(forward);
        slots[3] = [f[0], f[1], f[2], (2.0 * tan_half / height as f64) as f32];

        let lookup = |d: &ParamDecl| params.lookup(d);
        check_shape_values(scene, time, &lookup)?;
        for (index, light) in lights.iter().enumerate() {
            let (xyz, kind) = match &light.kind {
                LightKind::Directional { direction } => {
                    let d = direction.eval(time, &lookup);
                    if !finite3(d) {
                        return Err(FrameError::NonFiniteLight { index, what: "direction", time });
                    }
                    let unit =
                        DVec3::from_array(d).try_normalize().ok_or(FrameError::ZeroLightDirection { index, time })?;
                    (unit, 0.0)
                }
                LightKind::Point { position } => {
                    let pos = position.eval(time, &lookup);
                    if !finite3(pos) {
                        return Err(FrameError::NonFiniteLight { index, what: "position", time });
                    }
                    (DVec3::from_array(pos) - anchor, 1.0)
                }
            };
            let colour = DVec3::from_array(light.color.eval(time, &lookup));
            let intensity = light.intensity.eval(time, &lookup);
            let radiance = colour * intensity;
            if !radiance.is_finite() {
                return Err(FrameError::NonFiniteLight { index, what: "colour · intensity", time });
            }
            let slot = layout.light_slot(index);
            let xyz = f32x3(xyz);
            slots[slot] = [xyz[0], xyz[1], xyz[2], kind];
            let rad = f32x3(radiance);
            slots[slot + 1] = [rad[0], rad[1], rad[2], 0.0];
        }

        let first = layout.params_slot();
        for (j, &v) in params.values().iter().enumerate() {
            slots[first + j / 4][j % 4] = v as f32;
        }
        if let Some(spec) = reference {
            let position = pose.position.to_array();
            let [a, b] = spec.axes.map(|axis| position[axis as usize % 3]);
            let orbit = fractal_dsl::formula::mandelbrot::reference_orbit(a, b, spec.iterations);
            slots[layout.reference_slot()] = [(orbit.len() - 1) as f32, 0.0, 0.0, 0.0];
            for (k, pair) in orbit.chunks(2).enumerate() {
                let second = pair.get(1).copied().unwrap_or([0.0, 0.0]);
                slots[layout.orbit_slot(k)] = [pair[0][0], pair[0][1], second[0], second[1]];
            }
        }
        Ok(Frame { layout, width, height, slots, origin_low })
    }

    /// The scene's own view at `time`: its camera, every parameter at its default, for a `width`×`height` image.
    pub fn default_view(scene: &Scene, time: f64, width: u32, height: u32) -> Result<Frame, FrameError> {
        let pose = Pose::from_camera(&scene.camera, time, &|p| p.default)?;
        Frame::new(scene, &pose, time, width, height, &ParamValues::defaults(scene))
    }

    /// The frame layout of `scene`: the slots [`Frame::new`] packs for it.
    pub fn layout_of(scene: &Scene) -> FrameLayout {
        layout(scene.effective_lights().len(), scene.params().len(), fractal_dsl::analyse::scene_reference(scene))
    }

    /// A frame from slots packed elsewhere (hand-written kernels, replays); the slot count must match `layout`.
    pub fn from_slots(layout: FrameLayout, width: u32, height: u32, slots: Vec<[f32; 4]>) -> Result<Frame, FrameError> {
        check_image_size(width, height)?;
        if slots.len() != layout.slots() {
            return Err(FrameError::SlotCount { expected: layout.slots(), got: slots.len() });
        }
        Ok(Frame { layout, width, height, slots, origin_low: [0.0; 3] })
    }

    pub fn layout(&self) -> FrameLayout {
        self.layout
    }
    pub fn width(&self) -> u32 {
        self.width
    }
    pub fn height(&self) -> u32 {
        self.height
    }
    pub fn slots(&self) -> &[[f32; 4]] {
        &self.slots
    }
    /// The slots as the bytes of the uniform buffer.
    pub fn as_bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.slots)
    }
    /// The slots as an f64 kernel reads them ([`fractal_dsl::back::Scalar::F64`]): the same values, the camera
    /// position to the precision [`Frame::camera_origin`] keeps.
    pub fn wide_slots(&self) -> Vec<[f64; 4]> {
        let mut slots: Vec<[f64; 4]> = self.slots.iter().map(|s| s.map(f64::from)).collect();
        let origin = self.camera_origin();
        slots[0][..3].copy_from_slice(&origin);
        slots
    }
    /// The uniform buffer's bytes for a kernel computing in `scalar`.
    pub fn bytes_in(&self, scalar: Scalar) -> Vec<u8> {
        match scalar {
            Scalar::F32 => self.as_bytes().to_vec(),
            Scalar::F64 => bytemuck::cast_slice(&self.wide_slots()).to_vec(),
        }
    }
    /// The time, as the kernels read it.
    pub fn time(&self) -> f32 {
        self.slots[0][3]
    }
    /// This frame with the kernels' time set to `time` and nothing else changed (the camera, lights and parameters
    /// stay as they were packed): two frames of a scene whose distance tree and materials do not read `t` draw the
    /// same image when they are equal at one time.
    pub fn with_time(&self, time: f32) -> Frame {
        let mut frame = self.clone();
        frame.slots[0][3] = time;
        frame
    }
    /// The frame's anchor: the origin, or (for a camera more than [`ANCHOR_BEYOND`] from it) the camera's position
    /// rounded to f32. The kernels compute positions relative to it and the scene functions add it back, subtracting
    /// the scene's translations from it first ([`fractal_dsl::eval::Env::anchor`]), so a scene far from the origin
    /// seen from nearby draws in f32 as it does at the origin.
    pub fn anchor(&self) -> [f64; 3] {
        let a = self.slots[4];
        [0, 1, 2].map(|i| f64::from(a[i]))
    }
    /// Points of the scene (xyz; w kept) relative to the anchor, as the kernels' scene functions take them.
    pub fn relative_to_anchor(&self, points: &[[f32; 4]]) -> Vec<[f32; 4]> {
        let a = self.anchor();
        points
            .iter()
            .map(|p| {
                let r = [0, 1, 2].map(|i| (f64::from(p[i]) - a[i]) as f32);
                [r[0], r[1], r[2], p[3]]
            })
            .collect()
    }
    /// Camera position (relative to the anchor), right·tan(fov/2), up·tan(fov/2) and forward, as the kernels read
    /// them.
    pub fn camera(&self) -> [[f32; 3]; 4] {
        [0, 1, 2, 3].map(|i| [self.slots[i][0], self.slots[i][1], self.slots[i][2]])
    }
    /// The camera position relative to the anchor to about 48 bits: the f32 the kernels read plus what its rounding
    /// lost. A close zoom needs it: near 1 the f32 position is 6e-8 off, and a camera 1e-9 from a surface would stand
    /// inside it.
    pub fn camera_origin(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| f64::from(self.slots[0][i]) + f64::from(self.origin_low[i]))
    }
    /// Pixel footprint per unit distance: 2·tan(fov/2)/height.
    pub fn pixel_footprint(&self) -> f32 {
        self.slots[3][3]
    }
    /// The lights, as the kernels read them (a point light's position relative to the anchor).
    pub fn lights(&self) -> Vec<LightSlot> {
        (0..self.layout.lights)
            .map(|i| {
                let a = self.slots[self.layout.light_slot(i)];
                let b = self.slots[self.layout.light_slot(i) + 1];
                if a[3] == 0.0 {
                    LightSlot::Directional { direction: [a[0], a[1], a[2]], radiance: [b[0], b[1], b[2]] }
                } else {
                    LightSlot::Point { position: [a[0], a[1], a[2]], radiance: [b[0], b[1], b[2]] }
                }
            })
            .collect()
    }
    /// The parameter values, as the kernels read them.
    pub fn params(&self) -> Vec<f32> {
        let first = self.layout.params_slot();
        (0..self.layout.params).map(|j| self.slots[first + j / 4][j % 4]).collect()
    }
    /// This frame with each pixel's one ray through the point (dx, dy) of the pixel (from its top left corner; the
    /// centre is (½, ½)) and, with `lens` (an offset along the image's right and up axes in scene units, and the
    /// distance in focus), from that point of a thin lens towards the plane of focus: the ray sample (dx, dy, lens) of
    /// the pixel program ([`fractal_dsl::ray::pixel::camera_ray`]) takes. The camera moves to the lens point and its
    /// forward axis turns so that the pixel's centre ray is that ray; a perturbation orbit stays the camera's.
    pub fn jittered(&self, dx: f64, dy: f64, lens: Option<([f64; 2], f64)>) -> Frame {
        let d = |s: [f32; 4]| DVec3::new(f64::from(s[0]), f64::from(s[1]), f64::from(s[2]));
        let origin = DVec3::from_array(self.camera_origin());
        let (right, up, forward) = (d(self.slots[1]), d(self.slots[2]), d(self.slots[3]));
        let h = f64::from(self.height);
        // The image point moves by (dx − ½, dy − ½) pixels: u by 2(dx − ½)/h, v by −2(dy − ½)/h.
        let mut forward = forward + right * (2.0 * (dx - 0.5) / h) - up * (2.0 * (dy - 0.5) / h);
        let mut origin = origin;
        if let Some(([x, y], focus)) = lens {
            let offset = right.normalize_or_zero() * x + up.normalize_or_zero() * y;
            origin += offset;
            // Towards the same point of the plane of focus: focus·(forward + …) − offset.
            forward -= offset / focus;
        }
        let mut slots = self.slots.clone();
        let set = |slot: &mut [f32; 4], v: [f32; 3]| (slot[0], slot[1], slot[2]) = (v[0], v[1], v[2]);
        let (high, origin_low) = split(origin);
        set(&mut slots[0], high);
        set(&mut slots[3], f32x3(forward));
        Frame { slots, origin_low, ..self.clone() }
    }

    /// The perturbation reference orbit up to its last entry, as the kernels read it (empty without one).
    pub fn reference_orbit(&self) -> Vec<[f32; 2]> {
        if self.layout.orbit == 0 {
            return Vec::new();
        }
        let last = self.slots[self.layout.reference_slot()][0] as usize;
        (0..=last.min(self.layout.orbit - 1))
            .map(|i| {
                let slot = self.slots[self.layout.orbit_slot(i / 2)];
                if i % 2 == 0 {
                    [slot[0], slot[1]]
                } else {
                    [slot[2], slot[3]]
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::*;

    fn pose() -> Pose {
        Pose::look_at(DVec3::new(0.0, 0.0, -3.0), DVec3::ZERO, 90.0).unwrap()
    }

    #[test]
    fn the_default_view_is_the_scenes_camera_with_default_parameters() {
        let s = scene(sphere(param("r", 1.0, 0.5..2.0))).camera(camera([0.0, 1.0, -3.0], [0.0; 3]));
        let pose = Pose::from_camera(&s.camera, 0.5, &|p| p.default).unwrap();
        let want = Frame::new(&s, &pose, 0.5, 16, 9, &ParamValues::defaults(&s)).unwrap();
        assert_eq!(Frame::default_view(&s, 0.5, 16, 9), Ok(want));
    }

    #[test]
    fn camera_slots_follow_the_layout() {
        let s = scene(sphere(1.0));
        let f = Frame::new(&s, &pose(), 2.5, 200, 100, &ParamValues::defaults(&s)).unwrap();
        assert_eq!(f.layout(), FrameLayout { lights: 1, params: 0, orbit: 0 });
        assert_eq!(f.slots().len(), 7);
        assert_eq!(f.as_bytes().len(), 7 * 16);
        let s0 = f.slots()[0];
        assert_eq!(s0, [0.0, 0.0, -3.0, 2.5]);
        // fov 90°: tan(45°) = 1, so right and up are unit vectors.
        let close = |a: [f32; 4], b: [f32; 4]| a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-6);
        assert!(close(f.slots()[1], [1.0, 0.0, 0.0, 200.0]), "{:?}", f.slots()[1]);
        assert!(close(f.slots()[2], [0.0, 1.0, 0.0, 100.0]), "{:?}", f.slots()[2]);
        assert!(close(f.slots()[3], [0.0, 0.0, 1.0, 0.02]), "{:?}", f.slots()[3]);
        // A camera near the origin anchors the frame there.
        assert_eq!(f.slots()[4], [0.0; 4]);
        // The default key light, normalised.
        let l = DVec3::new(0.6, 0.8, -0.4).normalize().as_vec3();
        assert!(close(f.slots()[5], [l.x, l.y, l.z, 0.0]));
        assert_eq!(f.slots()[6], [1.0, 1.0, 1.0, 0.0]);
    }

    #[test]
    fn a_camera_far_out_anchors_its_frame_and_positions_are_taken_from_the_anchor() {
        let far = DVec3::new(1e6 + 0.3, -2.0e6, 5.0);
        let s = scene(sphere(1.0).translate([1e6, -2.0e6, 5.0]))
            .light(point_light(vec3(1e6 + 2.0, -2.0e6, 5.0), rgb(1.0, 1.0, 1.0)));
        let pose = Pose::look_at(far, far + DVec3::Z, 60.0).unwrap();
        // A scene that takes the whole point at once gains nothing from an anchor: its frames keep the origin.
        let unmoved = scene(sphere(1.0));
        let f = Frame::new(&unmoved, &pose, 0.0, 8, 8, &ParamValues::defaults(&unmoved)).unwrap();
        assert_eq!(f.anchor(), [0.0; 3]);
        let f = Frame::new(&s, &pose, 0.0, 8, 8, &ParamValues::defaults(&s)).unwrap();
        let anchor = DVec3::from_array(f.anchor());
        assert_eq!(anchor, DVec3::from_array(f32x3(far).map(f64::from)));
        // The camera relative to the anchor keeps what f32 rounded away: 0.3 at a million is 0.0625 apart in f32.
        let origin = DVec3::from_array(f.camera_origin());
        assert!((anchor + origin - far).abs().max_element() < 1e-9, "{origin}");
        let LightSlot::Point { position, .. } = f.lights()[0] else { panic!("a point light") };
        assert_eq!(position.map(f64::from), [1e6 + 2.0 - anchor.x, 0.0, 0.0]);
        let points = f.relative_to_anchor(&[[1e6, -2.0e6, 5.0, 7.0]]);
        assert_eq!(points[0], [(1e6 - anchor.x) as f32, 0.0, 0.0, 7.0]);
        let near = Pose::look_at(DVec3::new(ANCHOR_BEYOND, 0.0, 0.0), DVec3::ZERO, 60.0).unwrap();
        let f = Frame::new(&s, &near, 0.0, 8, 8, &ParamValues::defaults(&s)).unwrap();
        assert_eq!(f.anchor(), [0.0; 3]);
    }

    #[test]
    fn lights_and_params_are_evaluated_on_the_host() {
        let glow = param("glow", 2.0, 0.0..10.0);
        let s = scene(sphere(param("radius", 1.0, 0.1..2.0)))
            .light(point_light(vec3(time(), 2.0, 0.0), rgb(1.0, 0.5, 0.25)).intensity(glow.clone() * 3.0))
            .light(directional([0.0, 2.0, 0.0], rgb(0.5, 0.5, 0.5)).intensity(sin(time())));
        let mut params = ParamValues::defaults(&s);
        assert_eq!(params.values(), &[1.0, 2.0]);
        params.set("glow", 4.0).unwrap();
        let f = Frame::new(&s, &pose(), 0.5, 8, 8, &params).unwrap();
        assert_eq!(f.layout(), FrameLayout { lights: 2, params: 2, orbit: 0 });
        assert_eq!(f.slots()[5], [0.5, 2.0, 0.0, 1.0]);
        assert_eq!(f.slots()[6], [12.0, 6.0, 3.0, 0.0]);
        assert_eq!(f.slots()[7], [0.0, 1.0, 0.0, 0.0]);
        let s8 = (0.5f64.sin() * 0.5) as f32;
        assert_eq!(f.slots()[8], [s8, s8, s8, 0.0]);
        assert_eq!(f.slots()[9], [1.0, 4.0, 0.0, 0.0]);
        assert_eq!(f.params(), vec![1.0, 4.0]);
        assert!(matches!(f.lights()[0], LightSlot::Point { position: [0.5, 2.0, 0.0], .. }));
    }

    #[test]
    fn five_params_take_two_slots() {
        let p = |n: &str| param(n, 0.5, 0.0..1.0);
        let r = p("a") + p("b") + p("c") + p("d") + p("e");
        let s = scene(sphere(r));
        let values = [0.1, 0.2, 0.3, 0.4, 0.5];
        let f = Frame::new(&s, &pose(), 0.0, 4, 4, &ParamValues::from_values(&s, &values).unwrap()).unwrap();
        assert_eq!(f.layout().param_slots(), 2);
        assert_eq!(f.slots().len(), 5 + 2 + 2);
        assert_eq!(f.slots()[7], [0.1, 0.2, 0.3, 0.4]);
        assert_eq!(f.slots()[8], [0.5, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let s = scene(sphere(param("radius", 1.0, 0.1..2.0)));
        let ok = ParamValues::defaults(&s);
        for (w, h) in [(0, 0), (0, 10), (100_000, 100_000), (MAX_IMAGE_SIDE + 1, 1)] {
            assert!(matches!(Frame::new(&s, &pose(), 0.0, w, h, &ok), Err(FrameError::ImageSize { .. })));
        }
        assert!(matches!(Frame::new(&s, &pose(), f64::NAN, 8, 8, &ok), Err(FrameError::Time(_))));
        let mut p = ok.clone();
        assert!(matches!(p.set("radius", 3.0), Err(FrameError::ParamOutOfRange { .. })));
        assert!(matches!(p.set("nope", 1.0), Err(FrameError::UnknownParam(_))));
        assert!(matches!(ParamValues::from_values(&s, &[]), Err(FrameError::ParamCount { expected: 1, got: 0 })));
        let other = ParamValues::defaults(&scene(sphere(1.0)));
        assert!(matches!(Frame::new(&s, &pose(), 0.0, 8, 8, &other), Err(FrameError::ParamCount { .. })));
        let dark = scene(sphere(1.0)).light(directional([0.0, 0.0, 0.0], rgb(1.0, 1.0, 1.0)));
        let dark_params = ParamValues::defaults(&dark);
        assert!(matches!(
            Frame::new(&dark, &pose(), 0.0, 8, 8, &dark_params),
            Err(FrameError::ZeroLightDirection { index: 0, .. })
        ));
        let mut wide = pose();
        wide.fov_degrees = 0.0;
        assert!(matches!(
            Frame::new(&s, &wide, 0.0, 8, 8, &ok),
            Err(FrameError::Camera(crate::error::CameraError::FieldOfView(_)))
        ));
    }
}
