//! Where `fractal accuracy` writes: the report's path (one default for the sweep, one for `--image`) and its plots'
//! folder, shared by the sweep and the image study.

use crate::cli::args::AccuracyArgs;
use crate::cli::error::CliError;

/// Where `--report` writes: `--out`, else `docs/accuracy.md` (`docs/image-accuracy.md` with `--image`).
pub fn report_path(args: &AccuracyArgs) -> std::path::PathBuf {
    let default = if args.image { "docs/image-accuracy.md" } else { "docs/accuracy.md" };
    args.out.clone().unwrap_or_else(|| default.into())
}

/// Where plots go: `--plot`, or with `--report` the folder named after the report beside it.
pub fn plot_dir(args: &AccuracyArgs) -> Option<std::path::PathBuf> {
    match (&args.plot, args.report && !args.default_only) {
        (Some(dir), _) => Some(dir.clone()),
        (None, true) => Some(report_path(args).with_extension("")),
        (None, false) => None,
    }
}

/// Writes `svg` to `path`, making its folder.
pub fn write_plot(path: &std::path::Path, svg: Result<String, String>) -> Result<(), CliError> {
    let svg = svg.map_err(|e| CliError::failure(format!("cannot draw {}: {e}", path.display())))?;
    path.parent()
        .map_or(Ok(()), std::fs::create_dir_all)
        .and_then(|()| std::fs::write(path, svg))
        .map_err(|e| CliError::failure(format!("cannot write {}: {e}", path.display())))
}
