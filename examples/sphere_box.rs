//! Union, subtraction and smooth union of a sphere and a box, in the interactive viewer.
//!
//! Run: `cargo run --release --example sphere_box`.
//!
//! Click to capture the mouse, WASD/QE to fly, H for the other keys. With no display the scene is rendered to
//! `sphere_box.png` in the current folder instead.

use fractal::view::{example_main, ViewerScene};

fn main() -> std::process::ExitCode {
    example_main("sphere_box", ViewerScene::compiled("sphere_box", &fractal::scenes::SPHERE_BOX))
}
