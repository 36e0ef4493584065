//! The scene being shown: its IR with the viewer's effect overrides applied, the kernels compiled from it, and its CPU
//! evaluator (the native one of a compiled scene, or the interpreter of a loaded one); plus the file watch that
//! reloads a `.fractal` file on save.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::Evaluator;
use fractal_dsl::{Kernels, NativeFns, Scene};
use fractal_render::renderer::KernelSources;
use notify::{RecursiveMode, Watcher};

use super::effects::EffectOverrides;
use super::session::ViewerScene;

/// The CPU form of a scene.
#[derive(Clone, Debug)]
enum CpuEvaluator {
    Native(NativeFns),
    Interpreted(Box<Interpreter>),
}

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct LiveScene {
    pub name: String,
    /// The scene as written, before the effect overrides.
    authored: Scene,
    /// What is rendered: `authored` with the overrides applied.
    pub scene: Scene,
    wgsl: String,
    wgsl_f64: String,
    opencl: String,
    opencl_f64: String,
    evaluator: CpuEvaluator,
}

impl LiveScene {
    /// Loads a viewer scene (reading and compiling a file) with no overrides.
    pub fn load(source: &ViewerScene) -> Result<LiveScene, String> {
        match source {
            ViewerScene::Compiled { name, scene } => Ok(LiveScene {
                name: name.clone(),
                authored: scene.scene().clone(),
                scene: scene.scene().clone(),
                wgsl: scene.wgsl().to_string(),
                wgsl_f64: scene.wgsl_f64().to_string(),
                opencl: scene.opencl().to_string(),
                opencl_f64: scene.opencl_f64().to_string(),
                evaluator: CpuEvaluator::Native(scene.native()),
            }),
            ViewerScene::Built { name, scene } => LiveScene::from_scene(name.clone(), (**scene).clone()),
            ViewerScene::File(path) => {
                let text = fractal_dsl::parse::read_source(path).map_err(|e| format!("{}: {e}", path.display()))?;
                LiveScene::from_text(source.name(), path, &text)
            }
        }
    }

    /// Parses and compiles scene text; errors read `file:line:column: message`.
    pub fn from_text(name: String, path: &Path, text: &str) -> Result<LiveScene, String> {
        let mut scene = fractal_dsl::parse::parse_str(text).map_err(|e| format!("{}:{e}", path.display()))?;
        for note in crate::step_factors::apply_recorded(&mut scene, &path.display().to_string()) {
            eprintln!("fractal: {note}");
        }
        LiveScene::from_scene(name, scene).map_err(|e| format!("{}: {e}", path.display()))
    }

    fn from_scene(name: String, scene: Scene) -> Result<LiveScene, String> {
        let kernels = fractal_dsl::compile(&scene).map_err(|e| e.to_string())?;
        let interpreter = Interpreter::new(&scene).map_err(|e| e.to_string())?;
        Ok(LiveScene {
            name,
            evaluator: CpuEvaluator::Interpreted(Box::new(interpreter)),
            authored: scene.clone(),
            scene,
            wgsl: kernels.wgsl,
            wgsl_f64: kernels.wgsl_f64,
            opencl: kernels.opencl,
            opencl_f64: kernels.opencl_f64,
        })
    }

    pub fn authored(&self) -> &Scene {
        &self.authored
    }

    /// The same scene with `overrides` applied; the kernels are recompiled when the settings change. The evaluator
    /// is kept: it reads geometry and materials only, and the CPU renderer takes the settings from the scene. An
    /// override the scene's rules refuse is an error naming the setting; the caller keeps the current scene.
    pub fn with_overrides(&self, overrides: &EffectOverrides) -> Result<LiveScene, String> {
        let settings = overrides.apply(&self.authored.settings);
        if settings == self.scene.settings {
            return Ok(self.clone());
        }
        let mut scene = self.authored.clone();
        scene.settings = settings;
        let kernels = fractal_dsl::compile(&scene).map_err(|e| e.to_string())?;
        let (wgsl, wgsl_f64) = (kernels.wgsl, kernels.wgsl_f64);
        let (opencl, opencl_f64) = (kernels.opencl, kernels.opencl_f64);
        Ok(LiveScene { scene, wgsl, wgsl_f64, opencl, opencl_f64, ..self.clone() })
    }

    pub fn wgsl(&self) -> &str {
        &self.wgsl
    }

    /// Every form of the scene, for whichever renderer draws it.
    pub fn kernels(&self) -> KernelSources<'_> {
        KernelSources::default()
            .with_wgsl(&self.wgsl)
            .with_wgsl_f64(&self.wgsl_f64)
            .with_opencl(&self.opencl)
            .with_opencl_f64(&self.opencl_f64)
            .with_cpu(self.evaluator(), &self.scene)
            .with_cpu_wide(self.evaluator_wide())
    }

    /// The CPU evaluator: geometry and materials, whatever the settings.
    pub fn evaluator(&self) -> &dyn Evaluator<f32> {
        match &self.evaluator {
            CpuEvaluator::Native(native) => native,
            CpuEvaluator::Interpreted(interpreter) => &**interpreter,
        }
    }

    /// The same evaluator in f64, for frames drawn in f64.
    pub fn evaluator_wide(&self) -> &dyn Evaluator<f64> {
        match &self.evaluator {
            CpuEvaluator::Native(native) => native,
            CpuEvaluator::Interpreted(interpreter) => &**interpreter,
        }
    }

    /// What a progressive pass draws: the scene with one sample a pixel and its trace kernels, compiled here.
    pub fn one_sample(&self) -> Result<OneSample, fractal_dsl::validate::InvalidScene> {
        let mut scene = self.scene.clone();
        scene.settings.samples = 1;
        let kernels = fractal_dsl::compile(&scene)?.tracing();
        Ok(OneSample { scene, kernels })
    }
}

/// A scene's one-sample form ([`LiveScene::one_sample`]): the scene (for the CPU renderer, which reads its settings)
/// and its trace kernels (for the GPU renderers, whose `trace` returns each pixel's linear colour).
#[derive(Clone, Debug)]
pub struct OneSample {
    pub scene: Scene,
    pub kernels: Kernels,
}

impl OneSample {
    /// The pass's forms of the scene, with `live`'s CPU evaluator.
    pub fn sources<'a>(&'a self, live: &'a LiveScene) -> KernelSources<'a> {
        KernelSources::compiled(&self.kernels)
            .with_cpu(live.evaluator(), &self.scene)
            .with_cpu_wide(live.evaluator_wide())
    }
}

/// Editors save in bursts (truncate, write, rename); the file is read once it has been quiet this long.
const SETTLE: Duration = Duration::from_millis(120);

/// Watches one file through its folder (editors often replace a file rather than write it in place).
pub struct FileWatch {
    _watcher: notify::RecommendedWatcher,
    events: mpsc::Receiver<notify::Result<notify::Event>>,
    path: PathBuf,
    last_text: Option<String>,
    last_event: Option<Instant>,
}

impl FileWatch {
    pub fn new(path: &Path, current_text: Option<String>) -> Result<FileWatch, String> {
        let (sender, events) = mpsc::channel();
        let mut watcher = notify::recommended_watcher(move |event| {
            let _ = sender.send(event);
        })
        .map_err(|e| e.to_string())?;
        let folder = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        watcher.watch(&folder, RecursiveMode::NonRecursive).map_err(|e| format!("{}: {e}", folder.display()))?;
        Ok(FileWatch { _watcher: watcher, events, path: path.to_path_buf(), last_text: current_text, last_event: None })
    }

    /// The file's new text, once it changed and settled; `None` while nothing changed.
    pub fn poll(&mut self) -> Option<Result<String, String>> {
        let name = self.path.file_name();
        while let Ok(event) = self.events.try_recv() {
            let ours = match &event {
                Ok(e) => e.paths.is_empty() || e.paths.iter().any(|p| p.file_name() == name),
                Err(_) => true,
            };
            if ours {
                self.last_event = Some(Instant::now());
            }
        }
        let settled = self.last_event.is_some_and(|at| at.elapsed() >= SETTLE);
        if !settled {
            return None;
        }
        self.last_event = None;
        match fractal_dsl::parse::read_source(&self.path) {
            Ok(text) if Some(&text) == self.last_text.as_ref() => None,
            Ok(text) => {
                self.last_text = Some(text.clone());
                Some(Ok(text))
            }
            // Mid-save the file may be missing for a moment; the rename that completes the save brings another event.
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            Err(e) => Some(Err(format!("{}: {e}", self.path.display()))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_recompile_only_when_settings_change() {
        let source =
            ViewerScene::built("ball", fractal_dsl::builder::scene(fractal_dsl::builder::sphere(1.0))).unwrap();
        let live = LiveScene::load(&source).unwrap();
        let same = live.with_overrides(&EffectOverrides::default()).unwrap();
        assert_eq!(same.wgsl(), live.wgsl());
        let mut overrides = EffectOverrides::default();
        overrides.toggle_ambient_occlusion(&live.authored().settings);
        let with_ao = live.with_overrides(&overrides).unwrap();
        assert!(with_ao.scene.settings.ambient_occlusion.is_some());
        assert_ne!(with_ao.wgsl(), live.wgsl(), "the kernel gains the ambient occlusion code");
        assert_eq!(with_ao.authored(), live.authored());
    }

    #[test]
    fn broken_text_names_file_line_and_column() {
        let err = LiveScene::from_text("s".into(), Path::new("dir/s.fractal"), "scene(sphere(1.0)\n  .frobnicate())")
            .unwrap_err();
        assert!(err.starts_with("dir/s.fractal:2:"), "{err}");
        let missing = LiveScene::load(&ViewerScene::file("no/such.fractal")).unwrap_err();
        assert!(missing.starts_with("no/such.fractal: "), "{missing}");
    }

    #[test]
    fn a_saved_file_is_seen_once() {
        let dir = std::env::temp_dir().join(format!("fractal-watch-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("scene.fractal");
        std::fs::write(&file, "scene(sphere(1.0))").unwrap();
        let mut watch = FileWatch::new(&file, Some("scene(sphere(1.0))".into())).unwrap();
        std::fs::write(&file, "scene(sphere(2.0))").unwrap();
        let deadline = Instant::now() + Duration::from_secs(10);
        let mut seen = None;
        while seen.is_none() && Instant::now() < deadline {
            seen = watch.poll();
            std::thread::sleep(Duration::from_millis(20));
        }
        assert_eq!(seen, Some(Ok("scene(sphere(2.0))".to_string())));
        // Touching the file without changing it reports nothing.
        std::fs::write(&file, "scene(sphere(2.0))").unwrap();
        std::thread::sleep(SETTLE * 3);
        assert_eq!(watch.poll(), None);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
