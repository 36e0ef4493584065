//! The panel: an egui window in the top-left corner with what the viewer is doing (device, precision, frame time,
//! render size, the still picture's passes), the scene time (a slider and play/pause), the quality (samples a pixel,
//! step budget, hit epsilon, effects) and every `param(..)` as a slider over its range with a typed entry. What the
//! user changes comes back as [`UiAction`]s the game loop applies, so a key and its widget do the same thing.
//! Parameters are uniforms (nothing recompiles); quality and effects are compiled into the kernels.

use egui::{Color32, RichText};
use fractal_dsl::{HitEpsilon, Shadows};

use super::widgets::Widgets;
use crate::viewer::controls::{Action, HELP};

/// One parameter as the panel shows it.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamRow {
    pub name: String,
    pub value: f64,
    pub min: f64,
    pub max: f64,
}

/// What the panel shows, taken from the viewer's state each frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PanelView {
    pub scene: String,
    /// Device, precision, frame time and render size, one line.
    pub status: String,
    /// The still picture's passes (`None` while moving).
    pub still: Option<String>,
    pub time: f64,
    /// The time slider's range: 0 to this.
    pub time_span: f64,
    pub paused: bool,
    pub samples: u32,
    pub steps: u32,
    pub epsilon: HitEpsilon,
    pub shadows: Shadows,
    pub ambient_occlusion: bool,
    pub glow: bool,
    pub fog: bool,
    pub params: Vec<ParamRow>,
    /// The parameter the arrow keys change.
    pub selected: usize,
    /// The camera follows the scene's path (not the user's free camera).
    pub following_path: bool,
    /// Whether the scene has a source the editor can show.
    pub editable: bool,
    pub editor_open: bool,
    /// The bookmarks' names, in the order saved.
    pub bookmarks: Vec<String>,
    /// The size a still is rendered at (F9), and its progressive passes (1: the scene's usual frame).
    pub still_size: (u32, u32),
    pub still_passes: u32,
}

/// A change the user made in the UI.
#[derive(Clone, Debug, PartialEq)]
pub enum UiAction {
    SetTime(f64),
    SetParam(usize, f64),
    ResetParam(usize),
    SetSamples(u32),
    SetSteps(u32),
    SetEpsilon(HitEpsilon),
    /// What the key bound to this action does (pause, effect toggles, screenshot, back to the path, …).
    Key(Action),
    ToggleEditor,
    /// The editor's text changed (recompiled after a short pause).
    SourceEdited,
    SaveSource,
    /// Go to the bookmark of this name.
    GoToBookmark(String),
    /// The still's size and passes.
    SetStill((u32, u32), u32),
}

/// Samples a pixel the panel offers, and the step budget's and epsilon's ranges (the overrides' own).
const SAMPLES_RANGE: std::ops::RangeInclusive<u32> = 1..=64;
const STEPS_RANGE: std::ops::RangeInclusive<u32> = 8..=4096;

/// Draws the panel into `ctx` and collects what the user changed.
pub fn show(ctx: &egui::Context, view: &PanelView, widgets: &mut Widgets, actions: &mut Vec<UiAction>) {
    egui::Window::new(RichText::new(&view.scene).strong())
        .id(egui::Id::unique("panel"))
        .default_pos(egui::pos2(8.0, 8.0))
        .resizable(false)
        .collapsible(true)
        .show(ctx, |ui| {
            ui.label(&view.status);
            if let Some(still) = &view.still {
                ui.label(RichText::new(format!("still: {still}")).color(Color32::from_rgb(150, 200, 255)));
            }
            ui.separator();
            time_row(ui, view, widgets, actions);
            ui.separator();
            quality(ui, view, widgets, actions);
            if !view.params.is_empty() {
                ui.separator();
                params(ui, view, widgets, actions);
            }
            ui.separator();
            ui.horizontal(|ui| {
                if ui.add_enabled(!view.following_path, egui::Button::new("scene camera")).clicked() {
                    actions.push(UiAction::Key(Action::FollowScenePath));
                }
                if ui.button("screenshot").clicked() {
                    actions.push(UiAction::Key(Action::Screenshot));
                }
                if view.editable {
                    let label = if view.editor_open { "hide source" } else { "edit source" };
                    let r = ui.button(label);
                    widgets.record("edit source", r.rect);
                    if r.clicked() {
                        actions.push(UiAction::ToggleEditor);
                    }
                }
            });
            ui.separator();
            views(ui, view, widgets, actions);
            egui::CollapsingHeader::new("keys").default_open(false).show(ui, |ui| {
                ui.label(RichText::new(HELP).monospace().size(11.0));
            });
        });
}

fn time_row(ui: &mut egui::Ui, view: &PanelView, widgets: &mut Widgets, actions: &mut Vec<UiAction>) {
    ui.horizontal(|ui| {
        let r = ui.button(if view.paused { "play" } else { "pause" });
        widgets.record("pause", r.rect);
        if r.clicked() {
            actions.push(UiAction::Key(Action::TogglePause));
        }
        let mut time = view.time;
        let r = ui.add(egui::Slider::new(&mut time, 0.0..=view.time_span).text("time (s)").max_decimals(2));
        widgets.record_slider("time", &r);
        if r.changed() {
            actions.push(UiAction::SetTime(time));
        }
    });
}

fn quality(ui: &mut egui::Ui, view: &PanelView, widgets: &mut Widgets, actions: &mut Vec<UiAction>) {
    egui::Grid::new("quality").num_columns(2).show(ui, |ui| {
        ui.label("samples a pixel");
        let mut samples = view.samples;
        let r = ui.add(egui::DragValue::new(&mut samples).range(SAMPLES_RANGE));
        widgets.record("samples", r.rect);
        if r.changed() {
            actions.push(UiAction::SetSamples(samples));
        }
        ui.end_row();
        ui.label("max steps");
        let mut steps = view.steps;
        let r = ui.add(egui::DragValue::new(&mut steps).range(STEPS_RANGE).speed(4.0));
        widgets.record("steps", r.rect);
        if r.changed() {
            actions.push(UiAction::SetSteps(steps));
        }
        ui.end_row();
        match view.epsilon {
            HitEpsilon::Pixel(k) => {
                ui.label("hit epsilon (pixels)");
                let mut k = k;
                let r = ui.add(egui::DragValue::new(&mut k).range(1e-3..=64.0).speed(0.01).max_decimals(3));
                if r.changed() {
                    actions.push(UiAction::SetEpsilon(HitEpsilon::Pixel(k)));
                }
            }
            HitEpsilon::Fixed(e) => {
                ui.label("hit epsilon");
                let mut e = e;
                let r = ui.add(egui::DragValue::new(&mut e).range(1e-7..=1.0).speed(1e-5).max_decimals(7));
                if r.changed() {
                    actions.push(UiAction::SetEpsilon(HitEpsilon::Fixed(e)));
                }
            }
        }
        ui.end_row();
    });
    ui.horizontal(|ui| {
        let shadows = match view.shadows {
            Shadows::None => "shadows: none",
            Shadows::Hard => "shadows: hard",
            Shadows::Soft(_) => "shadows: soft",
        };
        let r = ui.button(shadows);
        widgets.record("shadows", r.rect);
        if r.clicked() {
            actions.push(UiAction::Key(Action::CycleShadows));
        }
        let mut toggle = |ui: &mut egui::Ui, on: bool, name: &str, action: Action| {
            let r = ui.selectable_label(on, name);
            widgets.record(name, r.rect);
            if r.clicked() {
                actions.push(UiAction::Key(action));
            }
        };
        toggle(ui, view.ambient_occlusion, "AO", Action::ToggleAmbientOcclusion);
        toggle(ui, view.glow, "glow", Action::ToggleGlow);
        toggle(ui, view.fog, "fog", Action::ToggleFog);
    });
}

/// Bookmarks (save, go to) and the still's size.
fn views(ui: &mut egui::Ui, view: &PanelView, widgets: &mut Widgets, actions: &mut Vec<UiAction>) {
    ui.horizontal_wrapped(|ui| {
        let r = ui.button("bookmark (B)");
        widgets.record("bookmark", r.rect);
        if r.clicked() {
            actions.push(UiAction::Key(Action::Bookmark));
        }
        for name in &view.bookmarks {
            let r = ui.small_button(name).on_hover_text("go to this view");
            widgets.record(&format!("bookmark:{name}"), r.rect);
            if r.clicked() {
                actions.push(UiAction::GoToBookmark(name.clone()));
            }
        }
    });
    ui.horizontal(|ui| {
        let ((mut w, mut h), mut passes) = (view.still_size, view.still_passes);
        let r = ui.button("still (F9)");
        widgets.record("still", r.rect);
        if r.clicked() {
            actions.push(UiAction::Key(Action::RenderStill));
        }
        let mut entry = |ui: &mut egui::Ui, name: &str, value: &mut u32, max: u32, text: (&str, &str)| {
            let r = ui.add(egui::DragValue::new(value).range(1..=max).prefix(text.0).suffix(text.1));
            widgets.record(name, r.rect);
            r.changed()
        };
        let changed = entry(ui, "still width", &mut w, 8192, ("", ""))
            | entry(ui, "still height", &mut h, 8192, ("x ", ""))
            | entry(ui, "still passes", &mut passes, 4096, ("", " passes"));
        if changed {
            actions.push(UiAction::SetStill((w, h), passes));
        }
    });
}

fn params(ui: &mut egui::Ui, view: &PanelView, widgets: &mut Widgets, actions: &mut Vec<UiAction>) {
    for (i, p) in view.params.iter().enumerate() {
        ui.horizontal(|ui| {
            let mut value = p.value;
            let name = if i == view.selected { RichText::new(&p.name).strong() } else { RichText::new(&p.name) };
            // The slider's number box takes a typed value; the range clamps what is typed.
            let r = ui.add(egui::Slider::new(&mut value, p.min..=p.max).text(name).max_decimals(4));
            widgets.record_slider(&format!("param:{}", p.name), &r);
            if r.changed() {
                actions.push(UiAction::SetParam(i, value));
            }
            if ui.small_button("reset").on_hover_text("back to the scene's default").clicked() {
                actions.push(UiAction::ResetParam(i));
            }
        });
    }
}
