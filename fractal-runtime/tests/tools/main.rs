//! The tools' integration tests, in one binary: export of every built-in scene to every target, and the engine
//! packages, each checked by the nearest thing to its engine this machine has; the truth of an image and its
//! metrics.

mod common;
mod engines;
mod export;
mod image;
