//! Time against true error, drawn: one SVG per sweep with a panel per error figure (hit mismatch; and, where the
//! render was traced, interior depth error), every setting a point — green within the budget, grey outside it, the
//! scene's own setting ringed — and the Pareto front (settings no other beats on both time and that error) joined and
//! labelled. SVG only: text in a bitmap needs a font file, and SVG leaves it to the viewer.

use plotters::prelude::*;

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

/// The SVG text of the plot of `points` (a sweep of scene `title`), judged by `budget`.
pub fn svg(title: &str, points: &[SweepPoint], budget: &Budget) -> Result<String, String> {
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root =
            root.titled(&format!("{title}: time against true error"), ("sans-serif", 20)).map_err(|e| e.to_string())?;
        let panels: Vec<&Panel> = PANELS.iter().filter(|p| points.iter().any(|q| (p.error)(q).is_some())).collect();
        let areas = root.split_evenly((1, panels.len().max(1)));
        for (panel, area) in panels.iter().zip(&areas) {
            draw_panel(area, panel, points, budget).map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(text)
}

fn draw_panel(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    panel: &Panel,
    points: &[SweepPoint],
    budget: &Budget,
) -> Result<(), Box<dyn std::error::Error>> {
    let measured: Vec<(&SweepPoint, f64)> = points.iter().filter_map(|p| (panel.error)(p).map(|e| (p, e))).collect();
    let limit = (panel.limit)(budget);
    let x_max = measured.iter().map(|(p, _)| p.time_ms).fold(0.0, f64::max) * 1.1 + 1e-3;
    let x_min = measured.iter().map(|(p, _)| p.time_ms).fold(f64::INFINITY, f64::min).min(x_max) * 0.8;
    let y_max = measured.iter().map(|&(_, e)| e).filter(|e| e.is_finite()).fold(limit, f64::max) * 1.1 + 1e-6;
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(52)
        .build_cartesian_2d(x_min..x_max, 0.0..y_max)?;
    chart.configure_mesh().x_desc("render time (ms)").y_desc(panel.caption).light_line_style(WHITE).draw()?;

    // The budget as a dashed horizontal line.
    chart.draw_series(DashedLineSeries::new([(x_min, limit), (x_max, limit)], 6, 4, RED.mix(0.6).stroke_width(1)))?;

    let error_of = |p: &SweepPoint| (panel.error)(p).unwrap_or(f64::INFINITY);
    let front = pareto(points, error_of);
    chart.draw_series(LineSeries::new(front.iter().map(|p| (p.time_ms, error_of(p))), BLUE.stroke_width(2)))?;
    for &(p, e) in &measured {
        let within = budget.violations(&p.error).is_empty();
        let colour = if within { GREEN.mix(0.9) } else { BLACK.mix(0.35) };
        chart.draw_series(std::iter::once(Circle::new((p.time_ms, e.min(y_max)), 4, colour.filled())))?;
        if p.quality.is_default() {
            chart.draw_series(std::iter::once(Circle::new((p.time_ms, e.min(y_max)), 8, BLACK.stroke_width(2))))?;
        }
    }
    for p in &front {
        let label = if p.quality.is_default() { "scene default".to_string() } else { p.quality.to_string() };
        chart.draw_series(std::iter::once(Text::new(
            label,
            (p.time_ms, error_of(p).min(y_max)),
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
}
