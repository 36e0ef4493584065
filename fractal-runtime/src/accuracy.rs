//! Speed against true error: renders measured against the ground truth ([`crate::truth`]) — [`metrics`] — and sweeps
//! of the quality settings ([`crate::quality`]) behind `fractal accuracy`, as tables ([`table`]) and time-against-error
//! plots ([`plot`]); and images against the truth of the image ([`crate::truth::image`]) — [`image`] — with the
//! anti-aliasing settings' front ([`samples`]).

pub mod image;
pub mod metrics;
pub mod plot;
pub mod samples;
pub mod sweep;
pub mod table;

pub use metrics::{measure, Observed, Spread, TracedError, TrueError};
pub use sweep::{Budget, SweepPoint};
