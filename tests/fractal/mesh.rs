//! `fractal mesh` on every built-in scene at 128 cells along the longest side: the mesh is closed (every directed
//! edge of a triangle is matched by the reverse edge of another: no boundary, consistent orientation), 2-manifold
//! (every edge shared by exactly two triangles, as slicers and engines expect), has triangles, and its vertices lie
//! on the surface of the field meshed (the scene's distance cut to the meshing box, at the level
//! the scene is meshed at: 0, or a quarter of a cell for a scene with a fractal, whose estimate need not change sign).
//!
//! "On the surface" is checked by looking for the other side of the field within half a cell of each vertex: along
//! ±its normal and the 26 grid directions in steps of a sixteenth of the radius, the six axis directions in steps of
//! 1/256 (a vertex the mesher bisected onto a grid edge, where a fractal's estimate is no distance, has the
//! other side within 1/64 of a cell along that edge, possibly on a thin sliver). Every vertex must pass.

use fractal::runtime::mesh::{default_bounds, default_level, extract, field, MeshSettings};
use fractal::scenes;

const RESOLUTION: u32 = 128;

#[test]
fn every_scene_meshes_closed_with_vertices_on_the_surface() {
    for (name, compiled) in scenes::ALL {
        let scene = compiled.scene();
        let settings = MeshSettings {
            bounds: default_bounds(scene),
            resolution: RESOLUTION,
            level: default_level(scene),
            time: 0.0,
            params: compiled.default_params::<f32>().to_vec(),
        };
        let native = compiled.native();
        let started = std::time::Instant::now();
        let mesh = extract(&native, &settings, &|_, _| {});
        let seconds = started.elapsed().as_secs_f64();
        let b = settings.bounds;
        let cell = (0..3).map(|a| b.max[a] - b.min[a]).fold(0.0, f64::max) / RESOLUTION as f64;
        let field = field(&native, &settings);
        let beyond = |radius: f64| -> Vec<&[f32; 3]> {
            mesh.positions
                .iter()
                .zip(&mesh.normals)
                .filter(|(p, n)| !surface_within(&field, p.map(f64::from), n.map(f64::from), radius))
                .map(|(p, _)| p)
                .collect()
        };
        let far = beyond(0.5 * cell);
        let unmatched = mesh.unmatched_edges();
        eprintln!(
            "{name:>22}: {} vertices, {} triangles, {unmatched} unmatched edges, {} non-manifold edges, {} \
             vertices farther than half a cell from the surface, {seconds:.2} s",
            mesh.positions.len(),
            mesh.triangles.len(),
            mesh.non_manifold_edges(),
            far.len()
        );
        assert!(!mesh.triangles.is_empty(), "{name}: no triangles");
        assert_eq!(unmatched, 0, "{name}: the mesh is not closed");
        assert_eq!(mesh.non_manifold_edges(), 0, "{name}: edges shared by more than two triangles");
        assert!(far.is_empty(), "{name}: vertices farther than half a cell from the surface: {far:?}");
        assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < mesh.positions.len()));
    }
}

/// Closed and 2-manifold at other resolutions too (odd and even, coarse), where other cells are ambiguous.
#[test]
fn every_scene_meshes_closed_and_manifold_at_other_resolutions() {
    for resolution in [48, 61, 64] {
        for (name, compiled) in scenes::ALL {
            let scene = compiled.scene();
            let settings = MeshSettings {
                bounds: default_bounds(scene),
                resolution,
                level: default_level(scene),
                time: 0.0,
                params: compiled.default_params::<f32>().to_vec(),
            };
            let mesh = extract(&compiled.native(), &settings, &|_, _| {});
            let (unmatched, shared) = (mesh.unmatched_edges(), mesh.non_manifold_edges());
            assert!(!mesh.triangles.is_empty(), "{name} at {resolution}: no triangles");
            assert_eq!((unmatched, shared), (0, 0), "{name} at {resolution}: unmatched and non-manifold edges");
        }
    }
}

/// Whether the field changes side within `radius` of `p`: a sample at a sixteenth, two, … or all of the
/// radius, along ±`normal` or one of the 26 grid directions, has the other sign.
fn surface_within(field: &dyn Fn([f64; 3]) -> f32, p: [f64; 3], normal: [f64; 3], radius: f64) -> bool {
    // 0 counts as inside, as the mesher counts it (an estimator's singular point is inside its set).
    let inside = |q: [f64; 3]| field(q) <= 0.0;
    let d = inside(p);
    for sign in [1.0, -1.0] {
        for step in 1..=16 {
            let t = sign * radius * f64::from(step) / 16.0;
            if inside([p[0] + normal[0] * t, p[1] + normal[1] * t, p[2] + normal[2] * t]) != d {
                return true;
            }
        }
    }
    for dx in -1..=1i32 {
        for dy in -1..=1i32 {
            for dz in -1..=1i32 {
                let dir = [dx, dy, dz].map(f64::from);
                let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
                if len == 0.0 {
                    continue;
                }
                // The grid axes finely: a vertex the mesher placed by bisecting a grid edge has the other side
                // within 1/64 of a cell along it, on a sliver the coarser steps can step over.
                let steps = if len == 1.0 { 256 } else { 16 };
                for step in 1..=steps {
                    let t = radius * f64::from(step) / f64::from(steps) / len;
                    let q = [p[0] + dir[0] * t, p[1] + dir[1] * t, p[2] + dir[2] * t];
                    if inside(q) != d {
                        return true;
                    }
                }
            }
        }
    }
    false
}
