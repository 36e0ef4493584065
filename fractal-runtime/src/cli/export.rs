//! `fractal export`: a scene as an engine package ([`crate::package`]: files into a directory), its render kernel
//! ([`crate::export`]) or its camera as a glTF animation ([`crate::output::gltf_camera`]), to files (written
//! atomically) or to standard output. SPIR-V is binary, so it goes to standard output only when that is not a
//! terminal.

use std::io::{IsTerminal, Write};

use crate::cli::args::{ExportArgs, ExportTarget};
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary};
use crate::output::png::{prepare_output, write_atomic};
use crate::package::Engine;

/// Most samples a camera export writes (fps × seconds).
const MAX_CAMERA_SAMPLES: f64 = 1e6;

pub fn export(args: &ExportArgs, library: &SceneLibrary) -> Result<(), CliError> {
    let loaded = LoadedScene::load(&args.scene, library)?;
    let Some(target) = args.target else {
        return export_camera(args, &loaded);
    };
    if args.fps.is_some() || args.duration.is_some() || args.size.is_some() {
        return Err(CliError::usage("--fps, --duration and --size go with --camera-path, not --target"));
    }
    let target = match target {
        ExportTarget::Package(engine) => return export_package(args, &loaded, engine),
        ExportTarget::Kernel(target) => target,
    };
    let stdout = std::io::stdout();
    if args.output.is_none() && target.is_binary() && stdout.is_terminal() {
        return Err(CliError::usage(format!(
            "{target} is binary: write it to a file with -o {}.{} (or redirect standard output)",
            loaded.name,
            target.extension()
        )));
    }
    if let Some(path) = &args.output {
        prepare_output(path)?;
    }
    let exported = loaded.export(target).map_err(|e| CliError::failure(format!("export to {target}: {e}")))?;
    write(args, exported.as_bytes(), &target.to_string())
}

/// An engine package: its files into the directory `-o` names (a one-file package may go to standard output).
fn export_package(args: &ExportArgs, loaded: &LoadedScene, engine: Engine) -> Result<(), CliError> {
    let package = crate::package::package(&loaded.scene, &loaded.name, engine)
        .map_err(|e| CliError::failure(format!("package {} for {engine}: {e}", loaded.name)))?;
    let Some(dir) = &args.output else {
        return match package.files.as_slice() {
            [only] => write(args, only.contents.as_bytes(), &format!("{engine} package")),
            _ => Err(CliError::usage(format!(
                "the {engine} package is {} files: name a directory for them with -o DIR",
                package.files.len()
            ))),
        };
    };
    if dir.is_file() {
        return Err(CliError::usage(format!(
            "{} is a file: -o names a directory for the {engine} package",
            dir.display()
        )));
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::failure(format!("cannot create the directory {}: {e}", dir.display())))?;
    for file in &package.files {
        write_atomic(&dir.join(&file.name), file.contents.as_bytes())?;
    }
    let names: Vec<&str> = package.files.iter().map(|f| f.name.as_str()).collect();
    eprintln!("wrote the {engine} package of {} to {}: {}", loaded.name, dir.display(), names.join(", "));
    Ok(())
}

/// `--camera-path`: the scene's camera as glTF.
fn export_camera(args: &ExportArgs, loaded: &LoadedScene) -> Result<(), CliError> {
    let scene = &loaded.scene;
    let (fps, duration) = (args.fps.unwrap_or(30.0), args.duration.unwrap_or(10.0));
    let (width, height) = args.size.unwrap_or((1920, 1080));
    let (start, end) = crate::output::gltf_camera::time_span(scene, duration);
    let span = end - start;
    if span * fps > MAX_CAMERA_SAMPLES {
        return Err(CliError::usage(format!(
            "{fps} fps over {span} s is more than {MAX_CAMERA_SAMPLES} camera samples: lower --fps"
        )));
    }
    if let Some(path) = &args.output {
        prepare_output(path)?;
    }
    let aspect = f64::from(width) / f64::from(height);
    let gltf = crate::output::gltf_camera::camera_gltf(scene, fps, duration, aspect)
        .map_err(|e| CliError::failure(format!("camera of {}: {e}", loaded.name)))?;
    write(args, gltf.as_bytes(), "glTF camera")
}

/// Writes `bytes` to the output file or standard output.
fn write(args: &ExportArgs, bytes: &[u8], what: &str) -> Result<(), CliError> {
    let stdout = std::io::stdout();
    match &args.output {
        Some(path) => {
            write_atomic(path, bytes)?;
            eprintln!("wrote {} ({} bytes of {what})", path.display(), bytes.len());
        }
        None => {
            let mut out = stdout.lock();
            out.write_all(bytes)
                .and_then(|()| out.flush())
                .map_err(|e| CliError::failure(format!("writing to standard output: {e}")))?;
        }
    }
    Ok(())
}
