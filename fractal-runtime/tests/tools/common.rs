//! What the tools' tests share: the built-in scenes, the external validators, and the rule for backends and tools
//! that are missing (skip with a note, or fail when FRACTAL_REQUIRE_GPU_BACKENDS=1).

use fractal_render::device::backends_required;
use std::path::Path;

use fractal_dsl::Scene;
use fractal_render::RenderError;

/// The opened backend, or `None` with a printed note when it is missing and not required.
pub fn available<T>(backend: &str, opened: Result<T, RenderError>) -> Option<T> {
    match opened {
        Ok(renderer) => Some(renderer),
        Err(e) if backends_required() => {
            panic!("{backend} is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but could not be opened: {e}")
        }
        Err(e) => {
            eprintln!("note: skipping {backend} test, backend unavailable: {e}");
            None
        }
    }
}

/// Every built-in scene's file name (without extension) and scene, read from `scenes/fractal/*.fractal`.
pub fn builtin_scenes() -> Vec<(String, Scene)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/fractal");
    let mut files: Vec<std::path::PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .map(|entry| entry.expect("directory entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "fractal"))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no .fractal files in {}", dir.display());
    files
        .into_iter()
        .map(|path| {
            let name = path.file_stem().expect("file name").to_string_lossy().into_owned();
            let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let scene = fractal_dsl::parse::parse_str(&text).unwrap_or_else(|e| panic!("{}:{e}", path.display()));
            (name, scene)
        })
        .collect()
}

/// Whether the external validator `tool` can be run; a missing one fails the test only when it is required.
pub fn tool_available(tool: &str) -> bool {
    let package = if tool == "spirv-val" { "spirv-tools" } else { "glslang-tools" };
    match std::process::Command::new(tool).arg("--version").output() {
        Ok(_) => true,
        Err(e) if backends_required() => {
            panic!("{tool} is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but cannot be run ({e}): install {package}")
        }
        Err(e) => {
            eprintln!("note: skipping the {tool} check, {tool} cannot be run ({e}): install {package}");
            false
        }
    }
}

/// Runs a validator on `file`; its output is the failure message.
pub fn run_validator(tool: &str, args: &[&str], file: &Path) {
    let output = std::process::Command::new(tool).args(args).arg(file).output().expect("run the validator");
    assert!(
        output.status.success(),
        "{tool} {} rejected {} ({}):\n{}{}",
        args.join(" "),
        file.display(),
        output.status,
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
}
