//! Time against true error, drawn: one SVG per sweep with a panel per error figure (hit mismatch; and, where the
//! render was traced, interior depth error), every setting a point — green within the budget, grey outside it, the
//! scene's own setting ringed — and the Pareto front (settings no other beats on both time and that error) joined and
//! labelled; and the same for the samples front ([`image_svg`]): PSNR against the truth of the image against time.
//! SVG only: text in a bitmap needs a font file, and SVG leaves it to the viewer.

use plotters::prelude::*;

use crate::accuracy::image::ImageBudget;
use crate::accuracy::samples::SamplePoint;
use crate::accuracy::sweep::{pareto, Budget, SweepPoint};

const WIDTH: u32 = 1000;
const HEIGHT: u32 = 420;

/// One error figure of a point, with its axis caption and the budget's line for it.
struct Panel {
    caption: &'static str,
    error: fn(&SweepPoint) -> Option<f64>,
    limit: fn(&Budget) -> f64,
}

const PANELS: [Panel; 2] = [
    Panel {
        caption: "hit mismatch (% of pixels)",
        error: |p| Some(100.0 * p.error.hit_mismatch()),
        limit: |b| 100.0 * b.hit_mismatch,
    },
    Panel {
        caption: "interior depth error p99 (footprints)",
        error: |p| p.error.traced.as_ref().map(|t| t.depth_cone_interior.p99),
        limit: |b| b.depth_p99_interior,
    },
];

/// A setting as the plot draws it.
struct Dot {
    time_ms: f64,
    value: f64,
    within: bool,
    default: bool,
    label: String,
}

/// What one panel shows: its axis caption, the budget's line, and which way is better.
struct Axis<'a> {
    caption: &'a str,
    limit: f64,
    higher_is_better: bool,
}

/// The SVG text of the plot of `points` (a sweep of scene `title`), judged by `budget`.
pub fn svg(title: &str, points: &[SweepPoint], budget: &Budget) -> Result<String, String> {
    let panels: Vec<(Axis, Vec<Dot>)> = PANELS
        .iter()
        .filter(|p| points.iter().any(|q| (p.error)(q).is_some()))
        .map(|panel| {
            let dots = points
                .iter()
                .filter_map(|p| {
                    (panel.error)(p).map(|value| Dot {
                        time_ms: p.time_ms,
                        value,
                        within: budget.violations(&p.error).is_empty(),
                        default: p.quality.is_default(),
                        label: if p.quality.is_default() { "scene default".to_string() } else { p.quality.to_string() },
                    })
                })
                .collect();
            (Axis { caption: panel.caption, limit: (panel.limit)(budget), higher_is_better: false }, dots)
        })
        .collect();
    draw(&format!("{title}: time against true error"), &panels)
}

/// The SVG text of the samples front of scene `title`: PSNR against the truth of the image, against time.
pub fn image_svg(title: &str, points: &[SamplePoint], budget: &ImageBudget) -> Result<String, String> {
    let own = points.iter().find(|p| p.default).map_or(f64::NAN, |p| p.threshold);
    let dots = points
        .iter()
        .map(|p| Dot {
            time_ms: p.time_ms,
            value: p.error.psnr,
            within: budget.violations(&p.error).is_empty(),
            default: p.default,
            label: p.label(own),
        })
        .collect();
    let axis = Axis { caption: "PSNR against the image truth (dB)", limit: budget.psnr, higher_is_better: true };
    draw(&format!("{title}: time against image error"), &[(axis, dots)])
}

fn draw(title: &str, panels: &[(Axis, Vec<Dot>)]) -> Result<String, String> {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root = root.titled(title, ("sans-serif", 20)).map_err(|e| e.to_string())?;
        let areas = root.split_evenly((1, panels.len().max(1)));
        for ((axis, dots), area) in panels.iter().zip(&areas) {
            draw_panel(area, axis, dots).map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(text)
}

fn draw_panel(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    axis: &Axis,
    dots: &[Dot],
) -> Result<(), Box<dyn std::error::Error>> {
    let limit = axis.limit;
    let x_max = dots.iter().map(|d| d.time_ms).fold(0.0, f64::max) * 1.1 + 1e-3;
    let x_min = dots.iter().map(|d| d.time_ms).fold(f64::INFINITY, f64::min).min(x_max) * 0.8;
    let finite = || dots.iter().map(|d| d.value).filter(|v| v.is_finite());
    let (y_min, y_max) = if axis.higher_is_better {
        let low = finite().fold(limit, f64::min);
        let high = finite().fold(limit, f64::max);
        (low - 0.1 * (high - low) - 1.0, high + 0.1 * (high - low) + 1.0)
    } else {
        (0.0, finite().fold(limit, f64::max) * 1.1 + 1e-6)
    };
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d(x_min..x_max, y_min..y_max)?;
    chart.configure_mesh().x_desc("render time (ms)").y_desc(axis.caption).light_line_style(WHITE).draw()?;

    // The budget as a dashed horizontal line.
    chart.draw_series(DashedLineSeries::new([(x_min, limit), (x_max, limit)], 6, 4, RED.mix(0.6).stroke_width(1)))?;

    let clamp = |v: f64| if v.is_finite() { v.clamp(y_min, y_max) } else { y_max };
    let sign = if axis.higher_is_better { -1.0 } else { 1.0 };
    let front = pareto(dots, |d| d.time_ms, |d| if d.value.is_finite() { sign * d.value } else { f64::INFINITY });
    chart.draw_series(LineSeries::new(front.iter().map(|d| (d.time_ms, clamp(d.value))), BLUE.stroke_width(2)))?;
    for d in dots {
        let colour = if d.within { GREEN.mix(0.9) } else { BLACK.mix(0.35) };
        chart.draw_series(std::iter::once(Circle::new((d.time_ms, clamp(d.value)), 4, colour.filled())))?;
        if d.default {
            chart.draw_series(std::iter::once(Circle::new((d.time_ms, clamp(d.value)), 8, BLACK.stroke_width(2))))?;
        }
    }
    for d in &front {
        chart.draw_series(std::iter::once(Text::new(
            d.label.clone(),
            (d.time_ms, clamp(d.value)),
            ("sans-serif", 12).into_font().color(&BLUE),
        )))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accuracy::metrics::TrueError;
    use crate::quality::Quality;

    fn point(quality: Quality, time_ms: f64, hit_mismatch: f64) -> SweepPoint {
        let error = TrueError {
            width: 8,
            height: 8,
            false_hits: hit_mismatch,
            false_hits_cone: hit_mismatch,
            false_misses: 0.0,
            psnr: 30.0,
            traced: None,
        };
        SweepPoint { quality, time_ms, error }
    }

    #[test]
    fn the_plot_marks_every_setting_and_labels_the_front() {
        let points = [
            point(Quality::default(), 10.0, 0.004),
            point(Quality { max_steps: Some(64), ..Quality::default() }, 6.0, 0.02),
            point(Quality { max_steps: Some(512), ..Quality::default() }, 30.0, 0.01),
        ];
        let text = svg("test", &points, &Budget::default()).unwrap();
        assert!(text.starts_with("<svg") && text.trim_end().ends_with("</svg>"), "{text}");
        // Three points, the ring of the default, two labels on the front (the 512-step point is beaten by the default).
        assert_eq!(text.matches("<circle").count(), 4, "{text}");
        assert!(text.contains("scene default") && text.contains("steps 64") && !text.contains("steps 512"), "{text}");
        assert!(text.contains("hit mismatch") && !text.contains("interior depth"), "{text}");
    }

    #[test]
    fn the_samples_plot_rings_the_default_and_labels_its_front() {
        use crate::accuracy::image::{ImageBudget, ImageError};
        use crate::accuracy::samples::SamplePoint;
        let point = |samples: u32, time_ms: f64, psnr: f64| SamplePoint {
            samples,
            threshold: 0.004,
            rays_per_pixel: 1.0,
            time_ms,
            error: ImageError { psnr, ssim: 0.9, off: 0.01 },
            flicker: None,
            default: samples == 16,
        };
        // 5 samples are slower than 16 and worse: off the front.
        let points = [point(1, 10.0, 30.0), point(5, 30.0, 33.0), point(16, 25.0, 40.0)];
        let text = image_svg("test", &points, &ImageBudget::default()).unwrap();
        assert_eq!(text.matches("<circle").count(), 4, "{text}");
        assert!(text.contains("samples 16") && text.contains("samples 1\n") && !text.contains("samples 5"), "{text}");
        assert!(text.contains("PSNR against the image truth"), "{text}");
    }
}
