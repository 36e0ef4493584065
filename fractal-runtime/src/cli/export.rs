//! `fractal export`: a scene's render kernel for another engine ([`crate::export`]), to a file (written atomically) or
//! to standard output. SPIR-V is binary, so it goes to standard output only when that is not a terminal.

use std::io::{IsTerminal, Write};

use crate::cli::args::ExportArgs;
use crate::cli::error::CliError;
use crate::cli::scene::LoadedScene;
use crate::cli::SceneLibrary;
use crate::output::png::{prepare_output, write_atomic};

pub fn export(args: &ExportArgs, library: &SceneLibrary) -> Result<(), CliError> {
    let loaded = LoadedScene::load(&args.scene, library)?;
    let stdout = std::io::stdout();
    if args.output.is_none() && args.target.is_binary() && stdout.is_terminal() {
        return Err(CliError::usage(format!(
            "{} is binary: write it to a file with -o {}.{} (or redirect standard output)",
            args.target,
            loaded.name,
            args.target.extension()
        )));
    }
    if let Some(path) = &args.output {
        prepare_output(path)?;
    }
    let exported =
        loaded.export(args.target).map_err(|e| CliError::failure(format!("export to {}: {e}", args.target)))?;
    match &args.output {
        Some(path) => {
            write_atomic(path, exported.as_bytes())?;
            eprintln!("wrote {} ({} bytes of {})", path.display(), exported.as_bytes().len(), args.target);
        }
        None => {
            let mut out = stdout.lock();
            out.write_all(exported.as_bytes())
                .and_then(|()| out.flush())
                .map_err(|e| CliError::failure(format!("writing to standard output: {e}")))?;
        }
    }
    Ok(())
}
