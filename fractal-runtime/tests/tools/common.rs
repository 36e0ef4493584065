//! What the tools' tests share: the external validators and the rule for backends and tools
//! that are missing (skip with a note, or fail when FRACTAL_REQUIRE_GPU_BACKENDS=1).

use fractal_render::device::backends_required;
use std::path::Path;

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
