//! Samples per pixel and the thin lens ([`fractal_dsl::ray::pixel`]) on every backend: the same samples and the same
//! adaptive stops on the CPU (scalar and packets) and in the kernels, extra samples where a pixel's colour changes,
//! a pixel's value converging to its box-filtered integral, and a lens that blurs what is out of focus only.

use fractal_dsl::builder::*;
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::Evaluator;
use fractal_dsl::number::math::v3;
use fractal_dsl::ray::pixel::FIRST;
use fractal_dsl::Scene;
use fractal_render::backend::cpu::{render_packets, render_scene, trace_scene};
use fractal_render::image::{pack_linear, unpack_rgba8};
use fractal_render::{CpuRenderer, Frame, Image, KernelSources, RenderJob, Renderer, WgpuRenderer};

use crate::common::available;

/// A sphere before a box, lit with shadows and occlusion: silhouettes, a shadow edge and smooth shading.
fn ball_and_box() -> Scene {
    scene(union(sphere(0.6).translate([-0.3, 0.0, 0.0]), box3([0.4, 0.4, 0.4]).translate([0.6, -0.2, 1.2])))
        .camera(camera([0.0, 0.6, -3.0], [0.0, 0.0, 0.0]).fov(45.0))
        .soft_shadows(8.0)
        .ambient_occlusion(0.5)
}

/// The box-filtered pixel integral of `s` at `w`×`h`: the scene traced at `k`×`k` rays per pixel on a regular lattice
/// (one ray through each cell's centre, f64), each ray's linear colour clamped, averaged, then displayed.
fn integral(s: &Scene, w: u32, h: u32, k: u32) -> Image {
    let fine = Frame::default_view(s, 0.0, w * k, h * k).unwrap();
    let one = s.clone().samples(1);
    let traces = trace_scene::<f64, _>(&Interpreter::new(&one).unwrap(), &one, &fine).unwrap();
    let pixels = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let mut sum = [0.0; 3];
            for j in 0..k * k {
                let t = &traces[((y * k + j / k) * w * k + x * k + j % k) as usize];
                for (c, v) in sum.iter_mut().zip(t.colour) {
                    *c += v.clamp(0.0, 1.0);
                }
            }
            let n = f64::from(k * k);
            pack_linear(v3((sum[0] / n) as f32, (sum[1] / n) as f32, (sum[2] / n) as f32), s.settings.gamma)
        })
        .collect();
    Image { width: w, height: h, pixels }
}

/// PSNR of `a` against `b` over RGB, in dB.
fn psnr(a: &Image, b: &Image) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        for (x, y) in unpack_rgba8(*p).iter().zip(unpack_rgba8(*q)).take(3) {
            sum += (f64::from(*x) - f64::from(y)).powi(2);
            n += 1.0;
        }
    }
    10.0 * (255.0f64 * 255.0 / (sum / n)).log10()
}

fn cpu(s: &Scene, frame: &Frame) -> Image {
    let interpreter = Interpreter::new(s).unwrap();
    CpuRenderer::new().render(&RenderJob::new(KernelSources::default().with_cpu(&interpreter, s), frame)).unwrap()
}

/// More samples bring a pixel to its integral: 16 adaptive samples are far closer to the 8×8-lattice integral than
/// one ray, at a fraction of 16 rays per pixel (a pixel whose first pass matches its neighbours keeps its one ray).
#[test]
fn samples_converge_to_the_pixels_integral_where_it_needs_them() {
    let (w, h) = (48, 32);
    let s = ball_and_box();
    let frame = Frame::default_view(&s, 0.0, w, h).unwrap();
    let truth = integral(&s, w, h, 8);
    let one = psnr(&cpu(&s, &frame), &truth);
    let many = s.clone().samples(16).sample_threshold(0.002);
    let sixteen = psnr(&cpu(&many, &frame), &truth);
    // Measured: 33.6 dB and 48.3 dB; the 4×4 and 16×16 lattices' integrals are 51 dB from the 8×8 one.
    assert!(sixteen > 45.0 && sixteen > one + 10.0, "one sample {one:.1} dB, sixteen {sixteen:.1} dB");
    let traces = trace_scene::<f32, _>(&Interpreter::new(&many).unwrap(), &many, &frame).unwrap();
    let taken: Vec<u32> = traces.iter().map(|t| t.samples).collect();
    let mean = taken.iter().sum::<u32>() as f64 / taken.len() as f64;
    assert!(taken.iter().all(|&n| n == 1 || (FIRST..=16).contains(&n)), "{taken:?}");
    assert!(mean < 4.0, "{mean:.2} samples per pixel: adaptivity does not pay");
    // Where a pixel's neighbourhood crosses a silhouette it refines; most pixels inside one surface or the
    // background keep their one ray.
    let hit: Vec<bool> = traces.iter().map(|t| t.hit).collect();
    let at = |x: i64, y: i64| hit[(y.clamp(0, h as i64 - 1) * w as i64 + x.clamp(0, w as i64 - 1)) as usize];
    let (mut inner, mut inner_one, mut edges, mut refined) = (0, 0, 0, 0);
    for y in 0..h as i64 {
        for x in 0..w as i64 {
            let around = (-1..=1).flat_map(|j| (-1..=1).map(move |i| (i, j)));
            let one = taken[(y * w as i64 + x) as usize] == 1;
            if around.clone().any(|(i, j)| at(x + i, y + j) != at(x, y)) {
                edges += 1;
                refined += usize::from(!one);
            } else {
                inner += 1;
                inner_one += usize::from(one);
            }
        }
    }
    assert!(refined * 10 >= edges * 9, "{refined} of {edges} pixels across a silhouette refined");
    assert!(inner_one * 2 >= inner, "{inner_one} of {inner} pixels inside kept their one ray");
}

/// The packet renderer takes the scalar renderer's samples and stops where it stops, and the kernels draw the same
/// supersampled images (a lens too) within the backends' usual tolerance.
#[test]
fn supersampled_images_agree_on_every_backend() {
    let mut gpu = available("wgpu", WgpuRenderer::new());
    #[cfg(feature = "opencl")]
    let mut cl = available("OpenCL", fractal_render::OpenClRenderer::new(false));
    let lens = ball_and_box().camera(camera([0.0, 0.6, -3.0], [0.0, 0.0, 0.0]).fov(45.0).aperture(0.3));
    for (name, s) in [("ball and box", ball_and_box().samples(12)), ("lens", lens.samples(12))] {
        let frame = Frame::default_view(&s, 0.0, 45, 30).unwrap();
        let interp = Interpreter::new(&s).unwrap();
        let packets = Evaluator::<f32>::packets(&interp).expect("the interpreter has a packet instance");
        let packed = render_packets(packets, &s, &frame).unwrap();
        let scalar = render_scene::<f32, _>(&interp, &s, &frame).unwrap();
        let differing = packed.pixels.iter().zip(&scalar.pixels).filter(|(a, b)| a != b).count();
        assert_eq!(differing, 0, "{name}: {differing} pixels differ between packet and scalar sampling");
        let kernels = fractal_dsl::compile(&s).unwrap();
        let tracing = kernels.tracing();
        let cpu_samples: Vec<u32> =
            trace_scene::<f32, _>(&interp, &s, &frame).unwrap().iter().map(|t| t.samples).collect();
        assert!(cpu_samples.contains(&1) || name == "lens", "{name}: no pixel kept its one ray");
        let check = |backend: &str, renderer: &mut dyn Renderer| {
            let image = renderer.render(&RenderJob::new(KernelSources::compiled(&kernels), &frame)).unwrap();
            let off = crate::common::fraction_different(&scalar, &image, 3);
            assert!(off < 0.02, "{name}: {:.2} % of {backend}'s pixels differ by more than 3 levels", off * 100.0);
            // The trace kernel's second pass writes the samples of the pixels it refined.
            let traced = renderer.trace(&RenderJob::new(KernelSources::compiled(&tracing), &frame)).unwrap();
            let same = traced.pixels.iter().zip(&cpu_samples).filter(|(t, &n)| t.samples == n).count();
            assert!(same * 50 >= cpu_samples.len() * 49, "{name}: {backend} took the CPU's samples at {same} pixels");
        };
        if let Some(gpu) = gpu.as_mut() {
            check("wgpu", gpu);
        }
        #[cfg(feature = "opencl")]
        if let Some(cl) = cl.as_mut() {
            check("OpenCL", cl);
        }
    }
}

/// A thin lens focused on the sphere keeps its silhouette where the pinhole has it and blurs the box behind it;
/// focused far behind both, it blurs the sphere too. One sample is the pinhole's ray whatever the lens.
#[test]
fn a_lens_blurs_what_is_out_of_focus() {
    let (w, h) = (60, 40);
    let base = ball_and_box().samples(64).sample_threshold(0.0);
    let lens = |focus: f64| {
        base.clone().camera(camera([0.0, 0.6, -3.0], [0.0, 0.0, 0.0]).fov(45.0).aperture(0.5).focus(focus))
    };
    let frame = Frame::default_view(&base, 0.0, w, h).unwrap();
    let pinhole = cpu(&base, &frame);
    let on_ball = cpu(&lens(3.0), &frame);
    let far = cpu(&lens(30.0), &frame);
    // The left half holds the sphere, the right half the box behind it.
    let half_psnr = |a: &Image, b: &Image, left: bool| {
        let pick = |i: &Image| Image {
            width: w / 2,
            height: h,
            pixels: (0..h)
                .flat_map(|y| (0..w / 2).map(move |x| (x + if left { 0 } else { w / 2 }, y)))
                .map(|(x, y)| i.pixels[(y * w + x) as usize])
                .collect(),
        };
        psnr(&pick(a), &pick(b))
    };
    let (sharp_ball, blurred_box) = (half_psnr(&on_ball, &pinhole, true), half_psnr(&on_ball, &pinhole, false));
    let blurred_ball = half_psnr(&far, &pinhole, true);
    assert!(sharp_ball > blurred_box + 5.0, "in focus {sharp_ball:.1} dB, out of focus {blurred_box:.1} dB");
    assert!(sharp_ball > blurred_ball + 5.0, "in focus {sharp_ball:.1} dB, focused far {blurred_ball:.1} dB");
    let single = cpu(&lens(30.0).samples(1), &frame);
    assert_eq!(single.pixels, cpu(&base.clone().samples(1), &frame).pixels, "one sample is the pinhole's ray");
}

/// A progressive render's passes are the pixel program's samples, drawn by moving the camera: nine passes of the
/// one-sample program draw what nine samples a pixel (no adaptive stop) draw, through a lens too, on the CPU and on
/// wgpu.
#[test]
fn progressive_passes_take_the_pixel_programs_samples() {
    use fractal_render::progressive::Progressive;
    let lens = ball_and_box().camera(camera([0.0, 0.6, -3.0], [0.0, 0.0, 0.0]).fov(45.0).aperture(0.3));
    for (name, s) in [("pinhole", ball_and_box()), ("lens", lens)] {
        let frame = Frame::default_view(&s, 0.0, 40, 30).unwrap();
        let direct = cpu(&s.clone().samples(9).sample_threshold(0.0), &frame);
        let one = s.clone().samples(1);
        let interp = Interpreter::new(&one).unwrap();
        let kernels = fractal_dsl::compile(&one).unwrap().tracing();
        let mut renderers: Vec<(&str, Box<dyn Renderer>, KernelSources)> =
            vec![("CPU", Box::new(CpuRenderer::new()), KernelSources::default().with_cpu(&interp, &one))];
        if let Some(gpu) = available("wgpu", WgpuRenderer::new()) {
            renderers.push(("wgpu", Box::new(gpu), KernelSources::compiled(&kernels)));
        }
        for (backend, mut renderer, sources) in renderers {
            let mut passes = Progressive::new(&one, &frame);
            for _ in 0..9 {
                passes.draw(renderer.as_mut(), &RenderJob::new(sources, &frame)).unwrap();
            }
            let alike = psnr(&passes.image(), &direct);
            // The moved camera is rounded to f32 and the kernels' arithmetic is not the CPU's: not bit-equal.
            assert!(alike > 40.0, "{name} on {backend}: nine passes are {alike:.1} dB from nine samples");
        }
    }
}
