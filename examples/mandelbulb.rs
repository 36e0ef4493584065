//! The power-8 Mandelbulb, in the interactive viewer.
//!
//! Run: `cargo run --release --example mandelbulb`.
//!
//! Click to capture the mouse, WASD/QE to fly, H for the other keys. With no display the scene is rendered to
//! `mandelbulb.png` in the current folder instead.

use fractal::view::{example_main, ViewerScene};

fn main() -> std::process::ExitCode {
    example_main("mandelbulb", ViewerScene::compiled("mandelbulb", &fractal::scenes::MANDELBULB))
}
