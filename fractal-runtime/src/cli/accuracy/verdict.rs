//! How a measured point reads in the report: one line with the budget's verdict, and the note on an iteration count
//! the fractal family caps. Shared by the sweep's own time and the camera path's other keys.

use crate::accuracy::sweep::{self, Budget};

/// A measured point as one line (its time, the figures its image holds and the budget's verdict on them), and the
/// budget's violations (none: within budget).
pub(super) fn judged(point: &sweep::SweepPoint, budget: &Budget) -> (String, Vec<String>) {
    let verdict = budget.verdict(&point.error);
    (format!("{:.1} ms, {}; {}", point.time_ms, point.error.describe(), verdict.sentence()), verdict.violations)
}

/// ", capped at N, the family's most" where the family's iteration limit holds `factor` × the scene's iterations of
/// its first escape-time fractal below that product.
pub(super) fn capped(scene: &fractal_dsl::Scene, factor: u32) -> String {
    let own = sweep::escape_time_iterations(scene);
    let scaled = sweep::escape_time_iterations(&crate::quality::with_iterations_scaled(scene, factor));
    match (own, scaled) {
        (Some(own), Some(n)) if n < own.saturating_mul(factor) => format!(", capped at {n}, the family's most"),
        _ => String::new(),
    }
}
