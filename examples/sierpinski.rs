//! A Menger sponge and a Sierpinski tetrahedron side by side, in the interactive viewer.
//!
//! Run: `cargo run --release --example sierpinski`.
//!
//! Click to capture the mouse, WASD/QE to fly, H for the other keys. With no display the scene is rendered to
//! `sierpinski.png` in the current folder instead.

use fractal::view::{example_main, ViewerScene};

fn main() -> std::process::ExitCode {
    example_main("sierpinski", ViewerScene::compiled("sierpinski_collection", &fractal::scenes::SIERPINSKI_COLLECTION))
}
