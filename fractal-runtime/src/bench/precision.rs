//! The error a bench's speed was bought with: a backend's image against the CPU renderer running the f64 interpreter
//! on the same frame uniforms and settings.
//!
//! Hit masks are read from the pixels, as the accuracy metrics read them ([`scene_hits`]); for the baseline the miss
//! colour is its vertical gradient.

use fractal_dsl::Scene;
use fractal_render::backend::cpu::render_scene;
use fractal_render::error::RenderError;
use fractal_render::frame::Frame;
use fractal_render::image::{linear_rgba8, unpack_rgba8, Image};

use crate::accuracy::metrics::{is_miss, scene_hits};

/// How far a bench's image lies from the f64 reference: one comparison.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Deviation {
    /// Size the comparison was made at.
    pub width: u32,
    pub height: u32,
    /// Fraction of pixels whose hit/miss differs from the reference's (`None` when misses cannot be told apart).
    pub hit_mismatch: Option<f64>,
    /// Mean |difference| over all pixels and RGB channels, in 8-bit levels (`None` when the colours are not
    /// comparable, as for the baseline's own shading).
    pub mean_colour_difference: Option<f64>,
}

impl Deviation {
    pub fn describe(&self) -> String {
        let mask = match self.hit_mismatch {
            Some(f) => format!("hit/miss differs on {:.3} % of pixels", 100.0 * f),
            None => "hit/miss not compared (glow tints misses)".to_string(),
        };
        let colour = match self.mean_colour_difference {
            Some(d) => format!("mean |colour difference| {d:.3} levels"),
            None => "colours not compared (different shading by design)".to_string(),
        };
        format!("{mask}, {colour} (at {}x{}, same settings)", self.width, self.height)
    }
}

/// The reference image: the CPU renderer in f64 with the interpreter.
pub fn reference(scene: &Scene, frame: &Frame) -> Result<Image, RenderError> {
    render_scene::<f64, _>(&fractal_dsl::lower::tape::interpreter(scene)?, scene, frame)
}

/// Hit mask of a baseline image: pixels unlike the baseline's background gradient.
pub fn baseline_hits(image: &Image) -> Vec<bool> {
    let h = image.height as f64;
    (0..image.height)
        .flat_map(|y| {
            let v = -(2.0 * (y as f64 + 0.5) - h) / h;
            let background = linear_rgba8([0.08, 0.09, 0.12].map(|c| c + 0.08 * v), 2.0);
            let row = y as usize * image.width as usize;
            image.pixels[row..row + image.width as usize].iter().map(move |&p| !is_miss(p, background))
        })
        .collect()
}

fn mismatch(a: &[bool], b: &[bool]) -> f64 {
    a.iter().zip(b).filter(|(x, y)| x != y).count() as f64 / a.len().max(1) as f64
}

fn mean_colour_difference(a: &Image, b: &Image) -> f64 {
    let total: u64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .map(|(&p, &q)| {
            unpack_rgba8(p).iter().zip(unpack_rgba8(q)).take(3).map(|(x, y)| x.abs_diff(y) as u64).sum::<u64>()
        })
        .sum();
    total as f64 / (3 * a.pixels.len().max(1)) as f64
}

/// A scene image against its reference.
pub fn compare_scene(scene: &Scene, image: &Image, reference: &Image) -> Deviation {
    let hit_mismatch = match (scene_hits(scene, image), scene_hits(scene, reference)) {
        (Some(a), Some(b)) => Some(mismatch(&a, &b)),
        _ => None,
    };
    Deviation {
        width: image.width,
        height: image.height,
        hit_mismatch,
        mean_colour_difference: Some(mean_colour_difference(image, reference)),
    }
}

/// A baseline image against the reference of the scene set up like it: hit masks only.
pub fn compare_baseline(scene: &Scene, image: &Image, reference: &Image) -> Deviation {
    let hit_mismatch = scene_hits(scene, reference).map(|r| mismatch(&baseline_hits(image), &r));
    Deviation { width: image.width, height: image.height, hit_mismatch, mean_colour_difference: None }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::baseline;
    use fractal_dsl::builder::{camera, mandelbulb, rgb, scene, sphere, ShapeExt};

    use fractal_render::image::pack_rgba8;

    #[test]
    fn an_image_agrees_with_itself_and_not_with_a_blank() {
        let s = scene(sphere(1.0)).camera(camera([0.0, 0.0, -3.0], [0.0, 0.0, 0.0]));
        let f = Frame::default_view(&s, 0.0, 32, 24).unwrap();
        let r = reference(&s, &f).unwrap();
        let same = compare_scene(&s, &r, &r);
        assert_eq!((same.hit_mismatch, same.mean_colour_difference), (Some(0.0), Some(0.0)));
        let hits = scene_hits(&s, &r).unwrap();
        let covered = hits.iter().filter(|&&h| h).count() as f64 / hits.len() as f64;
        assert!(covered > 0.1 && covered < 0.9, "sphere covers {covered}");
        let bg = pack_rgba8(linear_rgba8(s.settings.background, s.settings.gamma));
        let blank = Image { width: 32, height: 24, pixels: vec![bg; 32 * 24] };
        let off = compare_scene(&s, &blank, &r);
        assert!((off.hit_mismatch.unwrap() - covered).abs() < 1e-12);
        assert!(off.mean_colour_difference.unwrap() > 1.0);
    }

    #[test]
    fn glow_has_no_hit_mask() {
        let s = scene(sphere(1.0)).glow(rgb(0.2, 0.1, 0.0));
        let f = Frame::default_view(&s, 0.0, 8, 8).unwrap();
        let r = reference(&s, &f).unwrap();
        assert_eq!(compare_scene(&s, &r, &r).hit_mismatch, None);
    }

    #[test]
    fn the_baseline_port_matches_a_scene_set_up_like_it() {
        // The baseline's camera and Mandelbulb, as the built-in `mandelbulb` scene sets them up.
        let s = scene(mandelbulb(8).iterations(8).bailout(2.0).material(rgb(0.95, 0.75, 0.55)))
            .max_steps(128)
            .max_distance(6.0)
            .epsilon(0.0005);
        let f = Frame::default_view(&s, 0.0, 48, 27).unwrap();
        let r = reference(&s, &f).unwrap();
        let baseline = compare_baseline(&s, &baseline::render(48, 27), &r);
        assert!(baseline.hit_mismatch.unwrap() < 0.03, "{}", baseline.describe());
        let hits = baseline_hits(&baseline::render(48, 27)).iter().filter(|&&h| h).count();
        assert!(hits > 48 * 27 / 10, "only {hits} baseline hits");
    }
}
