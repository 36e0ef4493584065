//! The `fractal` crate's integration tests, one binary: the scene language end to end (macro, files, kernels and
//! their snapshots), every evaluator against the f64 interpreter, rendered images across backends, the `fractal`
//! program, the viewer and hostile input. Each module's header says what it proves.

mod agreement;
mod backends;
mod cli;
mod compiled_scene;
mod file_vs_macro;
mod fuzz;
mod hard_cases;
mod hostile;
mod kernels;
mod mandelbrot_zoom;
mod mesh;
mod precision;
mod ui;
mod viewer;
