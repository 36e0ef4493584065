//! Triangle meshes of a scene's surface (`fractal mesh`), for 3D printing, DCC tools and engines: the surface is
//! extracted by surface nets ([`surface_nets`]) from the scene's distance function, streamed through the grid a
//! layer at a time so memory holds two layers of samples and the mesh itself, and written as binary glTF, PLY, STL or
//! OBJ ([`mod@write`]).
//!
//! A fractal's estimate need not change sign at its surface, so scenes with one are meshed at a small positive level
//! ([`default_level`]), the surface a sphere tracer's hit epsilon sees.
//!
//! The mesh is closed: the scene is meshed intersected with the meshing box (its bound, or the box given), so a
//! floor or an infinite repetition ends in a cap at the box instead of an open edge. It is 2-manifold: each sheet of
//! surface through a cell has its own vertex (module `cell_topology`), and the few edges that still end up shared by
//! four triangles are split at one end (module `repair`). Each vertex is the mean of its sheet's edge crossings,
//! moved once along the gradient onto the surface; its normal is the distance gradient and its colour the material's
//! albedo there.
//!
//! Files are written in glTF's right-handed frame, the renderer's with z mirrored (see
//! [`crate::output::gltf_camera`]), in every format, so meshes and exported cameras line up.

mod cell_topology;
mod repair;
pub mod surface_nets;
pub mod write;

use std::collections::HashMap;

use fractal_dsl::analyse::{bound, fold::fold_node, Aabb};
use fractal_dsl::Scene;

pub use surface_nets::{extract, field};
pub use write::{write_mesh, MeshFormat};

/// The box meshed when a scene has no finite bound (a floor, repetition): this cube around the origin.
pub const DEFAULT_HALF_EXTENT: f64 = 4.0;

/// A triangle mesh in the renderer's coordinates; triangles wind counter-clockwise (right-hand rule) seen from
/// outside.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<[f32; 3]>,
    pub normals: Vec<[f32; 3]>,
    /// Linear albedo, 0..1.
    pub colours: Vec<[f32; 3]>,
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// Edges used by triangles other than in matched pairs: each directed edge a→b must be met by as many b→a for the
    /// mesh to be closed and consistently oriented. Returns the number of directed edges left unmatched (0: closed).
    pub fn unmatched_edges(&self) -> usize {
        self.edge_uses().values().map(|&(forward, backward)| forward.abs_diff(backward) as usize).sum()
    }

    /// Undirected edges shared by more than two triangles (0 for a 2-manifold mesh, as [`extract`] makes).
    pub fn non_manifold_edges(&self) -> usize {
        self.edge_uses().values().filter(|&&(forward, backward)| forward + backward > 2).count()
    }

    /// Per undirected edge (low index, high index): how many triangles run it low → high and high → low.
    fn edge_uses(&self) -> HashMap<(u32, u32), (u32, u32)> {
        edge_uses(&self.triangles)
    }
}

/// Per undirected edge (low index, high index) of `triangles`: how many run it low → high and high → low.
fn edge_uses<'a>(triangles: impl IntoIterator<Item = &'a [u32; 3]>) -> HashMap<(u32, u32), (u32, u32)> {
    let mut uses: HashMap<(u32, u32), (u32, u32)> = HashMap::new();
    for t in triangles {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            let entry = uses.entry((a.min(b), a.max(b))).or_default();
            if a < b {
                entry.0 += 1;
            } else {
                entry.1 += 1;
            }
        }
    }
    uses
}

/// What to mesh: the box and the grid's resolution along its longest side, the level, the scene time and parameter
/// values.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshSettings {
    pub bounds: Aabb,
    /// Cells along the longest side of `bounds` (cells are cubes).
    pub resolution: u32,
    /// The level set meshed, in cells: distance = `level` × the cell size ([`default_level`]).
    pub level: f64,
    pub time: f32,
    pub params: Vec<f32>,
}

/// The level a scene is meshed at, in cells: 0 (the surface itself) for exact distances; a quarter of a cell for a
/// scene with a fractal, whose estimate may never go below 0 (the Mandelbox's is 0 only on the set itself, a dust no
/// grid sample lands on): the mesh is then the surface a sphere tracer with a hit epsilon of a quarter cell sees.
pub fn default_level(scene: &Scene) -> f64 {
    if scene.root.has_fractal() {
        FRACTAL_LEVEL
    } else {
        0.0
    }
}

/// The level of [`default_level`] for scenes with a fractal, in cells.
pub const FRACTAL_LEVEL: f64 = 0.25;

/// The box to mesh `scene` in: its bound, or the cube of [`DEFAULT_HALF_EXTENT`] around the origin.
pub fn default_bounds(scene: &Scene) -> Aabb {
    bound(&fold_node(&scene.root)).unwrap_or_else(|| Aabb::centered([DEFAULT_HALF_EXTENT; 3]))
}
