//! What every engine writer reads: the scene as a [`Source`] (its library program, its parameters as host
//! identifiers, its lights at t = 0), the file a writer returns, and the few spellings they share.
//!
//! Kept apart from the package facade, which calls the writers, so the writers read it without reading their caller.

use fractal_dsl::back::kernel::{Library, LightValue};
use fractal_dsl::ir::ParamDecl;
use fractal_dsl::lower::Program;
use fractal_dsl::validate::InvalidScene;
use fractal_dsl::Scene;
use fractal_render::error::{CameraError, FrameError};
use fractal_render::frame::{Frame, LightSlot, ParamValues};
use fractal_render::Pose;

/// One file of a package.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PackageFile {
    /// The file's name (no directories).
    pub name: String,
    pub contents: String,
}

/// Why a scene could not be packaged.
#[derive(Debug, thiserror::Error)]
pub enum PackageError {
    #[error(transparent)]
    InvalidScene(#[from] InvalidScene),
    /// The scene's camera (whose view the Shadertoy package starts from) is not a valid camera at t = 0.
    #[error("the scene's camera at t = 0: {0}")]
    Camera(#[from] CameraError),
    /// The lights at t = 0 could not be evaluated.
    #[error("the scene's lights at t = 0: {0}")]
    Lights(#[from] FrameError),
}

/// A scene as the engine writers read it.
pub(super) struct Source<'a> {
    pub(super) scene: &'a Scene,
    /// The scene's name as an identifier: lower case letters, digits and `_`, not starting with a digit.
    pub(super) name: String,
    pub(super) program: Program,
    pub(super) params: Vec<HostParam>,
    pub(super) lights: Vec<LightValue>,
}

/// A scene parameter as the host sees it.
pub(super) struct HostParam {
    /// The parameter's name as an identifier, unique in the scene and never `time`.
    pub(super) ident: String,
    pub(super) decl: ParamDecl,
}

impl HostParam {
    /// The global (GLSL, HLSL) or uniform the library reads it from: `sdf_<ident>`.
    pub(super) fn global(&self) -> String {
        format!("sdf_{}", self.ident)
    }
}

/// The global every library but WGSL's reads the time from.
pub(super) const TIME_GLOBAL: &str = "sdf_time";

impl<'a> Source<'a> {
    pub(super) fn new(scene: &'a Scene, name: &str) -> Result<Source<'a>, PackageError> {
        fractal_dsl::validate::checked(scene)?;
        let program = fractal_dsl::lower::lower_library(scene);
        let mut params: Vec<HostParam> = Vec::new();
        for decl in program.params.iter().cloned() {
            let mut ident = identifier(&decl.name);
            if ident == "time" {
                ident.push('_');
            }
            while params.iter().any(|p| p.ident == ident) {
                ident.push('_');
            }
            params.push(HostParam { ident, decl });
        }
        let pose = Pose::from_camera(&scene.camera, 0.0, &|p| p.default)?;
        let frame = Frame::new(scene, &pose, 0.0, 1, 1, &ParamValues::defaults(scene))?;
        let lights = frame
            .lights()
            .into_iter()
            .map(|light| {
                let (position, radiance) = match light {
                    LightSlot::Directional { direction, radiance } => (direction, radiance),
                    LightSlot::Point { position, radiance } => (position, radiance),
                };
                LightValue { position: position.map(f64::from), radiance: radiance.map(f64::from) }
            })
            .collect();
        Ok(Source { scene, name: identifier(name), program, params, lights })
    }

    /// The library's host values: time and parameters read as `time` and `param(p)` spell them, after `prologue`.
    pub(super) fn library(&self, time: &str, param: impl Fn(&HostParam) -> String, prologue: String) -> Library {
        Library {
            time: time.to_string(),
            params: self.params.iter().map(param).collect(),
            lights: self.lights.clone(),
            prologue,
        }
    }

    /// The corners of the scene's bound (±max distance for an unbounded scene), as the library's constants.
    pub(super) fn bound(&self) -> ([f64; 3], [f64; 3]) {
        fractal_dsl::back::kernel::library::bound(&self.program)
    }

    /// A Markdown table of the parameters: name, the uniform holding it, default and range.
    pub(super) fn param_table(&self, uniform: impl Fn(&HostParam) -> String) -> String {
        if self.params.is_empty() {
            return "The scene has no parameters.\n".to_string();
        }
        let mut table = String::from("| parameter | uniform | default | range |\n|---|---|---|---|\n");
        for p in &self.params {
            let d = &p.decl;
            table.push_str(&format!("| `{}` | `{}` | {} | {} … {} |\n", d.name, uniform(p), d.default, d.min, d.max));
        }
        table
    }

    /// The README's opening: what the package holds and the library's functions.
    pub(super) fn readme_head(&self, engine: &str, files: &str, vec3: &str) -> String {
        format!(
            "# {name} for {engine}\n\n\
             Generated by `fractal export {name} --target …` from the scene description; edit the scene, not these files.\n\n\
             {files}\n\n\
             ## The library\n\n\
             | function | what |\n|---|---|\n\
             | `float sdf({vec3} p)` | the scene's distance estimate (a bound on the distance to the surface) |\n\
             | `{vec3} sdf_normal({vec3} p)` | unit surface normal (central differences of `sdf`) |\n\
             | `{vec3} sdf_material({vec3} p)` | the surface's albedo at p |\n\
             | `sdf_raymarch(ro, rd, footprint)` | the viewer's march and shading along the unit ray (ro, rd): xyz = linear colour, w = the hit's distance t, or −1 for a miss; `footprint` = 2·tan(fov/2)/height, the pixel's angle |\n\
             | `sdf_display(colour)` | clamp and gamma as the viewer writes a pixel (for non-sRGB targets) |\n\
             | `sdf_display_linear(colour)` | the linear colour whose sRGB encoding is `sdf_display(colour)` (for sRGB targets) |\n\
             | `SDF_BOUND_MIN`, `SDF_BOUND_MAX`, `SDF_BOUND_CENTER`, `SDF_BOUND_RADIUS` | the scene's bounding box and sphere: size the proxy mesh to them |\n\n\
             Coordinates are the scene's: left-handed, y up (Unity's convention). Lights are constants (their values at t = 0).\n",
            name = self.name,
        )
    }
}

/// `name` as an identifier: ASCII letters lower-cased, anything else but digits `_`, and `_` before a leading digit.
fn identifier(name: &str) -> String {
    let mut ident: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '_' }).collect();
    if ident.is_empty() || ident.starts_with(|c: char| c.is_ascii_digit()) {
        ident.insert(0, '_');
    }
    ident
}

/// A constant in GLSL or HLSL source: the shortest f32 decimal, always with a point.
pub(super) fn float(v: f64) -> String {
    fractal_dsl::back::f32_literal(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identifiers_are_safe_in_every_language() {
        assert_eq!(identifier("Power"), "power");
        assert_eq!(identifier("fold limit"), "fold_limit");
        assert_eq!(identifier("3d"), "_3d");
        assert_eq!(identifier(""), "_");
    }
}
