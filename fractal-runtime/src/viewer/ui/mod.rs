//! The viewer's UI: egui, fed by the window's events through egui-winit (or by a script's [`UiInput`]), laid out
//! each frame — the panel (module `panel`) and the scene editor (module `editor`) — into a [`UiPaint`]: egui's
//! meshes and textures, which the wgpu surface draws with egui-wgpu after the frame's blit, and the host presenter
//! takes as an [`Overlay`] rasterised here (module `raster`). What the user changes comes back as [`UiAction`]s; the
//! game loop applies them as it applies keys.

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
pub use raster::covered;

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

/// What the UI draws over a frame, as egui gave it: the wgpu surface's painter takes it as it is (module
/// `present::gpu`), the host presenter as [`Ui::overlay`] rasterises it.
#[derive(Default)]
pub struct UiPaint {
    /// The frame's meshes, positions in points.
    pub primitives: Vec<egui::epaint::ClippedPrimitive>,
    pub pixels_per_point: f32,
    /// The window's size in pixels the meshes were laid out for.
    pub window: (u32, u32),
    /// Textures set and freed since a GPU painter last took them (egui sends each change once).
    pub textures: egui::TexturesDelta,
    /// The window pixels the meshes cover (left, top, width, height); `None` when nothing is drawn.
    pub rect: Option<(u32, u32, u32, u32)>,
}

/// egui's state and what draws it.
pub struct Ui {
    ctx: egui::Context,
    winit: Option<egui_winit::State>,
    /// The host's copy of egui's textures and the overlay it last drew.
    raster: Rasterizer,
    /// The last frame's drawing, and the textures its frame freed (forgotten on the host once it is painted).
    paint: UiPaint,
    freed: egui::TexturesDelta,
    /// A presenter started since the last frame: the next frame's textures are all of them, whole.
    resend: bool,
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
            paint: UiPaint::default(),
            freed: egui::TexturesDelta::default(),
            resend: false,
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

    /// Lays the UI out for a `size`-pixel window: the panel when `panel` is given, the editor when open. What it
    /// draws is kept for the presenters ([`Ui::paint`], [`Ui::overlay`]); what the user changed is returned.
    pub fn frame(&mut self, window: Option<&Window>, size: (u32, u32), panel: Option<&PanelView>) -> Vec<UiAction> {
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
        let output = self.ctx.run_pass(input, |ctx| {
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
        // The host's copy: the last frame's freed textures go now that it is painted; this frame's arrive.
        self.raster.free_textures(&self.freed);
        self.freed.clear();
        self.raster.set_textures(&output.textures_delta);
        self.freed.free = output.textures_delta.free.clone();
        let mut textures = std::mem::take(&mut self.paint.textures);
        if std::mem::take(&mut self.resend) {
            textures.append(self.raster.full_textures());
        }
        textures.append(output.textures_delta);
        let ppp = output.pixels_per_point;
        let primitives = self.ctx.tessellate(output.shapes, ppp);
        let rect = covered(&primitives, ppp, size);
        self.paint = UiPaint { primitives, pixels_per_point: ppp, window: size, textures, rect };
        actions
    }

    /// The last frame's drawing, for a painter that draws egui's meshes itself; it takes the textures it applies.
    pub fn paint(&mut self) -> &mut UiPaint {
        &mut self.paint
    }

    /// The window pixels the last frame's UI covers (left, top, width, height); `None` when nothing is drawn.
    pub fn rect(&self) -> Option<(u32, u32, u32, u32)> {
        self.paint.rect
    }

    /// The last frame's drawing rasterised on the host, for the host presenter; kept while it does not change. The
    /// host presenter needs no textures sent: they are forgotten here, so they do not pile up.
    pub fn overlay(&mut self) -> Option<Overlay> {
        self.paint.textures.clear();
        let paint = &self.paint;
        self.raster.paint(&paint.primitives, paint.pixels_per_point, paint.window)
    }

    /// A presenter has started: the next frame hands it every texture, whole (the textures egui sent before are on
    /// the host only).
    pub fn resend_textures(&mut self) {
        self.resend = true;
        self.paint.textures.clear();
    }
}

/// `paint` drawn by the host rasteriser alone, from its own textures (which it leaves in place).
#[cfg(test)]
pub(crate) fn host_overlay(paint: &UiPaint) -> Option<Overlay> {
    let mut raster = Rasterizer::default();
    raster.set_textures(&paint.textures);
    raster.paint(&paint.primitives, paint.pixels_per_point, paint.window)
}

impl Drop for Ui {
    /// Textures no painter took are the host's copy only (egui checks that none is dropped unseen).
    fn drop(&mut self) {
        self.paint.textures.clear();
        self.freed.clear();
    }
}
