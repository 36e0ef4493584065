//! `fractal mesh`: a scene's surface as a triangle mesh file ([`crate::mesh`]), or one per frame of an animation
//! (`--frames`, a numbered pattern), with a progress bar over the grid's layers and a summary line per file:
//! vertices, triangles, whether the mesh is closed, time and peak memory.

use std::io::IsTerminal;
use std::path::Path;
use std::time::Instant;

use fractal_dsl::analyse::Aabb;
use fractal_render::frame::check_time;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::cli::args::MeshArgs;
use crate::cli::error::CliError;
use crate::cli::scene::{LoadedScene, SceneLibrary};
use crate::mesh::{default_bounds, default_level, extract, write_mesh, MeshFormat, MeshSettings};
use crate::output::png::{prepare_output, write_atomic_with};
use crate::output::FramePattern;

/// Meshes up to this many triangles are checked for closure before they are written.
const CHECKED_TRIANGLES: usize = 4_000_000;

pub fn mesh(args: &MeshArgs, library: &SceneLibrary) -> Result<(), CliError> {
    let format = MeshFormat::from_path(&args.output).ok_or_else(|| {
        CliError::usage(format!("{}: meshes are written as {}", args.output.display(), MeshFormat::EXTENSIONS))
    })?;
    let loaded = LoadedScene::load(&args.scene, library)?;
    let params = loaded.params(&args.params)?;
    let bounds = match args.bounds {
        Some(b) => Aabb::new([b[0], b[1], b[2]], [b[3], b[4], b[5]]),
        None => default_bounds(&loaded.scene),
    };
    let settings = |time: f64| MeshSettings {
        bounds,
        resolution: args.resolution,
        level: default_level(&loaded.scene),
        time: time as f32,
        params: params.values().iter().map(|&v| v as f32).collect(),
    };
    let Some(frames) = args.frames else {
        check_time(args.time).map_err(|e| CliError::usage(e.to_string()))?;
        prepare_output(&args.output)?;
        return mesh_one(args, &loaded, format, &settings(args.time), &args.output);
    };
    let text = args.output.to_string_lossy();
    let pattern = FramePattern::parse(&text).map_err(|e| CliError::usage(format!("--frames: {e}")))?;
    for frame in frames.iter() {
        let time = frame as f64 / args.fps;
        check_time(time).map_err(|e| CliError::usage(e.to_string()))?;
        let path = pattern.path(frame);
        prepare_output(&path)?;
        mesh_one(args, &loaded, format, &settings(time), &path)?;
    }
    Ok(())
}

/// Meshes one moment into `path`.
fn mesh_one(
    args: &MeshArgs,
    loaded: &LoadedScene,
    format: MeshFormat,
    settings: &MeshSettings,
    path: &Path,
) -> Result<(), CliError> {
    let bar = if std::io::stderr().is_terminal() {
        let style = ProgressStyle::with_template("mesh [{bar:30}] {pos}/{len} layers, {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar());
        ProgressBar::new(0).with_style(style)
    } else {
        ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden())
    };
    let start = Instant::now();
    let mesh = extract(loaded.evaluator(), settings, &|done, total| {
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    // The closure check counts every edge in a hash map: worth it only for meshes that are not huge.
    let closed = match mesh.triangles.len() <= CHECKED_TRIANGLES {
        true if mesh.unmatched_edges() == 0 => "closed",
        true => "NOT closed",
        false => "closure not checked at this size",
    };
    let (vertices, triangles) = (mesh.positions.len(), mesh.triangles.len());
    write_atomic_with(path, |out| write_mesh(mesh, format, out))?;
    let memory = peak_memory_mib().map_or(String::new(), |m| format!(", peak memory {m:.0} MiB"));
    eprintln!(
        "wrote {} ({vertices} vertices, {triangles} triangles, {closed}; {} cells along the longest side; {:.1} s\
         {memory})",
        path.display(),
        args.resolution,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The process's peak resident memory, where the system tells it (Linux: VmHWM).
fn peak_memory_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}
