//! Any built-in scene in the interactive viewer, by name: every scene of the library runs as an example.
//!
//! Run: `cargo run --release --example scene -- julia` (no name: the showcase `mandelbulb`; an unknown name lists
//! them all).
//!
//! With no display the scene is rendered to `<name>.png` in the current folder instead.

use fractal::view::{example_main, ViewerScene};

fn main() -> std::process::ExitCode {
    let name = std::env::args().nth(1).unwrap_or_else(|| "mandelbulb".to_string());
    match fractal::scenes::by_name(&name) {
        Some(compiled) => example_main(&name, ViewerScene::compiled(&name, compiled)),
        None => {
            eprintln!(
                "error: no built-in scene `{name}`; the scenes: {}",
                fractal::scenes::names().collect::<Vec<_>>().join(", ")
            );
            std::process::ExitCode::from(2)
        }
    }
}
