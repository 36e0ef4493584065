//! Fidget 0.5.1 (JIT and VM) against fractal's evaluators, one thread, same machine, same points, in one run: a unit
//! sphere, a union of 16 spheres and iq's Menger sponge of 3 levels (Fidget with `floor` for the modulo, as the SIMD
//! issue measured it).
//!
//! `cargo run --release --manifest-path benches/fidget/Cargo.toml [-- ROUNDS]` prints M points/s per evaluator
//! (median of the rounds; the evaluators take turns within each round so drift hits them alike), the ratio of
//! fractal's packets to Fidget's JIT, and the largest difference between the two evaluators' distances.

use std::hint::black_box;
use std::time::Instant;

use fidget::context::Tree;
use fidget::jit::JitFunction;
use fidget::shape::EzShape;
use fidget::vm::VmFunction;
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::CompiledScene;
use fractal_macros::scene;

#[path = "../../shared/expressions.rs"]
mod expressions;
use expressions::{points, sixteen_spheres, POINTS};

/// Fidget gets the points in slices of this many, its fastest: measured here, the JIT gave 344 / 369 / 346 / 254 M
/// points/s on the sphere for slices of 512 / 4096 / 65536 / all 2^20 points, and the VM 119 / 126 / 115 / 100.
const FIDGET_CHUNK: usize = 4096;

const SPHERE_CENTRES: [f32; 4] = [-0.75, -0.25, 0.25, 0.75];

fn length(x: Tree, y: Tree, z: Tree) -> Tree {
    (x.square() + y.square() + z.square()).sqrt()
}

fn fidget_sphere() -> Tree {
    length(Tree::x(), Tree::y(), Tree::z()) - 1.0
}

fn fidget_sixteen_spheres() -> Tree {
    let mut spheres = Vec::new();
    for cy in SPHERE_CENTRES {
        for cx in SPHERE_CENTRES {
            spheres.push(length(Tree::x() - cx, Tree::y() - cy, Tree::z()) - 0.2);
        }
    }
    spheres.into_iter().reduce(|a, b| a.min(b)).expect("sixteen spheres")
}

/// iq's Menger sponge in [−1, 1]³, the formulation of fractal's `menger`.
fn fidget_menger(levels: u32) -> Tree {
    let (x, y, z) = (Tree::x(), Tree::y(), Tree::z());
    let q = [x.abs() - 1.0, y.abs() - 1.0, z.abs() - 1.0];
    let outside = length(q[0].max(0.0), q[1].max(0.0), q[2].max(0.0));
    let inside = q[0].max(q[1].max(q[2].clone())).min(0.0);
    let mut d = outside + inside;
    let mut s = 1.0f32;
    for _ in 0..levels {
        let fold = |v: &Tree| {
            let v = v.clone() * s;
            let m = v.clone() - (v / 2.0).floor() * 2.0;
            let a = m - 1.0;
            (Tree::constant(1.0) - a.abs() * 3.0).abs()
        };
        let r = [fold(&x), fold(&y), fold(&z)];
        s *= 3.0;
        let da = r[0].max(r[1].clone());
        let db = r[1].max(r[2].clone());
        let dc = r[2].max(r[0].clone());
        let cut = (da.min(db).min(dc) - 1.0) / s;
        d = d.max(cut);
    }
    d
}

/// One evaluator under test: fills `out` with distances of the points.
type Run<'a> = Box<dyn FnMut(&[f32], &[f32], &[f32], &mut [f32]) + 'a>;

fn fidget_run<F: fidget::eval::Function + fidget::eval::MathFunction + 'static>(tree: &Tree) -> Run<'static>
where
    F::FloatSliceEval: 'static,
    <F::FloatSliceEval as fidget::eval::BulkEvaluator>::Tape: 'static,
{
    let shape = fidget::shape::Shape::<F>::from(tree.clone());
    let tape = shape.ez_float_slice_tape();
    let mut eval = fidget::shape::Shape::<F>::new_float_slice_eval();
    Box::new(move |x, y, z, out| {
        for (i, out) in out.chunks_mut(FIDGET_CHUNK).enumerate() {
            let range = i * FIDGET_CHUNK..i * FIDGET_CHUNK + out.len();
            let result = eval.eval(&tape, &x[range.clone()], &y[range.clone()], &z[range]);
            out.copy_from_slice(result.expect("Fidget evaluates the slice"));
        }
    })
}

fn main() {
    let rounds: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(9);
    let [x, y, z] = points();
    let cases: [(&str, CompiledScene, Tree); 3] = [
        ("sphere", scene! { sphere(1.0) }, fidget_sphere()),
        ("16 spheres", sixteen_spheres(), fidget_sixteen_spheres()),
        ("menger 3", scene! { menger(3) }, fidget_menger(3)),
    ];
    println!("{POINTS} points, one thread, median of {rounds} rounds, M points/s");
    println!(
        "| expression | fractal native packets | fractal interpreter packets | Fidget JIT | Fidget VM | native / JIT | \
         interpreter / VM | max |fractal − Fidget| |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (name, compiled, tree) in &cases {
        let interpreter = Interpreter::new(compiled.scene()).expect("a valid scene");
        let params = compiled.default_params();
        let mut runs: Vec<Run> = vec![
            Box::new(|x, y, z, out| compiled.distance_slice(x, y, z, out)),
            Box::new(|x, y, z, out| interpreter.distance_slice(0.0, params, x, y, z, out)),
            fidget_run::<JitFunction>(tree),
            fidget_run::<VmFunction>(tree),
        ];
        // One output buffer for all: the working set (inputs and output, 16 MiB) is what criterion's runs see.
        let mut out = vec![0.0f32; POINTS];
        let mut first_results = Vec::new();
        let mut seconds = vec![Vec::new(); runs.len()];
        for round in 0..rounds {
            for (i, run) in runs.iter_mut().enumerate() {
                let start = Instant::now();
                run(&x, &y, &z, &mut out);
                black_box(&out);
                seconds[i].push(start.elapsed().as_secs_f64());
                if round == 0 {
                    first_results.push(out.clone());
                }
            }
        }
        let rate: Vec<f64> = seconds
            .iter_mut()
            .map(|s| {
                s.sort_by(f64::total_cmp);
                POINTS as f64 / s[s.len() / 2] / 1e6
            })
            .collect();
        let difference =
            first_results[0].iter().zip(&first_results[2]).map(|(a, b)| (a - b).abs()).fold(0.0f32, f32::max);
        println!(
            "| {name} | {:.0} | {:.1} | {:.0} | {:.1} | {:.2} | {:.2} | {difference:.1e} |",
            rate[0],
            rate[1],
            rate[2],
            rate[3],
            rate[0] / rate[2],
            rate[1] / rate[3]
        );
    }
}
