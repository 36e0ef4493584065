//! Where the cubes go, and what the five shots must show.
//!
//! The cubes are placed from the project's depth of the same view (`fractal render --aov depth`): the front one's far
//! side nearer than every hit, the behind one's near side farther than every hit, each over part of the fractal.
//! Checks, against that render and its depth: the fractal's pixels agree (holes: the project hits and the engine shows
//! background; the budget is 0.2 % of the fractal's pixels), its colours agree within a stated tolerance, the front
//! cube hides every fractal pixel it covers, and the fractal hides the behind cube where they overlap.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use bevy::math::Vec3;

/// Holes allowed, as a fraction of the fractal's pixels in the project's render.
pub const MAX_HOLES: f64 = 0.002;
/// Pixels both call fractal whose colour may differ by more than [`COLOUR_STEP`] in a channel (the march in f32 on
/// another GPU stack lands a step apart on some rays: edges of shadows, grazing hits).
pub const MAX_OFF_COLOUR: f64 = 0.01;
/// A channel difference, in 8-bit steps, above which a pixel counts as off.
pub const COLOUR_STEP: u8 = 8;
/// Mean absolute channel difference allowed over pixels both call fractal, in 8-bit steps.
pub const MAX_MEAN_COLOUR: f64 = 1.0;

/// The imported mesh's silhouette may miss, or exceed, the fractal's by this share of its pixels: the mesh is the
/// surface sampled on a grid (`run.sh` meshes at 128 cells), so fine detail and thin gaps are lost.
pub const MAX_MESH_MISMATCH: f64 = 0.05;

/// A camera as `fractal render --camera-pos/--camera-target/--fov` gives it, in the scene's frame.
#[derive(Clone, Copy, Debug)]
pub struct View {
    pub eye: Vec3,
    pub target: Vec3,
    pub fov_degrees: f32,
    pub size: (u32, u32),
}

impl View {
    fn basis(&self) -> (Vec3, Vec3, Vec3) {
        // Left-handed, y up: right = up × forward.
        let forward = (self.target - self.eye).normalize();
        let right = Vec3::Y.cross(forward).normalize();
        (forward, right, forward.cross(right))
    }

    /// The unit ray through the centre of pixel (x, y), y down.
    fn ray(&self, x: f32, y: f32) -> Vec3 {
        let (forward, right, up) = self.basis();
        let (w, h) = (self.size.0 as f32, self.size.1 as f32);
        let tan_half = (0.5 * self.fov_degrees.to_radians()).tan();
        let u = (2.0 * (x + 0.5) - w) / h;
        let v = (h - 2.0 * (y + 0.5)) / h;
        (forward + tan_half * (u * right + v * up)).normalize()
    }
}

/// Ray distances per pixel (row-major, y down; +inf for a miss), from the depth OpenEXR `fractal render` writes.
fn read_depth(path: &Path) -> Result<(Vec<f32>, usize, usize), String> {
    use exr::prelude::*;
    let image = read_first_flat_layer_from_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let size = image.layer_data.size;
    let channel = image.layer_data.channel_data.list.first().ok_or(format!("{}: no channel", path.display()))?;
    let values: Vec<f32> = channel.sample_data.values_as_f32().collect();
    Ok((values, size.0, size.1))
}

/// The front and behind cubes (centre, half size) for `view`, from the project's depth of it.
pub fn place_cubes(view: View, depth: &Path) -> Result<((Vec3, f32), (Vec3, f32)), String> {
    let (t, w, h) = read_depth(depth)?;
    if (w as u32, h as u32) != view.size {
        return Err(format!("{}: {w}x{h}, not the view's size", depth.display()));
    }
    let (forward, _, _) = view.basis();
    let hits: Vec<(usize, usize, f32)> =
        (0..w * h).filter(|&i| t[i].is_finite()).map(|i| (i % w, i / w, t[i])).collect();
    if hits.len() < 100 {
        return Err(format!(
            "{}: the fractal covers {} pixels; choose a view that shows it",
            depth.display(),
            hits.len()
        ));
    }
    // Nearest and farthest hit, as depth along the view axis and as ray distance.
    let z_min = hits.iter().map(|&(x, y, t)| t * view.ray(x as f32, y as f32).dot(forward)).fold(f32::MAX, f32::min);
    let t_max = hits.iter().map(|&(_, _, t)| t).fold(0.0, f32::max);
    let nearest_to = |fx: f32, fy: f32| {
        let (tx, ty) = (fx * w as f32, fy * h as f32);
        let d = |&&(x, y, _): &&(usize, usize, f32)| (x as f32 - tx).powi(2) + (y as f32 - ty).powi(2);
        *hits.iter().min_by(|a, b| d(a).total_cmp(&d(b))).expect("hits")
    };
    // In front: centred on a fractal pixel left of the middle, at half the nearest depth; an axis-aligned cube reaches
    // at most √3·half beyond its centre's depth, so with half = 0.08·z its far side is nearer than every hit.
    let (fx, fy, _) = nearest_to(0.4, 0.45);
    let ray = view.ray(fx as f32, fy as f32);
    let front_half = 0.08 * z_min;
    let front = (view.eye + ray * (0.5 * z_min / ray.dot(forward)), front_half);
    // Behind: centred on the right edge of the fractal's silhouette at its middle height, its near side beyond the
    // farthest hit, wide enough to show on both sides of that edge.
    let right_edge = hits.iter().map(|&(x, _, _)| x).max().expect("hits");
    let mid_y = hits.iter().map(|&(_, y, _)| y).sum::<usize>() / hits.len();
    let ray = view.ray(right_edge as f32, mid_y as f32);
    let behind_half = 0.3 * t_max * (0.5 * view.fov_degrees.to_radians()).tan();
    let centre_depth = t_max + 1.8 * behind_half;
    let behind = (view.eye + ray * (centre_depth / ray.dot(forward)), behind_half);
    Ok((front, behind))
}

fn read_rgb(path: &Path) -> Result<image::RgbImage, String> {
    Ok(image::open(path).map_err(|e| format!("{}: {e}", path.display()))?.to_rgb8())
}

const MAGENTA: [u8; 3] = [255, 0, 255];
const GREEN: [u8; 3] = [0, 255, 0];

fn near(a: [u8; 3], b: [u8; 3], step: u8) -> bool {
    a.iter().zip(b).all(|(&x, y)| x.abs_diff(y) <= step)
}

/// `check --out DIR --reference PNG --depth EXR`: prints the figures, fails when one is outside its bound.
pub fn run(args: &[String]) -> ExitCode {
    match check(args) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("check: {e}");
            ExitCode::from(2)
        }
    }
}

fn check(args: &[String]) -> Result<bool, String> {
    let value = |flag: &str| -> Result<PathBuf, String> {
        let i = args.iter().position(|a| a == flag).ok_or(format!("missing {flag}"))?;
        args.get(i + 1).map(PathBuf::from).ok_or(format!("{flag} needs a value"))
    };
    let out = value("--out")?;
    let reference = read_rgb(&value("--reference")?)?;
    let (depth, w, h) = read_depth(&value("--depth")?)?;
    let shot = |name: &str| read_rgb(&out.join(format!("bevy-{name}.png")));
    let (fractal, front_cube, front, behind_cube, behind) =
        (shot("fractal")?, shot("front_cube")?, shot("front")?, shot("behind_cube")?, shot("behind")?);
    for (name, image) in [("fractal", &fractal), ("reference", &reference)] {
        if image.dimensions() != (w as u32, h as u32) {
            return Err(format!("{name} is {:?}, the depth {w}x{h}", image.dimensions()));
        }
    }
    let px = |image: &image::RgbImage, i: usize| image.get_pixel((i % w) as u32, (i / w) as u32).0;
    let mut ok = true;
    let mut verdict = |name: &str, pass: bool, text: String| {
        println!("{} {name}: {text}", if pass { "ok  " } else { "FAIL" });
        ok &= pass;
    };

    // The fractal against the project's render.
    let project_hits = depth.iter().filter(|d| d.is_finite()).count();
    let engine_hit = |i: usize| !near(px(&fractal, i), MAGENTA, 2);
    let holes = (0..w * h).filter(|&i| depth[i].is_finite() && !engine_hit(i)).count();
    let extra = (0..w * h).filter(|&i| !depth[i].is_finite() && engine_hit(i)).count();
    let share = |n: usize| n as f64 / project_hits.max(1) as f64;
    verdict(
        "holes",
        share(holes) <= MAX_HOLES,
        format!(
            "{holes} of the project's {project_hits} fractal pixels are background in Bevy ({:.3} %, at most {:.1} %); {extra} extra ({:.3} %)",
            100.0 * share(holes),
            100.0 * MAX_HOLES,
            100.0 * share(extra)
        ),
    );
    let both: Vec<usize> = (0..w * h).filter(|&i| depth[i].is_finite() && engine_hit(i)).collect();
    let mut sum = [0.0f64; 3];
    let mut mean_engine = [0.0f64; 3];
    let mut mean_project = [0.0f64; 3];
    let mut off = 0;
    for &i in &both {
        let (a, b) = (px(&fractal, i), px(&reference, i));
        for c in 0..3 {
            sum[c] += f64::from(a[c].abs_diff(b[c]));
            mean_engine[c] += f64::from(a[c]);
            mean_project[c] += f64::from(b[c]);
        }
        off += usize::from(!near(a, b, COLOUR_STEP));
    }
    let n = both.len().max(1) as f64;
    let mean = sum.map(|s| s / n);
    verdict(
        "colour",
        mean.iter().all(|&m| m <= MAX_MEAN_COLOUR) && off as f64 / n <= MAX_OFF_COLOUR,
        format!(
            "mean |Δ| per channel {:.2} {:.2} {:.2} (at most {MAX_MEAN_COLOUR}); {:.2} % of pixels off by more than {COLOUR_STEP}/255 \
             (at most {:.0} %); mean colour Bevy {:.0?}, project {:.0?}",
            mean[0],
            mean[1],
            mean[2],
            100.0 * off as f64 / n,
            100.0 * MAX_OFF_COLOUR,
            mean_engine.map(|s| s / n),
            mean_project.map(|s| s / n)
        ),
    );

    // Occlusion. In front: every pixel of the cube stays the cube's, and some of them cover the fractal.
    let cube = |image: &image::RgbImage, i: usize| near(px(image, i), GREEN, 2);
    let front_pixels: Vec<usize> = (0..w * h).filter(|&i| cube(&front_cube, i)).collect();
    let covered = front_pixels.iter().filter(|&&i| engine_hit(i)).count();
    let shown = front_pixels.iter().filter(|&&i| cube(&front, i)).count();
    verdict(
        "cube in front",
        covered >= 100 && shown == front_pixels.len(),
        format!("{shown} of its {} pixels show the cube, {covered} of them over the fractal", front_pixels.len()),
    );
    // Behind: where it overlaps the fractal, the fractal shows (its own colour); elsewhere the cube does.
    let behind_pixels: Vec<usize> = (0..w * h).filter(|&i| cube(&behind_cube, i)).collect();
    let (over, beside): (Vec<usize>, Vec<usize>) = behind_pixels.iter().partition(|&&i| engine_hit(i));
    let fractal_shows = over.iter().filter(|&&i| near(px(&behind, i), px(&fractal, i), 2)).count();
    let cube_shows = beside.iter().filter(|&&i| cube(&behind, i)).count();
    verdict(
        "cube behind",
        // (A scene with a floor may hide the whole cube: then there is no "elsewhere" to see.)
        over.len() >= 100 && fractal_shows == over.len() && cube_shows == beside.len(),
        format!(
            "the fractal shows on {fractal_shows} of the {} pixels where they overlap; the cube on {cube_shows} of its {} others",
            over.len(),
            beside.len()
        ),
    );
    // The imported mesh (`fractal mesh`): its silhouette against the fractal's, within what a mesh of that
    // resolution can hold.
    if let Ok(mesh) = shot("mesh") {
        let drawn = |i: usize| !near(px(&mesh, i), MAGENTA, 2);
        let missed = (0..w * h).filter(|&i| depth[i].is_finite() && !drawn(i)).count();
        let extra = (0..w * h).filter(|&i| !depth[i].is_finite() && drawn(i)).count();
        // A scene reaching the image's border (a floor, an unbounded set) is meshed only inside its bounding box:
        // then only the mesh's extra pixels count (it must not cover what is not the fractal).
        let border = (0..w).flat_map(|x| [x, (h - 1) * w + x]).chain((0..h).flat_map(|y| [y * w, y * w + w - 1]));
        let bounded = !border.into_iter().any(|i| depth[i].is_finite());
        verdict(
            "mesh",
            (!bounded || share(missed) <= MAX_MESH_MISMATCH) && share(extra) <= MAX_MESH_MISMATCH,
            format!(
                "the imported mesh misses {:.2} % of the fractal's pixels{} and covers {:.2} % more (each at most {:.0} %)",
                100.0 * share(missed),
                if bounded { "" } else { " (not judged: the scene reaches the image's border)" },
                100.0 * share(extra),
                100.0 * MAX_MESH_MISMATCH
            ),
        );
    }
    Ok(ok)
}
