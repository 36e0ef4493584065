//! The Amazing Box — a Mandelbox of negative scale — seen from inside its shell, in the interactive viewer.
//!
//! Run: `cargo run --release --example mandelbox`.
//!
//! Tab selects the `scale` parameter and ↑ / ↓ change it without recompiling. With no display the scene is rendered
//! to `mandelbox.png` instead.

use fractal::view::{example_main, ViewerScene};

fn main() -> std::process::ExitCode {
    example_main("mandelbox", ViewerScene::compiled("amazing_box", &fractal::scenes::AMAZING_BOX))
}
