//! Conservative axis-aligned bounds of every node: the shape (where the distance is ≤ 0) lies inside; `None` means
//! unbounded (planes, infinite repetition, or a value range without a limit).

use crate::ir::Node;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: [f64; 3],
    pub max: [f64; 3],
}

impl Aabb {
    pub fn center(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| 0.5 * (self.min[i] + self.max[i]))
    }
    pub fn half_extents(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| 0.5 * (self.max[i] - self.min[i]))
    }
}

/// The bound of `node`, or `None` when it is unbounded.
pub fn bound(node: &Node) -> Option<Aabb> {
    let _ = node;
    todo!("bounds analysis")
}
