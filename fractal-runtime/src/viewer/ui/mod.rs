//! The viewer's UI: egui, fed by the window's events through egui-winit (or by a script's [`UiInput`]), laid out
//! each frame — the panel (module `panel`) and the scene editor (module `editor`) — and drawn on the host into an
//! [`Overlay`] (module `raster`) that both presenters blend over the frame. What the user changes comes back as
//! [`UiAction`]s; the game loop applies them as it applies keys.

mod editor;
mod overlay;
mod panel;
mod raster;
mod widgets;

use std::time::Instant;

use winit::event::WindowEvent;
use winit::window::Window;

pub use editor::{EditError, Editor};
pub use overlay::Overlay;
pub use panel::{PanelView, ParamRow, UiAction};

use raster::Rasterizer;
use widgets::Widgets;

/// A scripted input to the UI, as a person's pointer and keyboard would give it (module `script`).
#[derive(Clone, Debug, PartialEq)]
pub enum UiInput {
    /// Press the primary button on the widget `widget` (a name the UI gives its widgets: `time`, `pause`,
    /// `param:NAME`, `samples`, `steps`, `shadows`, `AO`, `glow`, `fog`, `edit source`, `source`, `save`), at
    /// fraction `at` of it (across, down; a slider's rail between its ends).
    Press { widget: String, at: (f32, f32) },
    /// Move the pointer to a widget (a drag while pressed).
    MoveTo { widget: String, at: (f32, f32) },
    /// Release the primary button where the pointer is.
    Release,
    /// Type text where the keyboard focus is.
    Type(String),
    /// A key with Ctrl (⌘ on macOS) held: `'A'` selects all, `'S'` saves the source.
    Command(char),
    /// A key by egui's name for it (`Enter`, `Tab`, `Escape`, …), pressed and released.
    Key(String),
}

/// egui's state and what draws it.
pub struct Ui {
    ctx: egui::Context,
    winit: Option<egui_winit::State>,
    raster: Rasterizer,
    widgets: Widgets,
    /// Scripted events for the next frame, and where the scripted pointer is.
    scripted: Vec<egui::Event>,
    pointer: egui::Pos2,
    started: Instant,
    pub editor: Option<Editor>,
}

impl Ui {
    pub fn new(editor: Option<Editor>) -> Ui {
        Ui {
            ctx: egui::Context::default(),
            winit: None,
            raster: Rasterizer::default(),
            widgets: Widgets::default(),
            scripted: Vec::new(),
            pointer: egui::Pos2::ZERO,
            started: Instant::now(),
            editor,
        }
    }

    /// Takes input from `window` from now on.
    pub fn attach(&mut self, window: &Window) {
        let viewport = self.ctx.viewport_id();
        let state =
            egui_winit::State::new(self.ctx.clone(), viewport, window, Some(window.scale_factor() as f32), None, None);
        self.winit = Some(state);
    }

    /// Gives egui a window event; `true` when egui uses it (a click on the panel, typing in the editor), so the
    /// viewer's own controls should not.
    pub fn on_window_event(&mut self, window: &Window, event: &WindowEvent) -> bool {
        let Some(state) = &mut self.winit else {
            return false;
        };
        let response = state.on_window_event(window, event);
        let keyboard = matches!(event, WindowEvent::KeyboardInput { .. }) && self.ctx.egui_wants_keyboard_input();
        let pointer = matches!(event, WindowEvent::MouseInput { .. } | WindowEvent::MouseWheel { .. })
            && (self.ctx.is_pointer_over_egui() || self.ctx.egui_is_using_pointer());
        response.consumed || keyboard || pointer
    }

    /// Queues a scripted input for the next frame; a widget that was not drawn last frame is an error naming the
    /// ones that were.
    pub fn script(&mut self, input: &UiInput) -> Result<(), String> {
        let ppp = self.ctx.pixels_per_point();
        let at = |widgets: &Widgets, widget: &str, at: (f32, f32)| {
            widgets.point(widget, at).map(|(x, y)| egui::pos2(x / ppp, y / ppp)).ok_or_else(|| {
                format!("scripted UI input: no widget `{widget}` on screen (drawn: {})", widgets.names().join(", "))
            })
        };
        let modifiers = egui::Modifiers::NONE;
        match input {
            UiInput::Press { widget, at: fraction } => {
                self.pointer = at(&self.widgets, widget, *fraction)?;
                self.scripted.push(egui::Event::PointerMoved(self.pointer));
                self.scripted.push(egui::Event::PointerButton {
                    pos: self.pointer,
                    button: egui::PointerButton::Primary,
                    pressed: true,
                    modifiers,
                });
            }
            UiInput::MoveTo { widget, at: fraction } => {
                self.pointer = at(&self.widgets, widget, *fraction)?;
                self.scripted.push(egui::Event::PointerMoved(self.pointer));
            }
            UiInput::Release => self.scripted.push(egui::Event::PointerButton {
                pos: self.pointer,
                button: egui::PointerButton::Primary,
                pressed: false,
                modifiers,
            }),
            UiInput::Type(text) => self.scripted.push(egui::Event::Text(text.clone())),
            UiInput::Command(c) => self.press_key(&c.to_string(), egui::Modifiers::COMMAND)?,
            UiInput::Key(name) => self.press_key(name, egui::Modifiers::NONE)?,
        }
        Ok(())
    }

    fn press_key(&mut self, name: &str, modifiers: egui::Modifiers) -> Result<(), String> {
        let key = egui::Key::from_name(name).ok_or_else(|| format!("scripted UI input: no key named {name:?}"))?;
        for pressed in [true, false] {
            self.scripted.push(egui::Event::Key { key, physical_key: None, pressed, repeat: false, modifiers });
        }
        Ok(())
    }

    /// Lays the UI out for a `size`-pixel window and draws it: the panel when `panel` is given, the editor when open.
    /// Returns the overlay (`None`: nothing to draw) and what the user changed.
    pub fn frame(
        &mut self,
        window: Option<&Window>,
        size: (u32, u32),
        panel: Option<&PanelView>,
    ) -> (Option<Overlay>, Vec<UiAction>) {
        let mut input = match (&mut self.winit, window) {
            (Some(state), Some(window)) => state.take_egui_input(window),
            _ => egui::RawInput {
                screen_rect: Some(egui::Rect::from_min_size(
                    egui::Pos2::ZERO,
                    egui::vec2(size.0 as f32, size.1 as f32) / self.ctx.pixels_per_point(),
                )),
                time: Some(self.started.elapsed().as_secs_f64()),
                ..Default::default()
            },
        };
        if !self.scripted.is_empty() {
            // A script's input counts as a focused window's (without a window manager, an X window is never focused).
            input.focused = true;
            input.events.append(&mut self.scripted);
        }
        let mut actions = Vec::new();
        let (widgets, editor) = (&mut self.widgets, &mut self.editor);
        widgets.begin(self.ctx.pixels_per_point());
        let mut output = self.ctx.run_pass(input, |ctx| {
            if let Some(view) = panel {
                panel::show(ctx, view, widgets, &mut actions);
            }
            if let Some(editor) = editor.as_mut() {
                editor.show(ctx, widgets, &mut actions);
            }
        });
        widgets.end();
        if let (Some(state), Some(window)) = (&mut self.winit, window) {
            state.handle_platform_output(window, output.platform_output);
        }
        self.raster.set_textures(&output.textures_delta);
        let primitives = self.ctx.tessellate(output.shapes, output.pixels_per_point);
        let overlay = self.raster.paint(&primitives, output.pixels_per_point, size);
        self.raster.free_textures(&output.textures_delta);
        // Applied: egui checks that no delta is dropped unseen.
        output.textures_delta.clear();
        (overlay, actions)
    }
}
