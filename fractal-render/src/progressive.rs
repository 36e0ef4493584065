//! Progressive renders: a still refined pass by pass. Each pass draws every pixel's one ray at the next sample of the
//! pixel program ([`fractal_dsl::ray::pixel::sample_point`], through the lens where the camera has one) by moving the
//! frame's camera ([`Frame::jittered`]), so any backend draws it with the scene's one-sample kernels; the mean of the
//! passes' clamped linear colours is the pixel program's box-filtered value, to as many samples as there were passes.

use fractal_dsl::number::math::v3;
use fractal_dsl::ray::pixel::{lens_point, sample_point};
use fractal_dsl::ray::Lens;
use fractal_dsl::Scene;

use crate::error::RenderError;
use crate::frame::Frame;
use crate::image::{pack_linear, Image};
use crate::renderer::{RenderJob, Renderer, Traced};

/// The passes drawn so far and the sum of their colours.
#[derive(Clone, Debug)]
pub struct Progressive {
    frame: Frame,
    lens: Option<Lens>,
    gamma: f64,
    sums: Vec<[f64; 3]>,
    passes: u32,
}

impl Progressive {
    /// No passes yet, of `scene` seen through `frame`.
    pub fn new(scene: &Scene, frame: &Frame) -> Progressive {
        let pixels = frame.width() as usize * frame.height() as usize;
        Progressive {
            frame: frame.clone(),
            lens: Lens::of(&scene.camera),
            gamma: scene.settings.gamma,
            sums: vec![[0.0; 3]; pixels],
            passes: 0,
        }
    }

    /// The frame the next pass draws: sample `passes` of every pixel.
    pub fn next_frame(&self) -> Frame {
        let ([dx, dy], on_lens) = sample_point::<f64>(f64::from(self.passes), self.lens.is_some());
        let lens = self.lens.map(|lens| (lens_point(&lens, on_lens), lens.focus));
        self.frame.jittered(dx, dy, lens)
    }

    /// Adds a pass drawn from [`Progressive::next_frame`] by a `trace` (whose colours are linear).
    pub fn add(&mut self, pass: &Traced) {
        for (sum, pixel) in self.sums.iter_mut().zip(&pass.pixels) {
            for (s, c) in sum.iter_mut().zip(pixel.colour) {
                *s += c.clamp(0.0, 1.0);
            }
        }
        self.passes += 1;
    }

    /// Draws the next pass with `renderer`, whose job's kernels are the scene's one-sample trace kernels (or its CPU
    /// evaluator).
    pub fn draw(&mut self, renderer: &mut dyn Renderer, job: &RenderJob) -> Result<(), RenderError> {
        let frame = self.next_frame();
        let pass = renderer.trace(&RenderJob::new(job.kernels, &frame))?;
        self.add(&pass);
        Ok(())
    }

    /// Draws passes as [`Progressive::draw`] until `seconds` have passed since the call, at least one.
    pub fn draw_for(&mut self, renderer: &mut dyn Renderer, job: &RenderJob, seconds: f64) -> Result<(), RenderError> {
        let start = std::time::Instant::now();
        let first = self.passes;
        while self.passes == first || start.elapsed().as_secs_f64() < seconds {
            self.draw(renderer, job)?;
        }
        Ok(())
    }

    pub fn passes(&self) -> u32 {
        self.passes
    }

    /// The mean of the passes so far, displayed.
    pub fn image(&self) -> Image {
        let n = f64::from(self.passes.max(1));
        let pixels = self.sums.iter().map(|s| pack_linear(v3(s[0] / n, s[1] / n, s[2] / n), self.gamma));
        Image { width: self.frame.width(), height: self.frame.height(), pixels: pixels.collect() }
    }
}
