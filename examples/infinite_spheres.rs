//! A scene written in Rust with `scene!`: one sphere repeated forever by domain repetition, its radius a parameter.
//! The macro checks the scene when this file compiles and turns it into OpenCL C, WGSL and a native evaluator.
//!
//! Run: `cargo run --release --example infinite_spheres`.
//!
//! Tab selects `radius`, ↑ / ↓ change it. With no display the scene is rendered to `infinite_spheres.png` instead.
//! The same scene ships as `scenes/fractal/infinite_spheres.fractal`.

use fractal::prelude::*;
use fractal::view::{example_main, ViewerScene};

static SPHERES: CompiledScene = scene! {
    scene(
        sphere(param("radius", 0.45, 0.1..0.95))
            .repeat(vec3(2.0, 0.0, 2.0))
            .material(phong(rgb(0.3, 0.6, 0.95), 0.2, 0.8, 0.6, 48.0)),
    )
        .light(directional(vec3(0.3, 0.9, -0.4), rgb(1.0, 0.97, 0.9)))
        .camera(camera_path(
            key(0.0, vec3(1.0, 1.6, -6.0), vec3(1.0, 0.0, 0.0)),
            key(10.0, vec3(1.0, 1.6, 14.0), vec3(1.0, 0.0, 20.0)),
        ).linear().fov(60.0))
        .max_steps(160)
        .max_distance(60.0)
        .pixel_epsilon(0.5)
        .fog(rgb(0.7, 0.75, 0.85), 0.05)
        .background(rgb(0.7, 0.75, 0.85))
};

fn main() -> std::process::ExitCode {
    example_main("infinite_spheres", ViewerScene::compiled("infinite_spheres", &SPHERES))
}
