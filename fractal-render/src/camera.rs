//! Camera poses: where the camera is and where it looks at a given time, from a scene's [`Camera`] (a fixed look-at
//! or a keyed path).
//!
//! Paths: key positions are joined by a **centripetal** Catmull-Rom spline (α = ½, which never forms cusps or
//! self-intersections within a segment) or straight lines; orientations are the keys' look-at rotations, slerped.
//! Within a segment both use the same fraction of the segment's time span, so the camera reaches each key exactly at
//! its time. Before the first key and after the last the camera rests on that key. A looped path repeats with period
//! `last.time − first.time` and should end on its first key; the spline treats the last key as the first, so a loop
//! that closes has no kink at the seam.

use fractal_dsl::{Camera, CameraKey, CameraPlacement, ParamDecl, PathInterpolation};
use glam::{DMat3, DQuat, DVec3};

use crate::error::CameraError;

/// The world's up direction: cameras keep their horizon level with it.
pub const WORLD_UP: DVec3 = DVec3::Y;

/// Where the camera is and where it looks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub position: DVec3,
    /// View direction (unit length).
    pub forward: DVec3,
    /// Up direction hint; [`Pose::basis`] makes it orthogonal to `forward`.
    pub up: DVec3,
    /// Vertical field of view in degrees.
    pub fov_degrees: f64,
}

impl Pose {
    /// A camera at `position` looking at `target` with the horizon level.
    pub fn look_at(position: DVec3, target: DVec3, fov_degrees: f64) -> Result<Pose, CameraError> {
        let rotation = look_rotation(position, target)?;
        Ok(Pose::from_rotation(position, rotation, fov_degrees))
    }

    /// A camera at `position` oriented by `rotation` (camera space: +x right, +y up, +z forward).
    pub fn from_rotation(position: DVec3, rotation: DQuat, fov_degrees: f64) -> Pose {
        Pose { position, forward: rotation * DVec3::Z, up: rotation * DVec3::Y, fov_degrees }
    }

    /// The pose of `camera` at `time`; `param` gives each parameter's value (for look-at expressions).
    pub fn from_camera(camera: &Camera, time: f64, param: &dyn Fn(&ParamDecl) -> f64) -> Result<Pose, CameraError> {
        check_fov(camera.fov_degrees)?;
        match &camera.placement {
            CameraPlacement::LookAt { position, target } => {
                let position = DVec3::from_array(position.eval(time, param));
                let target = DVec3::from_array(target.eval(time, param));
                if !position.is_finite() || !target.is_finite() {
                    return Err(CameraError::NonFinite { time });
                }
                Pose::look_at(position, target, camera.fov_degrees)
            }
            CameraPlacement::Path { keys, interpolation, looped } => {
                let path = CameraPath::new(keys, *interpolation, *looped)?;
                Ok(path.pose(time, camera.fov_degrees))
            }
        }
    }

    /// Right, up and forward: an orthonormal, right-handed-as-columns basis (right × up = forward). A view straight
    /// along the up hint keeps a stable right vector instead of collapsing.
    pub fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let forward = self.forward.normalize_or(DVec3::Z);
        let right = self
            .up
            .cross(forward)
            .try_normalize()
            .or_else(|| WORLD_UP.cross(forward).try_normalize())
            .unwrap_or_else(|| DVec3::Z.cross(forward).normalize_or(DVec3::X));
        (right, forward.cross(right), forward)
    }

    /// The camera's rotation (camera space: +x right, +y up, +z forward).
    pub fn rotation(&self) -> DQuat {
        let (right, up, forward) = self.basis();
        DQuat::from_mat3(&DMat3::from_cols(right, up, forward)).normalize()
    }
}

fn check_fov(fov: f64) -> Result<(), CameraError> {
    if fov.is_finite() && fov > 0.0 && fov < 180.0 {
        Ok(())
    } else {
        Err(CameraError::FieldOfView(fov))
    }
}

/// The rotation of a camera at `position` looking at `target` with a level horizon.
pub fn look_rotation(position: DVec3, target: DVec3) -> Result<DQuat, CameraError> {
    let forward =
        (target - position).try_normalize().ok_or(CameraError::NoViewDirection { position: position.to_array() })?;
    Ok(Pose { position, forward, up: WORLD_UP, fov_degrees: 60.0 }.rotation())
}

/// A camera path ready to be sampled: keys sorted by time with their rotations.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraPath {
    times: Vec<f64>,
    positions: Vec<DVec3>,
    rotations: Vec<DQuat>,
    interpolation: PathInterpolation,
    looped: bool,
}

/// Centripetal Catmull-Rom exponent.
const CENTRIPETAL_ALPHA: f64 = 0.5;
/// Knot spacing used when two keys coincide, so coincident keys never divide by zero.
const MIN_KNOT_SPACING: f64 = 1e-9;

impl CameraPath {
    /// Checks and sorts the keys (by time, stably).
    pub fn new(keys: &[CameraKey], interpolation: PathInterpolation, looped: bool) -> Result<CameraPath, CameraError> {
        if keys.is_empty() {
            return Err(CameraError::EmptyPath);
        }
        let mut sorted: Vec<(usize, &CameraKey)> = keys.iter().enumerate().collect();
        for &(index, k) in &sorted {
            let finite = k.time.is_finite() && k.position.iter().chain(&k.target).all(|v| v.is_finite());
            if !finite {
                return Err(CameraError::NonFiniteKey { index });
            }
        }
        sorted.sort_by(|a, b| a.1.time.total_cmp(&b.1.time));
        let mut rotations = Vec::with_capacity(keys.len());
        for &(_, k) in &sorted {
            let mut q = look_rotation(DVec3::from_array(k.position), DVec3::from_array(k.target))?;
            // Keep neighbouring rotations in the same hemisphere so slerp takes the short way and stays continuous.
            if let Some(prev) = rotations.last() {
                if q.dot(*prev) < 0.0 {
                    q = -q;
                }
            }
            rotations.push(q);
        }
        Ok(CameraPath {
            times: sorted.iter().map(|(_, k)| k.time).collect(),
            positions: sorted.iter().map(|(_, k)| DVec3::from_array(k.position)).collect(),
            rotations,
            interpolation,
            looped,
        })
    }

    /// The time the path starts and ends at.
    pub fn span(&self) -> (f64, f64) {
        (self.times[0], self.times[self.times.len() - 1])
    }

    /// The pose at `time` with the given field of view.
    pub fn pose(&self, time: f64, fov_degrees: f64) -> Pose {
        let (position, rotation) = self.sample(time);
        Pose::from_rotation(position, rotation, fov_degrees)
    }

    /// Position and rotation at `time`.
    pub fn sample(&self, time: f64) -> (DVec3, DQuat) {
        let n = self.times.len();
        let (first, last) = self.span();
        let time = if self.looped && last > first && time.is_finite() {
            first + (time - first).rem_euclid(last - first)
        } else {
            time
        };
        // Non-finite times (and times outside a non-looped path) rest on the nearest end.
        if n == 1 || time.is_nan() || time <= first {
            return (self.positions[0], self.rotations[0]);
        }
        if time >= last {
            return (self.positions[n - 1], self.rotations[n - 1]);
        }
        // Segment i runs from key i to key i + 1; the search skips zero-length segments.
        let i = self.times.partition_point(|&t| t <= time) - 1;
        let fraction = (time - self.times[i]) / (self.times[i + 1] - self.times[i]);
        let position = match self.interpolation {
            PathInterpolation::Linear => self.positions[i].lerp(self.positions[i + 1], fraction),
            PathInterpolation::CatmullRom => {
                let (p0, p3) = self.outer_neighbours(i);
                centripetal_catmull_rom(p0, self.positions[i], self.positions[i + 1], p3, fraction)
            }
        };
        let rotation = self.rotations[i].slerp(self.rotations[i + 1], fraction).normalize();
        (position, rotation)
    }

    /// The control points before key i and after key i + 1 for segment i.
    fn outer_neighbours(&self, i: usize) -> (DVec3, DVec3) {
        let p = &self.positions;
        let n = p.len();
        // In a loop the last key stands for the first, so the neighbours wrap past it.
        let before = if i > 0 {
            p[i - 1]
        } else if self.looped && n > 2 {
            p[n - 2]
        } else {
            2.0 * p[0] - p[1]
        };
        let after = if i + 2 < n {
            p[i + 2]
        } else if self.looped && n > 2 {
            p[1]
        } else {
            2.0 * p[n - 1] - p[n - 2]
        };
        (before, after)
    }
}

/// Point at fraction `u` ∈ [0, 1] of the centripetal Catmull-Rom segment from `p1` to `p2`, in cubic Hermite form:
/// u = 0 gives `p1` and u = 1 gives `p2` exactly.
pub fn centripetal_catmull_rom(p0: DVec3, p1: DVec3, p2: DVec3, p3: DVec3, u: f64) -> DVec3 {
    let knot = |a: DVec3, b: DVec3| a.distance(b).powf(CENTRIPETAL_ALPHA).max(MIN_KNOT_SPACING);
    let (d01, d12, d23) = (knot(p0, p1), knot(p1, p2), knot(p2, p3));
    // Tangents of the non-uniform Catmull-Rom spline at p1 and p2, scaled to the segment's knot span.
    let m1 = ((p1 - p0) / d01 - (p2 - p0) / (d01 + d12) + (p2 - p1) / d12) * d12;
    let m2 = ((p2 - p1) / d12 - (p3 - p1) / (d12 + d23) + (p3 - p2) / d23) * d12;
    let (u2, u3) = (u * u, u * u * u);
    let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
    let h10 = u3 - 2.0 * u2 + u;
    let h01 = -2.0 * u3 + 3.0 * u2;
    let h11 = u3 - u2;
    p1 * h00 + m1 * h10 + p2 * h01 + m2 * h11
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::{camera, camera_path, key};

    fn keys() -> Vec<CameraKey> {
        vec![
            key(0.0, [0.0, 0.0, -4.0], [0.0, 0.0, 0.0]),
            key(1.0, [4.0, 1.0, 0.0], [0.0, 0.0, 0.0]),
            key(3.0, [0.0, 2.0, 4.0], [0.0, 0.5, 0.0]),
            key(4.0, [-4.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
            key(6.0, [0.0, 0.0, -4.0], [0.0, 0.0, 0.0]),
        ]
    }

    fn path(interpolation: PathInterpolation, looped: bool) -> CameraPath {
        CameraPath::new(&keys(), interpolation, looped).expect("valid path")
    }

    fn all_paths() -> Vec<CameraPath> {
        let mut out = Vec::new();
        for interpolation in [PathInterpolation::Linear, PathInterpolation::CatmullRom] {
            for looped in [false, true] {
                out.push(path(interpolation, looped));
            }
        }
        out
    }

    #[test]
    fn keys_are_hit_exactly() {
        for p in all_paths() {
            for k in keys() {
                let pose = p.pose(k.time, 45.0);
                assert_eq!(pose.position.to_array(), k.position, "{:?} at t = {}", p.interpolation, k.time);
                let want = (DVec3::from_array(k.target) - DVec3::from_array(k.position)).normalize();
                assert!(pose.forward.distance(want) < 1e-12, "forward {:?} vs {want:?}", pose.forward);
                assert!(pose.up.dot(pose.forward).abs() < 1e-12);
                // Look-at keys keep the horizon level: right has no vertical component.
                let (right, _, _) = pose.basis();
                assert!(right.y.abs() < 1e-12, "right {right:?}");
            }
        }
    }

    #[test]
    fn paths_are_continuous() {
        // Small steps in time give small steps in position and view direction, including across every key and the
        // loop seam; the bounds are generous multiples of the fastest segment's speed.
        let dt = 1e-4;
        for p in all_paths() {
            let mut t = -1.0;
            let (mut pos, mut rot) = p.sample(t);
            while t < 14.0 {
                t += dt;
                let (next_pos, next_rot) = p.sample(t);
                assert!(next_pos.distance(pos) < 20.0 * dt, "{:?} jumps at t = {t}", p.interpolation);
                assert!(next_rot.angle_between(rot) < 10.0 * dt, "rotation jumps at t = {t}");
                pos = next_pos;
                rot = next_rot;
            }
        }
    }

    #[test]
    fn catmull_rom_is_smooth_at_keys() {
        // The direction of motion is continuous across interior keys (G1); linear paths turn a corner there.
        let velocity = |p: &CameraPath, t: f64, side: f64| {
            let h = 1e-6 * side;
            ((p.sample(t + h).0 - p.sample(t).0) / h).normalize()
        };
        let smooth = path(PathInterpolation::CatmullRom, false);
        let linear = path(PathInterpolation::Linear, false);
        for t in [1.0, 3.0, 4.0] {
            let (before, after) = (velocity(&smooth, t, -1.0), velocity(&smooth, t, 1.0));
            assert!(before.dot(after) > 1.0 - 1e-4, "kink at t = {t}: {before:?} vs {after:?}");
            let (before, after) = (velocity(&linear, t, -1.0), velocity(&linear, t, 1.0));
            assert!(before.dot(after) < 0.99, "linear path should turn at t = {t}");
        }
        // A closed loop is smooth across its seam too.
        let looped = path(PathInterpolation::CatmullRom, true);
        let (before, after) = (velocity(&looped, 6.0, -1.0), velocity(&looped, 6.0, 1.0));
        assert!(before.dot(after) > 1.0 - 1e-4, "kink at the loop seam: {before:?} vs {after:?}");
    }

    #[test]
    fn looped_paths_repeat_and_open_paths_rest_at_the_ends() {
        let looped = path(PathInterpolation::CatmullRom, true);
        for t in [0.3, 2.5, 5.9] {
            let (a, _) = looped.sample(t);
            let (b, _) = looped.sample(t + 6.0);
            let (c, _) = looped.sample(t - 12.0);
            assert!(a.distance(b) < 1e-9 && a.distance(c) < 1e-9, "loop does not repeat at t = {t}");
        }
        let open = path(PathInterpolation::CatmullRom, false);
        assert_eq!(open.sample(-5.0).0, DVec3::new(0.0, 0.0, -4.0));
        assert_eq!(open.sample(100.0).0, DVec3::new(0.0, 0.0, -4.0));
        assert_eq!(open.sample(f64::NAN).0, DVec3::new(0.0, 0.0, -4.0));
    }

    #[test]
    fn linear_paths_are_straight_between_keys() {
        let p = path(PathInterpolation::Linear, false);
        let mid = p.sample(0.5).0;
        assert!(mid.distance(DVec3::new(2.0, 0.5, -2.0)) < 1e-12);
    }

    #[test]
    fn coincident_keys_give_finite_positions() {
        let keys = vec![
            key(0.0, [1.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
            key(1.0, [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            key(1.0, [2.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
            key(2.0, [2.0, 0.0, 0.0], [0.0, 0.0, 0.0]),
        ];
        let p = CameraPath::new(&keys, PathInterpolation::CatmullRom, false).unwrap();
        for i in 0..=200 {
            let (pos, rot) = p.sample(i as f64 * 0.01);
            assert!(pos.is_finite() && rot.is_finite(), "non-finite at {}", i as f64 * 0.01);
        }
    }

    #[test]
    fn bad_cameras_are_errors() {
        assert_eq!(CameraPath::new(&[], PathInterpolation::Linear, false), Err(CameraError::EmptyPath));
        let nan_key = [key(0.0, [f64::NAN, 0.0, 0.0], [0.0, 0.0, 0.0])];
        assert_eq!(
            CameraPath::new(&nan_key, PathInterpolation::Linear, false),
            Err(CameraError::NonFiniteKey { index: 0 })
        );
        let still = camera([1.0, 2.0, 3.0], [1.0, 2.0, 3.0]);
        assert!(matches!(Pose::from_camera(&still, 0.0, &|p| p.default), Err(CameraError::NoViewDirection { .. })));
        let wide = camera([0.0, 0.0, -1.0], [0.0, 0.0, 0.0]).fov(180.0);
        assert_eq!(Pose::from_camera(&wide, 0.0, &|p| p.default), Err(CameraError::FieldOfView(180.0)));
    }

    #[test]
    fn look_at_cameras_follow_their_expressions() {
        use fractal_dsl::builder::{param, time, vec3};
        let cam = camera(vec3(time(), param("height", 2.0, 0.0..5.0), -3.0), [0.0, 0.0, 0.0]);
        let pose = Pose::from_camera(&cam, 1.5, &|p| if p.name == "height" { 4.0 } else { p.default }).unwrap();
        assert_eq!(pose.position, DVec3::new(1.5, 4.0, -3.0));
        assert!(pose.forward.distance(-pose.position.normalize()) < 1e-12);
        let from_path = Pose::from_camera(&camera_path(keys()), 1.0, &|p| p.default).unwrap();
        assert_eq!(from_path.position, DVec3::new(4.0, 1.0, 0.0));
    }

    #[test]
    fn straight_down_views_have_a_basis() {
        let pose = Pose::look_at(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO, 45.0).unwrap();
        let (right, up, forward) = pose.basis();
        assert!(forward.distance(-DVec3::Y) < 1e-12);
        assert!(right.is_normalized() && up.is_normalized());
        assert!(right.dot(up).abs() < 1e-12 && right.dot(forward).abs() < 1e-12);
        assert!(right.cross(up).distance(forward) < 1e-12, "basis is not right × up = forward");
    }
}
