//! Which of a cell's sign-changing edges belong to one sheet of surface, so surface nets gives each sheet in a cell a
//! vertex of its own. One vertex per cell joins sheets that only pass near each other: where two sheets cross one
//! cell, the quads of both meet in the same vertices and an edge ends up shared by four triangles (a mesh no slicer
//! or engine takes as manifold).
//!
//! The sheets are the marching-cubes contour's pieces: on each face of the cell the contour joins the face's
//! sign-changing edges in pairs, and a sheet is a set of edges joined through the faces. A face with two changing
//! edges joins them; a face with four (its diagonal corners alike: the ambiguous face) is resolved by the asymptotic
//! decider — the value of the bilinear interpolant at its saddle says whether the inside corners connect across the
//! face — which reads only the face's four values, so the two cells sharing a face resolve it alike.
//!
//! Corners are numbered by their offsets, x + 2y + 4z; edges by axis and the offsets of the other two axes in
//! increasing axis order: 4·axis + u + 2v.

/// No sheet: the edge does not change sign.
pub const NO_SHEET: u8 = 0xF;

/// The sheet of each of a cell's 12 edges ([`NO_SHEET`] for an edge with no sign change), numbered from 0 in edge
/// order, and how many there are.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sheets {
    sheet: [u8; 12],
    pub count: u8,
    /// Bit `s`: sheet `s` crosses a face of the cell twice (all four changing edges of an ambiguous face are on it).
    /// Only such a sheet's vertex can end up on an edge four triangles share (module `repair`).
    pub crosses_a_face_twice: u16,
}

impl Sheets {
    /// No edge changes sign.
    pub const NONE: Sheets = Sheets { sheet: [NO_SHEET; 12], count: 0, crosses_a_face_twice: 0 };

    /// The sheet edge `edge` belongs to, or `None` where it does not change sign.
    pub fn of(&self, edge: usize) -> Option<u8> {
        (self.sheet[edge] != NO_SHEET).then_some(self.sheet[edge])
    }
}

/// The corners at the ends of `edge`, low end first.
pub fn edge_corners(edge: usize) -> (usize, usize) {
    let (axis, u, v) = (edge / 4, edge & 1, (edge >> 1) & 1);
    let (p, q) = other_axes(axis);
    let low = (u << p) | (v << q);
    (low, low | (1 << axis))
}

/// The edge along `axis` through the corner at offsets `at` (its `axis` offset ignored).
pub fn edge_at(axis: usize, at: [usize; 3]) -> usize {
    let (p, q) = other_axes(axis);
    4 * axis + at[p] + 2 * at[q]
}

/// The two axes other than `axis`, in increasing order.
fn other_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// The sheets of a cell whose corner values are `values` (x + 2y + 4z); `inside` says which side a value is on.
pub fn sheets(values: [f32; 8], inside: impl Fn(f32) -> bool) -> Sheets {
    let side = values.map(&inside);
    let changes = |edge: usize| {
        let (a, b) = edge_corners(edge);
        side[a] != side[b]
    };
    let mut parent: [usize; 12] = std::array::from_fn(|e| e);
    fn root(parent: &mut [usize; 12], mut e: usize) -> usize {
        while parent[e] != e {
            parent[e] = parent[parent[e]];
            e = parent[e];
        }
        e
    }
    let mut join = |a: usize, b: usize| {
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        parent[ra.max(rb)] = ra.min(rb);
    };
    let mut ambiguous = Vec::new();
    for axis in 0..3 {
        let (p, q) = other_axes(axis);
        for s in 0..2 {
            // The face at offset `s` along `axis`; its corners at face offsets (a, b) along (p, q).
            let corner = |a: usize, b: usize| (s << axis) | (a << p) | (b << q);
            let mut at = [0; 3];
            at[axis] = s;
            // The face's edges: along p at q-offset 0 and 1, along q at p-offset 0 and 1.
            let edge_p = |b: usize| edge_at(p, with(at, q, b));
            let edge_q = |a: usize| edge_at(q, with(at, p, a));
            let face = [edge_p(0), edge_p(1), edge_q(0), edge_q(1)];
            let changing: Vec<usize> = face.into_iter().filter(|&e| changes(e)).collect();
            match changing.as_slice() {
                [a, b] => join(*a, *b),
                [_, _, _, _] => {
                    ambiguous.push(face);
                    // Diagonal corners alike: the saddle's side says whether corner (0, 0)'s side connects across
                    // the face. The contour cuts off the two corners of the other side, each with its two edges.
                    let v = [corner(0, 0), corner(1, 0), corner(0, 1), corner(1, 1)].map(|c| f64::from(values[c]));
                    let denominator = v[0] + v[3] - v[1] - v[2];
                    let saddle = if denominator != 0.0 { (v[0] * v[3] - v[1] * v[2]) / denominator } else { v[0] };
                    let diagonal_connects = inside(saddle as f32) == side[corner(0, 0)];
                    if diagonal_connects {
                        // Corners (1, 0) and (0, 1) are cut off: (1, 0) by the edges along p at q = 0 and along q
                        // at p = 1; (0, 1) by those along p at q = 1 and along q at p = 0.
                        join(edge_p(0), edge_q(1));
                        join(edge_p(1), edge_q(0));
                    } else {
                        join(edge_p(0), edge_q(0));
                        join(edge_p(1), edge_q(1));
                    }
                }
                _ => {}
            }
        }
    }
    let mut count = 0u8;
    let mut label = [NO_SHEET; 12];
    let sheet = std::array::from_fn(|e| {
        if !changes(e) {
            return NO_SHEET;
        }
        let r = root(&mut parent, e);
        if label[r] == NO_SHEET {
            label[r] = count;
            count += 1;
        }
        label[r]
    });
    let crosses_a_face_twice = ambiguous
        .iter()
        .filter(|face| face.iter().all(|&e| sheet[e] == sheet[face[0]]))
        .fold(0u16, |bits, face| bits | 1 << sheet[face[0]]);
    Sheets { sheet, count, crosses_a_face_twice }
}

fn with(mut at: [usize; 3], axis: usize, value: usize) -> [usize; 3] {
    at[axis] = value;
    at
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inside(v: f32) -> bool {
        v <= 0.0
    }

    /// Corner values with the corners in `inner` at −1 and the rest at +1.
    fn cell(inner: &[usize]) -> [f32; 8] {
        std::array::from_fn(|c| if inner.contains(&c) { -1.0 } else { 1.0 })
    }

    #[test]
    fn edges_and_corners_agree() {
        for edge in 0..12 {
            let (a, b) = edge_corners(edge);
            let axis = edge / 4;
            assert_eq!(b - a, 1 << axis, "edge {edge} runs along its axis");
            let at = [a & 1, (a >> 1) & 1, a >> 2];
            assert_eq!(edge_at(axis, at), edge);
        }
    }

    #[test]
    fn one_corner_or_one_face_is_one_sheet() {
        let one = sheets(cell(&[0]), inside);
        assert_eq!(one.count, 1);
        assert_eq!((0..12).filter(|&e| one.of(e).is_some()).count(), 3);
        let face = sheets(cell(&[0, 1, 2, 3]), inside);
        assert_eq!(face.count, 1);
        assert_eq!((0..12).filter(|&e| face.of(e).is_some()).count(), 4, "the four edges along z");
    }

    #[test]
    fn opposite_corners_are_two_sheets() {
        // Corners 0 and 7 share no face: two separate caps.
        let s = sheets(cell(&[0, 7]), inside);
        assert_eq!(s.count, 2);
        assert_ne!(s.of(edge_at(0, [0, 0, 0])), s.of(edge_at(0, [0, 1, 1])));
    }

    #[test]
    fn an_ambiguous_face_follows_its_saddle() {
        // Corners 0 and 3 inside, on the face z = 0: diagonal corners alike. Deep inside corners put the saddle
        // inside (one sheet around a bridge of inside); shallow ones leave it outside (two caps).
        let mut deep = cell(&[0, 3]);
        deep[0] = -4.0;
        deep[3] = -4.0;
        assert_eq!(sheets(deep, inside).count, 1);
        let mut shallow = cell(&[0, 3]);
        shallow[0] = -0.25;
        shallow[3] = -0.25;
        assert_eq!(sheets(shallow, inside).count, 2);
    }
}
