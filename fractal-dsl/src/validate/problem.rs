//! What validation reports and the limits it holds scenes to.

use std::fmt;

/// Deepest a distance tree may nest.
pub const MAX_DEPTH: usize = 64;
/// Deepest one scalar expression may nest.
pub const MAX_EXPR_DEPTH: usize = 64;
/// Most expression nodes a whole scene may hold.
pub const MAX_EXPR_NODES: usize = 100_000;
/// Most lights a scene may have (each is a uniform slot pair and a shading loop iteration).
pub const MAX_LIGHTS: usize = 16;
/// Largest `max_steps`.
pub const MAX_MARCH_STEPS: u32 = 10_000;
/// Most rays a pixel may take (`samples`): a 16×16 supersampling, past which a still is better accumulated
/// progressively.
pub const MAX_SAMPLES: u32 = 256;
/// Largest `max_distance`. The kernels keep the ray parameter in f32, whose spacing is 64 units at 1e9; beyond the f32
/// range (3.4e38) one backend would march to infinity and another draw nothing.
pub const MAX_DISTANCE: f64 = 1e9;
pub use crate::ir::MAX_NODES;
pub use crate::vocab::ops::MAX_REPEAT_COUNT;

/// A broken rule in a scene, located by the path of the node (or the scene part) it concerns.
#[derive(Clone, Debug, PartialEq)]
pub struct ValidationError {
    /// Where: e.g. `union > child 2 > translate > sphere`, `light 1`, `camera`, `scene`, `param "power"`.
    pub path: String,
    pub message: String,
}

impl fmt::Display for ValidationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.path, self.message)
    }
}

impl std::error::Error for ValidationError {}

/// A scene that breaks rules of the language: every broken rule [`validate`](super::validate) found. Every way into the
/// compiler and the evaluators ([`crate::compile`], [`crate::eval::interp::Interpreter::new`]) returns it for a scene
/// made with the builder; the parser and `scene!` report the same rules at their source location instead.
#[derive(Clone, Debug, PartialEq)]
pub struct InvalidScene(pub Vec<ValidationError>);

impl fmt::Display for InvalidScene {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("the scene is invalid: ")?;
        for (i, e) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{e}")?;
        }
        Ok(())
    }
}

impl std::error::Error for InvalidScene {}

/// One broken rule found by a per-value check: which argument it concerns (by the name the vocabulary gives it;
/// `""` for the value as a whole) and, for an argument that repeats (the keys of a camera path), which one.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    pub arg: &'static str,
    pub index: Option<usize>,
    pub message: String,
}

impl Problem {
    pub(super) fn new(arg: &'static str, message: String) -> Problem {
        Problem { arg, index: None, message }
    }
}
