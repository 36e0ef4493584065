//! The user's camera: a fly camera (position, yaw, pitch) that WASD/QE move and the mouse turns, and the formatting of
//! a pose as a camera-path key.

use fractal_render::camera::{Pose, WORLD_UP};
use glam::DVec3;

use super::controls::Move;

/// Pitch stays this far from straight up or down, so the view never lines up with the world's up direction.
const MAX_PITCH: f64 = 89.0 * std::f64::consts::PI / 180.0;
/// How much faster the camera moves while Shift is held.
pub const SPRINT_FACTOR: f64 = 4.0;
/// Field of view limits of the mouse wheel, in degrees.
const FOV_RANGE: (f64, f64) = (5.0, 150.0);

/// A free-flying camera with a level horizon.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyCamera {
    pub position: DVec3,
    /// Turn about the world's up axis; 0 looks along +z, positive turns towards +x.
    pub yaw: f64,
    /// Angle above the horizon.
    pub pitch: f64,
    pub fov_degrees: f64,
}

impl FlyCamera {
    /// The fly camera that sees what `pose` sees (its roll, if any, is dropped: the horizon is level).
    pub fn from_pose(pose: &Pose) -> FlyCamera {
        let forward = pose.forward.normalize_or(DVec3::Z);
        FlyCamera {
            position: pose.position,
            yaw: forward.x.atan2(forward.z),
            pitch: forward.y.clamp(-1.0, 1.0).asin().clamp(-MAX_PITCH, MAX_PITCH),
            fov_degrees: pose.fov_degrees,
        }
    }

    pub fn forward(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        DVec3::new(cp * sy, sp, cp * cy)
    }

    pub fn pose(&self) -> Pose {
        Pose { position: self.position, forward: self.forward(), up: WORLD_UP, fov_degrees: self.fov_degrees }
    }

    /// Turns by a mouse motion of (`dx`, `dy`) pixels: right turns right, down looks down.
    pub fn look(&mut self, dx: f64, dy: f64, sensitivity: f64) {
        if !(dx.is_finite() && dy.is_finite()) {
            return;
        }
        self.yaw = (self.yaw + dx * sensitivity).rem_euclid(std::f64::consts::TAU);
        self.pitch = (self.pitch - dy * sensitivity).clamp(-MAX_PITCH, MAX_PITCH);
    }

    /// Moves for `dt` seconds at `speed` units per second along the held directions: forward and back along the view,
    /// left and right along the horizon, down and up along the world's up axis.
    pub fn step(&mut self, held: impl IntoIterator<Item = Move>, speed: f64, dt: f64) {
        let forward = self.forward();
        let (right, _, _) = self.pose().basis();
        let mut direction = DVec3::ZERO;
        for m in held {
            direction += match m {
                Move::Forward => forward,
                Move::Back => -forward,
                Move::Right => right,
                Move::Left => -right,
                Move::Up => WORLD_UP,
                Move::Down => -WORLD_UP,
            };
        }
        // Diagonal movement is no faster than straight movement.
        if let Some(unit) = direction.try_normalize() {
            let delta = unit * speed * dt;
            if delta.is_finite() {
                self.position += delta;
            }
        }
    }

    /// Widens (positive `steps`) or narrows the field of view by 5 % per step.
    pub fn zoom(&mut self, steps: f64) {
        if steps.is_finite() {
            self.fov_degrees = (self.fov_degrees * 1.05f64.powf(steps)).clamp(FOV_RANGE.0, FOV_RANGE.1);
        }
    }
}

/// A pose as a `.fractal` camera-path key and as a TOML `[[key]]` (the format of [`super::path_file`]); the target is
/// one unit along the view.
/// The pose as the `.fractal` camera line that reproduces it.
pub fn camera_line(pose: &Pose) -> String {
    let p = pose.position;
    let t = pose.position + pose.forward.normalize_or(DVec3::Z);
    format!(
        ".camera(camera(vec3({:.4}, {:.4}, {:.4}), vec3({:.4}, {:.4}, {:.4})).fov({:.2}))",
        p.x, p.y, p.z, t.x, t.y, t.z, pose.fov_degrees
    )
}

pub fn describe_pose(pose: &Pose, time: f64) -> String {
    let p = pose.position;
    let t = pose.position + pose.forward.normalize_or(DVec3::Z);
    format!(
        "camera at t = {time:.3}, fov {fov:.2}°:\n  \
         key({time:.3}, vec3({:.4}, {:.4}, {:.4}), vec3({:.4}, {:.4}, {:.4}))\n  \
         [[key]]\n  time = {time:.3}\n  position = [{:.4}, {:.4}, {:.4}]\n  target = [{:.4}, {:.4}, {:.4}]",
        p.x,
        p.y,
        p.z,
        t.x,
        t.y,
        t.z,
        p.x,
        p.y,
        p.z,
        t.x,
        t.y,
        t.z,
        fov = pose.fov_degrees,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: DVec3, b: DVec3) -> bool {
        a.distance(b) < 1e-12
    }

    #[test]
    fn a_pose_survives_the_round_trip() {
        let pose = Pose::look_at(DVec3::new(1.0, 2.0, -3.0), DVec3::new(0.0, 0.5, 0.0), 50.0).unwrap();
        let fly = FlyCamera::from_pose(&pose);
        let back = fly.pose();
        assert!(close(back.forward, pose.forward), "{:?} vs {:?}", back.forward, pose.forward);
        assert_eq!(back.position, pose.position);
        assert_eq!(back.fov_degrees, 50.0);
        // Same basis as the look-at pose, so the same image.
        let (r0, u0, f0) = pose.basis();
        let (r1, u1, f1) = back.basis();
        assert!(close(r0, r1) && close(u0, u1) && close(f0, f1));
    }

    #[test]
    fn keys_move_along_the_view_and_the_horizon() {
        let mut fly = FlyCamera::from_pose(&Pose::look_at(DVec3::ZERO, DVec3::Z, 60.0).unwrap());
        fly.step([Move::Forward], 2.0, 0.5);
        assert!(close(fly.position, DVec3::new(0.0, 0.0, 1.0)));
        fly.step([Move::Right], 1.0, 1.0);
        assert!(close(fly.position, DVec3::new(1.0, 0.0, 1.0)), "right is +x when looking along +z");
        fly.step([Move::Up], 1.0, 1.0);
        assert!(close(fly.position, DVec3::new(1.0, 1.0, 1.0)));
        fly.step([Move::Forward, Move::Back], 1.0, 1.0);
        assert!(close(fly.position, DVec3::new(1.0, 1.0, 1.0)), "opposite keys cancel");
        fly.step([Move::Forward, Move::Left], 1.0, 1.0);
        assert!((fly.position.distance(DVec3::new(1.0, 1.0, 1.0)) - 1.0).abs() < 1e-12, "diagonals are not faster");
    }

    #[test]
    fn the_mouse_turns_and_pitch_is_limited() {
        let mut fly = FlyCamera::from_pose(&Pose::look_at(DVec3::ZERO, DVec3::Z, 60.0).unwrap());
        fly.look(100.0, 0.0, 0.01);
        assert!(fly.forward().x > 0.8, "moving the mouse right turns right: {:?}", fly.forward());
        fly.look(0.0, 1e6, 0.01);
        assert!(fly.pitch >= -MAX_PITCH && fly.forward().y < -0.99);
        fly.look(f64::NAN, 0.0, 0.01);
        assert!(fly.forward().is_finite());
        fly.zoom(100.0);
        assert_eq!(fly.fov_degrees, FOV_RANGE.1);
    }

    #[test]
    fn printed_poses_name_position_and_target() {
        let pose = Pose::look_at(DVec3::new(0.0, 1.0, -4.0), DVec3::new(0.0, 1.0, 0.0), 45.0).unwrap();
        let text = describe_pose(&pose, 2.0);
        assert!(text.contains("key(2.000, vec3(0.0000, 1.0000, -4.0000), vec3(0.0000, 1.0000, -3.0000))"), "{text}");
        assert!(text.contains("position = [0.0000, 1.0000, -4.0000]"), "{text}");
    }

    #[test]
    fn printed_keys_paste_into_scene_files_and_path_files() {
        let a = Pose::look_at(DVec3::new(0.0, 1.0, -4.0), DVec3::ZERO, 45.0).unwrap();
        let b = Pose::look_at(DVec3::new(4.0, 1.0, 0.0), DVec3::ZERO, 45.0).unwrap();
        let line = |pose: &Pose, t: f64| describe_pose(pose, t).lines().nth(1).unwrap().trim().to_string();
        let source = format!("scene(sphere(1.0)).camera(camera_path({}, {}))", line(&a, 0.0), line(&b, 2.0));
        let scene = fractal_dsl::parse::parse_str(&source).unwrap_or_else(|e| panic!("{e}: {source}"));
        let at_end = Pose::from_camera(&scene.camera, 2.0, &|p| p.default).unwrap();
        assert!(at_end.position.distance(b.position) < 1e-9 && at_end.forward.distance(b.forward) < 1e-4);
        let toml: String = [(&a, 0.0), (&b, 2.0)]
            .iter()
            .map(|(pose, t)| {
                describe_pose(pose, *t).lines().skip(2).map(|l| l.trim().to_string() + "\n").collect::<String>()
            })
            .collect();
        let file = super::super::path_file::parse_camera_path(&toml).unwrap_or_else(|e| panic!("{e}: {toml}"));
        assert!(file.path.pose(0.0, 45.0).position.distance(a.position) < 1e-9);
    }
}
