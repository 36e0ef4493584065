//! The `fractal` command-line program: a shim over [`fractal_runtime::cli`] that hands it the built-in scene library
//! (render, bench, export, list; `fractal --help`).

use std::process::ExitCode;

fn main() -> ExitCode {
    fractal_runtime::cli::main(&fractal_runtime::cli::SceneLibrary {
        scenes: scenes::ALL,
        source_file: scenes::source_file,
    })
}
