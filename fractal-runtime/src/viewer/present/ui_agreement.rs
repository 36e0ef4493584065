//! The UI drawn both ways agrees: egui-wgpu in the wgpu presenter (on whatever adapter there is, lavapipe in CI) and
//! the host rasteriser that softbuffer's frames carry, from one egui frame, over one picture.

use fractal_render::backend::wgpu::WgpuRenderer;
use fractal_render::image::{pack_rgba8, unpack_rgba8, Image};

use super::GpuPresenter;
use crate::viewer::ui::{covered, UiPaint};

/// Window size in pixels.
const WINDOW: (u32, u32) = (320, 240);

/// One egui frame of a window with text, a slider, a button and a text field, laid out as the viewer's panel is
/// (several passes, so the window has faded in and sized itself).
fn egui_frame() -> UiPaint {
    let ctx = egui::Context::default();
    let mut textures = egui::TexturesDelta::default();
    let (mut value, mut text) = (0.4f32, String::from("sphere(1.0)"));
    let mut last = None;
    for i in 0..4 {
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(
                egui::Pos2::ZERO,
                egui::vec2(WINDOW.0 as f32, WINDOW.1 as f32),
            )),
            time: Some(i as f64),
            ..Default::default()
        };
        let output = ctx.run_ui(input, |ui| {
            egui::Window::new("panel").default_pos((9.0, 1.0)).show(ui.ctx(), |ui| {
                ui.label("wgpu in f32, 16.2 ms");
                ui.add(egui::Slider::new(&mut value, 0.0..=1.0).text("radius"));
                let _ = ui.button("bookmark (B)");
                ui.text_edit_singleline(&mut text);
            });
        });
        textures.append(output.textures_delta);
        last = Some((output.shapes, output.pixels_per_point));
    }
    let (shapes, ppp) = last.expect("frames ran");
    let primitives = ctx.tessellate(shapes, ppp);
    let rect = covered(&primitives, ppp, WINDOW);
    UiPaint { primitives, pixels_per_point: ppp, window: WINDOW, textures, rect }
}

#[test]
fn egui_wgpu_and_the_host_rasteriser_draw_the_same_ui() {
    let mut renderer = match WgpuRenderer::new() {
        Ok(r) => r,
        Err(e) => return eprintln!("skipped: no wgpu adapter ({e})"),
    };
    // A picture with detail under the UI: a gradient, so translucency shows.
    let picture = Image {
        width: WINDOW.0,
        height: WINDOW.1,
        pixels: (0..WINDOW.0 * WINDOW.1)
            .map(|i| {
                pack_rgba8([(i % WINDOW.0 * 255 / WINDOW.0) as u8, 160, (i / WINDOW.0 * 255 / WINDOW.1) as u8, 255])
            })
            .collect(),
    };
    let mut paint = egui_frame();
    let rect = paint.rect.expect("the window is drawn");

    // The host's drawing: the rasteriser's overlay blended over the picture as softbuffer's presenter blends it.
    let overlay = crate::viewer::ui::host_overlay(&paint).expect("an overlay");
    let mut host: Vec<u32> = picture
        .pixels
        .iter()
        .map(|&p| {
            let [r, g, b, _] = unpack_rgba8(p);
            (r as u32) << 16 | (g as u32) << 8 | b as u32
        })
        .collect();
    overlay.blend_over_xrgb(&mut host, WINDOW.0);

    let mut gpu = GpuPresenter::offscreen(&renderer).expect("an offscreen presenter");
    let shown = gpu.show(&mut renderer, &picture, WINDOW, true, Some(&mut paint)).expect("drawn").expect("a picture");

    // Both blend egui's premultiplied, gamma-encoded colours in gamma space; the GPU rounds to 8 bits after every
    // blend and the host once, at the end. Measured: at most 1 level apart. A triangle edge drawn twice or left out
    // (the stray lines the host drew along the shadow's edges before it kept the top-left rule) differs by tens.
    let mut worst = (0, (0, 0));
    for y in 0..WINDOW.1 {
        for x in 0..WINDOW.0 {
            let h = host[(y * WINDOW.0 + x) as usize];
            let h = [(h >> 16) as u8, (h >> 8) as u8, h as u8];
            let g = shown.rgba(x, y).expect("a window-sized picture");
            let d = (0..3).map(|c| (h[c] as i32 - g[c] as i32).abs()).max().unwrap_or(0);
            if d > worst.0 {
                worst = (d, (x, y));
            }
        }
    }
    assert!(worst.0 <= 3, "the two drawings differ by {} levels at {:?} (UI at {rect:?})", worst.0, worst.1);
}
