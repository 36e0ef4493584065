//! Flights: R starts recording the camera as the user flies, a key every [`KEY_INTERVAL`] seconds of flight, one
//! wherever the user presses Enter, and one where it stops; R again ends it and writes the flight beside the scene as a scene file whose camera is that
//! `camera_path(..)` (`NAME-flight-NNNN.fractal`, to open, render or edit) and as a glTF camera animation
//! (`NAME-flight-NNNN.gltf`, from the same exporter as `fractal export --camera`).

use std::path::{Path, PathBuf};

use fractal_dsl::{CameraKey, CameraPlacement, PathInterpolation, Scene};
use fractal_render::camera::Pose;

/// Seconds of flight between two recorded keys.
pub const KEY_INTERVAL: f64 = 1.0;
/// Frames a second of the glTF animation's samples.
const GLTF_FPS: f64 = 30.0;

/// A flight being recorded.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Flight {
    keys: Vec<CameraKey>,
    /// Seconds since recording started, when the next timed key is due, and the last pose seen.
    elapsed: f64,
    next_tick: f64,
    last: Option<Pose>,
    fov_degrees: f64,
}

impl Flight {
    /// Records `pose` after `dt` more seconds of flight: a key when the interval has passed since the last one.
    pub fn record(&mut self, pose: &Pose, dt: f64) {
        if !self.keys.is_empty() {
            self.elapsed += dt.max(0.0);
        }
        // Timed keys fall on whole intervals from the start, whatever keys Enter added between them.
        if self.keys.is_empty() || self.elapsed >= self.next_tick - 1e-9 {
            if self.keys.last().is_none_or(|k| self.elapsed - k.time > 1e-6) {
                self.keys.push(key(self.elapsed, pose));
            }
            self.next_tick = (self.elapsed / KEY_INTERVAL + 1e-9).floor() * KEY_INTERVAL + KEY_INTERVAL;
        }
        self.last = Some(*pose);
        self.fov_degrees = pose.fov_degrees;
    }

    /// A key at the last pose seen, now (unless one is there already).
    pub fn key_now(&mut self) {
        let Some(pose) = self.last else {
            return;
        };
        if self.keys.last().is_none_or(|k| self.elapsed - k.time > 1e-6) {
            self.keys.push(key(self.elapsed, &pose));
        }
    }

    /// The recorded keys, with one at the last pose seen if it is not a key already.
    pub fn finish(mut self) -> Vec<CameraKey> {
        if let (Some(pose), Some(last)) = (self.last, self.keys.last()) {
            if self.elapsed - last.time > 1e-6 {
                self.keys.push(key(self.elapsed, &pose));
            }
        }
        self.keys
    }

    pub fn fov_degrees(&self) -> f64 {
        self.fov_degrees
    }
}

fn key(time: f64, pose: &Pose) -> CameraKey {
    let target = pose.position + pose.forward.normalize_or(glam::DVec3::Z);
    // Key times to the microsecond: the file reads `key(1.0, ..)`, not `key(0.9999999999999999, ..)`.
    let time = (time * 1e6).round() / 1e6;
    CameraKey { time, position: pose.position.to_array(), target: target.to_array() }
}

/// `scene` with its camera replaced by the flight `keys` (Catmull-Rom through them).
pub fn scene_with_flight(scene: &Scene, keys: Vec<CameraKey>, fov_degrees: f64) -> Scene {
    let mut flown = scene.clone();
    flown.camera.placement =
        CameraPlacement::Path { keys, interpolation: PathInterpolation::CatmullRom, looped: false };
    flown.camera.fov_degrees = fov_degrees;
    flown
}

/// Writes the flight in `scene` (from [`scene_with_flight`]) as `STEM-flight-NNNN.fractal` and `.gltf` in
/// `folder`; returns both paths.
pub fn write_flight(scene: &Scene, folder: &Path, stem: &str, aspect: f64) -> Result<(PathBuf, PathBuf), String> {
    let base = (1..10_000)
        .map(|n| folder.join(format!("{stem}-flight-{n:04}")))
        .find(|p| !p.with_extension("fractal").exists())
        .ok_or("no free flight file name")?;
    let (fractal, gltf) = (base.with_extension("fractal"), base.with_extension("gltf"));
    let duration = match &scene.camera.placement {
        CameraPlacement::Path { keys, .. } => keys.last().map_or(0.0, |k| k.time),
        CameraPlacement::LookAt { .. } => 0.0,
    };
    let text =
        format!("// A flight recorded in the viewer ({duration:.1} s).\n{}\n", fractal_dsl::print::to_source(scene));
    std::fs::write(&fractal, text).map_err(|e| format!("cannot write {}: {e}", fractal.display()))?;
    let document = crate::output::gltf_camera::camera_gltf(scene, GLTF_FPS, duration.max(1.0 / GLTF_FPS), aspect)
        .map_err(|e| e.to_string())?;
    std::fs::write(&gltf, document).map_err(|e| format!("cannot write {}: {e}", gltf.display()))?;
    Ok((fractal, gltf))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn pose(z: f64) -> Pose {
        Pose { position: DVec3::new(0.0, 0.0, z), forward: DVec3::Z, up: DVec3::Y, fov_degrees: 40.0 }
    }

    #[test]
    fn a_flight_keys_every_interval_and_where_it_stops() {
        let mut flight = Flight::default();
        flight.record(&pose(-3.0), 0.5);
        for i in 1..=25 {
            flight.record(&pose(-3.0 + i as f64 * 0.1), 0.1);
            if i == 13 {
                flight.key_now();
                flight.key_now();
            }
        }
        let keys = flight.clone().finish();
        let times: Vec<f64> = keys.iter().map(|k| (k.time * 1e6).round() / 1e6).collect();
        assert_eq!(times, vec![0.0, 1.0, 1.3, 2.0, 2.5], "a key a second from the first, one on Enter, one at the end");
        assert_eq!(keys[0].position, [0.0, 0.0, -3.0]);
        assert_eq!(keys[0].target, [0.0, 0.0, -2.0]);
        assert!((keys[4].position[2] + 0.5).abs() < 1e-9);

        let scene = fractal_dsl::builder::scene(fractal_dsl::builder::sphere(1.0));
        let flown = scene_with_flight(&scene, keys, flight.fov_degrees());
        let dir = std::env::temp_dir().join(format!("fractal-flight-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (fractal, gltf) = write_flight(&flown, &dir, "ball", 16.0 / 9.0).unwrap();
        assert!(fractal.ends_with("ball-flight-0001.fractal"));
        let back = fractal_dsl::parse::parse_str(&std::fs::read_to_string(&fractal).unwrap()).unwrap();
        assert_eq!(back.camera, flown.camera, "the scene file holds the flight as its camera path");
        let json: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(gltf).unwrap()).unwrap();
        assert_eq!(json["asset"]["version"], "2.0");
        std::fs::remove_dir_all(dir).ok();
    }
}
