//! The CPU renderer: the render algorithm of [`fractal_dsl::back::render`] over a scene's [`Evaluator`], one rayon
//! task per image row. Generic over the precision, so the f64 instance renders reference images for accuracy work.
//! In f32, where the evaluator has a packet instance ([`Evaluator::packets`]), eight neighbouring pixels are traced
//! together ([`render_packets`]): primary rays, normals, occlusion and shadow rays in packets, the material and the
//! lighting sums a pixel at a time.
//!
//! It reads the camera, lights, time and parameters from the same [`Frame`] uniforms the kernels read, so the three
//! renderers draw the same pose from the same numbers.

use fractal_dsl::analyse::{bound, fold::fold_node, has_specular, sign_refinement, Aabb, SignRefinement};
use fractal_dsl::back::render::{
    AO_SAMPLES, AO_SPAN, AO_START, GLOW_FALLOFF, GLOW_NORM, MEMBERSHIP_STEP, MIN_DIRECTION, PROBE_REACH, PROBE_SHARE,
    REFINED_NORMAL_SHARE, REFINE_STEPS, T_SPACING,
};
use fractal_dsl::eval::{packet::sample_lane, Env, Evaluator, PacketEvaluator, Reference, Sample};
use fractal_dsl::lanes::{F32x8, LANES};
use fractal_dsl::math::{dot, length, normalize, v3, Real, V3};
use fractal_dsl::num::Num;
use fractal_dsl::{HitEpsilon, RenderSettings, Scene, Shadows};
use rayon::prelude::*;
use std::cell::Cell;

use crate::device::{Backend, DeviceInfo};
use crate::error::{FrameError, RenderError};
use crate::frame::{Frame, LightSlot};
use crate::image::Image;
pub use crate::renderer::PixelTrace;
use crate::renderer::{RenderJob, Renderer, Traced};

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
        match kernel.evaluator.packets() {
            Some(packets) => render_packets(kernel.evaluator, packets, kernel.scene, job.frame),
            None => render_scene::<f32, _>(kernel.evaluator, kernel.scene, job.frame),
        }
    }

    fn trace(&mut self, job: &RenderJob) -> Result<Traced, RenderError> {
        let kernel =
            job.kernels.cpu.ok_or(RenderError::MissingKernel { backend: Backend::Cpu, what: "CPU evaluator" })?;
        let pixels = trace_scene::<f32, _>(kernel.evaluator, kernel.scene, job.frame)?;
        let gamma = kernel.scene.settings.gamma;
        let packed = pixels.iter().map(|p| pack(v3(p.colour[0] as f32, p.colour[1] as f32, p.colour[2] as f32), gamma));
        let image = Image { width: job.width(), height: job.height(), pixels: packed.collect() };
        Ok(Traced { image, pixels })
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
                fractal_dsl::lanes::instruction_set()
            ),
            device_type: "Cpu".to_string(),
        }
    }
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
        let env = Env::new(view.time, &view.params);
        for (x, px) in row.iter_mut().enumerate() {
            *px = pack(view.trace_pixel(evaluator, &env, x as u32, y as u32).colour, view.gamma);
        }
    });
    Ok(Image { width: frame.width(), height: frame.height(), pixels })
}

/// [`render_scene`] in f32 with eight neighbouring pixels of a row traced together: their primary rays, normals,
/// occlusion and shadow rays evaluated by `packets`, their materials and lighting by `evaluator` a pixel at a time.
/// Every step is the render algorithm's, lane for lane,
/// so the image is the scalar renderer's wherever the two evaluators agree (they do to the last bit but where LLVM
/// folds a libm call in one instance and not the other).
pub fn render_packets<E: Evaluator<f32> + ?Sized>(
    evaluator: &E,
    packets: &dyn PacketEvaluator,
    scene: &Scene,
    frame: &Frame,
) -> Result<Image, RenderError> {
    let view = View::<f32>::new(scene, frame, bound(&fold_node(&scene.root)))?;
    let width = frame.width() as usize;
    let mut pixels = vec![0u32; width * frame.height() as usize];
    let params: Vec<F32x8> = view.params.iter().map(|&p| F32x8::splat(p)).collect();
    pixels.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        let env = Env::new(view.time, &view.params);
        let env8 = Env::new(F32x8::splat(view.time), &params);
        let row_rays: Vec<(V3<f32>, V3<f32>)> = (0..width).map(|x| view.ray(x as f32 + 0.5, y as f32 + 0.5)).collect();
        let mut row_marches = view.march_row(packets, &env8, &row_rays);
        if view.refine.is_some() {
            for (m, &(ro, rd)) in row_marches.iter_mut().zip(&row_rays) {
                *m = m.map(|m| view.refined(evaluator, &env, ro, rd, m));
            }
        }
        let mut shadows = Vec::with_capacity(view.lights.len());
        for (chunk, x0) in row.chunks_mut(LANES).zip((0..width).step_by(LANES)) {
            // The last group of a row repeats its last pixel; the repeats are not written.
            let rays: [(V3<f32>, V3<f32>); LANES] = std::array::from_fn(|i| row_rays[(x0 + i).min(width - 1)]);
            let marches: [Option<March<f32>>; LANES] =
                std::array::from_fn(|i| if x0 + i < width { row_marches[x0 + i] } else { None });
            let finished = view.finish_packet(evaluator, &env, packets, &env8, &rays, &marches, &mut shadows);
            for (px, pixel) in chunk.iter_mut().zip(finished) {
                *px = pack(pixel.colour, view.gamma);
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
    let counted = Counted(evaluator);
    traces.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        let env = Env::new(view.time, &view.params);
        for (x, out) in row.iter_mut().enumerate() {
            let before = EVALUATIONS.with(Cell::get);
            let pixel = view.trace_pixel(&counted, &env, x as u32, y as u32);
            *out = PixelTrace {
                colour: [pixel.colour.x.f64(), pixel.colour.y.f64(), pixel.colour.z.f64()],
                hit: pixel.hit,
                t: pixel.t.f64(),
                steps: pixel.steps,
                out_of_steps: pixel.out_of_steps,
                normal: pixel.normal.map(|n| [n.x.f64(), n.y.f64(), n.z.f64()]),
                evaluations: Some(EVALUATIONS.with(Cell::get) - before),
            };
        }
    });
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
}

impl View<f32> {
    /// The render algorithm's clip and march (steps 2–3) of a row of rays, eight lanes at a time: a lane whose
    /// march ends takes the row's next ray at once, so no lane idles while rays remain. Each ray takes exactly the
    /// scalar march's steps, whichever lane it runs in: the per-step arithmetic (the point, the hit epsilon, the
    /// test and the step) runs on the lanes together, in the scalar march's order of operations.
    fn march_row(
        &self,
        packets: &dyn PacketEvaluator,
        env: &Env<F32x8>,
        rays: &[(V3<f32>, V3<f32>)],
    ) -> Vec<Option<March<f32>>> {
        let mut out: Vec<Option<March<f32>>> = vec![None; rays.len()];
        let clipped = self.clip_row(rays);
        let mut lanes = RowLanes::default();
        let mut next = 0;
        loop {
            // Retire the lanes whose march ended and give each free lane the next ray that enters the bound.
            for lane in 0..LANES {
                if let Some(ray) = lanes.ray[lane] {
                    if lanes.running(lane, self.max_steps) {
                        continue;
                    }
                    out[ray] = Some(lanes.end(lane, self.max_steps));
                    lanes.ray[lane] = None;
                }
                while let Some(&(ro, rd)) = rays.get(next) {
                    next += 1;
                    // A ray that misses the bound has no march (`None` stays in `out`).
                    if let Some((t_near, t_far)) = clipped[next - 1] {
                        lanes.start(lane, next - 1, ro, rd, t_near, t_far, self.relaxation);
                        break;
                    }
                }
            }
            let Some(first) = lanes.ray.iter().position(Option::is_some) else { break };
            // An idle lane marches a copy of the first running lane (its result is not used).
            for lane in 0..LANES {
                if lanes.ray[lane].is_none() {
                    lanes.copy(first, lane);
                }
            }
            let t = F32x8(lanes.t);
            let p = V3 {
                x: F32x8(lanes.ro[0]) + F32x8(lanes.rd[0]) * t,
                y: F32x8(lanes.ro[1]) + F32x8(lanes.rd[1]) * t,
                z: F32x8(lanes.ro[2]) + F32x8(lanes.rd[2]) * t,
            };
            let d = packets.distance_x8(p, env);
            let eps = self.hit_epsilon_x8(t);
            let one = F32x8::splat(1.0);
            let (last_t, last_d) = (F32x8(lanes.last_t), F32x8(lanes.last_d));
            // Step 3b: near the surface of a scene refined by sign, a hit is a crossing and the step a sign step.
            let near = Num::lt(d, eps);
            let (hit_near, near_step) = if let Some(rule) = self.refine {
                (Num::le(d, F32x8::splat(0.0)), sign_step(rule, d, eps, t, (last_t, last_d)))
            } else {
                (near, d)
            };
            let (hit, step) = if self.relaxation > 1.0 {
                // The scalar march's over-relaxation, lane by lane (see `View::march`).
                let (omega, previous, stride) = (F32x8(lanes.omega), F32x8(lanes.previous), F32x8(lanes.stride));
                let abs_d = Num::abs(d);
                let overshot = Num::lt(one, omega) & Num::lt(abs_d + previous, stride);
                let near = !overshot & near;
                let stride = Num::select(overshot, stride - omega * stride, Num::select(near, near_step, d * omega));
                lanes.omega = Num::select(overshot | near, one, omega).0;
                lanes.previous = abs_d.0;
                lanes.stride = stride.0;
                (near & hit_near, stride)
            } else {
                (near & hit_near, Num::select(near, near_step, d))
            };
            if self.glow.is_some() {
                let glow = F32x8(lanes.glow);
                lanes.glow = Num::select(hit, glow, glow + one / (one + F32x8::splat(GLOW_FALLOFF as f32) * d * d)).0;
            }
            lanes.t = Num::select(hit, t, t + step).0;
            lanes.last_t = Num::select(hit, last_t, t).0;
            lanes.last_d = Num::select(hit, last_d, d).0;
            lanes.d = d.0;
            lanes.eps = eps.0;
            for (i, m) in hit.0.iter().enumerate() {
                lanes.steps[i] += 1;
                lanes.hit[i] = *m != 0;
            }
        }
        out
    }

    /// [`View::clip`] of every ray of a row, eight at a time with the same operations lane for lane.
    fn clip_row(&self, rays: &[(V3<f32>, V3<f32>)]) -> Vec<Option<(f32, f32)>> {
        let Some((lo, hi)) = self.bound else {
            return vec![Some((0.0, self.max_distance)); rays.len()];
        };
        let mut out = Vec::with_capacity(rays.len() + LANES);
        for chunk in rays.chunks(LANES) {
            // A short last chunk repeats its last ray.
            let lane = |i: usize| chunk[i.min(chunk.len() - 1)];
            let packet = |v: &dyn Fn(usize) -> V3<f32>| V3 {
                x: F32x8::from_fn(|i| v(i).x),
                y: F32x8::from_fn(|i| v(i).y),
                z: F32x8::from_fn(|i| v(i).z),
            };
            let (ro, rd) = (packet(&|i| lane(i).0), packet(&|i| lane(i).1));
            let (t_near, t_far, enters) =
                slab(packet(&|_| lo), packet(&|_| hi), F32x8::splat(self.max_distance), ro, rd);
            out.extend((0..chunk.len()).map(|i| (enters.0[i] != 0).then_some((t_near.0[i], t_far.0[i]))));
        }
        out
    }

    /// [`View::hit_epsilon`] on eight lanes, with the same operations in the same order.
    fn hit_epsilon_x8(&self, t: F32x8) -> F32x8 {
        let eps = match self.epsilon {
            HitEpsilon::Fixed(e) => F32x8::splat(e as f32),
            HitEpsilon::Pixel(k) => F32x8::splat(k as f32) * F32x8::splat(self.footprint) * t,
        };
        Num::max(eps, F32x8::splat(T_SPACING as f32) * t)
    }

    /// Steps 4–6 of eight marched rays: normals, occlusion and shadow rays evaluated in packets (lane for lane the
    /// scalar formulas), the material and lighting a pixel at a time. `shadows` is scratch space the caller keeps
    /// between calls (one entry per light, per lane).
    #[allow(clippy::too_many_arguments)]
    fn finish_packet<E: Evaluator<f32> + ?Sized>(
        &self,
        eval: &E,
        env: &Env<f32>,
        packets: &dyn PacketEvaluator,
        env8: &Env<F32x8>,
        rays: &[(V3<f32>, V3<f32>); LANES],
        marches: &[Option<March<f32>>; LANES],
        shadows: &mut Vec<[f32; LANES]>,
    ) -> [Pixel<f32>; LANES] {
        let hit: [bool; LANES] = std::array::from_fn(|i| marches[i].is_some_and(|m| m.hit));
        let Some(first) = hit.iter().position(|&h| h) else {
            return std::array::from_fn(|i| self.finish_pixel(eval, env, rays[i].0, rays[i].1, marches[i]));
        };
        // Lanes without a hit stand in for the first hit (their values are computed and not used).
        let lane = |i: usize| if hit[i] { i } else { first };
        let at = |i: usize| {
            let (ro, rd) = rays[lane(i)];
            let m = marches[lane(i)].expect("a hit lane has a march");
            (ro + rd * m.t, m.t, m.eps)
        };
        let points: [(V3<f32>, f32, f32); LANES] = std::array::from_fn(at);

        let taps: [[V3<f32>; 4]; LANES] =
            std::array::from_fn(|i| normal_taps(points[i].0, self.normal_tap(points[i].1, points[i].2)));
        let tap_distances: [[f32; LANES]; 4] =
            std::array::from_fn(|k| distances_x8(packets, env8, std::array::from_fn(|i| taps[i][k])));
        let normals: [V3<f32>; LANES] =
            std::array::from_fn(|i| normal_from(std::array::from_fn(|k| tap_distances[k][i])));

        let occlusion: [f32; LANES] = match self.ambient_occlusion {
            None => [1.0; LANES],
            Some(strength) => {
                let samples: [[V3<f32>; AO_SAMPLES as usize]; LANES] =
                    std::array::from_fn(|i| occlusion_points(points[i].0, normals[i]));
                let distances: [[f32; LANES]; AO_SAMPLES as usize] =
                    std::array::from_fn(|h| distances_x8(packets, env8, std::array::from_fn(|i| samples[i][h])));
                std::array::from_fn(|i| occlusion_from(strength, std::array::from_fn(|h| distances[h][i])))
            }
        };

        // shadows[light][lane]: the light reaching each hit, for lanes whose surface faces the light.
        shadows.clear();
        shadows.resize(self.lights.len(), [1.0; LANES]);
        if self.shadows != Shadows::None {
            for (light, lit) in self.lights.iter().zip(shadows.iter_mut()) {
                let rays: [(V3<f32>, V3<f32>, f32, bool); LANES] = std::array::from_fn(|i| {
                    let (p, _, eps) = points[i];
                    let (l, _, limit) = self.light_at(light, p);
                    let faces = hit[i] && dot(normals[i], l).max(0.0) > 0.0;
                    (self.shadow_origin(p, normals[i], eps), l, limit, faces)
                });
                let mut states: [ShadowMarch<f32>; LANES] = std::array::from_fn(|i| self.shadow_start(points[i].2));
                run_lanes(
                    packets,
                    env8,
                    &mut states,
                    |i, march| rays[i].3 && self.shadow_running(march, rays[i].2),
                    |i, march| rays[i].0 + rays[i].1 * march.t,
                    |i, march, d| self.shadow_step(march, d, points[i].2),
                );
                for (i, value) in lit.iter_mut().enumerate().filter(|(i, _)| rays[*i].3) {
                    *value = self.shadow_result(&states[i]);
                }
            }
        }

        // The materials at the hits, in one packet: a perturbed pattern reads each hit relative to the camera, rd·t.
        // (Only scenes with a perturbed pattern have an orbit; the offsets are formed for them alone.)
        let offset = |i: usize| rays[lane(i)].1 * marches[lane(i)].expect("a hit lane has a march").t;
        let orbit_env = Env {
            reference: (!self.orbit.is_empty())
                .then(|| Reference { offset: lanes_of(std::array::from_fn(offset)), orbit: &self.orbit }),
            ..*env8
        };
        let materials = packets.sample_x8(lanes_of(points.map(|(p, _, _)| p)), &orbit_env);

        std::array::from_fn(|i| {
            let (ro, rd) = rays[i];
            self.finish_with(ro, rd, marches[i], |p, t, eps| {
                let n = normals[i];
                let shadow = |light: usize, _: V3<f32>, _: V3<f32>, _: f32| shadows[light][i];
                (self.shade_lit(&sample_lane(&materials, i), p, n, rd, t, eps, occlusion[i], &shadow), n)
            })
        })
    }
}

/// Eight points as one packet.
fn lanes_of(points: [V3<f32>; LANES]) -> V3<F32x8> {
    V3 { x: F32x8::from_fn(|i| points[i].x), y: F32x8::from_fn(|i| points[i].y), z: F32x8::from_fn(|i| points[i].z) }
}

/// The distances at eight points, in one packet.
fn distances_x8(packets: &dyn PacketEvaluator, env: &Env<F32x8>, points: [V3<f32>; LANES]) -> [f32; LANES] {
    packets.distance_x8(lanes_of(points), env).0
}

/// Marches eight lanes together: while any lane is `running`, evaluates the distance at every running lane's `point`
/// in one packet (an idle lane repeats a running lane's point, so it costs what that lane costs) and hands it to
/// that lane's `step`.
fn run_lanes<S>(
    packets: &dyn PacketEvaluator,
    env: &Env<F32x8>,
    states: &mut [S; LANES],
    running: impl Fn(usize, &S) -> bool,
    point: impl Fn(usize, &S) -> V3<f32>,
    mut step: impl FnMut(usize, &mut S, f32),
) {
    loop {
        let live: [bool; LANES] = std::array::from_fn(|i| running(i, &states[i]));
        let Some(first) = live.iter().position(|&r| r) else { break };
        let points = std::array::from_fn(|i| if live[i] { point(i, &states[i]) } else { point(first, &states[first]) });
        let d = distances_x8(packets, env, points);
        for (i, state) in states.iter_mut().enumerate().filter(|(i, _)| live[*i]) {
            step(i, state, d[i]);
        }
    }
}

/// The eight marches of [`View::march_row`], a field per array so the per-step arithmetic runs on all lanes.
#[derive(Default)]
struct RowLanes {
    /// The ray each lane marches (`None`: idle).
    ray: [Option<usize>; LANES],
    ro: [[f32; LANES]; 3],
    rd: [[f32; LANES]; 3],
    t: [f32; LANES],
    t_far: [f32; LANES],
    eps: [f32; LANES],
    steps: [u32; LANES],
    hit: [bool; LANES],
    glow: [f32; LANES],
    /// Over-relaxation: each lane's ω, |d| at its last point and its last step.
    omega: [f32; LANES],
    previous: [f32; LANES],
    stride: [f32; LANES],
    /// The distance at t once the lane hits, and the sample before t (for the sign refinement).
    d: [f32; LANES],
    last_t: [f32; LANES],
    last_d: [f32; LANES],
}

impl RowLanes {
    /// Lane `lane` starts marching ray `ray` at `t_near`.
    #[allow(clippy::too_many_arguments)]
    fn start(&mut self, lane: usize, ray: usize, ro: V3<f32>, rd: V3<f32>, t_near: f32, t_far: f32, omega: f32) {
        self.ray[lane] = Some(ray);
        for (axis, (o, d)) in [(ro.x, rd.x), (ro.y, rd.y), (ro.z, rd.z)].into_iter().enumerate() {
            self.ro[axis][lane] = o;
            self.rd[axis][lane] = d;
        }
        (self.t[lane], self.t_far[lane], self.eps[lane]) = (t_near, t_far, 0.0);
        (self.steps[lane], self.hit[lane], self.glow[lane]) = (0, false, 0.0);
        (self.omega[lane], self.previous[lane], self.stride[lane]) = (omega, 0.0, 0.0);
        (self.d[lane], self.last_t[lane], self.last_d[lane]) = (0.0, t_near, 0.0);
    }
    /// Lane `to` takes lane `from`'s march (not its ray).
    fn copy(&mut self, from: usize, to: usize) {
        for axis in 0..3 {
            self.ro[axis][to] = self.ro[axis][from];
            self.rd[axis][to] = self.rd[axis][from];
        }
        (self.t[to], self.t_far[to], self.eps[to]) = (self.t[from], self.t_far[from], self.eps[from]);
        (self.steps[to], self.hit[to], self.glow[to]) = (self.steps[from], self.hit[from], self.glow[from]);
        (self.omega[to], self.previous[to], self.stride[to]) =
            (self.omega[from], self.previous[from], self.stride[from]);
        (self.d[to], self.last_t[to], self.last_d[to]) = (self.d[from], self.last_t[from], self.last_d[from]);
    }
    /// Whether lane `lane`'s march goes on: the kernels' loop condition (a NaN t stops it).
    fn running(&self, lane: usize, max_steps: u32) -> bool {
        !self.hit[lane] && self.steps[lane] < max_steps && self.t[lane] <= self.t_far[lane]
    }
    /// The end of lane `lane`'s march.
    fn end(&self, lane: usize, max_steps: u32) -> March<f32> {
        let (hit, t, steps) = (self.hit[lane], self.t[lane], self.steps[lane]);
        let out_of_steps = !hit && steps == max_steps && t <= self.t_far[lane];
        March {
            hit,
            t,
            eps: self.eps[lane],
            d: self.d[lane],
            last: (self.last_t[lane], self.last_d[lane]),
            steps,
            out_of_steps,
            glow: self.glow[lane],
        }
    }
}

/// Step 3b's sign step at 0 < d < eps. Displacement: eps, or a share of the distance to the zero of the line through
/// the last sample and this one where the ray nears the surface, up to the reach. Membership: a share of eps.
/// Written once for a ray and for eight.
#[inline(always)]
fn sign_step<N: Num>(rule: SignRefinement, d: N, eps: N, t: N, (last_t, last_d): (N, N)) -> N {
    if rule == SignRefinement::Membership {
        return N::lit(MEMBERSHIP_STEP) * eps;
    }
    let toward = N::lit(PROBE_SHARE) * d * (t - last_t) / (last_d - d);
    let step = N::select(N::lt(d, last_d), N::max(eps, toward), eps);
    N::min(step, N::lit(PROBE_REACH) * eps)
}

/// The slab test of the ray (ro, rd) against the box [lo, hi], clipped to [0, max_distance]: the interval's ends and
/// whether it is not empty. Written once for a ray ([`View::clip`]) and for eight ([`View::clip_row`]), so both take
/// the same operations.
#[inline(always)]
fn slab<N: Num>(lo: V3<N>, hi: V3<N>, max_distance: N, ro: V3<N>, rd: V3<N>) -> (N, N, N::Mask) {
    let (zero, min_dir) = (N::lit(0.0), N::lit(MIN_DIRECTION));
    // Each direction component kept at least MIN_DIRECTION from 0, with its sign.
    let safe = rd.map(|d| {
        let m = N::max(N::abs(d), min_dir);
        N::select(N::le(zero, d), m, -m)
    });
    let t0 = (lo - ro) / safe;
    let t1 = (hi - ro) / safe;
    let entry = t0.zip(t1, N::min).max_element();
    let exit = t0.zip(t1, N::max).min_element();
    let t_near = N::max(entry, zero);
    let t_far = N::min(exit, max_distance);
    (t_near, t_far, N::le(t_near, t_far))
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

/// The end of a march.
#[derive(Clone, Copy)]
struct March<F> {
    hit: bool,
    t: F,
    eps: F,
    /// The distance at t (at a hit; the last one evaluated otherwise).
    d: F,
    /// The sample before t: (t_last, d_last).
    last: (F, F),
    steps: u32,
    out_of_steps: bool,
    glow: F,
}

/// The render algorithm set up for one frame: camera, lights, settings and bound in precision `F`.
pub(crate) struct View<F> {
    origin: V3<F>,
    right: V3<F>,
    up: V3<F>,
    forward: V3<F>,
    width: F,
    height: F,
    footprint: F,
    time: F,
    params: Vec<F>,
    lights: Vec<Light<F>>,
    bound: Option<(V3<F>, V3<F>)>,
    specular: bool,
    max_steps: u32,
    max_distance: F,
    epsilon: HitEpsilon,
    shadows: Shadows,
    ambient_occlusion: Option<F>,
    glow: Option<V3<F>>,
    fog: Option<(V3<F>, F)>,
    background: V3<F>,
    gamma: f64,
    /// Over-relaxation factor of the march (1: plain sphere tracing, the render algorithm's).
    relaxation: F,
    /// Whether hits are refined by the distance's sign ([`sign_refinement`]), and why.
    refine: Option<SignRefinement>,
    /// The normal's taps in pixel footprints, when the scene sets them apart from the hit epsilon.
    normal_epsilon: Option<f64>,
    /// The frame's perturbation reference orbit (empty without one).
    orbit: Vec<[f32; 2]>,
}

enum Light<F> {
    Directional { direction: V3<F>, radiance: V3<F> },
    Point { position: V3<F>, radiance: V3<F> },
}

fn f3<F: Real>(v: [f32; 3]) -> V3<F> {
    v3(F::c(v[0] as f64), F::c(v[1] as f64), F::c(v[2] as f64))
}

fn d3<F: Real>(v: [f64; 3]) -> V3<F> {
    v3(F::c(v[0]), F::c(v[1]), F::c(v[2]))
}

fn c<F: Real>(v: f64) -> F {
    F::c(v)
}

impl<F: Real> View<F> {
    pub(crate) fn new(scene: &Scene, frame: &Frame, scene_bound: Option<Aabb>) -> Result<View<F>, RenderError> {
        let expected = Frame::layout_of(scene);
        if frame.layout() != expected {
            return Err(FrameError::SlotCount { expected: expected.slots(), got: frame.layout().slots() }.into());
        }
        let [origin, right, up, forward] = frame.camera();
        let RenderSettings {
            max_steps,
            max_distance,
            epsilon,
            over_relaxation,
            normal_epsilon,
            membership_hits: _,
            shadows,
            ambient_occlusion,
            glow,
            ref fog,
            background,
            gamma,
        } = scene.settings;
        let folded = fold_node(&scene.root);
        let lights = frame
            .lights()
            .into_iter()
            .map(|l| match l {
                LightSlot::Directional { direction, radiance } => {
                    Light::Directional { direction: f3(direction), radiance: f3(radiance) }
                }
                LightSlot::Point { position, radiance } => {
                    Light::Point { position: f3(position), radiance: f3(radiance) }
                }
            })
            .collect();
        Ok(View {
            origin: f3(origin),
            right: f3(right),
            up: f3(up),
            forward: f3(forward),
            width: c(frame.width() as f64),
            height: c(frame.height() as f64),
            footprint: c(frame.pixel_footprint() as f64),
            time: c(frame.time() as f64),
            params: frame.params().into_iter().map(|p| c(p as f64)).collect(),
            lights,
            bound: scene_bound.map(|b| (d3(b.min), d3(b.max))),
            specular: has_specular(&folded),
            max_steps,
            max_distance: c(max_distance),
            epsilon,
            normal_epsilon,
            shadows,
            // The kernels fold the factor 3 of the occlusion formula into the strength.
            ambient_occlusion: ambient_occlusion.map(|s| c(3.0 * s)),
            glow: glow.map(d3),
            fog: fog.as_ref().map(|f| (d3(f.color), c(f.density))),
            background: d3(background),
            gamma,
            relaxation: c(over_relaxation),
            refine: sign_refinement(&folded, &scene.settings),
            orbit: frame.reference_orbit(),
        })
    }

    /// What expressions read: the frame's time and parameters.
    pub(crate) fn env(&self) -> Env<'_, F> {
        Env::new(self.time, &self.params)
    }

    /// Pixel footprint per unit distance along a ray.
    pub(crate) fn footprint(&self) -> F {
        self.footprint
    }

    pub(crate) fn max_distance(&self) -> F {
        self.max_distance
    }

    pub(crate) fn background(&self) -> V3<F> {
        self.background
    }

    /// Step 1: the ray through the point (px, py) of the image, in pixels from the top left corner (a pixel's centre
    /// is at (x + 0.5, y + 0.5)).
    pub(crate) fn ray(&self, px: F, py: F) -> (V3<F>, V3<F>) {
        let two = c::<F>(2.0);
        let u = (two * px - self.width) / self.height;
        let v = -(two * py - self.height) / self.height;
        (self.origin, normalize(self.forward + self.right * u + self.up * v))
    }

    /// Steps 2–6 of the render algorithm for pixel (x, y): the linear colour before gamma, and how it was found.
    fn trace_pixel<E: Evaluator<F> + ?Sized>(&self, eval: &E, env: &Env<F>, x: u32, y: u32) -> Pixel<F> {
        let half = c::<F>(0.5);
        let (ro, rd) = self.ray(c::<F>(x as f64) + half, c::<F>(y as f64) + half);
        let march = self.march(eval, env, ro, rd);
        self.finish_pixel(eval, env, ro, rd, march)
    }

    /// Steps 4–6 for the ray (ro, rd) after its march (`None`: the ray misses the bound).
    fn finish_pixel<E: Evaluator<F> + ?Sized>(
        &self,
        eval: &E,
        env: &Env<F>,
        ro: V3<F>,
        rd: V3<F>,
        march: Option<March<F>>,
    ) -> Pixel<F> {
        self.finish_with(ro, rd, march, |p, t, eps| {
            let n = self.normal(eval, env, p, t, eps);
            (self.shade_hit(eval, env, p, n, rd, t, eps), n)
        })
    }

    /// Steps 4–6 with the hit's colour and normal from `shade(p, t, eps)`.
    fn finish_with(
        &self,
        ro: V3<F>,
        rd: V3<F>,
        march: Option<March<F>>,
        shade: impl FnOnce(V3<F>, F, F) -> (V3<F>, V3<F>),
    ) -> Pixel<F> {
        let Some(march) = march else {
            let background = self.background;
            return Pixel { colour: background, hit: false, t: F::nan(), steps: 0, out_of_steps: false, normal: None };
        };
        let (t, eps) = (march.t, march.eps);
        let (mut colour, normal) = if march.hit {
            let (colour, n) = shade(ro + rd * t, t, eps);
            (colour, Some(n))
        } else {
            (self.background, None)
        };
        if let Some(glow_colour) = self.glow {
            colour = colour + glow_colour * (march.glow / c(GLOW_NORM)).min(F::one());
        }
        Pixel { colour, hit: march.hit, t, steps: march.steps, out_of_steps: march.out_of_steps, normal }
    }

    /// Steps 2–3: clip to the bound and march; `None` for a ray that misses the bound.
    fn march<E: Evaluator<F> + ?Sized>(&self, eval: &E, env: &Env<F>, ro: V3<F>, rd: V3<F>) -> Option<March<F>> {
        let (t_near, t_far) = self.clip(ro, rd)?;
        let (mut t, mut eps, mut d, mut steps, mut glow) = (t_near, F::zero(), F::zero(), 0, F::zero());
        let mut last = (t_near, F::zero());
        let mut hit = false;
        // Over-relaxation (Keinert et al. 2014, "Enhanced sphere tracing"): step ω·d while the unbounding spheres of
        // successive points overlap; where they do not, the step may have passed the surface, so step back and go on
        // with ω = 1. With ω = 1 this is the render algorithm's march exactly (the fallback never fires).
        let mut omega = self.relaxation;
        let (mut previous, mut length) = (F::zero(), F::zero());
        // The kernels' loop condition, so a NaN t stops the march as it does there.
        while steps < self.max_steps && t <= t_far {
            steps += 1;
            d = eval.distance(ro + rd * t, env);
            eps = self.hit_epsilon(t);
            let overshot = omega > F::one() && d.abs() + previous < length;
            if overshot {
                length = length - omega * length;
                omega = F::one();
            } else if d < eps {
                let Some(rule) = self.refine.filter(|_| d > F::zero()) else {
                    hit = true;
                    break;
                };
                length = sign_step(rule, d, eps, t, last);
                omega = F::one();
            } else {
                length = d * omega;
            }
            previous = d.abs();
            if self.glow.is_some() {
                glow = glow + F::one() / (F::one() + c::<F>(GLOW_FALLOFF) * d * d);
            }
            last = (t, d);
            t = t + length;
        }
        let out_of_steps = !hit && steps == self.max_steps && t <= t_far;
        Some(self.refined(eval, env, ro, rd, March { hit, t, eps, d, last, steps, out_of_steps, glow }))
    }

    /// Step 3b's refinement of a march that ended, in a scene that [`View::refine`]s: a hit that brackets its
    /// crossing with the sample before it moves onto the crossing.
    fn refined<E: Evaluator<F> + ?Sized>(&self, eval: &E, env: &Env<F>, ro: V3<F>, rd: V3<F>, m: March<F>) -> March<F> {
        let ((mut a, mut fa), (mut b, mut fb)) = (m.last, (m.t, m.d));
        if !(self.refine.is_some() && m.hit && fa > F::zero()) {
            return m;
        }
        // Illinois: an end kept twice in a row has its value halved, so both ends move.
        let (half, mut side) = (c::<F>(0.5), F::zero());
        for _ in 0..REFINE_STEPS {
            let x = a + (b - a) * (fa / (fa - fb));
            let fx = eval.distance(ro + rd * x, env);
            if fx <= F::zero() {
                (b, fb) = (x, fx);
                if side < F::zero() {
                    fa = fa * half;
                }
                side = -F::one();
            } else {
                (a, fa) = (x, fx);
                if side > F::zero() {
                    fb = fb * half;
                }
                side = F::one();
            }
        }
        March { t: a + (b - a) * (fa / (fa - fb)), ..m }
    }

    pub(crate) fn hit_epsilon(&self, t: F) -> F {
        let eps = match self.epsilon {
            HitEpsilon::Fixed(e) => c(e),
            HitEpsilon::Pixel(k) => c::<F>(k) * self.footprint * t,
        };
        eps.max(c::<F>(T_SPACING) * t)
    }

    /// The part of the ray to march: inside the scene's bound (slab test) and before max_distance; `None` misses.
    fn clip(&self, ro: V3<F>, rd: V3<F>) -> Option<(F, F)> {
        let Some((lo, hi)) = self.bound else {
            return Some((F::zero(), self.max_distance));
        };
        let (t_near, t_far, enters) = slab(lo, hi, self.max_distance, ro, rd);
        enters.then_some((t_near, t_far))
    }

    /// Step 4's normal: the tetrahedral gradient of the distance at the hit `p` (ray distance `t`, epsilon `eps`).
    fn normal<E: Evaluator<F> + ?Sized>(&self, eval: &E, env: &Env<F>, p: V3<F>, t: F, eps: F) -> V3<F> {
        normal_from(normal_taps(p, self.normal_tap(t, eps)).map(|q| eval.distance(q, env)))
    }

    /// Step 4's tap of the normal at a hit at ray distance `t` with epsilon `eps`.
    fn normal_tap(&self, t: F, eps: F) -> F {
        if let Some(k) = self.normal_epsilon {
            c::<F>(k) * self.footprint * t
        } else if self.refine.is_some() {
            eps * c::<F>(REFINED_NORMAL_SHARE)
        } else {
            eps
        }
    }

    /// Step 4 after the normal: the colour of the hit at `p` (distance `t` along `rd`) with normal `n`.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn shade_hit<E: Evaluator<F> + ?Sized>(
        &self,
        eval: &E,
        env: &Env<F>,
        p: V3<F>,
        n: V3<F>,
        rd: V3<F>,
        t: F,
        eps: F,
    ) -> V3<F> {
        let de = |q: V3<F>| eval.distance(q, env);
        let ao = match self.ambient_occlusion {
            None => F::one(),
            Some(strength) => occlusion_from(strength, occlusion_points(p, n).map(de)),
        };
        let shadow = |_: usize, origin: V3<F>, l: V3<F>, limit: F| self.shadow(&de, origin, l, limit, eps);
        self.shade_lit(&self.material(eval, env, p, rd, t), p, n, rd, t, eps, ao, &shadow)
    }

    /// Light i's direction from `p`, its radiance there and how far a shadow ray goes towards it.
    fn light_at(&self, light: &Light<F>, p: V3<F>) -> (V3<F>, V3<F>, F) {
        match *light {
            Light::Directional { direction, radiance } => (direction, radiance, self.max_distance),
            Light::Point { position, radiance } => {
                let to_light = position - p;
                let distance = length(to_light);
                (to_light / distance, radiance / (distance * distance), distance)
            }
        }
    }

    /// The shadow ray of a lit hit: from `p` off the surface along the normal, towards light direction `l`.
    fn shadow_origin(&self, p: V3<F>, n: V3<F>, eps: F) -> V3<F> {
        p + n * (c::<F>(2.0) * eps)
    }

    /// The material at the hit `p`, distance `t` along `rd`.
    fn material<E: Evaluator<F> + ?Sized>(&self, eval: &E, env: &Env<F>, p: V3<F>, rd: V3<F>, t: F) -> Sample<F> {
        // A perturbed pattern reads the hit relative to the camera, rd·t, as the kernels pass it.
        let at_hit = Env {
            reference: (!self.orbit.is_empty()).then(|| Reference { offset: rd * t, orbit: &self.orbit }),
            ..*env
        };
        eval.sample(p, &at_hit)
    }

    /// Step 4 with the material `m`, the occlusion `ao` and, for each light i that faces the surface,
    /// `shadow(i, origin, l, limit)`.
    #[allow(clippy::too_many_arguments)]
    fn shade_lit(
        &self,
        m: &Sample<F>,
        p: V3<F>,
        n: V3<F>,
        rd: V3<F>,
        t: F,
        eps: F,
        ao: F,
        shadow: &dyn Fn(usize, V3<F>, V3<F>, F) -> F,
    ) -> V3<F> {
        let one = F::one();
        let mut colour = m.albedo * (m.ambient * ao);
        for (i, light) in self.lights.iter().enumerate() {
            let (l, radiance, limit) = self.light_at(light, p);
            let ndl = dot(n, l).max(F::zero());
            let shadow = if ndl > F::zero() { shadow(i, self.shadow_origin(p, n, eps), l, limit) } else { one };
            colour = colour + m.albedo * (m.diffuse * ndl) * radiance * shadow;
            if self.specular {
                let h = normalize(l - rd);
                let highlight = dot(n, h).max(F::zero()).powf(m.shininess);
                colour = colour + radiance * (m.specular * highlight) * shadow;
            }
        }
        if let Some((fog_colour, density)) = self.fog {
            let f = one - (-density * t).exp();
            colour = colour + (fog_colour - colour) * f;
        }
        colour
    }

    /// Light reaching `origin` from direction `l` within `limit`: 1 lit, 0 blocked, soft shadows in between.
    fn shadow(&self, de: &impl Fn(V3<F>) -> F, origin: V3<F>, l: V3<F>, limit: F, eps: F) -> F {
        if self.shadows == Shadows::None {
            return F::one();
        }
        let mut march = self.shadow_start(eps);
        while self.shadow_running(&march, limit) {
            let d = de(origin + l * march.t);
            self.shadow_step(&mut march, d, eps);
        }
        self.shadow_result(&march)
    }

    fn soft_k(&self) -> Option<F> {
        match self.shadows {
            Shadows::Soft(k) => Some(c::<F>(k)),
            _ => None,
        }
    }

    fn shadow_start(&self, eps: F) -> ShadowMarch<F> {
        // Soft shadows divide by t, so they start one step out; the origin is already off the surface.
        let t = if self.soft_k().is_some() { c::<F>(2.0) * eps } else { F::zero() };
        ShadowMarch { t, res: F::one(), steps: 0, blocked: false }
    }

    fn shadow_running(&self, march: &ShadowMarch<F>, limit: F) -> bool {
        !march.blocked && march.steps < self.max_steps && march.t < limit
    }

    /// One step of a shadow march that found distance `d` at its current point.
    fn shadow_step(&self, march: &mut ShadowMarch<F>, d: F, eps: F) {
        march.steps += 1;
        if d < eps {
            march.res = F::zero();
            march.blocked = true;
            return;
        }
        if let Some(k) = self.soft_k() {
            march.res = march.res.min(k * d / march.t);
        }
        march.t = march.t + d;
    }

    fn shadow_result(&self, march: &ShadowMarch<F>) -> F {
        let res = march.res;
        match self.soft_k() {
            None => res,
            Some(_) => res * res * (c::<F>(3.0) - c::<F>(2.0) * res),
        }
    }
}

/// A shadow ray's march so far.
#[derive(Clone, Copy)]
struct ShadowMarch<F> {
    t: F,
    res: F,
    steps: u32,
    blocked: bool,
}

/// The tetrahedron of offsets the normal samples the distance at.
fn tetrahedron<F: Real>() -> [V3<F>; 4] {
    let (one, neg) = (F::one(), -F::one());
    [v3(one, neg, neg), v3(neg, neg, one), v3(neg, one, neg), v3(one, one, one)]
}

/// Step 4's normal, sampled at these four points around `p`, `eps` apart.
fn normal_taps<F: Real>(p: V3<F>, eps: F) -> [V3<F>; 4] {
    tetrahedron::<F>().map(|k| p + k * eps)
}

/// The normal from the distances at [`normal_taps`]: the normalised tetrahedral gradient.
fn normal_from<F: Real>(distances: [F; 4]) -> V3<F> {
    let mut gradient = V3::splat(F::zero());
    for (k, d) in tetrahedron::<F>().into_iter().zip(distances) {
        gradient = gradient + k * d;
    }
    let len = length(gradient);
    // A flat gradient (all four taps equal) has no direction; the kernels then take +y.
    if len > F::zero() {
        gradient / len
    } else {
        v3(F::zero(), F::one(), F::zero())
    }
}

/// The distances of ambient occlusion's samples along the normal.
fn occlusion_heights<F: Real>() -> [F; AO_SAMPLES as usize] {
    std::array::from_fn(|i| c::<F>(AO_START) + c::<F>(AO_SPAN) * c::<F>(i as f64) / c::<F>((AO_SAMPLES - 1) as f64))
}

/// Ambient occlusion's sample points above `p`.
fn occlusion_points<F: Real>(p: V3<F>, n: V3<F>) -> [V3<F>; AO_SAMPLES as usize] {
    occlusion_heights::<F>().map(|h| p + n * h)
}

/// Ambient occlusion of `strength` (3 × the scene's) from the distances at [`occlusion_points`].
fn occlusion_from<F: Real>(strength: F, distances: [F; AO_SAMPLES as usize]) -> F {
    let one = F::one();
    let mut occ = F::zero();
    let mut weight = F::one();
    for (h, d) in occlusion_heights::<F>().into_iter().zip(distances) {
        occ = occ + (h - d) * weight;
        weight = weight * c::<F>(0.95);
    }
    (one - strength * occ).max(F::zero()).min(one)
}

/// Step 7: clamp, gamma, pack RGBA8 with R in the low byte.
pub(crate) fn pack<F: Real>(colour: V3<F>, gamma: f64) -> u32 {
    let channel = |v: F| {
        // Rust's max/min drop NaN, so a NaN channel becomes 0 rather than poisoning the pixel.
        let v = v.max(F::zero()).min(F::one());
        let v = if gamma == 2.0 {
            v.sqrt()
        } else if gamma == 1.0 {
            v
        } else {
            v.powf(c(1.0 / gamma))
        };
        ((v * c(255.0) + c(0.5)).f64() as u32).min(255)
    };
    channel(colour.x) | (channel(colour.y) << 8) | (channel(colour.z) << 16) | (255 << 24)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fractal_dsl::builder::*;

    #[test]
    fn packing_rounds_and_applies_gamma() {
        assert_eq!(pack(v3(1.0f32, 0.0, 0.25), 2.0), 0xff80_00ff);
        assert_eq!(pack(v3(0.5f32, 2.0, -1.0), 1.0), 0xff00_ff80);
        assert_eq!(pack(v3(f32::NAN, 0.0, 0.0), 2.0), 0xff00_0000);
    }

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
        let pose = crate::Pose::from_camera(&s.camera, 0.0, &|p| p.default).unwrap();
        let frame = Frame::new(&s, &pose, 0.0, 48, 48, &crate::ParamValues::defaults(&s)).unwrap();
        let render = |b: Option<Aabb>| render_with_bound::<f32, _>(&UnitSphere, &s, &frame, b).unwrap();
        // Marches that start at the bound's entry end within the hit epsilon of the same surface point.
        let unlike = |a: &Image, b: &Image| {
            let far = |p: &u32, q: &u32| unpack(*p).iter().zip(unpack(*q)).any(|(x, y)| x.abs_diff(y) > 1);
            a.pixels.iter().zip(&b.pixels).filter(|(p, q)| far(p, q)).count()
        };
        let unbounded = render(None);
        let tight = render(Some(Aabb { min: [-1.0; 3], max: [1.0; 3] }));
        assert_eq!(unlike(&tight, &unbounded), 0);
        let loose = render(Some(Aabb { min: [-1.5, -1.0, -1.2], max: [1.0, 2.0, 1.1] }));
        assert_eq!(unlike(&loose, &unbounded), 0);
        // A bound that holds only the top half of the sphere cuts the march short for rays towards the bottom half.
        let half = render(Some(Aabb { min: [-1.0, 0.0, -1.0], max: [1.0, 1.0, 1.0] }));
        let background = pack(v3(0.08f32, 0.09, 0.12), 2.0);
        let hits = unbounded.count_unlike(unpack(background), 0);
        let half_hits = half.count_unlike(unpack(background), 0);
        assert!(half_hits < hits * 9 / 10 && half_hits > hits / 4, "{half_hits} of {hits} hits left: no clipping");
        // A bound behind the camera: every ray misses.
        let behind = render(Some(Aabb { min: [-1.0, -1.0, -10.0], max: [1.0, 1.0, -9.0] }));
        assert!(behind.pixels.iter().all(|&p| p == background));
    }

    fn unpack(p: u32) -> [u8; 4] {
        p.to_le_bytes()
    }

    /// A scene's `normal_pixel_epsilon` takes the normal's tetrahedral taps that many footprints apart at the hit,
    /// whatever the hit epsilon: each traced normal is that gradient taken again at the traced hit, the march is
    /// unchanged, and on a fractal the normals turn from the fine epsilon's.
    #[test]
    fn the_normal_is_taken_at_the_scenes_normal_epsilon() {
        use fractal_dsl::eval::interp::Interpreter;
        let fine = scene(mandelbulb(8).iterations(6)).camera(camera([1.2, 1.0, -2.2], [0.0; 3])).pixel_epsilon(0.05);
        let wide = fine.clone().normal_pixel_epsilon(1.0);
        let pose = crate::Pose::from_camera(&fine.camera, 0.0, &|p| p.default).unwrap();
        let frame = Frame::new(&fine, &pose, 0.0, 40, 30, &crate::ParamValues::defaults(&fine)).unwrap();
        let trace = |s: &Scene| trace_scene::<f64, _>(&Interpreter::new(s).unwrap(), s, &frame).unwrap();
        let (before, after) = (trace(&fine), trace(&wide));
        let view = View::<f64>::new(&wide, &frame, None).unwrap();
        let interpreter = Interpreter::new(&wide).unwrap();
        let env = Env::new(view.time, &view.params);
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
            let taps = normal_taps(p, view.footprint * b.t);
            let expected = normal_from(taps.map(|q| Evaluator::<f64>::distance(&interpreter, q, &env)));
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
