//! The scene editor: the scene's source (its `.fractal` file, or a built-in scene's text) in a pane on the window's
//! right. An edit is compiled once typing pauses ([`EDIT_PAUSE`]); an error is marked at its `line:column` in the
//! pane and said in one line over the picture, which stays the last good one. Saving writes the file (a built-in
//! scene is saved as a new `.fractal` file); a save from another editor still reloads the scene, and replaces the
//! pane's text when the pane holds no unsaved edit.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use egui::text::{LayoutJob, TextFormat};
use egui::{Color32, FontId, RichText};

use super::panel::UiAction;
use super::widgets::Widgets;

/// Time without typing after which an edit is compiled.
pub const EDIT_PAUSE: Duration = Duration::from_millis(400);
const ERROR_LINE: Color32 = Color32::from_rgb(110, 30, 30);
const ERROR_TEXT: Color32 = Color32::from_rgb(255, 120, 110);

/// Where the last compile of the pane's text failed.
#[derive(Clone, Debug, PartialEq)]
pub struct EditError {
    /// 1-based `line:column`, when the error has a place in the text.
    pub at: Option<(usize, usize)>,
    pub message: String,
}

/// The pane's text and what became of it.
#[derive(Clone, Debug)]
pub struct Editor {
    pub open: bool,
    pub text: String,
    /// Where saving writes; for a built-in scene, a new file named after it.
    pub path: PathBuf,
    /// The text as last saved or loaded.
    saved: String,
    edited_at: Option<Instant>,
    pub error: Option<EditError>,
}

impl Editor {
    pub fn new(text: String, path: PathBuf) -> Editor {
        Editor { open: false, saved: text.clone(), text, path, edited_at: None, error: None }
    }

    /// Unsaved edits in the pane.
    pub fn dirty(&self) -> bool {
        self.text != self.saved
    }

    /// The file changed on disk (saved by another editor): the pane shows it unless it holds unsaved edits.
    pub fn reloaded(&mut self, text: &str) {
        if !self.dirty() {
            self.text = text.to_string();
        }
        self.saved = text.to_string();
    }

    /// The text to compile, once typing has paused for [`EDIT_PAUSE`] (at most once per edit).
    pub fn due(&mut self, now: Instant) -> Option<String> {
        let at = self.edited_at?;
        (now.duration_since(at) >= EDIT_PAUSE).then(|| {
            self.edited_at = None;
            self.text.clone()
        })
    }

    /// Compile the text on the next frame, whatever the pause (a scripted run, a save).
    pub fn compile_now(&mut self) {
        self.edited_at = Some(Instant::now() - EDIT_PAUSE);
    }

    /// Writes the pane's text to its file.
    pub fn save(&mut self) -> std::io::Result<()> {
        std::fs::write(&self.path, &self.text)?;
        self.saved = self.text.clone();
        Ok(())
    }

    /// Draws the pane (when open) and the error line over the picture (when the text does not compile).
    pub fn show(&mut self, ctx: &egui::Context, widgets: &mut Widgets, actions: &mut Vec<UiAction>) {
        if let Some(error) = &self.error {
            error_banner(ctx, error);
        }
        if !self.open {
            return;
        }
        let screen = ctx.content_rect();
        let name =
            self.path.file_name().map_or_else(|| self.path.display().to_string(), |n| n.to_string_lossy().into());
        let title = format!("{name}{}", if self.dirty() { " (edited)" } else { "" });
        egui::Window::new(title)
            .id(egui::Id::unique("editor"))
            .anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0])
            .default_size([screen.width() * 0.45, screen.height() - 60.0])
            .resizable(true)
            .collapsible(false)
            .show(ctx, |ui| {
                ui.horizontal(|ui| {
                    let save = ui.add_enabled(self.dirty(), egui::Button::new("save (Ctrl+S)"));
                    widgets.record("save", save.rect);
                    if save.clicked() {
                        actions.push(UiAction::SaveSource);
                    }
                    match &self.error {
                        Some(EditError { at: Some((line, column)), .. }) => {
                            ui.label(RichText::new(format!("error at {line}:{column}")).color(ERROR_TEXT));
                        }
                        Some(_) => {
                            ui.label(RichText::new("does not compile").color(ERROR_TEXT));
                        }
                        None if self.edited_at.is_some() => {
                            ui.label("compiling when you pause");
                        }
                        None => {
                            ui.label("compiles");
                        }
                    }
                });
                let error_line = self.error.as_ref().and_then(|e| e.at).map(|(line, _)| line);
                // Code is not wrapped: long lines scroll sideways, and line numbers in errors stay the file's.
                let mut layouter = |ui: &egui::Ui, text: &dyn egui::TextBuffer, _wrap: f32| {
                    ui.fonts_mut(|f| f.layout_job(highlight(text.as_str(), error_line)))
                };
                egui::ScrollArea::both().show(ui, |ui| {
                    let edit = egui::TextEdit::multiline(&mut self.text)
                        .code_editor()
                        .desired_width(f32::INFINITY)
                        .desired_rows(30)
                        .layouter(&mut layouter);
                    let response = ui.add(edit);
                    // The part on screen: the text is as wide as its longest line, and scrolls.
                    widgets.record("source", response.rect.intersect(ui.clip_rect()));
                    if response.changed() {
                        self.edited_at = Some(Instant::now());
                        actions.push(UiAction::SourceEdited);
                    }
                    if response.has_focus() && ui.input_mut(|i| i.consume_key(egui::Modifiers::COMMAND, egui::Key::S)) {
                        actions.push(UiAction::SaveSource);
                    }
                });
            });
    }
}

/// The text as the pane lays it out: monospace, the error's line on a red band.
fn highlight(text: &str, error_line: Option<usize>) -> LayoutJob {
    let mut job = LayoutJob::default();
    let font = FontId::monospace(13.0);
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let mut format = TextFormat::simple(font.clone(), Color32::from_gray(220));
        if error_line == Some(i + 1) {
            format.background = ERROR_LINE;
        }
        job.append(line, 0.0, format);
    }
    if text.is_empty() {
        job.append("", 0.0, TextFormat::simple(font, Color32::from_gray(220)));
    }
    job.wrap.max_width = f32::INFINITY;
    job
}

/// The error in one line over the last good picture, in the window's bottom-left corner (clear of the panel and the
/// editor's title).
fn error_banner(ctx: &egui::Context, error: &EditError) {
    let first = error.message.lines().next().unwrap_or_default();
    let text = match error.at {
        Some((line, column)) => format!("{line}:{column}: {first}"),
        None => first.to_string(),
    };
    egui::Area::new(egui::Id::unique("error banner")).anchor(egui::Align2::LEFT_BOTTOM, [8.0, -8.0]).show(ctx, |ui| {
        egui::Frame::popup(ui.style()).fill(Color32::from_rgba_unmultiplied(60, 10, 10, 230)).show(ui, |ui| {
            ui.label(RichText::new(text).color(ERROR_TEXT).monospace());
        });
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edits_compile_after_a_pause_and_saves_track_the_file() {
        let dir = std::env::temp_dir().join(format!("fractal-editor-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("s.fractal");
        let mut e = Editor::new("sphere(1.0)".into(), path.clone());
        let now = Instant::now();
        assert_eq!(e.due(now), None, "nothing edited");
        e.text.push('\n');
        e.edited_at = Some(now);
        assert_eq!(e.due(now + EDIT_PAUSE / 2), None, "still typing");
        assert_eq!(e.due(now + EDIT_PAUSE).as_deref(), Some("sphere(1.0)\n"));
        assert_eq!(e.due(now + EDIT_PAUSE * 3), None, "once per edit");
        assert!(e.dirty());
        e.reloaded("sphere(2.0)");
        assert_eq!(e.text, "sphere(1.0)\n", "an outside save keeps unsaved edits");
        e.save().unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "sphere(1.0)\n");
        assert!(!e.dirty());
        e.reloaded("sphere(3.0)");
        assert_eq!(e.text, "sphere(3.0)", "with nothing unsaved, the pane follows the file");
        let job = highlight("a\nb\nc", Some(2));
        assert_eq!(job.sections.len(), 3);
        assert_eq!(job.sections[1].format.background, ERROR_LINE);
        assert_eq!(job.sections[0].format.background, Color32::TRANSPARENT);
        std::fs::remove_dir_all(dir).ok();
    }
}
