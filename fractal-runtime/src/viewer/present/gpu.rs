//! [`GpuPresenter`]: the WGSL kernel computes into a storage buffer and the blit (module `blit`) draws that buffer
//! to the window's wgpu surface, in one submission; nothing crosses back to the host except screenshots. A host
//! image (a progressive picture, a frame in f64) is uploaded into the same buffer and drawn the same way. The UI is
//! drawn over it in the blit's pass by egui-wgpu, from the meshes egui laid out (`UiPaint`). Without a
//! window (`fractal view --headless`) the target is a texture of the window's size, frames are kept in flight as a
//! swapchain keeps them, and the device's timestamps time the kernel and the blit of each frame.

use std::collections::VecDeque;
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use fractal_dsl::back::Entry;
use fractal_render::backend::wgpu::{capture, check_size, map_read, read_back, WgpuRenderer};
use fractal_render::device::Backend;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::Image;
use winit::window::Window;

use super::blit::Blit;
use super::stretch::upscale;
use crate::viewer::ui::UiPaint;

/// Frames a texture target keeps in flight: the surface's `desired_maximum_frame_latency`.
const MAX_LATENCY: usize = 2;

/// Why a GPU frame was not shown.
#[derive(Debug)]
pub enum GpuFrameError {
    /// The kernel or the device failed: another backend may do better.
    Render(RenderError),
    /// The surface failed: present through softbuffer instead.
    Surface(String),
}

/// The device time of one frame's passes, from its timestamps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PassTimes {
    /// The kernel's passes; `None` for a host image uploaded.
    pub kernel_ms: Option<f64>,
    pub blit_ms: f64,
}

/// What the presenter draws to.
enum Target {
    /// A window's surface.
    Surface {
        surface: wgpu::Surface<'static>,
        config: wgpu::SurfaceConfiguration,
        /// Screenshots copy the surface texture; false when the surface cannot be copied from.
        copyable: bool,
    },
    /// A texture that stands in for the window; made again at each new window size.
    Texture { texture: Option<wgpu::Texture>, format: wgpu::TextureFormat },
}

/// The texture a frame is drawn into.
enum Drawable {
    Surface(wgpu::SurfaceTexture),
    Texture(wgpu::Texture),
}

impl Drawable {
    fn texture(&self) -> &wgpu::Texture {
        match self {
            Drawable::Surface(s) => &s.texture,
            Drawable::Texture(t) => t,
        }
    }
}

/// What fills the pixel buffer before it is drawn to the target.
#[derive(Clone, Copy)]
enum Fill<'a> {
    /// The WGSL kernel's frame.
    Kernel { wgsl: &'a str, frame: &'a Frame },
    /// A host image.
    Image(&'a Image),
    /// Nothing: the buffer keeps what it holds.
    Kept,
}

/// Timestamps of a texture target's frames: four per frame (kernel begin and end, blit begin and end), resolved in
/// the frame's submission into one of `reads`, one per frame that may be in flight.
struct Stamps {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    reads: Vec<wgpu::Buffer>,
    period_ns: f64,
}

/// A texture target's frame, submitted and not yet complete.
struct Pending {
    submission: wgpu::SubmissionIndex,
    stamps: Option<PendingStamps>,
}

/// A frame's timestamps on their way to the host.
struct PendingStamps {
    /// The readback in [`Stamps::reads`].
    slot: usize,
    mapped: mpsc::Receiver<Result<(), wgpu::BufferAsyncError>>,
    /// Whether the kernel ran (a host image was not computed).
    kernel: bool,
}

/// Presents wgpu frames straight from the kernel's output buffer, and host images through the same buffer.
pub struct GpuPresenter {
    target: Target,
    blit: Blit,
    /// egui's painter for the target's format, and the textures egui freed, forgotten before the next frame.
    ui: egui_wgpu::Renderer,
    ui_freed: Vec<egui::TextureId>,
    /// The kernel's pixels (or an uploaded image) and their size.
    pixels: Option<((u32, u32), wgpu::Buffer)>,
    /// The frame uniform, rewritten per frame.
    uniform: Option<wgpu::Buffer>,
    stamps: Option<Stamps>,
    pending: VecDeque<Pending>,
    submitted: usize,
    times: Vec<PassTimes>,
    /// Time the host has spent waiting for frames in flight.
    waited: Duration,
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
            desired_maximum_frame_latency: MAX_LATENCY as u32,
            alpha_mode,
            view_formats: Vec::new(),
            color_space: wgpu::SurfaceColorSpace::Auto,
        };
        let device = renderer.wgpu_device();
        let ((blit, ui), error) = capture(device, || {
            surface.configure(device, &config);
            (Blit::new(device, format), ui_painter(device, format))
        });
        if let Some(e) = error {
            return Err(e.to_string());
        }
        Ok(GpuPresenter::with_target(Target::Surface { surface, config, copyable }, (blit, ui), None))
    }

    /// A presenter with no window: frames are drawn into a texture of the window's size, as they would be to a
    /// surface, and timed by the device's timestamps where the renderer's device has them.
    pub fn offscreen(renderer: &WgpuRenderer) -> Result<GpuPresenter, String> {
        let device = renderer.wgpu_device();
        let format = wgpu::TextureFormat::Rgba8Unorm;
        let ((blit, ui, stamps), error) =
            capture(device, || (Blit::new(device, format), ui_painter(device, format), stamps(renderer)));
        if let Some(e) = error {
            return Err(e.to_string());
        }
        Ok(GpuPresenter::with_target(Target::Texture { texture: None, format }, (blit, ui), stamps))
    }

    fn with_target(target: Target, (blit, ui): (Blit, egui_wgpu::Renderer), stamps: Option<Stamps>) -> GpuPresenter {
        GpuPresenter {
            target,
            blit,
            ui,
            ui_freed: Vec::new(),
            pixels: None,
            uniform: None,
            stamps,
            pending: VecDeque::new(),
            submitted: 0,
            times: Vec::new(),
            waited: Duration::ZERO,
        }
    }

    /// `"wgpu surface"`, or `"wgpu texture"` without a window.
    pub fn name(&self) -> &'static str {
        match self.target {
            Target::Surface { .. } => "wgpu surface",
            Target::Texture { .. } => "wgpu texture",
        }
    }

    /// Renders `frame` with the WGSL kernel into the pixel buffer and draws it to a window of `window` pixels, with
    /// the UI over it. Returns the presented image when `screenshot` is set. `Ok(None)` for a frame skipped because
    /// the surface was busy or being resized.
    pub fn draw(
        &mut self,
        renderer: &mut WgpuRenderer,
        (wgsl, frame): (&str, &Frame),
        window: (u32, u32),
        screenshot: bool,
        ui: Option<&mut UiPaint>,
    ) -> Result<Option<Image>, GpuFrameError> {
        self.present(renderer, Fill::Kernel { wgsl, frame }, window, screenshot, ui)
    }

    /// Uploads a host `image` (a progressive picture) into the pixel buffer and draws it, as [`GpuPresenter::draw`].
    pub fn show(
        &mut self,
        renderer: &mut WgpuRenderer,
        image: &Image,
        window: (u32, u32),
        screenshot: bool,
        ui: Option<&mut UiPaint>,
    ) -> Result<Option<Image>, GpuFrameError> {
        self.present(renderer, Fill::Image(image), window, screenshot, ui)
    }

    /// Draws the pixel buffer again as it is (with this `ui`), as [`GpuPresenter::draw`]; nothing before the
    /// first frame.
    pub fn redraw(
        &mut self,
        renderer: &mut WgpuRenderer,
        window: (u32, u32),
        screenshot: bool,
        ui: Option<&mut UiPaint>,
    ) -> Result<Option<Image>, GpuFrameError> {
        self.present(renderer, Fill::Kept, window, screenshot, ui)
    }

    /// The time the host has spent waiting for a texture target's frames in flight, so far.
    pub fn waited(&self) -> Duration {
        self.waited
    }

    /// Waits for every frame in flight (a texture target's) and hands over the device times of the frames completed
    /// since the last call.
    pub fn finish(&mut self, renderer: &WgpuRenderer) -> Result<Vec<PassTimes>, GpuFrameError> {
        while !self.pending.is_empty() {
            self.complete_oldest(renderer.wgpu_device())?;
        }
        Ok(std::mem::take(&mut self.times))
    }

    fn present(
        &mut self,
        renderer: &mut WgpuRenderer,
        fill: Fill,
        window: (u32, u32),
        screenshot: bool,
        mut ui: Option<&mut UiPaint>,
    ) -> Result<Option<Image>, GpuFrameError> {
        if window.0 == 0 || window.1 == 0 {
            return Ok(None);
        }
        let (passes, size) = match fill {
            Fill::Kernel { wgsl, frame } => {
                let size = (frame.width(), frame.height());
                check_size(renderer.wgpu_device(), size, 0).map_err(GpuFrameError::Render)?;
                (Some(renderer.pixel_passes(Entry::Render, wgsl, size).map_err(GpuFrameError::Render)?), size)
            }
            Fill::Image(image) => (None, (image.width, image.height)),
            Fill::Kept => match &self.pixels {
                Some((size, _)) => (None, *size),
                None => return Ok(None),
            },
        };
        let device = renderer.wgpu_device().clone();
        let queue = renderer.queue().clone();
        let device_error =
            |e: String| GpuFrameError::Render(RenderError::Device { backend: Backend::Wgpu, message: e });
        let pixels = self.pixel_buffer(&device, size).map_err(device_error)?;
        // Uploaded before the target is asked for a texture, so a skipped frame still leaves the buffer holding
        // the picture a later redraw shows.
        if let Fill::Image(image) = fill {
            if image.pixels.len() as u64 * 4 != pixels.size() {
                return Err(device_error(format!("a {}x{} image with {} pixels", size.0, size.1, image.pixels.len())));
            }
            let ((), error) = capture(&device, || queue.write_buffer(&pixels, 0, bytemuck::cast_slice(&image.pixels)));
            error.map_or(Ok(()), |e| Err(device_error(e.to_string())))?;
        }
        // egui's textures are applied whether or not this frame is shown: egui sends each change once.
        let ((), error) = capture(&device, || self.apply_ui_textures((&device, &queue), ui.as_deref_mut()));
        error.map_or(Ok(()), |e| Err(device_error(e.to_string())))?;
        let Some(drawable) = self.acquire(&device, window)? else {
            return Ok(None);
        };
        let row_bytes = (window.0 * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
        let slot = self.submitted % (MAX_LATENCY + 1);
        let ((submission, readback), error) = capture(&device, || {
            let group = self.blit.prepare((&device, &queue), (&pixels, size), window);
            let uniform = match fill {
                Fill::Kernel { frame, .. } => Some(self.write_uniform((&device, &queue), frame.as_bytes())),
                _ => None,
            };
            let stamps = self.stamps.as_ref();
            let view = drawable.texture().create_view(&wgpu::TextureViewDescriptor::default());
            let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("viewer") });
            if let (Some(passes), Some(uniform)) = (&passes, &uniform) {
                passes.record_timed(&device, &mut encoder, (uniform, &pixels, None), stamps.map(|s| &s.set));
            }
            let ui = ui.as_deref().filter(|ui| ui.rect.is_some() && ui.window == window);
            let screen = ui.map(|ui| egui_wgpu::ScreenDescriptor {
                size_in_pixels: [window.0, window.1],
                pixels_per_point: ui.pixels_per_point,
            });
            let mut prepared = Vec::new();
            if let (Some(ui), Some(screen)) = (ui, &screen) {
                prepared = self.ui.update_buffers(&device, &queue, &mut encoder, &ui.primitives, screen);
            }
            let painter = &self.ui;
            self.blit.record(&mut encoder, &view, &group, stamps.map(|s| &s.set), |pass| {
                if let (Some(ui), Some(screen)) = (ui, &screen) {
                    painter.render(pass, &ui.primitives, screen);
                }
            });
            if let Some(s) = stamps {
                encoder.resolve_query_set(&s.set, 0..4, &s.resolve, 0);
                encoder.copy_buffer_to_buffer(&s.resolve, 0, &s.reads[slot], 0, 32);
            }
            let readback = (screenshot && self.copyable()).then(|| {
                let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("screenshot"),
                    size: row_bytes as u64 * window.1 as u64,
                    usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                encoder.copy_texture_to_buffer(
                    drawable.texture().as_image_copy(),
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
            (queue.submit(prepared.into_iter().chain([encoder.finish()])), readback)
        });
        if let Some(e) = error {
            // The compute pass and the blit share the submission; the surface path is given up first, and the
            // readback path then shows whether the kernel itself fails.
            return Err(GpuFrameError::Surface(e.to_string()));
        }
        self.submitted += 1;
        match drawable {
            Drawable::Surface(texture) => queue.present(texture),
            Drawable::Texture(_) => self.keep_in_flight(&device, submission, slot, passes.is_some())?,
        }
        if !screenshot {
            return Ok(None);
        }
        let image = match readback {
            Some(buffer) => self.read_target_copy(&device, &buffer, window, row_bytes),
            // The surface cannot be copied: what it shows is the pixel buffer stretched the same way.
            None => read_buffer(&device, &queue, &pixels, pixels.size())
                .map(|words| upscale(&Image { width: size.0, height: size.1, pixels: words }, window.0, window.1)),
        };
        image.map(Some).map_err(device_error)
    }

    /// Forgets the textures egui freed after the frame before, and applies the ones `ui` set since the last frame
    /// this presenter drew (taking them from it). Call inside an error scope.
    fn apply_ui_textures(&mut self, (device, queue): (&wgpu::Device, &wgpu::Queue), ui: Option<&mut UiPaint>) {
        for id in self.ui_freed.drain(..) {
            self.ui.free_texture(&id);
        }
        let Some(ui) = ui else {
            return;
        };
        let textures = &mut ui.textures;
        for (id, deltas) in textures.set.drain() {
            for delta in &deltas {
                self.ui.update_texture(device, queue, id, delta);
            }
        }
        self.ui_freed.extend(textures.free.drain());
    }

    /// The pixel buffer for images of `size`, made where the kept one has another size.
    fn pixel_buffer(&mut self, device: &wgpu::Device, size: (u32, u32)) -> Result<wgpu::Buffer, String> {
        if let Some((kept, buffer)) = &self.pixels {
            if *kept == size {
                return Ok(buffer.clone());
            }
        }
        self.pixels = None;
        let (buffer, error) = capture(device, || {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("viewer pixels"),
                size: size.0 as u64 * size.1 as u64 * 4,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        });
        if let Some(e) = error {
            return Err(e.to_string());
        }
        self.pixels = Some((size, buffer.clone()));
        Ok(buffer)
    }

    /// The frame uniform, holding `contents` once the next submission starts; made anew where its size changes.
    fn write_uniform(&mut self, (device, queue): (&wgpu::Device, &wgpu::Queue), contents: &[u8]) -> wgpu::Buffer {
        let uniform = match self.uniform.take() {
            Some(kept) if kept.size() == contents.len() as u64 => kept,
            _ => device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("frame"),
                size: contents.len() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
        };
        queue.write_buffer(&uniform, 0, contents);
        self.uniform = Some(uniform.clone());
        uniform
    }

    /// The texture to draw this frame into, resized to `window` first; `None` when the surface skips the frame.
    fn acquire(&mut self, device: &wgpu::Device, window: (u32, u32)) -> Result<Option<Drawable>, GpuFrameError> {
        match &mut self.target {
            Target::Surface { surface, config, .. } => {
                if (config.width, config.height) != window {
                    (config.width, config.height) = window;
                    configure(device, surface, config)?;
                }
                match surface.get_current_texture() {
                    wgpu::CurrentSurfaceTexture::Success(t) | wgpu::CurrentSurfaceTexture::Suboptimal(t) => {
                        Ok(Some(Drawable::Surface(t)))
                    }
                    wgpu::CurrentSurfaceTexture::Timeout | wgpu::CurrentSurfaceTexture::Occluded => Ok(None),
                    wgpu::CurrentSurfaceTexture::Outdated => configure(device, surface, config).map(|()| None),
                    other => Err(GpuFrameError::Surface(format!("cannot get the next surface texture: {other:?}"))),
                }
            }
            Target::Texture { texture, format } => {
                let extent = wgpu::Extent3d { width: window.0, height: window.1, depth_or_array_layers: 1 };
                if let Some(kept) = texture.as_ref().filter(|t| t.size() == extent) {
                    return Ok(Some(Drawable::Texture(kept.clone())));
                }
                let (made, error) = capture(device, || {
                    device.create_texture(&wgpu::TextureDescriptor {
                        label: Some("window"),
                        size: extent,
                        mip_level_count: 1,
                        sample_count: 1,
                        dimension: wgpu::TextureDimension::D2,
                        format: *format,
                        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                        view_formats: &[],
                    })
                });
                if let Some(e) = error {
                    return Err(GpuFrameError::Surface(format!("cannot make a {}x{} target: {e}", window.0, window.1)));
                }
                *texture = Some(made.clone());
                Ok(Some(Drawable::Texture(made)))
            }
        }
    }

    fn copyable(&self) -> bool {
        match self.target {
            Target::Surface { copyable, .. } => copyable,
            Target::Texture { .. } => true,
        }
    }

    /// Keeps a texture target's frame in flight, waiting for the oldest while more than [`MAX_LATENCY`] are.
    fn keep_in_flight(
        &mut self,
        device: &wgpu::Device,
        submission: wgpu::SubmissionIndex,
        slot: usize,
        kernel: bool,
    ) -> Result<(), GpuFrameError> {
        let stamps = self.stamps.as_ref().map(|s| {
            let (sender, mapped) = mpsc::channel();
            s.reads[slot].slice(..).map_async(wgpu::MapMode::Read, move |result| {
                let _ = sender.send(result);
            });
            PendingStamps { slot, mapped, kernel }
        });
        self.pending.push_back(Pending { submission, stamps });
        while self.pending.len() > MAX_LATENCY {
            self.complete_oldest(device)?;
        }
        Ok(())
    }

    /// Waits for the oldest frame in flight and reads its timestamps.
    fn complete_oldest(&mut self, device: &wgpu::Device) -> Result<(), GpuFrameError> {
        let Some(frame) = self.pending.pop_front() else {
            return Ok(());
        };
        let lost = |e: String| GpuFrameError::Render(RenderError::Device { backend: Backend::Wgpu, message: e });
        let wait = wgpu::PollType::Wait { submission_index: Some(frame.submission), timeout: None };
        let started = Instant::now();
        device.poll(wait).map_err(|e| lost(e.to_string()))?;
        self.waited += started.elapsed();
        let (Some(PendingStamps { slot, mapped, kernel }), Some(stamps)) = (frame.stamps, &self.stamps) else {
            return Ok(());
        };
        mapped.recv().map_err(|e| lost(e.to_string()))?.map_err(|e| lost(e.to_string()))?;
        let read = &stamps.reads[slot];
        let ticks: Vec<u64> =
            bytemuck::pod_collect_to_vec(&read.slice(..).get_mapped_range().map_err(|e| lost(e.to_string()))?);
        read.unmap();
        let ms = |from: u64, to: u64| (to > from).then(|| (to - from) as f64 * stamps.period_ns / 1e6);
        if let Some(blit_ms) = ms(ticks[2], ticks[3]) {
            self.times.push(PassTimes { kernel_ms: kernel.then(|| ms(ticks[0], ticks[1])).flatten(), blit_ms });
        }
        Ok(())
    }

    fn read_target_copy(
        &self,
        device: &wgpu::Device,
        buffer: &wgpu::Buffer,
        window: (u32, u32),
        row_bytes: u32,
    ) -> Result<Image, String> {
        let bytes = map_read(device, buffer, buffer.size())?;
        let format = match &self.target {
            Target::Surface { config, .. } => config.format,
            Target::Texture { format, .. } => *format,
        };
        let bgra = matches!(format, wgpu::TextureFormat::Bgra8Unorm | wgpu::TextureFormat::Bgra8UnormSrgb);
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

/// egui-wgpu's painter for targets of `format`: no depth, one sample, no dithering (the UI's pixels are the same
/// from frame to frame, as the host's overlay's are). Call inside an error scope.
fn ui_painter(device: &wgpu::Device, format: wgpu::TextureFormat) -> egui_wgpu::Renderer {
    let options = egui_wgpu::RendererOptions { dithering: false, ..egui_wgpu::RendererOptions::default() };
    egui_wgpu::Renderer::new(device, format, options)
}

fn configure(
    device: &wgpu::Device,
    surface: &wgpu::Surface,
    config: &wgpu::SurfaceConfiguration,
) -> Result<(), GpuFrameError> {
    let ((), error) = capture(device, || surface.configure(device, config));
    match error {
        Some(e) => Err(GpuFrameError::Surface(format!("cannot configure the surface: {e}"))),
        None => Ok(()),
    }
}

/// The timestamp queries and buffers of a texture target, where the renderer's device has timestamp queries.
fn stamps(renderer: &WgpuRenderer) -> Option<Stamps> {
    let device = renderer.wgpu_device();
    if !device.features().contains(wgpu::Features::TIMESTAMP_QUERY) {
        return None;
    }
    let buffer = |label, usage| {
        device.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size: 32, usage, mapped_at_creation: false })
    };
    Some(Stamps {
        set: device.create_query_set(&wgpu::QuerySetDescriptor {
            label: Some("viewer frame"),
            ty: wgpu::QueryType::Timestamp,
            count: 4,
        }),
        resolve: buffer("timestamps", wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC),
        reads: (0..=MAX_LATENCY)
            .map(|_| buffer("timestamps readback", wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST))
            .collect(),
        period_ns: f64::from(renderer.queue().get_timestamp_period()),
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
