//! The `fractal` command line: `render`, `bench`, `accuracy`, `export`, `mesh`, `list`, `gallery` and `view` (the
//! interactive viewer, [`crate::viewer`]). The binary is a shim that passes in the built-in scene table
//! ([`SceneLibrary`]), so the runtime does not depend on the scene library.
//!
//! Errors print as one `error: …` line on stderr and exit with 2 for usage errors and 1 for failures
//! ([`error::CliError`]); nothing a user types makes the program panic.

mod accuracy;
pub mod args;
mod bench;
pub mod error;
mod export;
mod gallery;
mod list;
mod mesh;
mod render;
pub mod scene;
mod view;

use std::ffi::OsString;
use std::process::ExitCode;

use clap::error::ErrorKind as ClapErrorKind;
use clap::Parser;

use args::{Cli, Command};
pub use error::CliError;
pub use scene::SceneLibrary;

/// Runs the program on the process's arguments.
pub fn main(library: &SceneLibrary) -> ExitCode {
    run_with_args(std::env::args_os(), library)
}

/// Runs the program on `args` (the first is the program name) and prints any error.
pub fn run_with_args(args: impl IntoIterator<Item = OsString>, library: &SceneLibrary) -> ExitCode {
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => return clap_exit(e),
    };
    match run(cli.command, library) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", fractal_dsl::sanitise::tidy(&e.to_string()));
            e.exit_code()
        }
    }
}

/// Help and version go to stdout with status 0; a value our parsers refused prints as clap's first line (which
/// carries our message), other grammar errors as clap writes them, with status 2.
fn clap_exit(e: clap::Error) -> ExitCode {
    match e.kind() {
        ClapErrorKind::InvalidValue | ClapErrorKind::ValueValidation => {
            let text = e.to_string();
            eprintln!("{}", fractal_dsl::sanitise::tidy(text.lines().next().unwrap_or("error: invalid value")));
            ExitCode::from(2)
        }
        _ => {
            let _ = e.print();
            ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2))
        }
    }
}

fn run(command: Command, library: &SceneLibrary) -> Result<(), CliError> {
    match command {
        Command::Render(args) => render::render(&args, library),
        Command::Bench(args) => bench::bench(&args, library),
        Command::Accuracy(args) => accuracy::accuracy(&args, library),
        Command::Export(args) => export::export(&args, library),
        Command::Mesh(args) => mesh::mesh(&args, library),
        Command::List => list::list(library),
        Command::Gallery(args) => gallery::gallery(&args, library),
        Command::View(args) => view::view(&args, library),
    }
}
