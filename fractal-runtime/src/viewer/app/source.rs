//! The scene's source while the viewer runs: the file reloaded when another program saves it, and the editor pane's
//! text compiled when typing pauses and written when the user saves. A text that does not compile leaves the last
//! good scene on screen; a scene that compiles replaces it with the user's parameter values kept by name.

use std::time::Instant;

use super::{App, LastGood};
use crate::viewer::live_scene::{FileWatch, LiveScene};
use crate::viewer::params::ParamControl;
use crate::viewer::session::ViewerScene;
use crate::viewer::ui::{EditError, Editor};

impl App {
    /// The editor for the scene: its file, or the text of a built-in scene (saved as `NAME.fractal` in the
    /// screenshot folder).
    pub(super) fn editor(&self) -> Editor {
        let folder = &self.options.screenshot_dir;
        match &self.source {
            ViewerScene::File(path) => {
                Editor::new(fractal_dsl::parse::read_source(path).unwrap_or_default(), path.clone())
            }
            ViewerScene::Compiled { name, scene } => {
                Editor::new(scene.source().to_string(), folder.join(format!("{name}.fractal")))
            }
            ViewerScene::Built { name, .. } => {
                Editor::new(fractal_dsl::print::to_source(self.live.authored()), folder.join(format!("{name}.fractal")))
            }
        }
    }

    /// A save of the scene's file by another program: the scene is reloaded (and the editor shows the text).
    pub(super) fn poll_reload(&mut self) {
        let (Some(watch), ViewerScene::File(path)) = (&mut self.watch, &self.source) else {
            return;
        };
        let Some(text) = watch.poll() else {
            return;
        };
        let path = path.clone();
        if let (Ok(text), Some(editor)) = (&text, &mut self.ui.editor) {
            if text == &editor.text {
                // The editor's own save: the scene on screen is this text already.
                editor.reloaded(text);
                return;
            }
            editor.reloaded(text);
        }
        let loaded = text
            .and_then(|text| LiveScene::from_text(self.live.name.clone(), &path, &text))
            .and_then(|loaded| loaded.with_overrides(&self.overrides));
        match loaded {
            Ok(loaded) => {
                println!("reloaded {}", path.display());
                self.replace_scene(loaded);
            }
            // The last good scene stays on screen.
            Err(e) => eprintln!("{e}"),
        }
    }

    /// The editor's text, once typing has paused: compiled, and shown when it compiles; its error is kept for the
    /// pane and the line over the picture otherwise.
    pub(super) fn poll_editor(&mut self, now: Instant) {
        let Some(editor) = &mut self.ui.editor else {
            return;
        };
        let Some(text) = editor.due(now) else {
            return;
        };
        let path = editor.path.clone();
        if let Err(e) = fractal_dsl::parse::parse_str(&text) {
            editor.error = Some(EditError { at: Some((e.line, e.column)), message: e.message });
            return;
        }
        let loaded = LiveScene::from_text(self.live.name.clone(), &path, &text)
            .and_then(|loaded| loaded.with_overrides(&self.overrides));
        match loaded {
            Ok(loaded) => {
                editor.error = None;
                self.replace_scene(loaded);
            }
            Err(message) => editor.error = Some(EditError { at: None, message }),
        }
    }

    /// Writes the editor's text to its file. A built-in scene becomes that file from then on (watched like any).
    pub(super) fn save_source(&mut self) {
        let Some(editor) = &mut self.ui.editor else {
            return;
        };
        if let Err(e) = editor.save() {
            return eprintln!("cannot save {}: {e}", editor.path.display());
        }
        println!("saved {}", editor.path.display());
        editor.compile_now();
        if !matches!(self.source, ViewerScene::File(_)) {
            self.source = ViewerScene::File(editor.path.clone());
            self.watch = FileWatch::new(&editor.path, Some(editor.text.clone())).ok();
        }
    }

    /// Shows `next` in place of the current scene; the current one is kept to go back to if the driver rejects the
    /// new kernels.
    fn replace_scene(&mut self, next: LiveScene) {
        let params = ParamControl::new(&next.scene, Some(&self.params));
        let previous = std::mem::replace(&mut self.live, next);
        let previous_params = std::mem::replace(&mut self.params, params);
        if self.last_good.is_none() {
            self.last_good =
                Some(LastGood { live: previous, params: previous_params, overrides: self.overrides.clone() });
        }
        self.last_report = None;
    }
}
