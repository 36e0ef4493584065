//! House rules a reader relies on and a test keeps: no source file over [`MAX_LINES`] lines.

use std::path::{Path, PathBuf};

/// Longest a Rust source file may be.
pub const MAX_LINES: usize = 800;

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    for entry in entries.flatten() {
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if path.is_dir() {
            if name != "target" && !name.starts_with('.') {
                rust_files(&path, out);
            }
        } else if name.ends_with(".rs") {
            out.push(path);
        }
    }
}

/// Every Rust file under `root` longer than [`MAX_LINES`], with its length.
pub fn long_files(root: &Path) -> Vec<(PathBuf, usize)> {
    let mut files = Vec::new();
    rust_files(root, &mut files);
    let mut long: Vec<(PathBuf, usize)> = files
        .into_iter()
        .filter_map(|f| {
            let lines = std::fs::read_to_string(&f).ok()?.lines().count();
            let shown = f.strip_prefix(root).unwrap_or(&f).to_path_buf();
            (lines > MAX_LINES).then_some((shown, lines))
        })
        .collect();
    long.sort();
    long
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_source_file_is_over_the_limit() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
        let long = long_files(root);
        let listed: Vec<String> = long.iter().map(|(f, n)| format!("{}: {n} lines", f.display())).collect();
        assert!(long.is_empty(), "files over {MAX_LINES} lines:\n{}", listed.join("\n"));
    }
}
