//! Writes a scene back as canonical scene source: `parse_str(&to_source(s))` rebuilds `s` exactly.

use crate::ir::Scene;

/// The scene in canonical `.fractal` syntax.
pub fn to_source(scene: &Scene) -> String {
    let _ = scene;
    todo!("printer")
}
