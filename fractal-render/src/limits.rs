//! The bounds a frame must keep: the largest image side and the largest scene time a renderer accepts.
//!
//! Plain constants below [`crate::error`] and [`crate::frame`]: the frame checks against them and the errors name them
//! in their messages, so neither has to read the other for a number.

/// The largest image side any renderer accepts; larger sizes are refused before anything is allocated.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// Largest |scene time| in seconds. The kernels receive time as f32, whose spacing at 1e5 s is 1/128 s: finer than a
/// frame at 120 fps. Past it frames of an animation collapse onto the same time, and at 1e39 time is infinite.
pub const MAX_TIME: f64 = 1e5;
