//! The agreement harness: rows (a scene with the time, parameter values and region its points come from), the
//! points, the evaluators under test behind one interface ([`Subject`]), and the comparison of each evaluator's
//! answers with the f64 interpreter's.
//!
//! Every evaluator sees exactly the same inputs: points, time and parameter values are f32 numbers (what the kernels
//! read), widened exactly to f64 for the f64 evaluators. Differences are therefore the evaluators' own rounding.

use std::fmt::Write as _;

use fractal::dsl::eval::interp::Interpreter;
use fractal::dsl::eval::{Env, Evaluator, Sample};
use fractal::dsl::number::math::{v3, Real, V3};
use fractal::dsl::{CompiledScene, Scene};

use super::tolerance::{distance_tolerance, material_tolerance, Class, Tol, MATERIAL_NEIGHBOUR_STEP, UNIT_ROUNDOFF};

/// Which tolerance a row's distances are held to: exact formulas with basic arithmetic and square roots, formulas
/// that also call sin/cos/pow at run time, and one family per fractal estimator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    Exact,
    Trig,
    Mandelbulb,
    Menger,
    Sierpinski,
    Julia,
    Mandelbox,
    Juliabulb,
    Kifs,
    /// A hybrid of a trigonometric bulb map and a box fold written as formulas.
    Hybrid,
    /// Shapes whose material reads the point (noise, the Mandelbrot pattern): exact distances.
    Pattern,
}

/// One scene of the table and where to look at it.
pub struct Row {
    pub name: &'static str,
    pub family: Family,
    pub compiled: &'static CompiledScene,
    /// Random points come from the cube `center ± half`.
    pub center: [f32; 3],
    pub half: f32,
    pub time: f32,
    /// Parameter values in uniform order; `None`: the declared defaults.
    pub params: Option<Vec<f32>>,
    /// Hand-picked points, evaluated before the random ones.
    pub extra: Vec<[f32; 3]>,
    /// For a smooth blend of materials: the blend radius k and the largest difference between blended material
    /// values (see [`Row::blends`]).
    pub blend: Option<(f64, f64)>,
}

impl Row {
    pub fn new(name: &'static str, family: Family, compiled: &'static CompiledScene) -> Row {
        Row {
            name,
            family,
            compiled,
            center: [0.0; 3],
            half: 2.0,
            time: 0.0,
            params: None,
            extra: Vec::new(),
            blend: None,
        }
    }
    pub fn within(mut self, half: f32) -> Row {
        self.half = half;
        self
    }
    pub fn around(mut self, center: [f32; 3], half: f32) -> Row {
        self.center = center;
        self.half = half;
        self
    }
    pub fn at_time(mut self, time: f32) -> Row {
        self.time = time;
        self
    }
    pub fn with_params(mut self, values: &[f32]) -> Row {
        self.params = Some(values.to_vec());
        self
    }
    pub fn with_points(mut self, points: &[[f32; 3]]) -> Row {
        self.extra.extend_from_slice(points);
        self
    }
    /// Declares that the row's materials are mixed by a smooth blend of radius `k` between values at most `span`
    /// apart. The blend weight w = clamp(½ + ½(a − b)/k) moves by (δa + δb)/(2k) when the two distances err by δa
    /// and δb, so each material channel may err by span · δ/k on top of its own rounding, δ being the distance
    /// tolerance.
    pub fn blends(mut self, k: f64, span: f64) -> Row {
        self.blend = Some((k, span));
        self
    }
    pub fn scene(&self) -> &Scene {
        self.compiled.scene()
    }
    pub fn param_values(&self) -> Vec<f32> {
        self.params.clone().unwrap_or_else(|| self.compiled.default_params::<f32>().to_vec())
    }
    /// The environment in precision `F`, from the f32 values the kernels read.
    fn env_values<F: Real>(&self) -> (F, Vec<F>) {
        (F::c(self.time as f64), self.param_values().iter().map(|&v| F::c(v as f64)).collect())
    }
}

/// What an evaluator answers at one point, in the probe kernels' order and widened to f64:
/// `[distance, ambient, diffuse, specular, albedo.r, albedo.g, albedo.b, shininess]`.
pub type Answer = [f64; 8];

const CHANNELS: [&str; 8] =
    ["distance", "ambient", "diffuse", "specular", "albedo.r", "albedo.g", "albedo.b", "shininess"];

/// An evaluator under test.
pub trait Subject {
    fn name(&self) -> &'static str;
    fn class(&self) -> Class;
    /// Answers at `points`; `Err` when the evaluator cannot run this row at all (a kernel refused, a device lost).
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String>;
}

/// Answers of a CPU evaluator in precision `F`. `sample(..).distance` must be `distance(..)` bit for bit: the two
/// entry points share their arithmetic, only the material bookkeeping differs.
pub fn cpu_answers<F: Real>(e: &dyn Evaluator<F>, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
    let (time, params) = row.env_values::<F>();
    let env = Env::new(time, &params);
    let mut out = Vec::with_capacity(points.len());
    for p in points {
        let q = p.cast::<F>();
        let d = e.distance(q, &env);
        let s = e.sample(q, &env);
        if s.distance.f64() != d.f64() && !(d.is_nan() && s.distance.is_nan()) {
            return Err(format!(
                "sample().distance = {:e} but distance() = {:e} at {:?}",
                s.distance.f64(),
                d.f64(),
                p
            ));
        }
        out.push(
            [d, s.ambient, s.diffuse, s.specular, s.albedo.x, s.albedo.y, s.albedo.z, s.shininess].map(|v| v.f64()),
        );
    }
    Ok(out)
}

/// The answers of a packet evaluator ([`fractal::dsl::eval::packet`]: eight points at a time) at the row's time and
/// parameters; `sample` is its sample slice, `distance` its distance slice, which must agree with each other.
pub fn packet_answers(
    sample: impl Fn(f32, &[f32], &[f32], &[f32], &[f32], &mut [Sample<f32>]),
    distance: impl Fn(f32, &[f32], &[f32], &[f32], &[f32], &mut [f32]),
    row: &Row,
    points: &[V3<f32>],
) -> Result<Vec<Answer>, String> {
    let (time, params) = row.env_values::<f32>();
    let x: Vec<f32> = points.iter().map(|p| p.x).collect();
    let y: Vec<f32> = points.iter().map(|p| p.y).collect();
    let z: Vec<f32> = points.iter().map(|p| p.z).collect();
    let blank =
        Sample { distance: 0.0, albedo: v3(0.0, 0.0, 0.0), ambient: 0.0, diffuse: 0.0, specular: 0.0, shininess: 0.0 };
    let mut samples = vec![blank; points.len()];
    sample(time, &params, &x, &y, &z, &mut samples);
    let mut distances = vec![0.0f32; points.len()];
    distance(time, &params, &x, &y, &z, &mut distances);
    for ((s, d), p) in samples.iter().zip(&distances).zip(points) {
        if s.distance.to_bits() != d.to_bits() && !(d.is_nan() && s.distance.is_nan()) {
            return Err(format!("sample_slice distance {:e} but distance_slice {:e} at {p:?}", s.distance, d));
        }
    }
    Ok(samples
        .into_iter()
        .map(|s| {
            [s.distance, s.ambient, s.diffuse, s.specular, s.albedo.x, s.albedo.y, s.albedo.z, s.shininess]
                .map(f64::from)
        })
        .collect())
}

/// The f64 interpreter of one row: the reference every evaluator is compared with.
pub struct Reference {
    interp: Interpreter,
    time: f64,
    params: Vec<f64>,
}

impl Reference {
    pub fn new(row: &Row) -> Reference {
        let (time, params) = row.env_values::<f64>();
        Reference { interp: Interpreter::new(row.scene()).unwrap(), time, params }
    }
    pub fn distance(&self, p: V3<f64>) -> f64 {
        Evaluator::<f64>::distance(&self.interp, p, &Env::new(self.time, &self.params))
    }
    pub fn answer(&self, p: V3<f64>) -> Answer {
        let env = Env::new(self.time, &self.params);
        let d = Evaluator::<f64>::distance(&self.interp, p, &env);
        let s = Evaluator::<f64>::sample(&self.interp, p, &env);
        [d, s.ambient, s.diffuse, s.specular, s.albedo.x, s.albedo.y, s.albedo.z, s.shininess]
    }
}

// ---- points ---------------------------------------------------------------------------------------------------------

/// SplitMix64: a fixed-seed generator, so every run and every evaluator sees the same points.
struct Rng(u64);

impl Rng {
    fn for_row(name: &str) -> Rng {
        // FNV-1a of the row name: each row its own sequence, stable when rows are added or reordered.
        Rng(name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)))
    }
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

pub const UNIFORM_POINTS: usize = 160;
pub const PLANE_POINTS: usize = 48;
pub const AXIS_POINTS: usize = 16;
/// Sphere-traced points near the surface (where escape-time estimators amplify rounding most).
pub const SURFACE_POINTS: usize = 48;

fn f32_point(p: [f64; 3]) -> V3<f32> {
    v3(p[0] as f32, p[1] as f32, p[2] as f32)
}

/// The row's points: hand-picked ones, uniform ones in the cube, ones on the coordinate planes and axes through its
/// centre, and ones near the surface found by sphere tracing the reference towards the centre.
pub fn points(row: &Row, reference: &Reference) -> Vec<V3<f32>> {
    let mut rng = Rng::for_row(row.name);
    let c = row.center.map(|v| v as f64);
    let h = row.half as f64;
    let uniform = |rng: &mut Rng| [0, 1, 2].map(|i| c[i] + h * rng.signed());
    let mut out: Vec<V3<f32>> = row.extra.iter().map(|p| v3(p[0], p[1], p[2])).collect();
    for _ in 0..UNIFORM_POINTS {
        out.push(f32_point(uniform(&mut rng)));
    }
    for i in 0..PLANE_POINTS {
        let mut p = uniform(&mut rng);
        p[i % 3] = c[i % 3];
        out.push(f32_point(p));
    }
    for i in 0..AXIS_POINTS {
        let mut p = c;
        p[i % 3] += h * rng.signed();
        out.push(f32_point(p));
    }
    let mut found = 0;
    for attempt in 0..4 * SURFACE_POINTS {
        if found == SURFACE_POINTS {
            break;
        }
        // From a point on the cube's surface towards a point in its inner half, stopping 1e-2 .. 1e-5 (times the
        // size) from the surface.
        let mut start = uniform(&mut rng);
        let face = rng.below(3);
        start[face] = c[face] + if rng.signed() < 0.0 { -h } else { h };
        let target = [0, 1, 2].map(|i| c[i] + 0.5 * h * rng.signed());
        let dir = [0, 1, 2].map(|i| target[i] - start[i]);
        let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        let dir = dir.map(|v| v / len);
        let stop = h.max(1.0) * 10f64.powi(-2 - (attempt % 4) as i32);
        let mut t = 0.0;
        for _ in 0..400 {
            let p = v3(start[0] + dir[0] * t, start[1] + dir[1] * t, start[2] + dir[2] * t);
            let d = reference.distance(p);
            if !d.is_finite() || t > 4.0 * h {
                break;
            }
            if d.abs() < stop {
                out.push(f32_point([p.x, p.y, p.z]));
                found += 1;
                break;
            }
            t += d.abs();
        }
    }
    out
}

// ---- comparison -----------------------------------------------------------------------------------------------------

/// How one evaluator did on one row.
#[derive(Clone, Debug, Default)]
pub struct Outcome {
    pub row: &'static str,
    pub points: usize,
    /// Largest |d − d_ref|.
    pub max_distance: f64,
    /// Largest |d − d_ref| / max(1, |p|, |d_ref|), in units of the f32 unit roundoff.
    pub max_distance_u: f64,
    /// Largest |d − d_ref| as a fraction of its tolerance.
    pub worst_fraction: f64,
    /// Where the largest |d − d_ref| was seen: the point, the answer and the reference.
    pub worst_at: Option<([f32; 3], f64, f64)>,
    /// Largest material difference at points compared at the point itself.
    pub max_material: f64,
    /// Points whose material lies within the range the reference takes within the distance tolerance of p.
    pub steep: usize,
    /// Points whose material matched the reference only at a neighbour (the point lies on a material boundary).
    pub boundary: usize,
    /// Set when the evaluator could not run the row.
    pub skipped: Option<String>,
    pub failures: Vec<String>,
}

fn scale_of(p: V3<f64>, d: f64) -> f64 {
    let r = (p.x * p.x + p.y * p.y + p.z * p.z).sqrt();
    1f64.max(r).max(d.abs())
}

/// p and the six points `step` away from it along the axes.
fn neighbours(p: V3<f64>, step: f64) -> impl Iterator<Item = V3<f64>> {
    (0..3).flat_map(move |axis| {
        [-step, step].map(|s| {
            let mut q = [p.x, p.y, p.z];
            q[axis] += s;
            v3(q[0], q[1], q[2])
        })
    })
}

/// Whether every material channel of `a` is within `tol` (of max(1, |v|)) plus `slack` of `b`'s.
fn material_matches(a: &Answer, b: &Answer, tol: Tol, slack: f64) -> bool {
    (1..8).all(|i| (a[i] - b[i]).abs() <= tol.of(b[i].abs().max(1.0)) + slack)
}

/// Compares a subject's answers on a row with the reference's; at most a few failures are described per row.
pub fn compare(row: &Row, reference: &Reference, points: &[V3<f32>], got: &[Answer], class: Class) -> Outcome {
    const DESCRIBED: usize = 4;
    let dtol = distance_tolerance(row.family, class);
    let mtol = material_tolerance(row.family, class);
    let mut o = Outcome { row: row.name, points: points.len(), ..Outcome::default() };
    let fail = |o: &mut Outcome, message: String| {
        if o.failures.len() < DESCRIBED {
            o.failures.push(message);
        } else if o.failures.len() == DESCRIBED {
            o.failures.push("…".to_string());
        }
    };
    for (p32, answer) in points.iter().zip(got) {
        let p = p32.cast::<f64>();
        let want = reference.answer(p);
        let at = format!("at ({:e}, {:e}, {:e})", p32.x, p32.y, p32.z);
        if want.iter().any(|v| !v.is_finite()) {
            fail(&mut o, format!("the reference is not finite {at}: {want:?}"));
            continue;
        }
        if let Some(i) = answer.iter().position(|v| !v.is_finite()) {
            fail(&mut o, format!("{} is {} {at} (reference {:e})", CHANNELS[i], answer[i], want[i]));
            continue;
        }
        // Inside a Juliabulb the orbit falls into an attracting cycle: dr shrinks towards 0 and the estimate
        // 0.5·ln r·r/dr grows without bound, amplifying every rounding on the way (measured up to 0.9 on the CPU
        // where the value is −14). There the value is not a distance and a renderer reads only its sign: inside the
        // set only the sign is compared.
        let sign_only = row.family == Family::Juliabulb && want[0] < 0.0 && answer[0] < 0.0;
        let diff = if sign_only { 0.0 } else { (answer[0] - want[0]).abs() };
        let scale = scale_of(p, want[0]);
        let allowed = dtol.of(scale);
        if diff > o.max_distance {
            o.max_distance = diff;
            o.worst_at = Some(([p32.x, p32.y, p32.z], answer[0], want[0]));
        }
        o.max_distance_u = o.max_distance_u.max(diff / scale / UNIT_ROUNDOFF);
        let fraction = if allowed > 0.0 {
            diff / allowed
        } else if diff > 0.0 {
            f64::INFINITY
        } else {
            0.0
        };
        o.worst_fraction = o.worst_fraction.max(fraction);
        if fraction > 1.0 {
            fail(
                &mut o,
                format!("distance {:e}, reference {:e} (|Δ| = {diff:.3e} > {allowed:.3e}) {at}", answer[0], want[0]),
            );
        }
        let material_diff = (1..8).map(|i| (answer[i] - want[i]).abs()).fold(0.0, f64::max);
        let slack = row.blend.map_or(0.0, |(k, span)| span * allowed / k);
        if material_matches(answer, &want, mtol, slack) {
            o.max_material = o.max_material.max(material_diff);
            continue;
        }
        if class != Class::Twin {
            // The reference's material at a point within the distance tolerance of p (the evaluator's own position
            // uncertainty): each channel inside the range the reference takes over p and its six neighbours at that
            // radius. A steep but continuous material lands here: an orbit trap near the set, where the iteration
            // amplifies rounding the way it does for the distance, or a narrow smooth blend.
            let around: Vec<Answer> = neighbours(p, allowed).map(|q| reference.answer(q)).collect();
            let within = (1..8).all(|i| {
                let lo = around.iter().fold(want[i], |m, a| m.min(a[i]));
                let hi = around.iter().fold(want[i], |m, a| m.max(a[i]));
                answer[i] >= lo - mtol.of(lo.abs().max(1.0)) - slack
                    && answer[i] <= hi + mtol.of(hi.abs().max(1.0)) + slack
            });
            if within {
                o.steep += 1;
                o.max_material = o.max_material.max(material_diff);
                continue;
            }
            // Otherwise it must be the whole material of a point MATERIAL_NEIGHBOUR_STEP (relative) away: p lies on
            // a boundary between materials (two children nearly equidistant) and rounding picked the other side.
            let step = MATERIAL_NEIGHBOUR_STEP * scale_of(p, 0.0);
            if neighbours(p, step).any(|q| material_matches(answer, &reference.answer(q), mtol, slack)) {
                o.boundary += 1;
                continue;
            }
        }
        let worst = (1..8).max_by(|&i, &j| (answer[i] - want[i]).abs().total_cmp(&(answer[j] - want[j]).abs()));
        let i = worst.unwrap_or(1);
        fail(
            &mut o,
            format!(
                "material {} = {:e}, reference {:e} (no nearby point has it) {at}",
                CHANNELS[i], answer[i], want[i]
            ),
        );
    }
    o
}

// ---- running a subject over a table ---------------------------------------------------------------------------------

/// One evaluator's results over a table.
pub struct Column {
    pub subject: &'static str,
    pub class: Class,
    pub outcomes: Vec<Outcome>,
    pub seconds: f64,
}

impl Column {
    pub fn failures(&self) -> Vec<String> {
        self.outcomes
            .iter()
            .flat_map(|o| o.failures.iter().map(move |f| format!("{} / {}: {f}", self.subject, o.row)))
            .collect()
    }
}

/// Runs `subject` over `rows` and compares every answer with the reference.
pub fn run(subject: &mut dyn Subject, rows: &[Row]) -> Column {
    let start = std::time::Instant::now();
    let mut outcomes = Vec::new();
    for row in rows {
        let reference = Reference::new(row);
        let pts = points(row, &reference);
        let outcome = match subject.answers(row, &pts) {
            Ok(got) if got.len() == pts.len() => compare(row, &reference, &pts, &got, subject.class()),
            Ok(got) => Outcome {
                row: row.name,
                failures: vec![format!("{} answers for {} points", got.len(), pts.len())],
                ..Outcome::default()
            },
            Err(e) => Outcome { row: row.name, failures: vec![e], ..Outcome::default() },
        };
        outcomes.push(outcome);
    }
    Column { subject: subject.name(), class: subject.class(), outcomes, seconds: start.elapsed().as_secs_f64() }
}

/// One evaluator's table: per row, the largest differences and how much of the tolerance they used.
pub fn column_table(c: &Column) -> String {
    let mut s = String::new();
    if let Some(why) = c.outcomes.first().and_then(|o| o.skipped.as_ref()) {
        let _ = writeln!(s, "\n== {}: skipped ({why}) ==", c.subject);
        return s;
    }
    let _ = writeln!(s, "\n== {} ({:?} tolerances, {:.1} s) ==", c.subject, c.class, c.seconds);
    let _ = writeln!(
        s,
        "{:<56} {:>5} {:>10} {:>9} {:>8} {:>10} {:>5} {:>5} {:>5}  worst |Δd|: answer vs reference at point",
        "row", "pts", "max|Δd|", "|Δd|/s/u", "of tol", "max|Δmat|", "steep", "bndry", "fails"
    );
    for o in &c.outcomes {
        let _ = writeln!(
            s,
            "{:<56} {:>5} {:>10.2e} {:>9.1} {:>7.0}% {:>10.2e} {:>5} {:>5} {:>5}  {}",
            o.row,
            o.points,
            o.max_distance,
            o.max_distance_u,
            100.0 * o.worst_fraction,
            o.max_material,
            o.steep,
            o.boundary,
            o.failures.len(),
            match o.worst_at {
                Some((p, got, want)) if got != want => format!("{got:e} vs {want:e} at {p:?}"),
                _ => String::new(),
            }
        );
    }
    s
}

/// How a summary table writes one outcome.
type Cell = fn(&Outcome) -> String;

/// Rows × evaluators: the largest distance difference each evaluator showed on each row (absolute, and in units of
/// u·max(1, |p|, |d|)), then the largest material difference.
pub fn summary_table(columns: &[Column]) -> String {
    let mut s = String::new();
    let tables: [(&str, Cell); 2] = [
        ("largest |d − d_ref| per row and evaluator (in parentheses: / (u·s))", |o| {
            format!("{:.2e} ({:.1})", o.max_distance, o.max_distance_u)
        }),
        ("largest material difference per row and evaluator (boundary points excluded)", |o| {
            format!("{:.2e}", o.max_material)
        }),
    ];
    for (title, cell) in tables {
        let _ = writeln!(s, "\n== {title} ==");
        let _ = write!(s, "{:<56}", "row");
        for c in columns {
            let _ = write!(s, " {:>18}", c.subject);
        }
        let _ = writeln!(s);
        let Some(first) = columns.first() else { return s };
        for (i, o) in first.outcomes.iter().enumerate() {
            let _ = write!(s, "{:<56}", o.row);
            for c in columns {
                let text = match c.outcomes.get(i) {
                    Some(o) if o.skipped.is_none() => cell(o),
                    _ => "—".to_string(),
                };
                let _ = write!(s, " {text:>18}");
            }
            let _ = writeln!(s);
        }
    }
    s
}

/// The column of an evaluator that could not be opened.
pub fn skipped(subject: &'static str, rows: &[Row], why: &str) -> Column {
    let outcomes =
        rows.iter().map(|r| Outcome { row: r.name, skipped: Some(why.to_string()), ..Outcome::default() }).collect();
    Column { subject, class: Class::Gpu, outcomes, seconds: 0.0 }
}

/// Summary column order: CPU evaluators first, then the kernels.
pub fn order_of(subject: &str) -> usize {
    [
        "interp f32",
        "interp x8",
        "native f64",
        "native f32",
        "native x8",
        "wgsl",
        "wgsl f64",
        "opencl",
        "opencl fast",
        "opencl f64",
    ]
    .iter()
    .position(|s| *s == subject)
    .unwrap_or(usize::MAX)
}
