//! A sweep written out: the terminal table, CSV rows and the Markdown table of `docs/accuracy.md`. One column list
//! serves all three.

use crate::accuracy::metrics::TrueError;
use crate::accuracy::sweep::{Budget, SweepPoint};

/// A column: its header and its cell for a point ("–" where the backend cannot tell).
struct Column {
    header: &'static str,
    cell: fn(&SweepPoint) -> Option<String>,
}

fn pct(v: f64) -> Option<String> {
    Some(format!("{:.3}", 100.0 * v))
}

fn traced<T>(e: &TrueError, f: impl Fn(&crate::accuracy::metrics::TracedError) -> T) -> Option<T> {
    e.traced.as_ref().map(f)
}

const COLUMNS: &[Column] = &[
    Column { header: "setting", cell: |p| Some(p.quality.to_string()) },
    Column { header: "ms", cell: |p| Some(format!("{:.1}", p.time_ms)) },
    Column {
        header: "evals/px",
        cell: |p| traced(&p.error, |t| t.evaluations_per_pixel.map(|e| format!("{e:.1}"))).flatten(),
    },
    Column { header: "false hit % thin", cell: |p| pct(p.error.false_hits) },
    Column { header: "false hit % cone", cell: |p| pct(p.error.false_hits_cone) },
    Column { header: "false miss %", cell: |p| pct(p.error.false_misses) },
    Column { header: "out of steps %", cell: |p| traced(&p.error, |t| pct(t.out_of_steps)).flatten() },
    Column { header: "depth p50", cell: |p| traced(&p.error, |t| format!("{:.2}", t.depth_thin.median)) },
    Column { header: "depth p99 thin", cell: |p| traced(&p.error, |t| format!("{:.2}", t.depth_thin.p99)) },
    Column { header: "depth p99 cone", cell: |p| traced(&p.error, |t| format!("{:.2}", t.depth_cone.p99)) },
    Column { header: "interior p99 cone", cell: |p| traced(&p.error, |t| format!("{:.2}", t.depth_cone_interior.p99)) },
    Column { header: "smooth p50 thin", cell: |p| traced(&p.error, |t| format!("{:.2}", t.depth_smooth.median)) },
    Column { header: "overshoot % thin", cell: |p| traced(&p.error, |t| pct(t.overshoot)).flatten() },
    Column { header: "overshoot % cone", cell: |p| traced(&p.error, |t| pct(t.overshoot_cone)).flatten() },
    Column { header: "normal p50°", cell: |p| traced(&p.error, |t| format!("{:.1}", t.normal.median)) },
    Column { header: "normal p99° centre", cell: |p| traced(&p.error, |t| format!("{:.1}", t.normal.p99)) },
    Column { header: "normal p99° cone", cell: |p| traced(&p.error, |t| format!("{:.1}", t.normal_cone.p99)) },
    Column {
        header: "normals measured %",
        cell: |p| traced(&p.error, |t| format!("{:.0}", 100.0 * t.normal_measured)),
    },
    Column { header: "PSNR dB", cell: |p| Some(format!("{:.1}", p.error.psnr)) },
    Column { header: "NaN/Inf", cell: |p| traced(&p.error, |t| t.non_finite.to_string()) },
];

fn cells(p: &SweepPoint) -> Vec<String> {
    COLUMNS.iter().map(|c| (c.cell)(p).unwrap_or_else(|| "–".to_string())).collect()
}

/// The table for a terminal: aligned columns and a budget verdict per row.
pub fn text(points: &[SweepPoint], budget: &Budget) -> String {
    let rows: Vec<Vec<String>> = points.iter().map(cells).collect();
    let widths: Vec<usize> = COLUMNS
        .iter()
        .enumerate()
        .map(|(i, c)| rows.iter().map(|r| r[i].chars().count()).chain([c.header.chars().count()]).max().unwrap_or(0))
        .collect();
    let line = |cells: Vec<String>, tail: &str| {
        let padded: Vec<String> = cells.iter().zip(&widths).map(|(c, w)| format!("{c:>w$}")).collect();
        format!("{}  {tail}\n", padded.join("  "))
    };
    let mut out = line(COLUMNS.iter().map(|c| c.header.to_string()).collect(), "budget");
    for (p, row) in points.iter().zip(rows) {
        out += &line(row, &budget.verdict(&p.error).to_string());
    }
    out
}

/// A Markdown table, with the budget verdict as the last column.
pub fn markdown(points: &[SweepPoint], budget: &Budget) -> String {
    let headers: Vec<&str> = COLUMNS.iter().map(|c| c.header).chain(["budget"]).collect();
    let mut out = format!("| {} |\n|{}\n", headers.join(" | "), "---|".repeat(headers.len()));
    for p in points {
        let mut row = cells(p);
        row.push(budget.verdict(&p.error).to_string());
        out += &format!("| {} |\n", row.join(" | "));
    }
    out
}

/// The CSV header line.
pub fn csv_header() -> String {
    let headers: Vec<String> = ["scene", "backend", "size"]
        .into_iter()
        .chain(COLUMNS.iter().map(|c| c.header))
        .chain(["budget"])
        .map(|h| h.replace(['%', '°'], "").trim().replace(' ', "_"))
        .collect();
    headers.join(",") + "\n"
}

/// CSV rows, one per point.
pub fn csv_rows(scene: &str, backend: &str, size: (u32, u32), points: &[SweepPoint], budget: &Budget) -> String {
    let quote =
        |s: &str| if s.contains([',', '"']) { format!("\"{}\"", s.replace('"', "\"\"")) } else { s.to_string() };
    points
        .iter()
        .map(|p| {
            let mut row = vec![scene.to_string(), backend.to_string(), format!("{}x{}", size.0, size.1)];
            row.extend(cells(p).into_iter().map(|c| if c == "–" { String::new() } else { c }));
            row.push(budget.verdict(&p.error).to_string());
            row.iter().map(|c| quote(c)).collect::<Vec<_>>().join(",") + "\n"
        })
        .collect()
}
