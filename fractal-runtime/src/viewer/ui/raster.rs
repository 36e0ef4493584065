//! Draws egui's output on the host: its textures (the font atlas, the images it uploads) and its triangle meshes,
//! rasterised into an [`Overlay`] that the host presenter (softbuffer, or host memory without a window) blends over
//! the frame — the CPU and OpenCL frames, and wgpu frames where no surface can present, have no GPU pipeline to draw
//! the UI with. The wgpu surface draws the same meshes with egui-wgpu. The store of textures here is also what a
//! presenter made later (after a fallback) is given again, since egui sends each texture once.
//!
//! Triangles are sampled at pixel centres with barycentric interpolation of colour and texture coordinates; egui
//! feathers its shapes' edges itself, so one sample a pixel is what its own renderers do. Colours are sRGB with
//! premultiplied alpha and are blended in that space, as egui expects of a gamma-space target.

use std::collections::HashMap;

use egui::epaint::{ClippedPrimitive, ImageData, ImageDelta, Primitive, TextureId, Vertex};
use egui::{Color32, ColorImage, TextureOptions, TexturesDelta};
use fractal_render::image::{pack_rgba8, Image};

use super::overlay::Overlay;

/// One texture egui gave: texels as premultiplied RGBA8.
struct Texture {
    size: [usize; 2],
    texels: Vec<[u8; 4]>,
    options: TextureOptions,
}

impl Texture {
    /// The bilinear sample at normalised (u, v), premultiplied, in 0..=1.
    fn sample(&self, u: f32, v: f32) -> [f32; 4] {
        let [w, h] = self.size;
        if w == 0 || h == 0 {
            return [0.0; 4];
        }
        let x = (u * w as f32 - 0.5).clamp(0.0, (w - 1) as f32);
        let y = (v * h as f32 - 0.5).clamp(0.0, (h - 1) as f32);
        let (x0, y0) = (x.floor() as usize, y.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
        let (fx, fy) = (x - x0 as f32, y - y0 as f32);
        let t = |x: usize, y: usize| self.texels[y * w + x];
        let mut out = [0.0; 4];
        for (c, o) in out.iter_mut().enumerate() {
            let top = t(x0, y0)[c] as f32 * (1.0 - fx) + t(x1, y0)[c] as f32 * fx;
            let bottom = t(x0, y1)[c] as f32 * (1.0 - fx) + t(x1, y1)[c] as f32 * fx;
            *o = (top * (1.0 - fy) + bottom * fy) / 255.0;
        }
        out
    }
}

/// The textures egui has uploaded so far, kept from frame to frame, and the last overlay drawn with the hash of
/// what drew it: the panel changes a few times a second at most while the frames go on, so most frames reuse it.
#[derive(Default)]
pub struct Rasterizer {
    textures: HashMap<TextureId, Texture>,
    last: Option<(u64, Option<Overlay>)>,
}

/// A hash of everything [`Rasterizer::paint`] reads besides the textures.
fn fingerprint(primitives: &[ClippedPrimitive], pixels_per_point: f32, window: (u32, u32)) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    (pixels_per_point.to_bits(), window).hash(&mut h);
    for p in primitives {
        let r = p.clip_rect;
        [r.min.x, r.min.y, r.max.x, r.max.y].map(f32::to_bits).hash(&mut h);
        if let Primitive::Mesh(mesh) = &p.primitive {
            mesh.texture_id.hash(&mut h);
            mesh.indices.hash(&mut h);
            for v in &mesh.vertices {
                [v.pos.x, v.pos.y, v.uv.x, v.uv.y].map(f32::to_bits).hash(&mut h);
                v.color.to_array().hash(&mut h);
            }
        }
    }
    h.finish()
}

impl Rasterizer {
    /// Applies a frame's new and changed textures (before painting it).
    pub fn set_textures(&mut self, delta: &TexturesDelta) {
        if !delta.set.is_empty() {
            self.last = None;
        }
        for (id, patches) in &delta.set {
            for patch in patches {
                let ImageData::Color(image) = &patch.image;
                let texels: Vec<[u8; 4]> = image.pixels.iter().map(|c| c.to_array()).collect();
                match patch.pos {
                    None => {
                        self.textures.insert(*id, Texture { size: image.size, texels, options: patch.options });
                    }
                    Some([px, py]) => {
                        let Some(texture) = self.textures.get_mut(id) else {
                            continue;
                        };
                        let [w, h] = texture.size;
                        for row in 0..image.size[1] {
                            for col in 0..image.size[0] {
                                let (x, y) = (px + col, py + row);
                                if x < w && y < h {
                                    texture.texels[y * w + x] = texels[row * image.size[0] + col];
                                }
                            }
                        }
                    }
                }
            }
        }
    }

    /// Every texture kept, whole: what a presenter that starts now needs before it draws a frame.
    pub fn full_textures(&self) -> TexturesDelta {
        let mut delta = TexturesDelta::default();
        for (id, texture) in &self.textures {
            let pixels =
                texture.texels.iter().map(|&[r, g, b, a]| Color32::from_rgba_premultiplied(r, g, b, a)).collect();
            let image = ColorImage::new(texture.size, pixels);
            delta.push(*id, ImageDelta::full(image, texture.options));
        }
        delta
    }

    /// Forgets the textures egui freed (after painting the frame).
    pub fn free_textures(&mut self, delta: &TexturesDelta) {
        for id in &delta.free {
            self.textures.remove(id);
        }
    }

    /// Rasterises `primitives` (positions in points, `pixels_per_point` pixels each) for a `window` of that many
    /// pixels, into the smallest overlay that holds them; `None` when nothing is drawn.
    pub fn paint(
        &mut self,
        primitives: &[ClippedPrimitive],
        pixels_per_point: f32,
        window: (u32, u32),
    ) -> Option<Overlay> {
        let key = fingerprint(primitives, pixels_per_point, window);
        if let Some((last, overlay)) = &self.last {
            if *last == key {
                return overlay.clone();
            }
        }
        let overlay = self.draw(primitives, pixels_per_point, window);
        self.last = Some((key, overlay.clone()));
        overlay
    }

    fn draw(&self, primitives: &[ClippedPrimitive], pixels_per_point: f32, window: (u32, u32)) -> Option<Overlay> {
        let ppp = pixels_per_point;
        let (x0, y0, width, height) = covered(primitives, ppp, window)?;
        let mut canvas = Canvas { origin: (x0, y0), width, height, pixels: Vec::new() };
        canvas.pixels = vec![[0.0; 4]; (canvas.width * canvas.height) as usize];
        for (mesh, clip, _) in meshes(primitives, ppp, window) {
            let texture = self.textures.get(&mesh.texture_id);
            for tri in mesh.indices.chunks_exact(3) {
                let corner = |i: u32| mesh.vertices.get(i as usize).copied();
                if let (Some(a), Some(b), Some(c)) = (corner(tri[0]), corner(tri[1]), corner(tri[2])) {
                    canvas.triangle([a, b, c], ppp, clip, texture);
                }
            }
        }
        Some(canvas.into_overlay())
    }
}

/// The meshes that draw inside a `window` of that many pixels, with their clip rectangles and the area they cover, in
/// pixels.
fn meshes(
    primitives: &[ClippedPrimitive],
    pixels_per_point: f32,
    window: (u32, u32),
) -> impl Iterator<Item = (&egui::Mesh, egui::Rect, egui::Rect)> {
    let screen = egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(window.0 as f32, window.1 as f32));
    primitives.iter().filter_map(move |p| match &p.primitive {
        Primitive::Mesh(mesh) if !mesh.indices.is_empty() => {
            let clip = p.clip_rect * pixels_per_point;
            let area = clip.intersect(mesh.calc_bounds() * pixels_per_point).intersect(screen);
            area.is_positive().then_some((mesh, clip, area))
        }
        _ => None,
    })
}

/// The smallest block of window pixels (left, top, width, height) that holds what `primitives` draw; `None` when
/// they draw nothing.
pub fn covered(
    primitives: &[ClippedPrimitive],
    pixels_per_point: f32,
    window: (u32, u32),
) -> Option<(u32, u32, u32, u32)> {
    let area = meshes(primitives, pixels_per_point, window).map(|m| m.2).reduce(|a, b| a.union(b))?;
    let (x0, y0) = (area.min.x.floor().max(0.0) as u32, area.min.y.floor().max(0.0) as u32);
    let (x1, y1) = (area.max.x.ceil().min(window.0 as f32) as u32, area.max.y.ceil().min(window.1 as f32) as u32);
    Some((x0, y0, x1 - x0, y1 - y0))
}

/// One edge of a triangle for the coverage test: 1 / |∇weight| (the weight's change per pixel across the edge) and
/// whether the triangle owns the pixel centres on the edge itself.
#[derive(Clone, Copy)]
struct Edge {
    inverse_slope: f32,
    owns_centres_on_it: bool,
}

impl Edge {
    /// The edge opposite the vertex whose barycentric weight is a + b·x + c·y. A centre on the edge (egui puts
    /// vertices on pixel centres) belongs to one of the two triangles sharing it, the one the edge bounds on its left
    /// or top (the top-left rule of GPU rasterisers), so a shared edge is neither drawn twice nor left out. The weight
    /// grows inwards along (b, c): a left edge has the triangle to its right (+x), a top edge below it (+y).
    fn new((_, b, c): (f32, f32, f32)) -> Edge {
        Edge { inverse_slope: 1.0 / b.hypot(c), owns_centres_on_it: b > 0.0 || (b == 0.0 && c > 0.0) }
    }

    /// Whether a pixel centre of barycentric `weight` lies on the triangle's side of the edge (within 10⁻⁴ pixel of
    /// it: on it).
    fn covers(self, weight: f32) -> bool {
        let distance = weight * self.inverse_slope;
        if distance.abs() > 1e-4 {
            distance > 0.0
        } else {
            self.owns_centres_on_it
        }
    }
}

/// A window-aligned block of premultiplied RGBA pixels in 0..=1.
struct Canvas {
    origin: (u32, u32),
    width: u32,
    height: u32,
    pixels: Vec<[f32; 4]>,
}

impl Canvas {
    fn triangle(&mut self, v: [Vertex; 3], ppp: f32, clip: egui::Rect, texture: Option<&Texture>) {
        let p = v.map(|v| v.pos * ppp);
        let area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
        if area.abs() < 1e-12 || !area.is_finite() {
            return;
        }
        // Barycentric weight i at pixel centre (x, y) is a[i] + b[i]·x + c[i]·y (the edge opposite vertex i over the
        // area), stepped along a row.
        let weight = |i: usize| {
            let (q, r) = (p[(i + 1) % 3], p[(i + 2) % 3]);
            let (b, c) = ((q.y - r.y) / area, (r.x - q.x) / area);
            (-(b * q.x + c * q.y), b, c)
        };
        let w = [weight(0), weight(1), weight(2)];
        let edges = w.map(Edge::new);
        let (ox, oy) = (self.origin.0 as f32, self.origin.1 as f32);
        let lo = |f: fn(f32, f32) -> f32, i: usize| f(f(p[0][i], p[1][i]), p[2][i]);
        let x_start = lo(f32::min, 0).max(clip.min.x).max(ox).floor() as i64;
        let x_end = lo(f32::max, 0).min(clip.max.x).min(ox + self.width as f32).ceil() as i64;
        let y_start = lo(f32::min, 1).max(clip.min.y).max(oy).floor() as i64;
        let y_end = lo(f32::max, 1).min(clip.max.y).min(oy + self.height as f32).ceil() as i64;
        let colour = v.map(|v| v.color.to_array().map(|c| c as f32 / 255.0));
        // Solid shapes sample one texel (egui's white one) at all three corners: sample it once.
        let same_uv = v[0].uv == v[1].uv && v[1].uv == v[2].uv;
        let flat_texel = match texture {
            Some(t) if same_uv => t.sample(v[0].uv.x, v[0].uv.y),
            Some(_) => [f32::NAN; 4],
            None => [1.0; 4],
        };
        let flat_colour = colour[0] == colour[1] && colour[1] == colour[2];
        for y in y_start..y_end {
            let cy = y as f32 + 0.5;
            if cy < clip.min.y || cy >= clip.max.y {
                continue;
            }
            let row = ((y as u32 - self.origin.1) * self.width) as usize;
            // The span of this row inside the triangle (each weight is linear in x), a pixel wider each side for
            // rounding; the weights below decide each pixel. egui fills shapes as fans of long thin triangles, whose
            // bounding boxes are mostly outside them.
            let (mut from, mut to) = (x_start as f32, x_end as f32);
            for &(a, b, c) in &w {
                let rest = a + c * cy;
                if b.abs() < 1e-12 {
                    if rest < -1e-6 {
                        (from, to) = (1.0, 0.0);
                    }
                } else if b > 0.0 {
                    from = from.max((-1e-6 - rest) / b - 1.5);
                } else {
                    to = to.min((-1e-6 - rest) / b + 1.5);
                }
            }
            if from >= to {
                continue;
            }
            let span = (from.floor() as i64).max(x_start)..(to.ceil() as i64).min(x_end);
            for x in span {
                let cx = x as f32 + 0.5;
                if cx < clip.min.x || cx >= clip.max.x {
                    continue;
                }
                let wt = w.map(|(a, b, c)| a + b * cx + c * cy);
                if !(0..3).all(|i| edges[i].covers(wt[i])) {
                    continue;
                }
                let mut src = if flat_colour {
                    colour[0]
                } else {
                    std::array::from_fn(|c| wt[0] * colour[0][c] + wt[1] * colour[1][c] + wt[2] * colour[2][c])
                };
                let texel = match texture {
                    Some(texture) if !same_uv => {
                        let u = wt[0] * v[0].uv.x + wt[1] * v[1].uv.x + wt[2] * v[2].uv.x;
                        let t = wt[0] * v[0].uv.y + wt[1] * v[1].uv.y + wt[2] * v[2].uv.y;
                        texture.sample(u, t)
                    }
                    _ => flat_texel,
                };
                for (s, t) in src.iter_mut().zip(texel) {
                    *s *= t;
                }
                let dst = &mut self.pixels[row + (x as u32 - self.origin.0) as usize];
                for c in 0..4 {
                    dst[c] = src[c] + dst[c] * (1.0 - src[3]);
                }
            }
        }
    }

    /// Straight-alpha RGBA8, as the presenters blend it.
    fn into_overlay(self) -> Overlay {
        let pixels = self
            .pixels
            .iter()
            .map(|&[r, g, b, a]| {
                let straight = |c: f32| if a > 0.0 { (c / a).clamp(0.0, 1.0) } else { 0.0 };
                let byte = |c: f32| (c * 255.0 + 0.5) as u8;
                pack_rgba8([byte(straight(r)), byte(straight(g)), byte(straight(b)), byte(a.clamp(0.0, 1.0))])
            })
            .collect();
        Overlay { image: Image { width: self.width, height: self.height, pixels }, origin: self.origin }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use egui::epaint::{ClippedPrimitive, Color32, Mesh, Rect};
    use egui::{pos2, vec2};

    fn square(color: Color32, at: egui::Pos2, size: f32) -> ClippedPrimitive {
        let mut mesh = Mesh::default();
        mesh.add_colored_rect(Rect::from_min_size(at, vec2(size, size)), color);
        ClippedPrimitive { clip_rect: Rect::EVERYTHING, primitive: Primitive::Mesh(mesh) }
    }

    #[test]
    fn a_rectangle_covers_exactly_its_pixels_and_blends_over_another() {
        let mut raster = Rasterizer::default();
        let red = square(Color32::from_rgb(255, 0, 0), pos2(2.0, 3.0), 4.0);
        // Half-transparent white (premultiplied) over the red square's right half and beyond.
        let white = square(Color32::from_white_alpha(128), pos2(4.0, 3.0), 4.0);
        let overlay = raster.paint(&[red, white], 1.0, (32, 32)).expect("something is drawn");
        assert_eq!(overlay.origin, (2, 3));
        assert_eq!((overlay.image.width, overlay.image.height), (6, 4));
        assert_eq!(overlay.image.rgba(0, 0), Some([255, 0, 0, 255]));
        let over = overlay.image.rgba(2, 1).unwrap();
        assert_eq!(over[3], 255);
        assert!((over[0] as i32 - 255).abs() <= 1 && (over[1] as i32 - 128).abs() <= 1, "{over:?}");
        assert_eq!(overlay.image.rgba(5, 3).map(|p| p[3]), Some(128), "white alone stays half transparent");
        // A clip rectangle cuts the mesh; twice the pixels per point doubles its size.
        let mut clipped = square(Color32::WHITE, pos2(0.0, 0.0), 8.0);
        clipped.clip_rect = Rect::from_min_max(pos2(0.0, 0.0), pos2(3.0, 8.0));
        let overlay = raster.paint(&[clipped], 2.0, (32, 32)).unwrap();
        assert_eq!((overlay.image.width, overlay.image.height), (6, 16));
        assert!(raster.paint(&[], 1.0, (32, 32)).is_none());
        let red = square(Color32::from_rgb(255, 0, 0), pos2(2.0, 3.0), 4.0);
        let again = raster.paint(std::slice::from_ref(&red), 1.0, (32, 32));
        assert_eq!(raster.paint(&[red], 1.0, (32, 32)), again, "the same shapes give the same overlay (kept)");
    }

    #[test]
    fn textures_are_sampled_and_patched() {
        use egui::epaint::{ColorImage, ImageDelta};
        use egui::TextureOptions;
        let mut raster = Rasterizer::default();
        let id = TextureId::Managed(7);
        let mut delta = TexturesDelta::default();
        let image = ColorImage::new([2, 2], vec![Color32::from_rgb(0, 0, 255); 4]);
        delta.set.insert(id, [ImageDelta::full(image, TextureOptions::NEAREST)].into_iter().collect());
        raster.set_textures(&delta);
        delta.clear();
        let mut patch = TexturesDelta::default();
        let green = ColorImage::new([1, 1], vec![Color32::from_rgb(0, 255, 0)]);
        patch.set.insert(id, [ImageDelta::partial([1, 1], green, TextureOptions::NEAREST)].into_iter().collect());
        raster.set_textures(&patch);
        patch.clear();
        let mut mesh = Mesh::with_texture(id);
        mesh.add_rect_with_uv(
            Rect::from_min_size(pos2(0.0, 0.0), vec2(8.0, 8.0)),
            Rect::from_min_max(pos2(0.0, 0.0), pos2(1.0, 1.0)),
            Color32::WHITE,
        );
        let prim = ClippedPrimitive { clip_rect: Rect::EVERYTHING, primitive: Primitive::Mesh(mesh) };
        let overlay = raster.paint(&[prim], 1.0, (8, 8)).unwrap();
        assert_eq!(overlay.image.rgba(0, 0), Some([0, 0, 255, 255]));
        assert_eq!(overlay.image.rgba(7, 7), Some([0, 255, 0, 255]), "the patched texel");
        let mut free = TexturesDelta::default();
        free.free.insert(id);
        raster.free_textures(&free);
        free.clear();
        assert!(raster.textures.is_empty());
    }
}
