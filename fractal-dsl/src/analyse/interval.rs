//! Interval arithmetic over expressions: the range a value can take for any time t ≥ 0 and any parameter value
//! within its declared range. Bounds use it so an animated radius is bounded by its largest value.

use crate::ir::Expr;

/// A closed range of values; infinite ends mean no limit is known.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interval {
    pub lo: f64,
    pub hi: f64,
}

/// The range of `e`.
pub fn range(e: &Expr) -> Interval {
    let _ = e;
    todo!("interval arithmetic")
}
