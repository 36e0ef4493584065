//! Surface nets over a scene's distance function, streamed through the grid one layer of cells at a time.
//!
//! The field meshed is max(scene distance, distance to the meshing box) − level: the scene cut to the box, so every
//! mesh is closed, at the level its settings give. The grid has one empty cell of padding around the box. Corner
//! samples are taken a layer at a time (rows in parallel); a tile of 8×8 corners whose centre is outside and farther
//! from the surface than the tile's half diagonal plus 1.5 cells is filled from that one sample — outside, the field is
//! a distance bound, so no surface passes through the tile and none of its corners sits on an edge the surface crosses.
//! Inside, a fractal's estimate is no distance (the Juliabulb's reads −0.5 a hair from its surface), so tiles inside
//! are always sampled.
//!
//! Every cell whose corners differ in sign gets one vertex per sheet of surface through it (module
//! `cell_topology`): the mean of the crossings on the sheet's edges (linear interpolation), moved once along the
//! gradient onto the surface and kept inside its cell. Every grid edge whose ends differ in sign joins, in a quad
//! wound so its normal points from inside to outside, the vertices of its sheet in the four cells around it.

use fractal_dsl::eval::{Env, Evaluator};
use fractal_dsl::number::math::{v3, V3};
use rayon::prelude::*;

use super::cell_topology::{edge_at, edge_corners, sheets, Sheets};
use super::{Mesh, MeshSettings};

/// Corners per tile side in the sampling cull.
const TILE: usize = 8;
/// No vertex for this cell, or for this edge of it.
const NONE: u32 = u32::MAX;

/// A cell's vertices: the first one's index, one per sheet in sheet order.
#[derive(Clone, Copy)]
struct CellVertices {
    first: u32,
    sheets: Sheets,
}

impl CellVertices {
    const EMPTY: CellVertices = CellVertices { first: NONE, sheets: Sheets::NONE };

    /// The vertex of the sheet `edge` belongs to.
    fn on(&self, edge: usize) -> u32 {
        match (self.first, self.sheets.of(edge)) {
            (NONE, _) | (_, None) => NONE,
            (first, Some(sheet)) => first + u32::from(sheet),
        }
    }
}
/// The grid's offset from the box's corner, in cells (see [`Grid::new`]).
const GRID_OFFSET: [f64; 3] = [0.0137, 0.0291, 0.0413];
/// A projected vertex is kept when the field changes sign within this many cells along its gradient (a margin under
/// the half cell promised).
const REACH: f64 = 0.45;

/// Whether a field value is inside the surface. 0 counts as inside: an estimator can return ±0 at its singular
/// point (the Mandelbulb's centre), and that point is inside the set.
fn is_inside(v: f32) -> bool {
    v <= 0.0
}

/// The grid: `cells` per axis (padding included), the position of corner 0 and the cell size.
struct Grid {
    cells: [usize; 3],
    origin: [f64; 3],
    h: f64,
    /// The level meshed, in distance units.
    level: f64,
    box_min: [f64; 3],
    box_max: [f64; 3],
}

impl Grid {
    fn new(settings: &MeshSettings) -> Grid {
        let (min, max) = (settings.bounds.min, settings.bounds.max);
        let longest = (0..3).map(|a| max[a] - min[a]).fold(0.0, f64::max).max(1e-9);
        let h = longest / f64::from(settings.resolution.max(1));
        let cells = [0, 1, 2].map(|a| (((max[a] - min[a]) / h).ceil() as usize).max(1) + 2);
        // Corners sit a few hundredths of a cell off the round coordinates: estimators are singular on some planes
        // and axes (the Mandelbulb's x = 0 and y = 0, its centre), where a corner would read a value its
        // neighbourhood does not have and put a sliver of surface there.
        let origin = [0, 1, 2].map(|a| min[a] - h + GRID_OFFSET[a] * h);
        Grid { cells, origin, h, level: settings.level * h, box_min: min, box_max: max }
    }
    fn corner(&self, i: usize, j: usize, k: usize) -> [f64; 3] {
        [self.origin[0] + i as f64 * self.h, self.origin[1] + j as f64 * self.h, self.origin[2] + k as f64 * self.h]
    }
    /// Corners per layer row.
    fn row(&self) -> usize {
        self.cells[0] + 1
    }
}

/// The field meshed: the scene's distance cut to the box, less the level.
struct Field<'a> {
    evaluator: &'a dyn Evaluator<f32>,
    env: Env<'a, f32>,
    grid: Grid,
}

impl<'a> Field<'a> {
    fn new(evaluator: &'a dyn Evaluator<f32>, settings: &'a MeshSettings) -> Field<'a> {
        Field { evaluator, env: Env::new(settings.time, &settings.params), grid: Grid::new(settings) }
    }
    fn at(&self, p: [f64; 3]) -> f32 {
        let q = v3(p[0] as f32, p[1] as f32, p[2] as f32);
        let mut scene = self.evaluator.distance(q, &self.env);
        if scene.is_nan() {
            // An estimator's singular point (the Mandelbulb's at the origin: r = 0) has no value; its neighbourhood
            // does, and a grid corner must not read NaN as outside.
            let nudge = 1e-3 * self.grid.h as f32;
            scene = self.evaluator.distance(q + v3(nudge, nudge, nudge), &self.env);
        }
        scene.max(self.box_distance(p)) - self.grid.level as f32
    }
    /// Exact distance to the meshing box (negative inside).
    fn box_distance(&self, p: [f64; 3]) -> f32 {
        let g = &self.grid;
        let d = [0, 1, 2].map(|a| {
            let centre = 0.5 * (g.box_min[a] + g.box_max[a]);
            (p[a] - centre).abs() - 0.5 * (g.box_max[a] - g.box_min[a])
        });
        let outside = d.iter().map(|x| x.max(0.0).powi(2)).sum::<f64>().sqrt();
        let inside = d[0].max(d[1]).max(d[2]).min(0.0);
        (outside + inside) as f32
    }
    /// The gradient by the tetrahedral differences the renderer uses for normals.
    fn gradient(&self, p: [f64; 3], e: f64) -> [f64; 3] {
        let k = [[1.0, -1.0, -1.0], [-1.0, -1.0, 1.0], [-1.0, 1.0, -1.0], [1.0, 1.0, 1.0]];
        let mut g = [0.0; 3];
        for ki in k {
            let d = f64::from(self.at([p[0] + ki[0] * e, p[1] + ki[1] * e, p[2] + ki[2] * e]));
            for a in 0..3 {
                g[a] += ki[a] * d;
            }
        }
        g.map(|c| c / (4.0 * e))
    }

    /// Whether the field changes side ([`is_inside`]) within `reach` of `p` along ±`dir`.
    fn crosses_along(&self, p: [f64; 3], dir: [f64; 3], reach: f64) -> bool {
        let d = is_inside(self.at(p));
        let at = |t: f64| self.at([p[0] + dir[0] * t, p[1] + dir[1] * t, p[2] + dir[2] * t]);
        [reach, -reach].iter().any(|&t| is_inside(at(t)) != d)
    }

    /// The sign change of the field on the grid edge from `pa` along `axis` (one cell long), by bisection to 1/32 of
    /// a cell; `a_inside` is the sign at `pa`.
    fn crossing(&self, pa: [f64; 3], axis: usize, a_inside: bool) -> [f64; 3] {
        let (mut lo, mut hi) = (0.0, self.grid.h);
        for _ in 0..5 {
            let mid = 0.5 * (lo + hi);
            let mut q = pa;
            q[axis] += mid;
            if is_inside(self.at(q)) == a_inside {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let mut q = pa;
        q[axis] += 0.5 * (lo + hi);
        q
    }

    /// Samples corner layer `k` into `out`, culling tiles far from the surface.
    fn sample_layer(&self, k: usize, out: &mut [f32]) {
        let g = &self.grid;
        let (row, rows) = (g.row(), g.cells[1] + 1);
        let reach = g.h * std::f64::consts::SQRT_2 * (TILE - 1) as f64 / 2.0 + 1.5 * g.h;
        out.par_chunks_mut(TILE * row).enumerate().for_each(|(tj, band)| {
            let j0 = tj * TILE;
            let band_rows = (rows - j0).min(TILE);
            for i0 in (0..row).step_by(TILE) {
                let cols = (row - i0).min(TILE);
                let centre = [
                    g.origin[0] + (i0 as f64 + (cols - 1) as f64 / 2.0) * g.h,
                    g.origin[1] + (j0 as f64 + (band_rows - 1) as f64 / 2.0) * g.h,
                    g.origin[2] + k as f64 * g.h,
                ];
                let dc = f64::from(self.at(centre));
                for dj in 0..band_rows {
                    for di in 0..cols {
                        let p = g.corner(i0 + di, j0 + dj, k);
                        band[dj * row + i0 + di] = if dc >= reach {
                            let off = ((p[0] - centre[0]).powi(2) + (p[1] - centre[1]).powi(2)).sqrt();
                            (dc - off) as f32
                        } else {
                            self.at(p)
                        };
                    }
                }
            }
        });
    }
}

/// The field a mesh of `settings` follows, at a point in the renderer's coordinates: the scene's distance cut to the
/// meshing box, less the level. A mesh vertex lies within half a cell of where it is 0.
pub fn field<'a>(evaluator: &'a dyn Evaluator<f32>, settings: &'a MeshSettings) -> impl Fn([f64; 3]) -> f32 + 'a {
    let field = Field::new(evaluator, settings);
    move |p| field.at(p)
}

/// Meshes the scene `evaluator` computes, as `settings` say; `progress(done, total)` after each layer of cells.
pub fn extract(evaluator: &dyn Evaluator<f32>, settings: &MeshSettings, progress: &dyn Fn(usize, usize)) -> Mesh {
    let field = Field::new(evaluator, settings);
    let [nx, ny, nz] = field.grid.cells;
    let row = field.grid.row();
    let layer_len = row * (ny + 1);
    let (mut below, mut above) = (vec![0.0f32; layer_len], vec![0.0f32; layer_len]);
    let (mut previous, mut current) = (vec![CellVertices::EMPTY; nx * ny], vec![CellVertices::EMPTY; nx * ny]);
    let mut mesh = Mesh::default();
    let mut twice = Vec::new();
    field.sample_layer(0, &mut below);
    for k in 0..nz {
        field.sample_layer(k + 1, &mut above);
        current.fill(CellVertices::EMPTY);
        cell_vertices(&field, k, &below, &above, (&mut current, &mut twice), &mut mesh);
        let mut quad = |cells: [u32; 4], a: f32, b: f32| {
            if is_inside(a) == is_inside(b) || cells.contains(&NONE) {
                return;
            }
            let [c0, c1, c2, c3] = if is_inside(a) { cells } else { [cells[3], cells[2], cells[1], cells[0]] };
            mesh.triangles.push([c0, c1, c2]);
            mesh.triangles.push([c0, c2, c3]);
        };
        // The vertex of the cell at (i, j) of `layer` on the sheet of its edge along `axis` at offsets `at`.
        let cell = |layer: &[CellVertices], i: usize, j: usize, axis: usize, at: [usize; 3]| {
            layer[j * nx + i].on(edge_at(axis, at))
        };
        // Edges along z from corner layer k to k + 1: the four cells of this layer around each.
        for j in 1..ny {
            for i in 1..nx {
                let cells = [
                    cell(&current, i - 1, j - 1, 2, [1, 1, 0]),
                    cell(&current, i, j - 1, 2, [0, 1, 0]),
                    cell(&current, i, j, 2, [0, 0, 0]),
                    cell(&current, i - 1, j, 2, [1, 0, 0]),
                ];
                quad(cells, below[j * row + i], above[j * row + i]);
            }
        }
        // Edges along x and y in corner layer k: cells of layers k − 1 (where the edge is on their top face) and k.
        if k > 0 {
            for j in 1..ny {
                for i in 0..nx {
                    let cells = [
                        cell(&previous, i, j - 1, 0, [0, 1, 1]),
                        cell(&previous, i, j, 0, [0, 0, 1]),
                        cell(&current, i, j, 0, [0, 0, 0]),
                        cell(&current, i, j - 1, 0, [0, 1, 0]),
                    ];
                    quad(cells, below[j * row + i], below[j * row + i + 1]);
                }
            }
            for j in 0..ny {
                for i in 1..nx {
                    let cells = [
                        cell(&previous, i - 1, j, 1, [1, 0, 1]),
                        cell(&current, i - 1, j, 1, [1, 0, 0]),
                        cell(&current, i, j, 1, [0, 0, 0]),
                        cell(&previous, i, j, 1, [0, 0, 1]),
                    ];
                    quad(cells, below[j * row + i], below[(j + 1) * row + i]);
                }
            }
        }
        std::mem::swap(&mut below, &mut above);
        std::mem::swap(&mut previous, &mut current);
        progress(k + 1, nz);
    }
    super::repair::split_non_manifold_edges(&mut mesh, &twice);
    mesh
}

/// The vertices of cell layer `k` (between corner layers `below` and `above`), one per sheet of each cell, appended
/// to `mesh`; each cell's first vertex and sheets written into `cells`, and the vertices of sheets that cross a face
/// of their cell twice appended to `twice`.
fn cell_vertices(
    field: &Field,
    k: usize,
    below: &[f32],
    above: &[f32],
    (cells, twice): (&mut [CellVertices], &mut Vec<u32>),
    mesh: &mut Mesh,
) {
    let g = &field.grid;
    let [nx, ny, _] = g.cells;
    let row = g.row();
    let corner_value = |i: usize, j: usize, dk: usize| if dk == 0 { below[j * row + i] } else { above[j * row + i] };
    let mut crossing = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let values: [f32; 8] = std::array::from_fn(|c| corner_value(i + (c & 1), j + ((c >> 1) & 1), c >> 2));
            let inside_count = values.iter().filter(|&&v| is_inside(v)).count();
            if inside_count != 0 && inside_count != 8 {
                crossing.push((i, j, values));
            }
        }
    }
    let cell_sheets: Vec<Sheets> = crossing.par_iter().map(|&(_, _, values)| sheets(values, is_inside)).collect();
    let vertices: Vec<Vertex> = crossing
        .par_iter()
        .zip(&cell_sheets)
        .flat_map_iter(|(&(i, j, values), &sheets)| {
            (0..sheets.count).map(move |sheet| sheet_vertex(field, [i, j, k], &values, |e| sheets.of(e) == Some(sheet)))
        })
        .collect();
    let mut first = mesh.positions.len() as u32;
    for (&(i, j, _), &sheets) in crossing.iter().zip(&cell_sheets) {
        cells[j * nx + i] = CellVertices { first, sheets };
        let crosses_twice = |s: &u8| sheets.crosses_a_face_twice >> s & 1 == 1;
        twice.extend((0..sheets.count).filter(crosses_twice).map(|s| first + u32::from(s)));
        first += u32::from(sheets.count);
    }
    for (p, normal, colour) in vertices {
        mesh.positions.push(p);
        mesh.normals.push(normal);
        mesh.colours.push(colour);
    }
}

/// A vertex's position, normal and colour.
type Vertex = ([f32; 3], [f32; 3], [f32; 3]);

/// The vertex of one sheet of the cell at `cell` (corner values `values`), whose edges `on_sheet` picks.
fn sheet_vertex(field: &Field, [i, j, k]: [usize; 3], values: &[f32; 8], on_sheet: impl Fn(usize) -> bool) -> Vertex {
    let g = &field.grid;
    // The mean of the sheet's edge crossings.
    let (mut sum, mut n) = ([0.0f64; 3], 0.0);
    let mut edges = Vec::with_capacity(6);
    for edge in (0..12).filter(|&e| on_sheet(e)) {
        let (a, b) = edge_corners(edge);
        let axis = edge / 4;
        let (va, vb) = (values[a], values[b]);
        let t = f64::from(va) / f64::from(va - vb);
        let pa = g.corner(i + (a & 1), j + ((a >> 1) & 1), k + (a >> 2));
        edges.push((pa, axis, is_inside(va)));
        for (s, x) in sum.iter_mut().zip(pa) {
            *s += x;
        }
        sum[axis] += t * g.h;
        n += 1.0;
    }
    let mean = sum.map(|s| s / n);
    // One step along the gradient onto the surface, kept inside the cell.
    let grad = field.gradient(mean, 0.05 * g.h);
    let len2 = grad.iter().map(|c| c * c).sum::<f64>();
    let d = f64::from(field.at(mean));
    let low = g.corner(i, j, k);
    // Where the field is no distance (a fractal estimate inside its set, a step across a discontinuity) the step can
    // land away from the surface: a vertex with no sign change within half a cell along the gradient is replaced by
    // the edge crossing nearest the mean, found by bisection on the field itself.
    let projected = [0, 1, 2].map(|a| {
        let moved = if len2 > 1e-12 { mean[a] - d * grad[a] / len2 } else { mean[a] };
        moved.clamp(low[a], low[a] + g.h)
    });
    let len = len2.sqrt();
    let unit = if len > 1e-12 { grad.map(|c| c / len) } else { [0.0, 1.0, 0.0] };
    let p = if field.crosses_along(projected, unit, REACH * g.h) {
        projected
    } else {
        let distance2 = |q: [f64; 3]| (0..3).map(|a| (q[a] - mean[a]).powi(2)).sum::<f64>();
        edges
            .iter()
            .map(|&(pa, axis, a_inside)| field.crossing(pa, axis, a_inside))
            .min_by(|x, y| distance2(*x).total_cmp(&distance2(*y)))
            .unwrap_or(projected)
    };
    let normal = unit.map(|c| c as f32);
    let q: V3<f32> = v3(p[0] as f32, p[1] as f32, p[2] as f32);
    let albedo = field.evaluator.sample(q, &field.env).albedo;
    (p.map(|x| x as f32), normal, [albedo.x, albedo.y, albedo.z].map(|c| c.clamp(0.0, 1.0)))
}
