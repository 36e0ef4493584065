//! Engine packages: a scene as code another engine calls from its own materials
//! (`fractal export <scene> --target bevy|godot|unity|unreal|shadertoy|glsl|hlsl|wgsl -o DIR`).
//!
//! Every package has two layers. The function library is the scene compiler's own output in the engine's language
//! ([`fractal_dsl::back::kernel::write_library`]): `sdf(p)`, `sdf_normal(p)`, `sdf_material(p)`, the bound as
//! constants, and `sdf_raymarch(ro, rd, footprint)`, the viewer's march and shading. The scene's parameters and time
//! are the engine's uniforms or properties, named `sdf_<param>` and `sdf_time`; the lights are constants, their
//! values at t = 0. On top sits a ready material for the engine (`bevy`, `godot`, `unity`, `unreal`,
//! `shadertoy`; `plain` has the library alone) that marches from the camera, shades like the viewer and writes
//! depth, so the fractal sits among the engine's meshes.
//!
//! Scenes are left-handed with y up (as Unity's world). Materials for right-handed engines (Bevy, Godot) mirror z
//! on the way in; Unreal's (left-handed, z up) turns its axes; the library itself works in scene coordinates.

mod bevy;
mod godot;
mod plain;
mod shadertoy;
mod unity;
mod unreal;

use std::fmt;
use std::str::FromStr;

use fractal_dsl::back::kernel::{Library, LightValue};
use fractal_dsl::ir::ParamDecl;
use fractal_dsl::lower::Program;
use fractal_dsl::validate::InvalidScene;
use fractal_dsl::Scene;
use fractal_render::error::{CameraError, FrameError};
use fractal_render::frame::{Frame, LightSlot, ParamValues};
use fractal_render::Pose;

/// An engine (or language) a scene can be packaged for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Engine {
    /// Bevy: a naga_oil WGSL module and a `Material` fragment shader importing it.
    Bevy,
    /// Godot 4: a `.gdshaderinc` library and a `spatial` `.gdshader` including it.
    Godot,
    /// Unity: an HLSL library with Shader Graph Custom Function entry points, and a ready `.shader`.
    Unity,
    /// Unreal Engine: a `.ush` library and the body of a material Custom node.
    Unreal,
    /// Shadertoy: one GLSL ES 3.00 `mainImage` to paste.
    Shadertoy,
    /// A GLSL function library (GLSL 4.50 and GLSL ES 3.00).
    Glsl,
    /// An HLSL function library.
    Hlsl,
    /// A WGSL function library.
    Wgsl,
}

impl Engine {
    /// Every engine, in the order `--help` lists them.
    pub const ALL: [Engine; 8] = [
        Engine::Bevy,
        Engine::Godot,
        Engine::Unity,
        Engine::Unreal,
        Engine::Shadertoy,
        Engine::Glsl,
        Engine::Hlsl,
        Engine::Wgsl,
    ];

    /// The name the command line and [`FromStr`] use.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Bevy => "bevy",
            Engine::Godot => "godot",
            Engine::Unity => "unity",
            Engine::Unreal => "unreal",
            Engine::Shadertoy => "shadertoy",
            Engine::Glsl => "glsl",
            Engine::Hlsl => "hlsl",
            Engine::Wgsl => "wgsl",
        }
    }
}

impl fmt::Display for Engine {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An engine name that is not one of [`Engine::ALL`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown engine `{0}`: expected one of bevy, godot, unity, unreal, shadertoy, glsl, hlsl, wgsl")]
pub struct UnknownEngine(pub String);

impl FromStr for Engine {
    type Err = UnknownEngine;

    /// Reads an engine name, ignoring ASCII case and surrounding whitespace.
    fn from_str(s: &str) -> Result<Engine, UnknownEngine> {
        let wanted = s.trim();
        Engine::ALL.into_iter().find(|e| e.name().eq_ignore_ascii_case(wanted)).ok_or_else(|| UnknownEngine(s.into()))
    }
}

/// One file of a package.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PackageFile {
    /// The file's name (no directories).
    pub name: String,
    pub contents: String,
}

/// The files of an engine package, the function library first.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Package {
    pub engine: Engine,
    pub files: Vec<PackageFile>,
}

impl Package {
    /// The file called `name`.
    pub fn file(&self, name: &str) -> Option<&str> {
        self.files.iter().find(|f| f.name == name).map(|f| f.contents.as_str())
    }
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

/// Packages `scene`, called `name` (the package's file names and module path are made of it), for `engine`.
pub fn package(scene: &Scene, name: &str, engine: Engine) -> Result<Package, PackageError> {
    let source = Source::new(scene, name)?;
    let files = match engine {
        Engine::Bevy => bevy::files(&source),
        Engine::Godot => godot::files(&source),
        Engine::Unity => unity::files(&source),
        Engine::Unreal => unreal::files(&source),
        Engine::Shadertoy => shadertoy::files(&source)?,
        Engine::Glsl => plain::glsl(&source),
        Engine::Hlsl => plain::hlsl(&source),
        Engine::Wgsl => plain::wgsl(&source),
    };
    Ok(Package { engine, files })
}

/// A scene as the engine writers read it.
struct Source<'a> {
    scene: &'a Scene,
    /// The scene's name as an identifier: lower case letters, digits and `_`, not starting with a digit.
    name: String,
    program: Program,
    params: Vec<HostParam>,
    lights: Vec<LightValue>,
}

/// A scene parameter as the host sees it.
struct HostParam {
    /// The parameter's name as an identifier, unique in the scene and never `time`.
    ident: String,
    decl: ParamDecl,
}

impl HostParam {
    /// The global (GLSL, HLSL) or uniform the library reads it from: `sdf_<ident>`.
    fn global(&self) -> String {
        format!("sdf_{}", self.ident)
    }
}

/// The global every library but WGSL's reads the time from.
const TIME_GLOBAL: &str = "sdf_time";

impl<'a> Source<'a> {
    fn new(scene: &'a Scene, name: &str) -> Result<Source<'a>, PackageError> {
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
    fn library(&self, time: &str, param: impl Fn(&HostParam) -> String, prologue: String) -> Library {
        Library {
            time: time.to_string(),
            params: self.params.iter().map(param).collect(),
            lights: self.lights.clone(),
            prologue,
        }
    }

    /// The corners of the scene's bound (±max distance for an unbounded scene), as the library's constants.
    fn bound(&self) -> ([f64; 3], [f64; 3]) {
        fractal_dsl::back::kernel::library::bound(&self.program)
    }

    /// A Markdown table of the parameters: name, the uniform holding it, default and range.
    fn param_table(&self, uniform: impl Fn(&HostParam) -> String) -> String {
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
    fn readme_head(&self, engine: &str, files: &str, vec3: &str) -> String {
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
fn float(v: f64) -> String {
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

    #[test]
    fn engines_read_back_by_name() {
        for engine in Engine::ALL {
            assert_eq!(engine.name().parse::<Engine>(), Ok(engine));
        }
        assert!("blender".parse::<Engine>().is_err());
    }
}
