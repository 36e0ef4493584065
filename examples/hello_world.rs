//! One lit sphere, in the interactive viewer.
//!
//! Run: `cargo run --release --example hello_world`.
//!
//! Click to capture the mouse, WASD/QE to fly, H for the other keys. With no display the scene is rendered to
//! `hello_world.png` in the current folder instead.

use fractal::view::{example_main, ViewerScene};

fn main() -> std::process::ExitCode {
    example_main("hello_world", ViewerScene::compiled("hello_world", &fractal::scenes::HELLO_WORLD))
}
