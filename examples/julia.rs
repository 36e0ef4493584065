//! A quaternion Julia set whose constant circles with time, in the interactive viewer.
//!
//! Run: `cargo run --release --example julia`.
//!
//! Press Space to pause the flow, ← / → to step time. With no display the scene is rendered to `julia.png` instead.

use fractal::view::{example_main, ViewerScene};

fn main() -> std::process::ExitCode {
    example_main("julia", ViewerScene::compiled("julia", &fractal::scenes::JULIA))
}
