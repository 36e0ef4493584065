//! Getting frames into the window, upscaled from the render size to the window size by nearest pixel.
//!
//! - [`GpuPresenter`]: the WGSL kernel computes into a storage buffer and a full-screen pass draws that buffer to the
//!   window's wgpu surface; nothing crosses back to the host (except for screenshots). A host image (a progressive
//!   picture) is uploaded into the same buffer and drawn the same way.
//! - [`SoftPresenter`]: any image on the host (CPU and OpenCL frames, wgpu frames read back) copied into a softbuffer
//!   surface.
//!
//! Both map window pixel `d` to source pixel `((2d + 1)·src) / (2·dst)` in integer arithmetic ([`source_index`]), the
//! pixel whose area contains the window pixel's centre, so the two presenters show identical pixels.

use std::num::NonZeroU32;
use std::sync::Arc;

use fractal_dsl::back::Entry;
use fractal_render::backend::wgpu::{capture, map_read, read_back, WgpuRenderer, RENDER_WORKGROUP};
use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::Image;
use rayon::prelude::*;
use wgpu::util::DeviceExt;
use winit::window::Window;

use super::panel::Overlay;

/// The source pixel shown at window pixel `d` when `src` pixels are stretched over `dst`.
pub fn source_index(d: u32, dst: u32, src: u32) -> u32 {
    let i = ((2 * d as u64 + 1) * src as u64) / (2 * dst.max(1) as u64);
    (i as u32).min(src.saturating_sub(1))
}

/// `image` stretched to `width`×`height`, each pixel passed through `convert`, written row by row into `out`.
fn upscale_into(image: &Image, width: u32, height: u32, out: &mut [u32], convert: impl Fn(u32) -> u32 + Sync) {
    let columns: Vec<usize> = (0..width).map(|x| source_index(x, width, image.width) as usize).collect();
    let src_width = image.width as usize;
    out.par_chunks_mut(width as usize).take(height as usize).enumerate().for_each(|(y, row)| {
        let sy = source_index(y as u32, height, image.height) as usize;
        let src = &image.pixels[sy * src_width..(sy + 1) * src_width];
        for (dst, &sx) in row.iter_mut().zip(&columns) {
            *dst = convert(src[sx]);
        }
    });
}

/// `image` stretched to `width`×`height` (what the window shows for it).
pub fn upscale(image: &Image, width: u32, height: u32) -> Image {
    let mut pixels = vec![0u32; width as usize * height as usize];
    upscale_into(image, width, height, &mut pixels, |p| p);
    Image { width, height, pixels }
}

/// Kernel pixels (R in the low byte) to softbuffer pixels (0x00RRGGBB).
fn to_softbuffer(p: u32) -> u32 {
    let [r, g, b, _] = p.to_le_bytes();
    (r as u32) << 16 | (g as u32) << 8 | b as u32
}

fn from_softbuffer(p: u32) -> u32 {
    let [b, g, r, _] = p.to_le_bytes();
    u32::from_le_bytes([r, g, b, 255])
}

/// Presents host images through softbuffer.
pub struct SoftPresenter {
    _context: softbuffer::Context<Arc<Window>>,
    surface: softbuffer::Surface<Arc<Window>, Arc<Window>>,
    size: (u32, u32),
    /// The image last presented, to present again ([`SoftPresenter::redraw`]).
    source: Option<Image>,
    /// The window pixels last presented (softbuffer layout), for screenshots.
    shown: Vec<u32>,
    shown_size: (u32, u32),
}

impl SoftPresenter {
    pub fn new(window: Arc<Window>) -> Result<SoftPresenter, String> {
        let context = softbuffer::Context::new(window.clone()).map_err(|e| format!("softbuffer: {e}"))?;
        let surface = softbuffer::Surface::new(&context, window).map_err(|e| format!("softbuffer: {e}"))?;
        Ok(SoftPresenter {
            _context: context,
            surface,
            size: (0, 0),
            source: None,
            shown: Vec::new(),
            shown_size: (0, 0),
        })
    }

    /// Shows `image` stretched over a window of `window` pixels.
    pub fn present(&mut self, image: &Image, window: (u32, u32), overlay: Option<&Overlay>) -> Result<(), String> {
        match &mut self.source {
            Some(source) => source.clone_from(image),
            None => self.source = Some(image.clone()),
        }
        self.redraw(window, overlay)
    }

    /// Shows the image last presented again (with this `overlay`); nothing before the first.
    pub fn redraw(&mut self, window: (u32, u32), overlay: Option<&Overlay>) -> Result<(), String> {
        let (Some(w), Some(h), Some(image)) = (NonZeroU32::new(window.0), NonZeroU32::new(window.1), &self.source)
        else {
            return Ok(());
        };
        if self.size != window {
            self.surface.resize(w, h).map_err(|e| format!("softbuffer: {e}"))?;
            self.size = window;
        }
        let mut buffer = self.surface.buffer_mut().map_err(|e| format!("softbuffer: {e}"))?;
        upscale_into(image, window.0, window.1, &mut buffer, to_softbuffer);
        if let Some(overlay) = overlay {
            overlay.blend_over_xrgb(&mut buffer, window.0);
        }
        self.shown.clear();
        self.shown.extend_from_slice(&buffer);
        self.shown_size = window;
        buffer.present().map_err(|e| format!("softbuffer: {e}"))
    }

    /// The window as last presented.
    pub fn screenshot(&self) -> Option<Image> {
        if self.shown.is_empty() {
            return None;
        }
        let pixels = self.shown.iter().map(|&p| from_softbuffer(p)).collect();
        Some(Image { width: self.shown_size.0, height: self.shown_size.1, pixels })
    }
}

/// Full-screen pass that draws the kernel's pixel buffer to the surface, stretched by [`source_index`].
const BLIT_WGSL: &str = r#"
struct Blit {
    src_size: vec2<u32>,
    dst_size: vec2<u32>,
    overlay_origin: vec2<u32>,
    overlay_size: vec2<u32>,
    decode_srgb: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<storage, read> pixels: array<u32>;
@group(0) @binding(1) var<uniform> blit: Blit;
// The panel (RGBA8 with alpha, R in the low byte), blended over its rectangle of the window.
@group(0) @binding(2) var<storage, read> overlay: array<u32>;

@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // One triangle that covers the whole target.
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

fn source_index(d: u32, dst: u32, src: u32) -> u32 {
    return min(((2u * d + 1u) * src) / (2u * dst), src - 1u);
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    let low = c / 12.92;
    let high = pow((c + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, c <= vec3<f32>(0.04045));
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let x = source_index(u32(position.x), blit.dst_size.x, blit.src_size.x);
    let y = source_index(u32(position.y), blit.dst_size.y, blit.src_size.y);
    var rgb = unpack4x8unorm(pixels[y * blit.src_size.x + x]).rgb;
    let d = vec2<u32>(position.xy);
    if all(d >= blit.overlay_origin) && all(d < blit.overlay_origin + blit.overlay_size) {
        let o = d - blit.overlay_origin;
        let over = unpack4x8unorm(overlay[o.y * blit.overlay_size.x + o.x]);
        rgb = mix(rgb, over.rgb, over.a);
    }
    // The kernels write display-encoded colour; an sRGB target would encode it again.
    if blit.decode_srgb == 1u {
        rgb = srgb_to_linear(rgb);
    }
    return vec4<f32>(rgb, 1.0);
}
"#;

/// Why a GPU frame was not shown.
#[derive(Debug)]
pub enum GpuFrameError {
    /// The kernel or the device failed: another backend may do better.
    Render(RenderError),
    /// The surface failed: present through softbuffer instead.
    Surface(String),
}

struct PixelBuffer {
    size: (u32, u32),
    buffer: wgpu::Buffer,
}

/// What fills the pixel buffer before it is drawn to the surface.
#[derive(Clone, Copy)]
enum Fill<'a> {
    /// The WGSL kernel's frame.
    Kernel { wgsl: &'a str, frame: &'a Frame },
    /// A host image.
    Image(&'a Image),
    /// Nothing: the buffer keeps what it holds.
    Kept,
}

/// Presents wgpu frames straight from the kernel's output buffer, and host images through the same buffer.
pub struct GpuPresenter {
    surface: wgpu::Surface<'static>,
    config: wgpu::SurfaceConfiguration,
    /// Screenshots copy the surface texture; false when the surface cannot be copied from.
    copyable: bool,
    blit: wgpu::RenderPipeline,
    pixels: Option<PixelBuffer>,
}

impl GpuPresenter {
    /// A surface for `window` on the renderer's device; fails when the adapter cannot present to it.
    pub fn new(renderer: &WgpuRenderer, window: Arc<Window>) -> Result<GpuPresenter, String> {
        let size = window.inner_size();
        let surface = renderer.instance().create_surface(window).map_err(|e| e.to_string())?;
        let adapter = renderer.adapter();
        if !adapter.is_surface_supported(&surface) {
            return Err(format!("{} cannot present to this window", adapter.get_info().name));
        }
        let caps = surface.get_capabilities(adapter);
        use wgpu::TextureFormat as F;
        let format = caps
            .formats
            .iter()
            .copied()
            .find(|f| matches!(f, F::Bgra8Unorm | F::Rgba8Unorm))
            .or_else(|| caps.formats.first().copied())
            .ok_or("the surface offers no texture format")?;
        let copyable = caps.usages.contains(wgpu::TextureUsages::COPY_SRC)
            && matches!(format, F::Bgra8Unorm | F::Rgba8Unorm | F::Bgra8UnormSrgb | F::Rgba8UnormSrgb);
        let present_mode = [wgpu::PresentMode::Mailbox, wgpu::PresentMode::Immediate]
            .into_iter()
            .find(|m| caps.present_modes.contains(m))
            .unwrap_or(wgpu::PresentMode::Fifo);
        let alpha_mode = if caps.alpha_modes.contains(&wgpu::CompositeAlphaMode::Opaque) {
            wgpu::CompositeAlphaMode::Opaque
        } else {
            caps.alpha_modes.first().copied().unwrap_or(wgpu::CompositeAlphaMode::Auto)
        };
        let mut usage = wgpu::TextureUsages::RENDER_ATTACHMENT;
        if copyable {
            usage |= wgpu::TextureUsages::COPY_SRC;
        }
        let config = wgpu::SurfaceConfiguration {
            usage,
            format,
            width: size.width.max(1),
            height: size.height.max(1),
            present_mode,
            desired_maximum_frame_latency: 2,
            alpha_mode,
            view_formats: Vec::new(),
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        let device = renderer.wgpu_device();
        let (blit, error) = capture(device, || {
            surface.configure(device, &config);
            blit_pipeline(device, format)
        });
        if let Some(e) = error {
            return Err(e.to_string());
        }
        Ok(GpuPresenter { surface, config, copyable, blit, pixels: None })
    }

    /// Renders `frame` with the WGSL kernel into the pixel buffer and draws it to a window of `window` pixels.
    /// Returns the presented image when `screenshot` is set. `Ok(None)` for a frame skipped because the surface was
    /// busy or being resized.
    pub fn draw(
        &mut self,
        renderer: &mut WgpuRenderer,
        wgsl: &str,
        frame: &Frame,
        window: (u32, u32),
        screenshot: bool,
        overlay: Option<&Overlay>,
    ) -> Result<Option<Image>, GpuFrameError> {
        self.present(renderer, Fill::Kernel { wgsl, frame }, window, screenshot, overlay)
    }

    /// Uploads a host `image` (a progressive picture) into the pixel buffer and draws it, as [`GpuPresenter::draw`].
    pub fn show(
        &mut self,
        renderer: &mut WgpuRenderer,
        image: &Image,
        window: (u32, u32),
        screenshot: bool,
        overlay: Option<&Overlay>,
    ) -> Result<Option<Image>, GpuFrameError> {
        self.present(renderer, Fill::Image(image), window, screenshot, overlay)
    }

    /// Draws the pixel buffer again as it is (with this `overlay`), as [`GpuPresenter::draw`]; nothing before the
    /// first frame.
    pub fn redraw(
        &mut self,
        renderer: &mut WgpuRenderer,
        window: (u32, u32),
        screenshot: bool,
        overlay: Option<&Overlay>,
    ) -> Result<Option<Image>, GpuFrameError> {
        self.present(renderer, Fill::Kept, window, screenshot, overlay)
    }

    fn present(
        &mut self,
        renderer: &mut WgpuRenderer,
        fill: Fill,
        window: (u32, u32),
        screenshot: bool,
        overlay: Option<&Overlay>,
    ) -> Result<Option<Image>, GpuFrameError> {
        if window.0 == 0 || window.1 == 0 {
            return Ok(None);
        }
        if (self.config.width, self.config.height) != window {
            self.config.width = window.0;
            self.config.height = window.1;
            self.configure(renderer)?;
        }
        let (passes, (width, height)) = match fill {
            Fill::Kernel { wgsl, frame } => {
                let size = (frame.width(), frame.height());
                (Some(renderer.pixel_passes(Entry::Render, wgsl, size).map_err(GpuFrameError::Render)?), size)
            }
            Fill::Image(image) => (None, (image.width, image.height)),
            Fill::Kept => match &self.pixels {
                Some(pixels) => (None, pixels.size),
                None => return Ok(None),
            },
        };
        let bytes = width as u64 * height as u64 * 4;
        let device = renderer.wgpu_device().clone();
        let queue = renderer.queue().clone();
        let limits = device.limits();
        let groups = (width.div_ceil(RENDER_WORKGROUP), height.div_ceil(RENDER_WORKGROUP));
        if bytes > limits.max_storage_buffer_binding_size.min(limits.max_buffer_size)
            || groups.0 > limits.max_compute_workgroups_per_dimension
            || groups.1 > limits.max_compute_workgroups_per_dimension
        {
            return Err(GpuFrameError::Render(RenderError::TooLarge {
                backend: Backend::Wgpu,
                what: format!("a {width}x{height} image"),
                detail: "larger than the device's storage buffers or workgroup grid".to_string(),
            }));
        }
        let device_error = |e: wgpu::Error| {
            GpuFrameError::Render(RenderError::Device { backend: Backend::Wgpu, message: e.to_string() })
        };
        if self.pixels.as_ref().is_none_or(|p| p.size != (width, height)) {
            self.pixels = None;
            let (buffer, error) = capture(&device, || {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("viewer pixels"),
                    size: bytes,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            });
            if let Some(e) = error {
                return Err(device_error(e));
            }
            self.pixels = Some(PixelBuffer { size: (width, height), buffer });
        }
        let Some(pixels) = self.pixels.as_ref() else {
            return Ok(None);
        };
        // Uploaded before the surface is asked for a texture, so a skipped frame still leaves the buffer holding
        // the picture a later redraw shows.
        if let Fill::Image(image) = fill {
            if image.pixels.len() as u64 * 4 != bytes {
                return Err(GpuFrameError::Render(RenderError::Device {
                    backend: Backend::Wgpu,
                    message: format!("a {width}x{height} image with {} pixels", image.pixels.len()),
                }));
            }
            let ((), error) =
                capture(&device, || queue.write_buffer(&pixels.buffer, 0, bytemuck::cast_slice(&image.pixels)));
            if let Some(e) = error {
                return Err(device_error(e));
            }
        }

        let texture = match self.surface.get_current_texture() {
            wgpu::CurrentSurfaceTexture::Success(t) | wgpu::CurrentSurfaceTexture::Suboptimal(t) => t,
            wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => return Ok(None),
            wgpu::CurrentSurfaceTexture::Outdated => {
                self.configure(renderer)?;
                return Ok(None);
            }
            other => return Err(GpuFrameError::Surface(format!("cannot get the next surface texture: {other:?}"))),
        };

        let row_bytes = (window.0 * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let (readback, error) = capture(&device, || {
            let decode_srgb = self.config.format.is_srgb() as u32;
            // No panel: an empty rectangle over a one-word buffer (a binding cannot be empty).
            let (origin, size, words) = match overlay {
                Some(o) => (o.origin, (o.image.width, o.image.height), o.image.pixels.as_slice()),
                None => ((0, 0), (0, 0), &[0u32][..]),
            };
            let uniform_words =
                [width, height, window.0, window.1, origin.0, origin.1, size.0, size.1, decode_srgb, 0, 0, 0];
            let blit_uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("blit"),
                contents: bytemuck::cast_slice(&uniform_words),
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let overlay_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("panel"),
                contents: bytemuck::cast_slice(words),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let blit_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("blit"),
                layout: &self.blit.get_bind_group_layout(0),
                entries: &[
                    wgpu::BindGroupEntry { binding: 0, resource: pixels.buffer.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 1, resource: blit_uniform.as_entire_binding() },
                    wgpu::BindGroupEntry { binding: 2, resource: overlay_buffer.as_entire_binding() },
                ],
            });
            let view = texture.texture.create_view(&wgpu::TextureViewDescriptor::default());
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("viewer") });
            if let (Some(passes), Fill::Kernel { frame, .. }) = (&passes, fill) {
                let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("frame"),
                    contents: frame.as_bytes(),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                passes.record(&device, &mut encoder, &uniform, &pixels.buffer, None);
            }
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("blit"),
                    color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                        view: &view,
                        depth_slice: None,
                        resolve_target: None,
                        ops: wgpu::Operations {
                            load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                            store: wgpu::StoreOp::Store,
                        },
                    })],
                    ..Default::default()
                });
                pass.set_pipeline(&self.blit);
                pass.set_bind_group(0, &blit_group, &[]);
                pass.draw(0..3, 0..1);
            }
            let readback = (screenshot && self.copyable).then(|| {
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("screenshot"),
                    size: row_bytes as u64 * window.1 as u64,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                encoder.copy_texture_to_buffer(
                    texture.texture.as_image_copy(),
                    wgpu::TexelCopyBufferInfo {
                        buffer: &buffer,
                        layout: wgpu::TexelCopyBufferLayout {
                            offset: 0,
                            bytes_per_row: Some(row_bytes),
                            rows_per_image: None,
                        },
                    },
                    wgpu::Extent3d { width: window.0, height: window.1, depth_or_array_layers: 1 },
                );
                buffer
            });
            queue.submit([encoder.finish()]);
            readback
        });
        if let Some(e) = error {
            // The compute pass and the blit share the submission; the surface path is given up first, and the
            // readback path then shows whether the kernel itself fails.
            return Err(GpuFrameError::Surface(e.to_string()));
        }
        queue.present(texture);
        if !screenshot {
            return Ok(None);
        }
        let image = match readback {
            Some(buffer) => self.read_surface_copy(&device, &buffer, window, row_bytes),
            // The surface cannot be copied: what it shows is the pixel buffer stretched the same way.
            None => read_buffer(&device, &queue, &pixels.buffer, bytes)
                .map(|words| upscale(&Image { width, height, pixels: words }, window.0, window.1)),
        };
        image
            .map(Some)
            .map_err(|message| GpuFrameError::Render(RenderError::Device { backend: Backend::Wgpu, message }))
    }

    fn configure(&self, renderer: &WgpuRenderer) -> Result<(), GpuFrameError> {
        let ((), error) =
            capture(renderer.wgpu_device(), || self.surface.configure(renderer.wgpu_device(), &self.config));
        match error {
            Some(e) => Err(GpuFrameError::Surface(format!("cannot configure the surface: {e}"))),
            None => Ok(()),
        }
    }

    fn read_surface_copy(
        &self,
        device: &wgpu::Device,
        buffer: &wgpu::Buffer,
        window: (u32, u32),
        row_bytes: u32,
    ) -> Result<Image, String> {
        let bytes = map_read(device, buffer, buffer.size())?;
        let bgra = matches!(self.config.format, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb);
        let mut pixels = Vec::with_capacity(window.0 as usize * window.1 as usize);
        for row in bytes.chunks_exact(row_bytes as usize).take(window.1 as usize) {
            for texel in row[..window.0 as usize * 4].chunks_exact(4) {
                let [a, b, c, _] = [texel[0], texel[1], texel[2], texel[3]];
                let rgb = if bgra { [c, b, a] } else { [a, b, c] };
                pixels.push(u32::from_le_bytes([rgb[0], rgb[1], rgb[2], 255]));
            }
        }
        Ok(Image { width: window.0, height: window.1, pixels })
    }
}

fn blit_pipeline(device: &wgpu::Device, format: wgpu::TextureFormat) -> wgpu::RenderPipeline {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("blit"),
        source: wgpu::ShaderSource::Wgsl(BLIT_WGSL.into()),
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("blit"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vs_main"),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fs_main"),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Copies `bytes` of `source` to a new mappable buffer and reads them as u32 words.
fn read_buffer(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    source: &wgpu::Buffer,
    bytes: u64,
) -> Result<Vec<u32>, String> {
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("pixels readback"),
        size: bytes,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    read_back(device, queue, source, &readback, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn upscaling_picks_the_covering_pixel() {
        assert_eq!((0..4).map(|d| source_index(d, 4, 2)).collect::<Vec<_>>(), vec![0, 0, 1, 1]);
        assert_eq!((0..3).map(|d| source_index(d, 3, 3)).collect::<Vec<_>>(), vec![0, 1, 2], "1:1 is the identity");
        assert_eq!(
            (0..2).map(|d| source_index(d, 2, 4)).collect::<Vec<_>>(),
            vec![1, 3],
            "downscaling samples centres"
        );
        assert_eq!(source_index(16383, 16384, 16384), 16383);
        let image = Image { width: 2, height: 1, pixels: vec![1, 2] };
        assert_eq!(upscale(&image, 4, 2).pixels, vec![1, 1, 2, 2, 1, 1, 2, 2]);
    }

    #[test]
    fn softbuffer_pixels_round_trip() {
        let p = u32::from_le_bytes([10, 20, 30, 255]);
        assert_eq!(to_softbuffer(p), 0x000a_141e);
        assert_eq!(from_softbuffer(to_softbuffer(p)), p);
    }
}
