//! The `<scene>` argument: a built-in scene by name (kernels and native evaluator compiled into the program, found in
//! the [`SceneLibrary`] the binary passes in) or a `.fractal` file, parsed and compiled at run time (kernels from the
//! scene compiler, the interpreter on the CPU).
//!
//! A name is looked up among the built-ins first; anything else is a path. An argument that looks like neither (no
//! such built-in, no such file, no path separator or `.fractal` extension) is reported as an unknown scene with the
//! list of built-ins.

use std::path::{Path, PathBuf};

use fractal_dsl::compiled::{CompiledScene, Kernels, NativeFns};
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::Evaluator;
use fractal_dsl::Scene;
use fractal_render::error::{FrameError, RenderError};
use fractal_render::frame::{Frame, ParamValues};
use fractal_render::precision::Precision;
use fractal_render::renderer::KernelSources;

use crate::cli::error::CliError;
use crate::export::{export, export_compiled, ExportError, Exported, Target};
use crate::frame_precision::FramePrecision;

/// The built-in scenes the program offers.
#[derive(Clone, Copy)]
pub struct SceneLibrary {
    /// Every built-in scene with its name.
    pub scenes: &'static [(&'static str, &'static CompiledScene)],
    /// The `.fractal` source of a built-in scene by name (its leading comment describes it in `fractal list`).
    pub source_file: fn(&str) -> Option<&'static str>,
}

/// Where a scene came from.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneOrigin {
    BuiltIn,
    File(PathBuf),
}

enum Forms<'a> {
    /// A built-in; `kernels` where a command-line setting made the build-time kernels stale.
    BuiltIn {
        compiled: &'a CompiledScene,
        native: NativeFns,
        kernels: Option<Box<Kernels>>,
    },
    File {
        kernels: Box<Kernels>,
        interpreter: Box<Interpreter>,
    },
}

/// A scene ready to render: its IR, kernels and CPU evaluator.
pub struct LoadedScene<'a> {
    pub name: String,
    pub origin: SceneOrigin,
    pub scene: Scene,
    forms: Forms<'a>,
}

impl<'a> LoadedScene<'a> {
    /// Resolves `arg` against `library`, then the file system.
    pub fn load(arg: &str, library: &SceneLibrary) -> Result<LoadedScene<'static>, CliError> {
        if let Some(&(name, compiled)) = library.scenes.iter().find(|(name, _)| *name == arg) {
            return Ok(LoadedScene {
                name: name.to_string(),
                origin: SceneOrigin::BuiltIn,
                scene: compiled.scene().clone(),
                forms: Forms::BuiltIn { compiled, native: compiled.native(), kernels: None },
            });
        }
        let path = Path::new(arg);
        let path_like = arg.contains(['/', '\\']) || path.extension().is_some_and(|e| e == "fractal");
        if !path.exists() && !path_like {
            let names: Vec<&str> = library.scenes.iter().map(|(n, _)| *n).collect();
            return Err(CliError::usage(format!(
                "unknown scene `{arg}`: not a built-in scene ({}) and no such file",
                names.join(", ")
            )));
        }
        let text = fractal_dsl::parse::read_source(path)
            .map_err(|e| CliError::failure(format!("cannot read scene file {}: {e}", path.display())))?;
        let mut scene =
            fractal_dsl::parse::parse_str(&text).map_err(|e| CliError::failure(format!("{}:{e}", path.display())))?;
        for note in crate::step_factors::apply_recorded(&mut scene, arg) {
            eprintln!("fractal: {note}");
        }
        let invalid = |e: fractal_dsl::validate::InvalidScene| CliError::failure(format!("{}: {e}", path.display()));
        let kernels = fractal_dsl::compile(&scene).map_err(invalid)?;
        let interpreter = fractal_dsl::lower::tape::interpreter(&scene).map_err(invalid)?;
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| arg.to_string());
        Ok(LoadedScene {
            name,
            origin: SceneOrigin::File(path.to_path_buf()),
            scene,
            forms: Forms::File { kernels: Box::new(kernels), interpreter: Box::new(interpreter) },
        })
    }

    /// Every form of the scene a renderer may run.
    pub fn sources(&self) -> KernelSources<'_> {
        match &self.forms {
            Forms::BuiltIn { compiled, kernels: None, .. } => KernelSources::default()
                .with_wgsl(compiled.wgsl())
                .with_wgsl_f64(compiled.wgsl_f64())
                .with_opencl(compiled.opencl())
                .with_opencl_f64(compiled.opencl_f64())
                .with_cpu(self.evaluator(), &self.scene)
                .with_cpu_wide(self.evaluator_wide()),
            Forms::BuiltIn { kernels: Some(kernels), .. } | Forms::File { kernels, .. } => {
                KernelSources::compiled(kernels)
                    .with_cpu(self.evaluator(), &self.scene)
                    .with_cpu_wide(self.evaluator_wide())
            }
        }
    }

    /// The scene with at most `samples` rays per pixel (`--samples`; `None` keeps the scene's own). A built-in's
    /// kernels are compiled again; its native evaluator does not depend on it.
    pub fn set_samples(&mut self, samples: Option<u32>) -> Result<(), CliError> {
        let Some(n) = samples.filter(|&n| n != self.scene.settings.samples) else { return Ok(()) };
        self.scene.settings.samples = n;
        let fresh = Box::new(fractal_dsl::compile(&self.scene).map_err(RenderError::from)?);
        match &mut self.forms {
            Forms::BuiltIn { kernels, .. } => *kernels = Some(fresh),
            Forms::File { kernels, .. } => *kernels = fresh,
        }
        Ok(())
    }

    /// The scene's trace kernels ([`Kernels::tracing`]), which a render with depth and normal images runs: a
    /// built-in's are compiled here, as only those renders need them.
    pub fn tracing(&self) -> Result<Kernels, CliError> {
        match &self.forms {
            Forms::BuiltIn { kernels: None, .. } => {
                Ok(fractal_dsl::compile(&self.scene).map_err(RenderError::from)?.tracing())
            }
            Forms::BuiltIn { kernels: Some(kernels), .. } => Ok(kernels.tracing()),
            Forms::File { kernels, .. } => Ok(kernels.tracing()),
        }
    }

    /// The CPU evaluator of the scene: the native one of a built-in, the interpreter of a file.
    pub fn evaluator(&self) -> &dyn Evaluator<f32> {
        match &self.forms {
            Forms::BuiltIn { native, .. } => native,
            Forms::File { interpreter, .. } => &**interpreter,
        }
    }

    /// The same evaluator in f64, for frames drawn in f64.
    pub fn evaluator_wide(&self) -> &dyn Evaluator<f64> {
        match &self.forms {
            Forms::BuiltIn { native, .. } => native,
            Forms::File { interpreter, .. } => &**interpreter,
        }
    }

    /// The precision `precision` gives `frame` of this scene (said when it changes).
    pub fn precision_of(&self, precision: &mut FramePrecision, frame: &Frame) -> Result<Precision, RenderError> {
        precision.of(&self.scene, frame, self.evaluator(), self.evaluator_wide())
    }

    /// The render kernel for another engine.
    pub fn export(&self, target: Target) -> Result<Exported, ExportError> {
        match &self.forms {
            Forms::BuiltIn { compiled, kernels: None, .. } => export_compiled(compiled, target),
            Forms::BuiltIn { kernels: Some(kernels), .. } => export(kernels, target),
            Forms::File { kernels, .. } => export(kernels, target),
        }
    }

    /// Parameter values: the defaults, overridden by `name=value` pairs from the command line.
    pub fn params(&self, assignments: &[(String, f64)]) -> Result<ParamValues, CliError> {
        let mut values = ParamValues::defaults(&self.scene);
        for (name, value) in assignments {
            values.set(name, *value).map_err(|e| match e {
                FrameError::UnknownParam(_) => {
                    let known: Vec<&str> = values.decls().iter().map(|d| d.name.as_str()).collect();
                    let known = if known.is_empty() { "none".to_string() } else { known.join(", ") };
                    CliError::usage(format!("{e} (its parameters: {known})"))
                }
                _ => CliError::usage(e.to_string()),
            })?;
        }
        Ok(values)
    }
}
