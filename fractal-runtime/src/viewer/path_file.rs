//! Camera paths from TOML files, for `--camera-path` and [`super::ViewerOptions::camera_path`]:
//!
//! ```toml
//! interpolation = "catmull_rom"   # or "linear"; default catmull_rom
//! looped = true                   # default false
//! fov = 55.0                      # degrees; default: the scene camera's
//!
//! [[key]]
//! time = 0.0
//! position = [0.0, 1.0, -4.0]
//! target = [0.0, 0.0, 0.0]
//!
//! [[key]]
//! time = 4.0
//! position = [4.0, 1.5, 0.0]
//! target = [0.0, 0.0, 0.0]
//! ```
//!
//! Positions are joined as [`CameraPath`] joins a scene's keys (centripetal Catmull-Rom or straight lines),
//! orientations are slerped between the keys' look-at rotations. The viewer's P key prints poses as `[[key]]` tables.

use std::path::Path;

use fractal_dsl::{CameraKey, PathInterpolation};
use fractal_render::camera::CameraPath;
use serde::Deserialize;

#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
enum Interpolation {
    #[default]
    CatmullRom,
    Linear,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct KeyTable {
    time: f64,
    position: [f64; 3],
    target: [f64; 3],
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PathTable {
    #[serde(default)]
    interpolation: Interpolation,
    #[serde(default)]
    looped: bool,
    fov: Option<f64>,
    #[serde(default)]
    key: Vec<KeyTable>,
}

/// A camera path read from a file.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraPathFile {
    pub path: CameraPath,
    /// Field of view in degrees, when the file sets one.
    pub fov_degrees: Option<f64>,
}

/// Parses the TOML text of a camera path; errors name the line and column when TOML does.
pub fn parse_camera_path(text: &str) -> Result<CameraPathFile, String> {
    let table: PathTable = toml::from_str(text).map_err(|e| e.to_string().trim_end().to_string())?;
    if let Some(fov) = table.fov {
        if !(fov.is_finite() && fov > 0.0 && fov < 180.0) {
            return Err(format!("fov = {fov} is outside (0, 180) degrees"));
        }
    }
    let keys: Vec<CameraKey> =
        table.key.iter().map(|k| CameraKey { time: k.time, position: k.position, target: k.target }).collect();
    let interpolation = match table.interpolation {
        Interpolation::CatmullRom => PathInterpolation::CatmullRom,
        Interpolation::Linear => PathInterpolation::Linear,
    };
    let path = CameraPath::new(&keys, interpolation, table.looped).map_err(|e| e.to_string())?;
    Ok(CameraPathFile { path, fov_degrees: table.fov })
}

/// Reads and parses a camera path file; errors start with the file name.
pub fn load_camera_path(file: &Path) -> Result<CameraPathFile, String> {
    let text = fractal_dsl::parse::read_source(file).map_err(|e| format!("{}: {e}", file.display()))?;
    parse_camera_path(&text).map_err(|e| format!("{}: {e}", file.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    const TWO_KEYS: &str = "
interpolation = \"linear\"
fov = 40.0

[[key]]
time = 0.0
position = [0.0, 0.0, -4.0]
target = [0.0, 0.0, 0.0]

[[key]]
time = 2.0
position = [4.0, 0.0, 0.0]
target = [0.0, 0.0, 0.0]
";

    #[test]
    fn keys_are_read_and_interpolated() {
        let file = parse_camera_path(TWO_KEYS).unwrap();
        assert_eq!(file.fov_degrees, Some(40.0));
        let pose = file.path.pose(1.0, 40.0);
        assert!(pose.position.distance(DVec3::new(2.0, 0.0, -2.0)) < 1e-12, "linear midpoint: {:?}", pose.position);
        assert_eq!(file.path.span(), (0.0, 2.0));
    }

    #[test]
    fn defaults_are_catmull_rom_and_open() {
        let text = TWO_KEYS.replace("interpolation = \"linear\"\n", "").replace("fov = 40.0\n", "");
        let file = parse_camera_path(&text).unwrap();
        assert_eq!(file.fov_degrees, None);
        let expected = CameraPath::new(
            &[
                CameraKey { time: 0.0, position: [0.0, 0.0, -4.0], target: [0.0; 3] },
                CameraKey { time: 2.0, position: [4.0, 0.0, 0.0], target: [0.0; 3] },
            ],
            PathInterpolation::CatmullRom,
            false,
        )
        .unwrap();
        assert_eq!(file.path, expected);
    }

    #[test]
    fn bad_files_are_clear_errors() {
        let missing_target = "[[key]]\ntime = 0.0\nposition = [0.0, 0.0, 1.0]\n";
        let err = parse_camera_path(missing_target).unwrap_err();
        assert!(err.contains("target"), "{err}");
        assert!(parse_camera_path("").unwrap_err().contains("no keys"));
        let err = parse_camera_path("interpolation = \"cubic\"\n").unwrap_err();
        assert!(err.contains("cubic") && err.contains("line 1"), "{err}");
        assert!(parse_camera_path("fov = 200.0\n").unwrap_err().contains("fov"));
        let err = parse_camera_path("[[key]]\ntime = 0.0\nposition = [1.0, 0.0, 0.0]\ntarget = [1.0, 0.0, 0.0]\n");
        assert!(err.unwrap_err().contains("no view direction"));
        let err = load_camera_path(Path::new("no/such/path.toml")).unwrap_err();
        assert!(err.starts_with("no/such/path.toml: "), "{err}");
    }
}
