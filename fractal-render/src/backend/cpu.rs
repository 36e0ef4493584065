//! The CPU renderer: the ray program ([`fractal_dsl::ray`]) over a scene's [`Evaluator`], one rayon task per image
//! row. Generic over the precision, so the f64 instance renders reference images for accuracy work. In f32, where
//! the evaluator has a packet instance ([`Evaluator::packets`]), eight neighbouring pixels are traced together
//! ([`render_packets`]): the same program on [`F32x8`] lanes, with a lane whose march ends taking the row's next ray.
//!
//! What is this renderer's own: the pixel loop and the lane scheduling; colours are packed as the kernels pack them
//! ([`pack_linear`]). It reads the camera, lights, time and parameters from the same [`Frame`] uniforms the kernels
//! read.

use fractal_dsl::analyse::{bound, fold::fold_node, Aabb};
use fractal_dsl::eval::{Env, Evaluator, PacketEvaluator, Reference, Sample};
use fractal_dsl::number::lanes::{F32x8, LANES};
use fractal_dsl::number::math::{v3, Real, V3};
use fractal_dsl::number::Num;
use fractal_dsl::ray::march::{self, March};
use fractal_dsl::ray::pixel::{self, Accumulated};
use fractal_dsl::ray::{self, shade, Light, Rules, SceneFns};
use fractal_dsl::Scene;
use rayon::prelude::*;
use std::cell::Cell;

use crate::device::{Backend, DeviceInfo};
use crate::error::{FrameError, RenderError};
use crate::frame::{Frame, LightSlot};
use crate::image::{pack_linear, unpack_rgba8, Image};
use crate::precision::Precision;
pub use crate::renderer::PixelTrace;
use crate::renderer::{CpuKernel, RenderJob, Renderer, Traced};

/// Renders with the job's CPU evaluator on all cores.
#[derive(Clone, Debug, Default)]
pub struct CpuRenderer {
    _private: (),
}

impl CpuRenderer {
    pub fn new() -> CpuRenderer {
        CpuRenderer { _private: () }
    }
}

impl Renderer for CpuRenderer {
    fn render(&mut self, job: &RenderJob) -> Result<Image, RenderError> {
        let kernel =
            job.kernels.cpu.ok_or(RenderError::MissingKernel { backend: Backend::Cpu, what: "CPU evaluator" })?;
        match (job.precision, kernel.evaluator.packets()) {
            (Precision::F64, _) => render_scene::<f64, _>(wide(&kernel)?, kernel.scene, job.frame),
            (Precision::F32, Some(packets)) => render_packets(packets, kernel.scene, job.frame),
            (Precision::F32, None) => render_scene::<f32, _>(kernel.evaluator, kernel.scene, job.frame),
        }
    }

    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError> {
        let kernel =
            job.kernels.cpu.ok_or(RenderError::MissingKernel { backend: Backend::Cpu, what: "CPU evaluator" })?;
        let pixels = match job.precision {
            Precision::F32 => trace_scene::<f32, _>(kernel.evaluator, kernel.scene, job.frame)?,
            Precision::F64 => trace_scene::<f64, _>(wide(&kernel)?, kernel.scene, job.frame)?,
        };
        let gamma = kernel.scene.settings.gamma;
        let packed =
            pixels.iter().map(|p| pack_linear(v3(p.colour[0] as f32, p.colour[1] as f32, p.colour[2] as f32), gamma));
        let image = Image { width: job.width(), height: job.height(), pixels: packed.collect() };
        Ok(Traced { image, pixels })
    }

    fn draws_in(&self, job: &RenderJob) -> bool {
        match job.precision {
            Precision::F32 => true,
            Precision::F64 => job.kernels.cpu.is_some_and(|kernel| kernel.wide.is_some()),
        }
    }

    fn device(&self) -> DeviceInfo {
        DeviceInfo {
            backend: Backend::Cpu,
            api: "rayon".to_string(),
            name: cpu_name(),
            // The march runs packets where the evaluator has them (the native evaluator and the interpreter do).
            driver: format!(
                "{} threads, rays in packets of {LANES} f32 lanes, {}",
                rayon::current_num_threads(),
                fractal_dsl::number::lanes::instruction_set()
            ),
            device_type: "Cpu".to_string(),
        }
    }
}

/// The f64 evaluator of a job in f64.
fn wide<'a>(kernel: &CpuKernel<'a>) -> Result<&'a dyn Evaluator<f64>, RenderError> {
    kernel.wide.ok_or(RenderError::MissingKernel { backend: Backend::Cpu, what: "f64 CPU evaluator" })
}

fn cpu_name() -> String {
    // Linux names the CPU in /proc/cpuinfo; elsewhere the architecture is the best cheap description.
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, name)| name.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string())
}

/// Renders `scene` seen through `frame` with `evaluator`, in precision `F`.
pub fn render_scene<F: Real, E: Evaluator<F> + ?Sized>(
    evaluator: &E,
    scene: &Scene,
    frame: &Frame,
) -> Result<Image, RenderError> {
    render_with_bound(evaluator, scene, frame, bound(&fold_node(&scene.root)))
}

/// [`render_scene`] with the scene bound given rather than computed (the kernels embed it as constants).
fn render_with_bound<F: Real, E: Evaluator<F> + ?Sized>(
    evaluator: &E,
    scene: &Scene,
    frame: &Frame,
    scene_bound: Option<Aabb>,
) -> Result<Image, RenderError> {
    let view = View::<F>::new(scene, frame, scene_bound)?;
    let width = frame.width() as usize;
    let mut pixels = vec![0u32; width * frame.height() as usize];
    pixels.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        let on = view.on(evaluator);
        for (x, px) in row.iter_mut().enumerate() {
            *px = pack_linear(view.trace_pixel(&on, x as u32, y as u32).colour, view.rules.gamma);
        }
    });
    if view.rules.sampling.samples > 1 {
        let first = FirstPass::<F>::new(&view.rules, pixels.clone(), frame);
        pixels.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
            let on = view.on(evaluator);
            for (x, px) in row.iter_mut().enumerate() {
                if let Some(all) = view.refine_pixel(&on, &first, (x, y)) {
                    *px = pack_linear(all.mean(), view.rules.gamma);
                }
            }
        });
    }
    Ok(Image { width: frame.width(), height: frame.height(), pixels })
}

/// The first pass of an image as the second reads it: each pixel's displayed colour (packed) and display luma.
struct FirstPass<F> {
    shown: Vec<u32>,
    lumas: Vec<F>,
    size: (usize, usize),
}

impl<F: Real> FirstPass<F> {
    fn new(rules: &Rules, shown: Vec<u32>, frame: &Frame) -> FirstPass<F> {
        let lumas = shown.par_iter().map(|&p| pixel::shown_luma(rules, unpack::<F>(p))).collect();
        FirstPass { shown, lumas, size: (frame.width() as usize, frame.height() as usize) }
    }

    /// Pixel (x, y)'s colour in linear light ([`pixel::undisplay`]), and whether it [`pixel::refines`]; the kernels
    /// read the same words.
    fn around(&self, rules: &Rules, (x, y): (usize, usize)) -> (V3<F>, bool) {
        let (width, height) = self.size;
        let luma = |x: usize, y: usize| self.lumas[y * width + x];
        let (x0, x2) = (x.saturating_sub(1), (x + 1).min(width - 1));
        let (y0, y2) = (y.saturating_sub(1), (y + 1).min(height - 1));
        let ring = [(x0, y0), (x, y0), (x2, y0), (x0, y), (x2, y), (x0, y2), (x, y2), (x2, y2)];
        let refines = pixel::refines(rules, luma(x, y), ring.map(|(x, y)| luma(x, y)));
        (pixel::undisplay(rules, unpack(self.shown[y * width + x])), refines)
    }
}

/// A packed pixel's colour channels in [0, 1].
fn unpack<F: Real>(p: u32) -> V3<F> {
    let [r, g, b, _] = unpack_rgba8(p);
    let channel = |c: u8| F::c(c as f64) / F::c(255.0);
    v3(channel(r), channel(g), channel(b))
}

/// [`render_scene`] in f32 with eight neighbouring pixels of a row traced together by `packets`: the ray program on
/// [`F32x8`] lanes, lane for lane the scalar program's arithmetic, so the image is the scalar renderer's wherever the
/// two evaluators agree (they do to the last bit but where LLVM folds a libm call in one instance and not the other).
pub fn render_packets(packets: &dyn PacketEvaluator, scene: &Scene, frame: &Frame) -> Result<Image, RenderError> {
    let view = View::<f32>::new(scene, frame, bound(&fold_node(&scene.root)))?;
    let view8 = splat_view(&view.view);
    let params: Vec<F32x8> = view.params.iter().map(|&p| F32x8::splat(p)).collect();
    let width = frame.width() as usize;
    let sampling = view.rules.sampling;
    let mut pixels = vec![0u32; width * frame.height() as usize];
    pixels.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        let on = Packets { packets, env: packet_env(&view, &params), orbit: &view.orbit };
        let (fy, half) = (y as f32, 0.5);
        let centres: Vec<(V3<f32>, V3<f32>)> = (0..width).map(|x| view.view.ray(x as f32 + half, fy + half)).collect();
        for (px, colour) in row.iter_mut().zip(view.shade_row(&view8, &on, &centres)) {
            *px = pack_linear(colour, view.rules.gamma);
        }
    });
    if sampling.samples <= 1 {
        return Ok(Image { width: frame.width(), height: frame.height(), pixels });
    }
    let first = FirstPass::<f32>::new(&view.rules, pixels.clone(), frame);
    pixels.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        let on = Packets { packets, env: packet_env(&view, &params), orbit: &view.orbit };
        // The second pass's samples, in the rounds `pixel::refine` decides at: each round's rays of every pixel
        // that wants more, shaded together, then added to their pixels in sample order.
        let mut sums: Vec<Option<Accumulated<f32>>> = (0..width)
            .map(|x| {
                let (centre, refines) = first.around(&view.rules, (x, y));
                refines.then(|| Accumulated::empty().with(centre))
            })
            .collect();
        for round in pixel::rounds(sampling.samples) {
            let wanting: Vec<usize> =
                (0..width).filter(|&x| sums[x].is_some_and(|sum| sum.wants_more(&view.rules))).collect();
            if wanting.is_empty() {
                break;
            }
            let rays: Vec<(V3<f32>, V3<f32>)> = wanting
                .iter()
                .flat_map(|&x| round.clone().map(move |k| (x, k)))
                .map(|(x, k)| {
                    let ([dx, dy], on_lens) = pixel::sample_point(k as f32, view.rules.lens.is_some());
                    pixel::camera_ray(&view.rules, &view.view, x as f32 + dx, y as f32 + dy, on_lens)
                })
                .collect();
            let shaded = view.shade_row(&view8, &on, &rays);
            for (&x, colours) in wanting.iter().zip(shaded.chunks(round.len())) {
                if let Some(sum) = sums[x].as_mut() {
                    for &c in colours {
                        *sum = sum.with(c);
                    }
                }
            }
        }
        for (px, sum) in row.iter_mut().zip(sums) {
            if let Some(sum) = sum {
                *px = pack_linear(sum.mean(), view.rules.gamma);
            }
        }
    });
    Ok(Image { width: frame.width(), height: frame.height(), pixels })
}

/// Renders like [`render_scene`] but keeps every pixel's [`PixelTrace`], in row-major order.
pub fn trace_scene<F: Real, E: Evaluator<F> + ?Sized>(
    evaluator: &E,
    scene: &Scene,
    frame: &Frame,
) -> Result<Vec<PixelTrace>, RenderError> {
    trace_scene_with(evaluator, scene, frame, MarchLevers { bound: bound(&fold_node(&scene.root)) })
}

/// How [`trace_scene_with`] marches, beside the scene's settings: the accuracy sweep's levers the kernels lack.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarchLevers {
    /// Rays are clipped to this box instead of the scene's own bound (`None`: march from 0 to max_distance).
    pub bound: Option<Aabb>,
}

/// [`trace_scene`] with the march's `levers` set.
pub fn trace_scene_with<F: Real, E: Evaluator<F> + ?Sized>(
    evaluator: &E,
    scene: &Scene,
    frame: &Frame,
    levers: MarchLevers,
) -> Result<Vec<PixelTrace>, RenderError> {
    let view = View::<F>::new(scene, frame, levers.bound)?;
    let width = frame.width() as usize;
    let mut traces = vec![PixelTrace::default(); width * frame.height() as usize];
    let mut first = vec![0u32; traces.len()];
    let counted = Counted(evaluator);
    traces.par_chunks_mut(width).zip(first.par_chunks_mut(width)).enumerate().for_each(|(y, (row, shown))| {
        let on = view.on(&counted);
        for (x, (out, shown)) in row.iter_mut().zip(shown).enumerate() {
            let before = EVALUATIONS.with(Cell::get);
            let pixel = view.trace_pixel(&on, x as u32, y as u32);
            *shown = pack_linear(pixel.colour, view.rules.gamma);
            *out = PixelTrace {
                colour: [pixel.colour.x.f64(), pixel.colour.y.f64(), pixel.colour.z.f64()],
                samples: 1,
                hit: pixel.hit,
                t: pixel.t.f64(),
                steps: pixel.steps,
                out_of_steps: pixel.out_of_steps,
                normal: pixel.normal.map(|n| [n.x.f64(), n.y.f64(), n.z.f64()]),
                evaluations: Some(EVALUATIONS.with(Cell::get) - before),
            };
        }
    });
    if view.rules.sampling.samples > 1 {
        let first = FirstPass::<F>::new(&view.rules, first, frame);
        traces.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
            let on = view.on(&counted);
            for (x, out) in row.iter_mut().enumerate() {
                let before = EVALUATIONS.with(Cell::get);
                if let Some(all) = view.refine_pixel(&on, &first, (x, y)) {
                    let mean = all.mean();
                    out.colour = [mean.x.f64(), mean.y.f64(), mean.z.f64()];
                    out.samples = all.count.f64() as u32;
                    out.evaluations = out.evaluations.map(|e| e + EVALUATIONS.with(Cell::get) - before);
                }
            }
        });
    }
    Ok(traces)
}

thread_local! {
    /// Distance evaluations made on this thread through [`Counted`] (each pixel runs on one thread).
    static EVALUATIONS: Cell<u64> = const { Cell::new(0) };
}

/// An evaluator that counts its distance and sample calls in [`EVALUATIONS`].
struct Counted<'a, E: ?Sized>(&'a E);

impl<F: Real, E: Evaluator<F> + ?Sized> Evaluator<F> for Counted<'_, E> {
    fn distance(&self, p: V3<F>, env: &Env<F>) -> F {
        EVALUATIONS.with(|n| n.set(n.get() + 1));
        self.0.distance(p, env)
    }
    fn sample(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        EVALUATIONS.with(|n| n.set(n.get() + 1));
        self.0.sample(p, env)
    }
    /// A gradient normal counts as one evaluation: one walk of the scene, in dual numbers.
    fn normal(&self, p: V3<F>, env: &Env<F>) -> Option<V3<F>> {
        let n = self.0.normal(p, env);
        if n.is_some() {
            EVALUATIONS.with(|n| n.set(n.get() + 1));
        }
        n
    }
}

/// The ray program's view of a scene through a scalar evaluator, at one frame's time and parameters.
pub struct Scalar<'a, F, E: ?Sized> {
    eval: &'a E,
    env: Env<'a, F>,
    /// The frame's perturbation reference orbit (empty without one).
    orbit: &'a [[f32; 2]],
}

impl<F: Real, E: Evaluator<F> + ?Sized> SceneFns<F> for Scalar<'_, F, E> {
    #[inline(always)]
    fn distance(&self, p: V3<F>) -> F {
        self.eval.distance(p, &self.env)
    }
    fn sample(&self, p: V3<F>, offset: V3<F>) -> Sample<F> {
        let reference = (!self.orbit.is_empty()).then_some(Reference { offset, orbit: self.orbit });
        self.eval.sample(p, &Env { reference, ..self.env })
    }
    fn normal(&self, p: V3<F>, h: F) -> V3<F> {
        self.eval.normal(p, &self.env).unwrap_or_else(|| ray::scene::normal(self, p, h))
    }
}

/// The ray program's view of a scene through a packet evaluator.
struct Packets<'a> {
    packets: &'a dyn PacketEvaluator,
    env: Env<'a, F32x8>,
    orbit: &'a [[f32; 2]],
}

impl SceneFns<F32x8> for Packets<'_> {
    #[inline(always)]
    fn distance(&self, p: V3<F32x8>) -> F32x8 {
        self.packets.distance_x8(p, &self.env)
    }
    fn sample(&self, p: V3<F32x8>, offset: V3<F32x8>) -> Sample<F32x8> {
        let reference = (!self.orbit.is_empty()).then_some(Reference { offset, orbit: self.orbit });
        self.packets.sample_x8(p, &Env { reference, ..self.env })
    }
    fn normal(&self, p: V3<F32x8>, h: F32x8) -> V3<F32x8> {
        self.packets.normal_x8(p, &self.env).unwrap_or_else(|| ray::scene::normal(self, p, h))
    }
}

/// One pixel in the renderer's precision.
struct Pixel<F> {
    colour: V3<F>,
    hit: bool,
    t: F,
    steps: u32,
    out_of_steps: bool,
    normal: Option<V3<F>>,
}

/// The ray program set up for one frame: its rules, the frame's camera and lights, time and parameters. Public for
/// tools that march rays of their own through a frame and shade them as this renderer does (the ground truth).
pub struct View<F> {
    rules: Rules,
    view: ray::View<F>,
    time: F,
    params: Vec<F>,
    /// The frame's perturbation reference orbit (empty without one).
    orbit: Vec<[f32; 2]>,
    /// The anchor the scene functions add to the view's positions, where it is not the origin.
    anchor: Option<V3<F>>,
}

fn f3<F: Real>(v: [f32; 3]) -> V3<F> {
    v3(F::c(v[0] as f64), F::c(v[1] as f64), F::c(v[2] as f64))
}

impl<F: Real> View<F> {
    /// The frame's view as the kernels compute it: positions relative to the frame's anchor ([`Frame::anchor`]).
    pub fn new(scene: &Scene, frame: &Frame, scene_bound: Option<Aabb>) -> Result<View<F>, RenderError> {
        View::build(scene, frame, scene_bound, true)
    }

    /// The frame's view in the scene's own coordinates (the anchor added back in `F`), for tools that evaluate the
    /// scene at the points they march (the ground truth).
    pub fn in_scene_coordinates(
        scene: &Scene,
        frame: &Frame,
        scene_bound: Option<Aabb>,
    ) -> Result<View<F>, RenderError> {
        View::build(scene, frame, scene_bound, false)
    }

    fn build(scene: &Scene, frame: &Frame, scene_bound: Option<Aabb>, anchored: bool) -> Result<View<F>, RenderError> {
        let expected = Frame::layout_of(scene);
        if frame.layout() != expected {
            return Err(FrameError::SlotCount { expected: expected.slots(), got: frame.layout().slots() }.into());
        }
        let [_, right, up, forward] = frame.camera();
        let anchor = frame.anchor().map(F::c);
        let anchor = v3(anchor[0], anchor[1], anchor[2]);
        let shift = if anchored { V3::splat(F::c(0.0)) } else { anchor };
        // In f32 the same position the kernels read; in f64 the one the pose had, to about 48 bits.
        let [ox, oy, oz] = frame.camera_origin();
        let lights = frame
            .lights()
            .into_iter()
            .map(|l| match l {
                LightSlot::Directional { direction, radiance } => {
                    Light::Directional { direction: f3(direction), radiance: f3(radiance) }
                }
                LightSlot::Point { position, radiance } => {
                    Light::Point { position: f3(position) + shift, radiance: f3(radiance) }
                }
            })
            .collect();
        let at_origin = frame.anchor() == [0.0; 3];
        Ok(View {
            anchor: (anchored && !at_origin).then_some(anchor),
            rules: Rules::with_bound(scene, scene_bound),
            view: ray::View {
                anchor: if anchored { anchor } else { V3::splat(F::c(0.0)) },
                origin: v3(F::c(ox), F::c(oy), F::c(oz)) + shift,
                right: f3(right),
                up: f3(up),
                forward: f3(forward),
                width: F::c(frame.width() as f64),
                height: F::c(frame.height() as f64),
                footprint: F::c(frame.pixel_footprint() as f64),
                lights,
            },
            time: F::c(frame.time() as f64),
            params: frame.params().into_iter().map(|p| F::c(p as f64)).collect(),
            orbit: frame.reference_orbit(),
        })
    }

    /// The scene through `eval` at this frame's time and parameters.
    pub fn on<'a, E: Evaluator<F> + ?Sized>(&'a self, eval: &'a E) -> Scalar<'a, F, E> {
        Scalar { eval, env: Env { anchor: self.anchor, ..Env::new(self.time, &self.params) }, orbit: &self.orbit }
    }

    /// Pixel footprint per unit distance along a ray.
    pub fn footprint(&self) -> F {
        self.view.footprint
    }

    pub fn max_distance(&self) -> F {
        F::c(self.rules.max_distance)
    }

    pub fn background(&self) -> V3<F> {
        let b = self.rules.background;
        v3(F::c(b[0]), F::c(b[1]), F::c(b[2]))
    }

    /// Step 1: the ray through the point (px, py) of the image, in pixels from the top left corner.
    pub fn ray(&self, px: F, py: F) -> (V3<F>, V3<F>) {
        self.view.ray(px, py)
    }

    pub fn hit_epsilon(&self, t: F) -> F {
        march::hit_epsilon(&self.rules, &self.view, t)
    }

    /// The march of the ray through the image point (px, py), alone: where it hit, at what distance, and the hit
    /// epsilon and the normal's tap there; `None` for a miss ([`crate::precision`] probes a frame with it).
    pub fn probe_hit<E: Evaluator<F> + ?Sized>(
        &self,
        on: &Scalar<'_, F, E>,
        px: f64,
        py: f64,
    ) -> Option<(V3<F>, F, F, F)> {
        let (ro, rd) = self.view.ray(F::c(px), F::c(py));
        let (m, enters) = march::march(&self.rules, &self.view, on, ro, rd);
        if !(enters && m.hit()) {
            return None;
        }
        let eps = march::hit_epsilon(&self.rules, &self.view, m.t);
        Some((march::point(ro, rd, &m), m.t, eps, shade::normal_tap(&self.rules, &self.view, m.t, eps)))
    }

    /// The first pass for pixel (x, y) ([`pixel::first_pass`]): its centre ray's colour and what it found.
    fn trace_pixel<E: Evaluator<F> + ?Sized>(&self, on: &Scalar<'_, F, E>, x: u32, y: u32) -> Pixel<F> {
        let drawn = pixel::first_pass(&self.rules, &self.view, on, F::c(x as f64), F::c(y as f64));
        let m = drawn.centre;
        if !drawn.enters {
            let colour = self.background();
            return Pixel { colour, hit: false, t: F::nan(), steps: 0, out_of_steps: false, normal: None };
        }
        let hit = m.hit();
        Pixel {
            colour: drawn.shaded.colour,
            hit,
            t: m.t,
            steps: m.steps.f64() as u32,
            out_of_steps: m.out_of_steps(self.rules.max_steps),
            normal: hit.then_some(drawn.shaded.normal),
        }
    }

    /// The second pass for pixel (x, y) from the `first` pass ([`pixel::refine`]): its
    /// samples, where it [`pixel::refines`]; `None` where it keeps its first pass.
    fn refine_pixel<E: Evaluator<F> + ?Sized>(
        &self,
        on: &Scalar<'_, F, E>,
        first: &FirstPass<F>,
        (x, y): (usize, usize),
    ) -> Option<Accumulated<F>> {
        let (centre, refines) = first.around(&self.rules, (x, y));
        let at = (F::c(x as f64), F::c(y as f64));
        refines.then(|| pixel::refine(&self.rules, &self.view, on, at, centre, true))
    }

    /// The colour of the surface at `p` with normal `n`, hit at distance `t` along `rd` from the camera with epsilon
    /// `eps`.
    #[allow(clippy::too_many_arguments)]
    pub fn shade_hit<E: Evaluator<F> + ?Sized>(
        &self,
        on: &Scalar<'_, F, E>,
        p: V3<F>,
        n: V3<F>,
        rd: V3<F>,
        t: F,
        eps: F,
    ) -> V3<F> {
        shade::surface(&self.rules, &self.view, on, p, n, (self.view.origin, rd), t, eps, true)
    }
}

impl View<f32> {
    /// Steps 2–6 of a row's rays in packets: marched with lanes refilled ([`View::march_row`]), then settled and
    /// shaded eight at a time. Each ray's linear colour.
    fn shade_row(&self, view8: &ray::View<F32x8>, on: &Packets<'_>, rays: &[(V3<f32>, V3<f32>)]) -> Vec<V3<f32>> {
        let marches = self.march_row(view8, on, rays);
        let mut colours = Vec::with_capacity(rays.len());
        for x0 in (0..rays.len()).step_by(LANES) {
            // The last group repeats its last ray; the repeats are not kept.
            let lane = |i: usize| (x0 + i).min(rays.len() - 1);
            let (mut ro, mut rd, mut m) =
                (V3::splat(F32x8::splat(0.0)), V3::splat(F32x8::splat(0.0)), March::splat(F32x8::splat(0.0)));
            for i in 0..LANES {
                set_lane3(&mut ro, i, rays[lane(i)].0);
                set_lane3(&mut rd, i, rays[lane(i)].1);
                m.set_lane(i, &marches[lane(i)].0);
            }
            // Hits are settled eight at a time, as they are shaded.
            let m = march::settle(&self.rules, on, (ro, rd), m);
            let shaded = shade::shade(&self.rules, view8, on, (ro, rd), &m);
            for i in 0..LANES.min(rays.len() - x0) {
                colours.push(if marches[x0 + i].1 { lane3(shaded.colour, i) } else { self.background() });
            }
        }
        colours
    }

    /// Steps 2–3 of a row of rays, eight lanes at a time: a lane whose march ends takes the row's next ray at once,
    /// so no lane idles while rays remain. Each ray takes exactly the scalar march's steps, whichever lane it runs in.
    /// Each ray's march end, and whether it entered the bound.
    fn march_row(
        &self,
        view8: &ray::View<F32x8>,
        on: &Packets<'_>,
        rays: &[(V3<f32>, V3<f32>)],
    ) -> Vec<(March<f32>, bool)> {
        let rules = &self.rules;
        let mut out: Vec<(March<f32>, bool)> = Vec::with_capacity(rays.len());
        for &(ro, rd) in rays {
            let (t_near, t_far, enters) = march::clip(rules, self.view.anchor, ro, rd);
            out.push((march::start(rules, t_near, t_far), enters));
        }
        let zero = V3::splat(F32x8::splat(0.0));
        let (mut ro, mut rd, mut m) = (zero, zero, March::splat(F32x8::splat(0.0)));
        let mut ray_of: [Option<usize>; LANES] = [None; LANES];
        let mut next = 0;
        let max_steps = F32x8::splat(rules.max_steps as f32);
        loop {
            let running = m.running() & Num::lt(m.steps, max_steps);
            // Retire the lanes whose march ended and give each free lane the next ray that enters the bound.
            for (lane, slot) in ray_of.iter_mut().enumerate() {
                if let Some(ray) = *slot {
                    if running.0[lane] != 0 {
                        continue;
                    }
                    out[ray].0 = m.lane(lane);
                    *slot = None;
                }
                while let Some(&(o, d)) = rays.get(next) {
                    next += 1;
                    // A ray that misses the bound is not marched.
                    if out[next - 1].1 {
                        set_lane3(&mut ro, lane, o);
                        set_lane3(&mut rd, lane, d);
                        m.set_lane(lane, &out[next - 1].0);
                        *slot = Some(next - 1);
                        break;
                    }
                }
            }
            let Some(first) = ray_of.iter().position(Option::is_some) else { break };
            // An idle lane marches a copy of the first running lane (its result is not used), so it costs what that
            // lane costs.
            for (lane, slot) in ray_of.iter().enumerate() {
                if slot.is_none() {
                    let (o, d, copy) = (lane3(ro, first), lane3(rd, first), m.lane(first));
                    set_lane3(&mut ro, lane, o);
                    set_lane3(&mut rd, lane, d);
                    m.set_lane(lane, &copy);
                }
            }
            let d = on.distance(march::point(ro, rd, &m));
            m = march::advance(rules, view8, m, d);
        }
        out
    }
}

/// The packets' environment of a view: its time, `params` (splatted) and anchor.
fn packet_env<'a>(view: &View<f32>, params: &'a [F32x8]) -> Env<'a, F32x8> {
    let anchor = view.anchor.map(|a| v3(F32x8::splat(a.x), F32x8::splat(a.y), F32x8::splat(a.z)));
    Env { anchor, ..Env::new(F32x8::splat(view.time), params) }
}

/// A frame's view with every number in all eight lanes.
fn splat_view(v: &ray::View<f32>) -> ray::View<F32x8> {
    let s = |v: V3<f32>| v3(F32x8::splat(v.x), F32x8::splat(v.y), F32x8::splat(v.z));
    ray::View {
        anchor: s(v.anchor),
        origin: s(v.origin),
        right: s(v.right),
        up: s(v.up),
        forward: s(v.forward),
        width: F32x8::splat(v.width),
        height: F32x8::splat(v.height),
        footprint: F32x8::splat(v.footprint),
        lights: v
            .lights
            .iter()
            .map(|l| match *l {
                Light::Directional { direction, radiance } => {
                    Light::Directional { direction: s(direction), radiance: s(radiance) }
                }
                Light::Point { position, radiance } => Light::Point { position: s(position), radiance: s(radiance) },
            })
            .collect(),
    }
}

/// Lane `i` of a vector of packets.
#[inline(always)]
fn lane3(v: V3<F32x8>, i: usize) -> V3<f32> {
    v3(v.x.0[i], v.y.0[i], v.z.0[i])
}

/// Sets lane `i` of a vector of packets.
#[inline(always)]
fn set_lane3(v: &mut V3<F32x8>, i: usize, x: V3<f32>) {
    (v.x.0[i], v.y.0[i], v.z.0[i]) = (x.x, x.y, x.z);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image::unpack_rgba8;
    use fractal_dsl::analyse::has_specular;
    use fractal_dsl::builder::*;
    use fractal_dsl::number::math::length;

    struct UnitSphere;
    impl Evaluator<f32> for UnitSphere {
        fn distance(&self, p: V3<f32>, _: &Env<f32>) -> f32 {
            length(p) - 1.0
        }
        fn sample(&self, p: V3<f32>, env: &Env<f32>) -> fractal_dsl::eval::Sample<f32> {
            let distance = self.distance(p, env);
            let albedo = v3(1.0, 1.0, 1.0);
            fractal_dsl::eval::Sample { distance, albedo, ambient: 0.2, diffuse: 0.8, specular: 0.0, shininess: 1.0 }
        }
    }

    #[test]
    fn the_bound_clips_rays_without_changing_what_is_inside() {
        let s = scene(sphere(1.0));
        let frame = Frame::default_view(&s, 0.0, 48, 48).unwrap();
        let render = |b: Option<Aabb>| render_with_bound::<f32, _>(&UnitSphere, &s, &frame, b).unwrap();
        // Marches that start at the bound's entry end within the hit epsilon of the same surface point.
        let unlike = |a: &Image, b: &Image| {
            let far = |p: &u32, q: &u32| unpack_rgba8(*p).iter().zip(unpack_rgba8(*q)).any(|(x, y)| x.abs_diff(y) > 1);
            a.pixels.iter().zip(&b.pixels).filter(|(p, q)| far(p, q)).count()
        };
        let unbounded = render(None);
        let tight = render(Some(Aabb { min: [-1.0; 3], max: [1.0; 3] }));
        assert_eq!(unlike(&tight, &unbounded), 0);
        let loose = render(Some(Aabb { min: [-1.5, -1.0, -1.2], max: [1.0, 2.0, 1.1] }));
        assert_eq!(unlike(&loose, &unbounded), 0);
        // A bound that holds only the top half of the sphere cuts the march short for rays towards the bottom half.
        let half = render(Some(Aabb { min: [-1.0, 0.0, -1.0], max: [1.0, 1.0, 1.0] }));
        let background = pack_linear(v3(0.08f32, 0.09, 0.12), 2.0);
        let hits = unbounded.count_unlike(unpack_rgba8(background), 0);
        let half_hits = half.count_unlike(unpack_rgba8(background), 0);
        assert!(half_hits < hits * 9 / 10 && half_hits > hits / 4, "{half_hits} of {hits} hits left: no clipping");
        // A bound behind the camera: every ray misses.
        let behind = render(Some(Aabb { min: [-1.0, -1.0, -10.0], max: [1.0, 1.0, -9.0] }));
        assert!(behind.pixels.iter().all(|&p| p == background));
    }

    /// A scene's `normal_pixel_epsilon` takes the normal's tetrahedral taps that many footprints apart at the hit,
    /// whatever the hit epsilon: each traced normal is that gradient taken again at the traced hit, the march is
    /// unchanged, and on a fractal the normals turn from the fine epsilon's.
    #[test]
    fn the_normal_is_taken_at_the_scenes_normal_epsilon() {
        use fractal_dsl::eval::interp::Interpreter;
        let fine = scene(mandelbulb(8).iterations(6)).camera(camera([1.2, 1.0, -2.2], [0.0; 3])).pixel_epsilon(0.05);
        let wide = fine.clone().normal_pixel_epsilon(1.0);
        let frame = Frame::default_view(&fine, 0.0, 40, 30).unwrap();
        let trace = |s: &Scene| trace_scene::<f64, _>(&Interpreter::new(s).unwrap(), s, &frame).unwrap();
        let (before, after) = (trace(&fine), trace(&wide));
        let view = View::<f64>::new(&wide, &frame, None).unwrap();
        let interpreter = Interpreter::new(&wide).unwrap();
        let on = view.on(&interpreter);
        let (mut hits, mut turned) = (0, 0);
        for (i, (a, b)) in before.iter().zip(&after).enumerate() {
            assert_eq!(
                (a.hit, a.t.to_bits()),
                (b.hit, b.t.to_bits()),
                "pixel {i}: the normal's taps changed the march"
            );
            let (Some(m), Some(n)) = (a.normal, b.normal) else { continue };
            let (x, y) = ((i % 40) as f64 + 0.5, (i / 40) as f64 + 0.5);
            let (ro, rd) = view.ray(x, y);
            let p = ro + rd * b.t;
            let expected = fractal_dsl::ray::scene::normal(&on, p, view.footprint() * b.t);
            let cos = expected.x * n[0] + expected.y * n[1] + expected.z * n[2];
            assert!(cos > 1.0 - 1e-9, "pixel {i}: normal {n:?}, taps a footprint apart give {expected:?}");
            hits += 1;
            turned += usize::from(m[0] * n[0] + m[1] * n[1] + m[2] * n[2] < 1f64.to_radians().cos());
        }
        assert!(hits > 100 && turned > hits / 10, "{turned} of {hits} normals turned by more than 1°");
    }

    #[test]
    fn specular_is_detected_from_materials() {
        assert!(!has_specular(&sphere(1.0)));
        assert!(!has_specular(&sphere(1.0).material(rgb(1.0, 0.0, 0.0))));
        assert!(has_specular(&union(sphere(1.0), box3([1.0, 1.0, 1.0]).material(rgb(1.0, 0.0, 0.0).specular(0.5)))));
    }
}
