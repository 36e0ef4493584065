//! Bookmarks: named views (camera, time, parameter values) kept in a TOML file beside the scene
//! (`NAME.bookmarks.toml` next to `NAME.fractal`), saved with B or the panel's button and restored from the panel.
//! The camera is kept as the fly camera holds it (position, yaw, pitch, field of view), so a restored view is the same
//! view to the last bit.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::camera_control::FlyCamera;

/// One saved view.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bookmark {
    pub name: String,
    pub time: f64,
    pub position: [f64; 3],
    /// Radians about the world's up axis (0 looks along +z) and above the horizon.
    pub yaw: f64,
    pub pitch: f64,
    pub fov_degrees: f64,
    #[serde(default)]
    pub params: BTreeMap<String, f64>,
}

impl Bookmark {
    pub fn new(name: String, camera: &FlyCamera, time: f64, params: BTreeMap<String, f64>) -> Bookmark {
        let p = camera.position;
        Bookmark {
            name,
            time,
            position: [p.x, p.y, p.z],
            yaw: camera.yaw,
            pitch: camera.pitch,
            fov_degrees: camera.fov_degrees,
            params,
        }
    }

    pub fn camera(&self) -> FlyCamera {
        FlyCamera { position: self.position.into(), yaw: self.yaw, pitch: self.pitch, fov_degrees: self.fov_degrees }
    }
}

#[derive(Debug, Default, Serialize, Deserialize)]
struct BookmarkFile {
    #[serde(default, rename = "bookmark")]
    bookmarks: Vec<Bookmark>,
}

/// A scene's bookmarks and the file they live in.
#[derive(Clone, Debug, PartialEq)]
pub struct Bookmarks {
    pub path: PathBuf,
    pub list: Vec<Bookmark>,
}

impl Bookmarks {
    /// The bookmark file beside `scene` (a `.fractal` path, or a folder and a built-in scene's name).
    pub fn beside(folder: &Path, stem: &str) -> PathBuf {
        folder.join(format!("{stem}.bookmarks.toml"))
    }

    /// The bookmarks in `path`; none when the file does not exist. A file that cannot be read is an error naming it.
    pub fn load(path: &Path) -> Result<Bookmarks, String> {
        let list = match std::fs::read_to_string(path) {
            Ok(text) => {
                toml::from_str::<BookmarkFile>(&text).map_err(|e| format!("{}: {e}", path.display()))?.bookmarks
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
            Err(e) => return Err(format!("{}: {e}", path.display())),
        };
        Ok(Bookmarks { path: path.to_path_buf(), list })
    }

    /// A name not taken yet: `view 1`, `view 2`, …
    pub fn next_name(&self) -> String {
        (1..).map(|n| format!("view {n}")).find(|name| self.list.iter().all(|b| &b.name != name)).unwrap_or_default()
    }

    /// Adds `bookmark` (replacing one of the same name) and writes the file.
    pub fn add(&mut self, bookmark: Bookmark) -> Result<(), String> {
        self.list.retain(|b| b.name != bookmark.name);
        self.list.push(bookmark);
        let file = BookmarkFile { bookmarks: self.list.clone() };
        let text = toml::to_string_pretty(&file).map_err(|e| e.to_string())?;
        std::fs::write(&self.path, text).map_err(|e| format!("cannot write {}: {e}", self.path.display()))
    }

    pub fn get(&self, name: &str) -> Option<&Bookmark> {
        self.list.iter().find(|b| b.name == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bookmarks_round_trip_exactly_through_their_file() {
        let dir = std::env::temp_dir().join(format!("fractal-bookmarks-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = Bookmarks::beside(&dir, "scene");
        let mut marks = Bookmarks::load(&path).unwrap();
        assert!(marks.list.is_empty(), "no file: no bookmarks");
        let camera = FlyCamera { position: [0.1, -2.0 / 3.0, 1e-17].into(), yaw: 0.3, pitch: -0.1, fov_degrees: 47.5 };
        let params = BTreeMap::from([("radius".to_string(), 0.7000000000000001)]);
        let name = marks.next_name();
        assert_eq!(name, "view 1");
        marks.add(Bookmark::new(name, &camera, 1.25, params)).unwrap();
        assert_eq!(marks.next_name(), "view 2");
        let loaded = Bookmarks::load(&path).unwrap();
        assert_eq!(loaded, marks);
        let back = loaded.get("view 1").unwrap().camera();
        assert_eq!(back.pose(), camera.pose(), "the same view to the last bit");
        std::fs::write(&path, "[[bookmark]]\nname = 3").unwrap();
        assert!(Bookmarks::load(&path).unwrap_err().contains("scene.bookmarks.toml"));
        std::fs::remove_dir_all(dir).ok();
    }
}
