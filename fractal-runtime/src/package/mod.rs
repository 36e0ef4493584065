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
mod source;
mod unity;
mod unreal;

use std::fmt;
use std::str::FromStr;

use fractal_dsl::Scene;

use source::Source;
pub use source::{PackageError, PackageFile};

/// An engine (or language) a scene can be packaged for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Engine {
    /// Bevy 0.20: a WESL module and a `Material` fragment shader importing it.
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engines_read_back_by_name() {
        for engine in Engine::ALL {
            assert_eq!(engine.name().parse::<Engine>(), Ok(engine));
        }
        assert!("blender".parse::<Engine>().is_err());
    }
}
