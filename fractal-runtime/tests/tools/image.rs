//! The truth of an image and the image metrics: a sphere's silhouette coverage against the analytic disc, the
//! estimate settling as its lattice grows, perfect and shifted images, flicker, the normals judged on a fractal, and
//! `fractal accuracy --image`'s handling of its options.

use std::process::ExitCode;

use fractal_dsl::builder::*;
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::number::math::dot;
use fractal_dsl::Scene;
use fractal_render::backend::cpu::{render_scene, trace_scene, View};
use fractal_render::frame::Frame;
use fractal_render::image::{pack_rgba8, unpack_rgba8, Image};
use fractal_runtime::accuracy::image::{flicker, image_error, normal_error, ssim};
use fractal_runtime::cli::{run_with_args, SceneLibrary};
use fractal_runtime::truth::image::{ImageTruth, ImageTruthSettings};

/// A unit sphere at the origin, seen from 3 units away.
fn ball() -> Scene {
    scene(sphere(1.0)).camera(camera([0.0, 0.0, -3.0], [0.0; 3]).fov(40.0))
}

/// `grid` sub-rays per side, never refined.
fn fixed(grid: u32) -> ImageTruthSettings {
    ImageTruthSettings { grid, max_grid: grid, ..Default::default() }
}

/// The share of pixel (x, y) the unit sphere covers, from a 64×64 lattice of analytic ray-sphere tests: far finer
/// than the truth's lattices, so its own error (under 1/128 for an edge crossing the pixel) is below the tolerances.
fn analytic_coverage(view: &View<f64>, x: u32, y: u32) -> f64 {
    let n = 64;
    let mut inside = 0;
    for j in 0..n {
        for i in 0..n {
            let (ro, rd) = view.ray(x as f64 + (i as f64 + 0.5) / n as f64, y as f64 + (j as f64 + 0.5) / n as f64);
            let b = dot(ro, rd);
            inside += (b * b - (dot(ro, ro) - 1.0) > 0.0) as usize;
        }
    }
    inside as f64 / (n * n) as f64
}

/// On a sphere the truth's coverage of a silhouette pixel is the disc's: an 8×8 lattice of cell centres counts an
/// edge crossing the pixel to within half a cell per row, 1/16 of the pixel, and the mean error is far less.
#[test]
fn a_spheres_silhouette_coverage_is_the_analytic_discs() {
    let s = ball();
    let (w, h) = (24, 18);
    let frame = Frame::default_view(&s, 0.0, w, h).unwrap();
    let truth =
        ImageTruth::compute(&s, &frame, ImageTruthSettings { grid: 4, max_grid: 8, ..Default::default() }).unwrap();
    let view = View::<f64>::new(&s, &frame, None).unwrap();
    let (mut edges, mut total) = (0, 0.0);
    for y in 0..h {
        for x in 0..w {
            let want = analytic_coverage(&view, x, y);
            let got = truth.at(x, y);
            let error = (got.coverage - want).abs();
            assert!(error <= 1.0 / 16.0 + 1.0 / 128.0, "({x}, {y}): {} against {want}", got.coverage);
            if want > 0.0 && want < 1.0 {
                edges += 1;
                total += error;
            }
        }
    }
    assert!(edges > 20, "{edges} silhouette pixels");
    assert!(total / (edges as f64) < 0.02, "mean coverage error {}", total / edges as f64);
}

/// The estimate settles as the lattice grows: the change from one lattice to the one of twice the sub-rays per side
/// shrinks at every doubling (a stratified estimate of an edge pixel errs by about a row's half cell, halving with
/// the spacing), and at 8→16 it is under 1 % of the range.
#[test]
fn the_image_truth_of_a_lit_sphere_settles_as_its_lattice_grows() {
    let s = ball();
    let frame = Frame::default_view(&s, 0.0, 24, 18).unwrap();
    let truths: Vec<Vec<[f64; 3]>> = [2, 4, 8, 16]
        .iter()
        .map(|&g| ImageTruth::compute(&s, &frame, fixed(g)).unwrap().pixels.iter().map(|p| p.display).collect())
        .collect();
    let rms = |a: &[[f64; 3]], b: &[[f64; 3]]| {
        let sum: f64 = a.iter().zip(b).flat_map(|(p, q)| (0..3).map(move |i| (p[i] - q[i]).powi(2))).sum();
        (sum / (3 * a.len()) as f64).sqrt()
    };
    let steps: Vec<f64> = truths.windows(2).map(|w| rms(&w[0], &w[1])).collect();
    assert!(steps[0] > steps[1] && steps[1] > steps[2], "changes per doubling {steps:?}");
    assert!(steps[2] < 0.01, "changes per doubling {steps:?}");
}

/// An image that is the truth scores PSNR +∞, SSIM 1 and no pixel off; the same shifted by one pixel scores less on
/// all three (the sphere's edge moves by a pixel, far more than 8 levels there).
#[test]
fn the_truth_itself_is_perfect_and_a_shift_by_one_pixel_is_not() {
    let s = ball();
    let frame = Frame::default_view(&s, 0.0, 32, 24).unwrap();
    let truth = ImageTruth::compute(&s, &frame, fixed(4)).unwrap().image();
    let same = image_error(&truth, &truth);
    assert!(same.psnr.is_infinite() && same.off == 0.0, "{}", same.describe());
    assert!((same.ssim - 1.0).abs() < 1e-12, "{}", same.describe());
    let shifted = shift(&truth);
    let error = image_error(&truth, &shifted);
    assert!(error.psnr.is_finite() && error.psnr < 35.0, "{}", error.describe());
    assert!(error.ssim < 0.99 && error.off > 0.01, "{}", error.describe());
    assert!((ssim(&truth, &shifted) - ssim(&shifted, &truth)).abs() < 1e-12, "SSIM is symmetric");
}

/// `image` moved one pixel right (its first column repeated).
fn shift(image: &Image) -> Image {
    let w = image.width as usize;
    let pixels = (0..image.pixels.len()).map(|i| image.pixels[if i % w == 0 { i } else { i - 1 }]).collect();
    Image { pixels, ..image.clone() }
}

/// Flicker counts the render's frame-to-frame change beyond the truth's: none for a still sequence, none where the
/// render moves exactly as the truth does, and the noise's RMS where a render adds ±4 levels to alternate frames.
#[test]
fn flicker_is_the_change_the_truth_does_not_make() {
    let s = ball();
    let frame = Frame::default_view(&s, 0.0, 32, 24).unwrap();
    let truth = ImageTruth::compute(&s, &frame, fixed(2)).unwrap().image();
    let moved = shift(&truth);
    assert_eq!(flicker(&[(truth.clone(), truth.clone()), (truth.clone(), truth.clone())]), 0.0);
    assert_eq!(flicker(&[(truth.clone(), truth.clone()), (moved.clone(), moved.clone())]), 0.0);
    // Mid-grey, so ±4 never clips.
    let grey = Image { pixels: vec![pack_rgba8([128, 128, 128, 255]); truth.pixels.len()], ..truth.clone() };
    let nudged = |d: i16| {
        let pixels = grey
            .pixels
            .iter()
            .map(|&p| {
                let c = unpack_rgba8(p).map(|v| (v as i16 + d) as u8);
                pack_rgba8([c[0], c[1], c[2], 255])
            })
            .collect();
        Image { pixels, ..grey.clone() }
    };
    let sequence: Vec<(Image, Image)> = [4, -4, 4].iter().map(|&d| (nudged(d), grey.clone())).collect();
    assert!((flicker(&sequence) - 8.0).abs() < 1e-12, "{}", flicker(&sequence));
}

/// On a fractal the render's normals are judged against the pixel-integrated true normal on at least 90 % of the
/// pixels either hits (the rest: pixels where one hits and the other has under half its sub-rays on the surface).
#[test]
fn normals_are_judged_on_most_hit_pixels_of_a_fractal() {
    let bulb = scene(mandelbulb(8).iterations(4)).camera(camera([1.2, 1.0, -2.2], [0.0; 3]));
    let frame = Frame::default_view(&bulb, 0.0, 32, 18).unwrap();
    let truth =
        ImageTruth::compute(&bulb, &frame, ImageTruthSettings { grid: 2, max_grid: 4, ..Default::default() }).unwrap();
    let traces = trace_scene::<f32, _>(&Interpreter::new(&bulb).unwrap(), &bulb, &frame).unwrap();
    let normals = normal_error(&truth, &traces);
    assert!(normals.hit_pixels > 100, "{}", normals.describe());
    assert!(normals.judged_share() >= 0.9, "{}", normals.describe());
    assert!(normals.median.is_finite(), "{}", normals.describe());
}

/// A one-ray render of a smooth sphere is the truth but for its silhouette's aliasing: high PSNR and SSIM, few pixels
/// off (those on the silhouette), and normals that are the exact ones to within the renderer's f32 taps.
#[test]
fn a_one_ray_render_of_a_sphere_errs_on_its_silhouette_only() {
    let s = ball();
    let frame = Frame::default_view(&s, 0.0, 48, 36).unwrap();
    let truth = ImageTruth::compute(&s, &frame, ImageTruthSettings::default()).unwrap();
    let interpreter = Interpreter::new(&s).unwrap();
    let image = render_scene::<f32, _>(&interpreter, &s, &frame).unwrap();
    let error = image_error(&truth.image(), &image);
    let silhouette = truth.pixels.iter().filter(|p| p.coverage > 0.0 && p.coverage < 1.0).count();
    assert!(error.psnr > 25.0 && error.ssim > 0.9, "{}", error.describe());
    assert!(error.off * (48.0 * 36.0) <= silhouette as f64, "{} ({silhouette} silhouette pixels)", error.describe());
    let normals = normal_error(&truth, &trace_scene::<f32, _>(&interpreter, &s, &frame).unwrap());
    assert!(normals.median < 1.0 && normals.judged_share() > 0.95, "{}", normals.describe());
}

fn library() -> SceneLibrary {
    SceneLibrary { scenes: scenes::ALL, source_file: scenes::source_file }
}

fn run(args: &[&str]) -> ExitCode {
    run_with_args(["fractal", "accuracy"].iter().chain(args).map(|a| a.into()), &library())
}

/// Bad options are usage errors, not panics; a tiny run succeeds.
#[test]
fn accuracy_image_refuses_bad_lattices_and_runs_a_small_scene() {
    let failed = |args: &[&str]| format!("{:?}", run(args)) != format!("{:?}", ExitCode::SUCCESS);
    assert!(failed(&["trivial", "--image", "--truth-grid", "8", "--truth-max-grid", "4"]));
    assert!(failed(&["trivial", "--image", "--truth-grid", "1"]));
    assert!(failed(&["trivial", "--image", "--truth-settle", "-1"]));
    assert!(failed(&["trivial", "--truth-grid", "4"]), "--truth-grid without --image");
    assert!(failed(&["trivial", "--image", "--report"]), "--report studies every scene");
    assert!(failed(&["--image"]), "no scene and no --report");
    assert!(failed(&["trivial", "--image", "--sample-thresholds", "2"]), "a threshold above 1");
    assert!(failed(&["trivial", "--sample-thresholds", "0.001"]), "--sample-thresholds without --image");
    assert!(failed(&["trivial", "--image", "--progressive", "0"]), "no time to refine in");
    assert!(!failed(&["trivial", "--image", "--size", "16x9", "--flicker-frames", "2", "--truth-max-grid", "4"]));
    assert!(!failed(&["trivial", "--image", "--size", "16x9", "--flicker-frames", "1", "--progressive", "0.05"]));
}

/// `--image --report` studies every built-in scene at each setting and writes the report, its summary line per
/// scene and a plot per scene beside it.
#[test]
fn accuracy_image_report_covers_every_scene_with_a_plot() {
    let dir = std::env::temp_dir().join(format!("fractal-image-report-{}", std::process::id()));
    let out = dir.join("image-accuracy.md");
    let status = run(&[
        "--image",
        "--report",
        "--size",
        "8x5",
        "--samples",
        "1,5",
        "--sample-thresholds",
        "0.004,0.001",
        "--flicker-frames",
        "1",
        "--truth-max-grid",
        "4",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(format!("{status:?}"), format!("{:?}", ExitCode::SUCCESS));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(text.contains("--samples 1,5 --sample-thresholds 0.004,0.001"), "the command is on record:\n{text}");
    for (name, _) in scenes::ALL {
        assert!(text.contains(&format!("\n| {name} | ")), "{name} has a summary line:\n{text}");
        assert!(text.contains(&format!("\n## {name}\n")), "{name} has a section");
        assert!(text.contains(&format!("](image-accuracy/{name}.svg)")), "{name}'s plot is linked");
        let plot = std::fs::read_to_string(dir.join("image-accuracy").join(format!("{name}.svg"))).unwrap();
        assert!(plot.contains("time against image error"), "{name}'s plot");
    }
    // One sample, then 5 at each threshold: three rows a scene, and the rule's choice.
    assert!(text.contains("| samples 5, threshold 0.001 |") && text.contains("The rule (the best image"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}
