//! Making a closed mesh 2-manifold: every edge shared by exactly two triangles.
//!
//! Surface nets gives each sheet of surface in a cell its own vertex (module `cell_topology`), which leaves one
//! case: a sheet that crosses a cell face twice, in both cells sharing the face. Their two vertices are then joined
//! twice, and the edge between them is shared by four triangles, two running it each way. Such an edge is undone by
//! splitting one of its ends: around that vertex, triangles that share an edge two triangles share belong together,
//! and at each edge four triangles share, each triangle running it one way is paired with one running it the other
//! way. The pairing is chosen so that the two pairs of every such edge fall in different groups; each group then
//! gets a copy of the vertex. Every group runs each of its edges as often one way as the other, so the mesh stays
//! closed and consistently wound, and the shared edge becomes two edges of two triangles each. A copy is moved a
//! twentieth of the way to its group's centre, so the copies do not coincide (programs that weld vertices by
//! position would join them again).
//!
//! An edge shared by six or more triangles, or a vertex at which no pairing separates the pairs, is left as it is.

use std::collections::HashMap;

use super::{edge_uses, Mesh};

/// How far a copy moves towards the centre of its group's outer vertices.
const NUDGE: f32 = 0.05;
/// The most edges four triangles share at one vertex whose pairings are tried (2^n pairings).
const MAX_SHARED: usize = 8;

/// Splits vertices until no edge at one of `candidates` (and the copies made) is shared by more than two triangles,
/// or none left can be split. Surface nets passes the vertices of sheets that cross a face of their cell twice, the
/// only ones such an edge can end at; the rest of the mesh is not counted, so a mesh of millions of triangles is
/// repaired in one pass over its triangles per round. Returns the vertices added.
pub fn split_non_manifold_edges(mesh: &mut Mesh, candidates: &[u32]) -> usize {
    let mut candidates = candidates.to_vec();
    let mut added = 0;
    // Each round tries the lower end of each shared edge, then the higher where the lower cannot be split; the
    // counts are those at the start of the round, so a vertex next to one split in the round waits for the next.
    for _ in 0..4 {
        candidates.sort_unstable();
        candidates.dedup();
        let around: HashMap<u32, Vec<usize>> = triangles_around(mesh, &candidates).into_iter().collect();
        let mut near: Vec<usize> = around.values().flatten().copied().collect();
        near.sort_unstable();
        near.dedup();
        let uses = edge_uses(near.iter().map(|&t| &mesh.triangles[t]));
        let shared: Vec<(u32, u32)> = uses.iter().filter(|(_, &(f, b))| f + b > 2).map(|(&e, _)| e).collect();
        if shared.is_empty() {
            break;
        }
        let mut touched = std::collections::HashSet::new();
        let before = added;
        for (low, high) in shared {
            for vertex in [low, high] {
                if touched.contains(&low) || touched.contains(&high) {
                    break;
                }
                let Some(groups) = around.get(&vertex).and_then(|t| groups(mesh, vertex, t, &uses)) else {
                    continue;
                };
                for group in &groups[1..] {
                    candidates.push(split_off(mesh, vertex, group));
                    added += 1;
                }
                for &t in groups.iter().flatten() {
                    touched.extend(mesh.triangles[t]);
                }
                touched.insert(vertex);
                break;
            }
        }
        if added == before {
            break;
        }
    }
    added
}

/// Gives the triangles of `group` a copy of `vertex`, moved towards the group's centre; returns the copy.
fn split_off(mesh: &mut Mesh, vertex: u32, group: &[usize]) -> u32 {
    let copy = mesh.positions.len() as u32;
    let centre = outer_centre(mesh, vertex, group);
    let p = mesh.positions[vertex as usize];
    mesh.positions.push(std::array::from_fn(|a| p[a] + NUDGE * (centre[a] - p[a])));
    mesh.normals.push(mesh.normals[vertex as usize]);
    mesh.colours.push(mesh.colours[vertex as usize]);
    for &t in group {
        for corner in &mut mesh.triangles[t] {
            if *corner == vertex {
                *corner = copy;
            }
        }
    }
    copy
}

/// The triangles around each of `vertices` (sorted, no repeats), in one pass over the mesh.
fn triangles_around(mesh: &Mesh, vertices: &[u32]) -> Vec<(u32, Vec<usize>)> {
    let mut around: Vec<(u32, Vec<usize>)> = vertices.iter().map(|&v| (v, Vec::new())).collect();
    if vertices.is_empty() {
        return around;
    }
    let mut wanted = vec![false; mesh.positions.len()];
    vertices.iter().for_each(|&v| wanted[v as usize] = true);
    for (t, triangle) in mesh.triangles.iter().enumerate() {
        for corner in triangle.iter().filter(|&&c| wanted[c as usize]) {
            if let Ok(i) = vertices.binary_search(corner) {
                around[i].1.push(t);
            }
        }
    }
    around
}

/// The groups `vertex`'s triangles fall into (see the module's text), the first pairing that separates the pairs
/// of every edge four triangles share; `None` where there is one group or no pairing separates them.
fn groups(
    mesh: &Mesh,
    vertex: u32,
    triangles: &[usize],
    uses: &HashMap<(u32, u32), (u32, u32)>,
) -> Option<Vec<Vec<usize>>> {
    // Per other end of an edge at `vertex`: the triangles (by position in `triangles`) running it out of `vertex`
    // and into it.
    let mut edges: HashMap<u32, (Vec<usize>, Vec<usize>)> = HashMap::new();
    for (i, &t) in triangles.iter().enumerate() {
        let [a, b, c] = mesh.triangles[t];
        for (from, to) in [(a, b), (b, c), (c, a)] {
            if from == vertex {
                edges.entry(to).or_default().0.push(i);
            } else if to == vertex {
                edges.entry(from).or_default().1.push(i);
            }
        }
    }
    let mut base: Vec<usize> = (0..triangles.len()).collect();
    let mut shared = Vec::new();
    for (&other, (out, into)) in &edges {
        let counted = uses.get(&(vertex.min(other), vertex.max(other))).map_or(0, |&(f, b)| f + b);
        match (out.as_slice(), into.as_slice()) {
            ([o], [i]) if counted == 2 => join(&mut base, *o, *i),
            ([o0, o1], [i0, i1]) => shared.push([*o0, *o1, *i0, *i1]),
            // Counts gone stale in this pass, or six triangles: leave the vertex.
            _ => return None,
        }
    }
    if shared.is_empty() || shared.len() > MAX_SHARED {
        return None;
    }
    for pairing in 0..1u32 << shared.len() {
        let mut parent = base.clone();
        for (bit, &[o0, o1, i0, i1]) in shared.iter().enumerate() {
            let (first, second) = if pairing >> bit & 1 == 0 { ((o0, i0), (o1, i1)) } else { ((o0, i1), (o1, i0)) };
            join(&mut parent, first.0, first.1);
            join(&mut parent, second.0, second.1);
        }
        if shared.iter().all(|&[o0, o1, _, _]| root(&mut parent, o0) != root(&mut parent, o1)) {
            let mut groups: HashMap<usize, Vec<usize>> = HashMap::new();
            for (i, &t) in triangles.iter().enumerate() {
                groups.entry(root(&mut parent, i)).or_default().push(t);
            }
            let mut groups: Vec<Vec<usize>> = groups.into_values().collect();
            groups.sort_by_key(|g| g[0]);
            return Some(groups);
        }
    }
    None
}

fn root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

fn join(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (root(parent, a), root(parent, b));
    parent[ra] = rb;
}

/// The mean position of the vertices of `group` other than `vertex`.
fn outer_centre(mesh: &Mesh, vertex: u32, group: &[usize]) -> [f32; 3] {
    let (mut sum, mut n) = ([0.0f32; 3], 0.0f32);
    for &t in group {
        for &c in mesh.triangles[t].iter().filter(|&&c| c != vertex) {
            let p = mesh.positions[c as usize];
            (0..3).for_each(|a| sum[a] += p[a]);
            n += 1.0;
        }
    }
    sum.map(|s| s / n.max(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A closed tetrahedron on `v`, wound outwards.
    fn tetrahedron([a, b, c, d]: [u32; 4]) -> Vec<[u32; 3]> {
        vec![[a, c, b], [a, b, d], [b, c, d], [c, a, d]]
    }

    #[test]
    fn two_solids_on_one_edge_come_apart_there() {
        // Two tetrahedra sharing the edge 0–1: four triangles on it.
        let positions = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, -1.0],
        ];
        let mut triangles = tetrahedron([0, 1, 2, 3]);
        triangles.extend(tetrahedron([0, 1, 5, 4]));
        let n = positions.len();
        let mut mesh = Mesh { positions, normals: vec![[0.0; 3]; n], colours: vec![[0.0; 3]; n], triangles };
        assert_eq!((mesh.unmatched_edges(), mesh.non_manifold_edges()), (0, 1));
        let added = split_non_manifold_edges(&mut mesh, &[0, 1, 2, 3, 4, 5]);
        assert_eq!(added, 1);
        assert_eq!((mesh.unmatched_edges(), mesh.non_manifold_edges()), (0, 0));
        assert_ne!(mesh.positions[6], mesh.positions[0], "the copy does not sit on the vertex");
    }

    #[test]
    fn a_manifold_mesh_is_left_alone() {
        let positions = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let mut mesh = Mesh {
            positions,
            normals: vec![[0.0; 3]; 4],
            colours: vec![[0.0; 3]; 4],
            triangles: tetrahedron([0, 1, 2, 3]),
        };
        let before = mesh.clone();
        assert_eq!(split_non_manifold_edges(&mut mesh, &[0, 1, 2, 3]), 0);
        assert_eq!(mesh, before);
    }
}
