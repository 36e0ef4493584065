//! Agreement: one meaning, many evaluators. The same points of every vocabulary item (and of the evaluation hard
//! cases) go through the interpreter in f32, a point at a time and in packets of eight, the native evaluator in f64,
//! f32 and packets of eight (`distance_slice`, `sample_slice`: the f32 tolerances), the WGSL probe kernel (wgpu;
//! lavapipe without a GPU; and in f64 where the adapter offers `SHADER_F64`, to the f32 its outputs hold) and the OpenCL
//! probe kernel (pocl without a GPU; precise, fast-math as a separate, looser
//! comparison, and in f64 where the device has `cl_khr_fp64`, to the f32 its outputs hold), and each must agree with the f64 interpreter within the tolerances of `agreement/tolerance.rs`.
//!
//! The suite is written once against [`harness::Subject`] and instantiated per evaluator (Fidget's
//! `float_slice_tests!` pattern). Each test prints its table of largest differences; the test finishing last prints
//! the rows × evaluators summary. GPU evaluators are skipped with a note when their driver is missing, and fail
//! instead when `FRACTAL_REQUIRE_GPU_BACKENDS=1`.

mod harness;
mod rows;
mod tolerance;

use fractal_render::device::backends_required;
use std::sync::Mutex;

use fractal::dsl::back::{self, Entry, Scalar};
use fractal::dsl::eval::interp::Interpreter;
use fractal::dsl::lower::lower;
use fractal::dsl::number::math::V3;
use fractal::render::{Frame, ParamValues, Pose, ProbeSample, WgpuRenderer};
use harness::{cpu_answers, Answer, Column, Row, Subject};
use tolerance::Class;

/// Every row: the vocabulary, then the hard cases.
fn all_rows() -> Vec<Row> {
    let mut rows = rows::vocabulary();
    rows.extend(rows::hard_cases());
    rows
}

/// A row's name as a file name: `mandelbulb(8) trig-free` → `mandelbulb_8_trig_free`; an operator standing alone
/// becomes a word (`expr: +` → `expr_plus`).
fn slug(name: &str) -> String {
    let words: Vec<String> = name
        .split_whitespace()
        .map(|w| match w {
            "+" => "plus".to_string(),
            "-" => "minus".to_string(),
            "*" => "times".to_string(),
            "/" => "over".to_string(),
            _ => w.chars().map(|c| if c.is_ascii_alphanumeric() { c.to_ascii_lowercase() } else { '_' }).collect(),
        })
        .collect();
    let joined = words.join("_");
    joined.split('_').filter(|part| !part.is_empty()).collect::<Vec<_>>().join("_")
}

/// The code every row runs through — its OpenCL C and WGSL probe kernels and its native evaluator — pinned per row,
/// so one diff shows what a change does to every vocabulary item's code.
#[test]
fn every_row_has_pinned_code() {
    let mut seen = std::collections::HashSet::new();
    for row in all_rows() {
        let name = slug(row.name);
        assert!(seen.insert(name.clone()), "two rows share the snapshot name {name}");
        let program = lower(row.scene());
        let text = format!(
            "// ---- OpenCL C probe\n{}\n// ---- WGSL probe\n{}\n// ---- native Rust\n{}",
            back::opencl::write(&program, Entry::Probe),
            back::wgsl::write(&program, Entry::Probe),
            back::rust::write(&program, "fractal_dsl"),
        );
        insta::with_settings!({ snapshot_path => "snapshots/rows", prepend_module_to_snapshot => false }, {
            insta::assert_snapshot!(name, text);
        });
    }
}

// ---- the evaluators -------------------------------------------------------------------------------------------------

struct InterpreterF32;
impl Subject for InterpreterF32 {
    fn name(&self) -> &'static str {
        "interp f32"
    }
    fn class(&self) -> Class {
        Class::CpuF32
    }
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
        cpu_answers::<f32>(&Interpreter::new(row.scene()).unwrap(), row, points)
    }
}

struct NativeF64;
impl Subject for NativeF64 {
    fn name(&self) -> &'static str {
        "native f64"
    }
    fn class(&self) -> Class {
        Class::Twin
    }
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
        cpu_answers::<f64>(&row.compiled.native(), row, points)
    }
}

struct NativeF32;
impl Subject for NativeF32 {
    fn name(&self) -> &'static str {
        "native f32"
    }
    fn class(&self) -> Class {
        Class::CpuF32
    }
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
        cpu_answers::<f32>(&row.compiled.native(), row, points)
    }
}

/// The interpreter on packets of eight points (what runs a `.fractal` file on the CPU without rustc).
struct InterpreterX8;
impl Subject for InterpreterX8 {
    fn name(&self) -> &'static str {
        "interp x8"
    }
    fn class(&self) -> Class {
        Class::CpuF32
    }
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
        let interp = Interpreter::new(row.scene()).unwrap();
        harness::packet_answers(
            |t, params, x, y, z, out| interp.sample_slice(t, params, x, y, z, out),
            |t, params, x, y, z, out| interp.distance_slice(t, params, x, y, z, out),
            row,
            points,
        )
    }
}

/// The native evaluator's packet instance (`distance_slice`, `sample_slice`).
struct NativeX8;
impl Subject for NativeX8 {
    fn name(&self) -> &'static str {
        "native x8"
    }
    fn class(&self) -> Class {
        Class::CpuF32
    }
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
        let native = row.compiled.native();
        harness::packet_answers(
            |t, params, x, y, z, out| native.sample_slice(t, params, x, y, z, out),
            |t, params, x, y, z, out| native.distance_slice(t, params, x, y, z, out),
            row,
            points,
        )
    }
}

/// The frame a probe kernel reads its time and parameters from (the pose and size do not matter to a probe).
fn probe_frame(row: &Row) -> Result<Frame, String> {
    let scene = row.scene();
    let pose = Pose::look_at(glam::DVec3::new(0.0, 0.0, -3.0), glam::DVec3::ZERO, 60.0).map_err(|e| e.to_string())?;
    let values: Vec<f64> = row.param_values().iter().map(|&v| v as f64).collect();
    let params = ParamValues::from_values(scene, &values).map_err(|e| e.to_string())?;
    Frame::new(scene, &pose, row.time as f64, 1, 1, &params).map_err(|e| e.to_string())
}

fn probe_points(points: &[V3<f32>]) -> Vec<[f32; 4]> {
    points.iter().map(|p| [p.x, p.y, p.z, 0.0]).collect()
}

/// A probe sample `[distance, ambient, diffuse, specular, r, g, b, shininess]` is already in [`Answer`] order.
fn widen(samples: Vec<ProbeSample>) -> Vec<Answer> {
    samples.into_iter().map(|s| s.map(f64::from)).collect()
}

/// The WGSL probe kernel in f32 or, on a device with `SHADER_F64`, in f64 (with the traced elementary functions).
struct WgslProbe(WgpuRenderer, Scalar);
impl Subject for WgslProbe {
    fn name(&self) -> &'static str {
        match self.1 {
            Scalar::F32 => "wgsl",
            Scalar::F64 => "wgsl f64",
        }
    }
    fn class(&self) -> Class {
        match self.1 {
            Scalar::F32 => Class::Gpu,
            Scalar::F64 => Class::GpuF64,
        }
    }
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
        let source = back::wgsl::write_in(&lower(row.scene()), Entry::Probe, self.1);
        let frame = probe_frame(row)?;
        self.0.probe((&source, self.1), &frame, &probe_points(points)).map(widen).map_err(|e| e.to_string())
    }
}

/// The wgpu renderer, where its adapter offers `SHADER_F64`.
fn wgsl_f64() -> Result<Box<dyn Subject>, (&'static str, String)> {
    match WgpuRenderer::new() {
        Ok(r) if r.has_fp64() => Ok(Box::new(WgslProbe(r, Scalar::F64))),
        Ok(r) => Err(("wgsl f64", format!("{} has no SHADER_F64", fractal::render::Renderer::device(&r)))),
        Err(e) => Err(("wgsl f64", e.to_string())),
    }
}

/// The OpenCL probe kernel in f32 (precise or fast math) or, precise, in f64.
#[cfg(feature = "opencl")]
struct OpenClProbe(fractal::render::OpenClRenderer, Scalar);
#[cfg(feature = "opencl")]
impl Subject for OpenClProbe {
    fn name(&self) -> &'static str {
        match (self.1, self.0.precise()) {
            (Scalar::F64, _) => "opencl f64",
            (Scalar::F32, true) => "opencl",
            (Scalar::F32, false) => "opencl fast",
        }
    }
    fn class(&self) -> Class {
        match (self.1, self.0.precise()) {
            (Scalar::F64, _) => Class::GpuF64,
            (Scalar::F32, true) => Class::Gpu,
            (Scalar::F32, false) => Class::FastMath,
        }
    }
    fn answers(&mut self, row: &Row, points: &[V3<f32>]) -> Result<Vec<Answer>, String> {
        let source = back::opencl::write_in(&lower(row.scene()), Entry::Probe, self.1);
        let frame = probe_frame(row)?;
        self.0.probe((&source, self.1), &frame, &probe_points(points)).map(widen).map_err(|e| e.to_string())
    }
}

/// The precise OpenCL renderer, where its device computes in f64.
#[cfg(feature = "opencl")]
fn opencl_f64() -> Result<Box<dyn Subject>, (&'static str, String)> {
    match fractal::render::OpenClRenderer::new(true) {
        Ok(r) if r.has_fp64() => Ok(Box::new(OpenClProbe(r, Scalar::F64))),
        Ok(r) => Err(("opencl f64", format!("{} has no cl_khr_fp64", fractal::render::Renderer::device(&r)))),
        Err(e) => Err(("opencl f64", e.to_string())),
    }
}

// ---- the suite, instantiated per evaluator --------------------------------------------------------------------------

/// How many columns the summary waits for: one per test below.
const SUBJECTS: usize = if cfg!(feature = "opencl") { 10 } else { 7 };

static COLUMNS: Mutex<Vec<Column>> = Mutex::new(Vec::new());

/// Runs every row through `subject` (or records why it could not be opened), prints its table, prints the summary
/// if this is the last column, and fails on any disagreement.
fn check(opened: Result<Box<dyn Subject>, (&'static str, String)>) {
    let column = match opened {
        Ok(mut subject) => harness::run(subject.as_mut(), &all_rows()),
        Err((name, why)) => {
            if backends_required() {
                panic!("{name} is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but unavailable: {why}");
            }
            harness::skipped(name, &all_rows(), &why)
        }
    };
    eprint!("{}", harness::column_table(&column));
    let failures = column.failures();
    {
        let mut columns = COLUMNS.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        columns.push(column);
        if columns.len() == SUBJECTS {
            columns.sort_by_key(|c| harness::order_of(c.subject));
            eprint!("{}", harness::summary_table(&columns));
        }
    }
    assert!(failures.is_empty(), "{} disagreements:\n{}", failures.len(), failures.join("\n"));
}

macro_rules! agreement_tests {
    ($($(#[$meta:meta])* $test:ident => $open:expr;)*) => {$(
        $(#[$meta])*
        #[test]
        fn $test() {
            check($open);
        }
    )*};
}

agreement_tests! {
    interpreter_f32_agrees_with_the_f64_interpreter => Ok(Box::new(InterpreterF32));
    native_f64_agrees_with_the_f64_interpreter => Ok(Box::new(NativeF64));
    native_f32_agrees_with_the_f64_interpreter => Ok(Box::new(NativeF32));
    interpreter_packets_agree_with_the_f64_interpreter => Ok(Box::new(InterpreterX8));
    native_packets_agree_with_the_f64_interpreter => Ok(Box::new(NativeX8));
    wgsl_probe_agrees_with_the_f64_interpreter => WgpuRenderer::new()
        .map(|r| Box::new(WgslProbe(r, Scalar::F32)) as Box<dyn Subject>)
        .map_err(|e| ("wgsl", e.to_string()));
    wgsl_f64_probe_agrees_with_the_f64_interpreter_to_the_f32_it_writes => wgsl_f64();
    #[cfg(feature = "opencl")]
    opencl_probe_agrees_with_the_f64_interpreter => fractal::render::OpenClRenderer::new(true)
        .map(|r| Box::new(OpenClProbe(r, Scalar::F32)) as Box<dyn Subject>)
        .map_err(|e| ("opencl", e.to_string()));
    #[cfg(feature = "opencl")]
    opencl_fast_math_probe_agrees_within_its_looser_tolerance => fractal::render::OpenClRenderer::new(false)
        .map(|r| Box::new(OpenClProbe(r, Scalar::F32)) as Box<dyn Subject>)
        .map_err(|e| ("opencl fast", e.to_string()));
    #[cfg(feature = "opencl")]
    opencl_f64_probe_agrees_with_the_f64_interpreter_to_the_f32_it_writes => opencl_f64();
}

/// The reference's two spellings of the power-8 Mandelbulb, the trig-free polynomial and the trigonometric form
/// (reached through a parameter power of 8; its range starts at 8, so the step factor is the same 0.75), are one map:
/// in f64 they must agree far below every f32 tolerance above, on the pole axis too. Otherwise the f32 comparisons of
/// one of them would be measured against a wrong reference.
#[test]
fn trig_free_and_trigonometric_mandelbulb_agree_at_power_8_in_f64() {
    let rows = rows::hard_cases();
    let poly = rows.iter().find(|r| r.name == "hard: mandelbulb(8) pole axis").expect("the pole row exists");
    let trig = rows.iter().find(|r| r.name.starts_with("hard: mandelbulb(power 8 by param")).expect("its twin exists");
    let (poly_ref, trig_ref) = (harness::Reference::new(poly), harness::Reference::new(trig));
    let mut worst = (0.0f64, [0.0f32; 3]);
    for p in harness::points(poly, &poly_ref) {
        let q = p.cast::<f64>();
        let diff = (poly_ref.distance(q) - trig_ref.distance(q)).abs();
        if diff > worst.0 {
            worst = (diff, [p.x, p.y, p.z]);
        }
    }
    eprintln!("trig-free vs trigonometric power-8 Mandelbulb in f64: largest |Δd| {:.2e} at {:?}", worst.0, worst.1);
    assert!(worst.0 <= TWO_FORMS_F64, "the two forms differ by {:e} at {:?}", worst.0, worst.1);
}

/// f64 rounding, amplified where the orbit passes near the pole: θ = acos(z/r) magnifies the rounding of z/r by
/// 1/√(1 − (z/r)²), ~10^7 at 1e-7 off the axis. Measured 1.0e-13 (at 1e-7 off the axis); far below every f32 tolerance.
const TWO_FORMS_F64: f64 = 1e-12;

/// A deliberate error applied to every answer of a row.
type Mutation = fn(&mut Answer);

/// The comparison itself can fail: an evaluator whose distances are off by a few times the tolerance, whose material
/// is the other child's, or that returns NaN, is caught, while the unchanged answers pass.
#[test]
fn the_comparison_catches_wrong_answers() {
    let rows = rows::vocabulary();
    let mutants: [(&str, Mutation); 3] = [
        ("sphere", |a| {
            a[0] += 4.0 * tolerance::distance_tolerance(harness::Family::Exact, Class::CpuF32).of(a[0].abs().max(2.0))
        }),
        ("material: union picks the nearer child", |a| {
            a[1] = if a[1] == 0.1f32 as f64 { 0.3f32 as f64 } else { 0.1f32 as f64 }
        }),
        ("mandelbulb(8) trig-free", |a| a[0] = f64::NAN),
    ];
    for (name, mutate) in mutants {
        let row = rows.iter().find(|r| r.name == name).expect("the row exists");
        let reference = harness::Reference::new(row);
        let points = harness::points(row, &reference);
        let mut got =
            cpu_answers::<f32>(&Interpreter::new(row.scene()).unwrap(), row, &points).expect("the interpreter runs");
        assert!(harness::compare(row, &reference, &points, &got, Class::CpuF32).failures.is_empty(), "{name}");
        got.iter_mut().for_each(mutate);
        let outcome = harness::compare(row, &reference, &points, &got, Class::CpuF32);
        assert!(!outcome.failures.is_empty(), "{name}: a wrong evaluator passed");
    }
}
