//! What the evaluator benchmarks share: the points (2^20 spread over [−1.5, 1.5]³, the same for every evaluator) and
//! the SIMD issue's union of 16 spheres. Included by `benches/evaluator.rs` and `benches/fidget`.

use fractal_dsl::CompiledScene;
use fractal_macros::scene;

pub const POINTS: usize = 1 << 20;

/// Points spread over [−1.5, 1.5]³ by three co-prime strides (deterministic, no RNG crate).
pub fn points() -> [Vec<f32>; 3] {
    let axis = |stride: usize, modulus: usize| -> Vec<f32> {
        (0..POINTS).map(|i| ((i * stride) % modulus) as f32 / modulus as f32 * 3.0 - 1.5).collect()
    };
    [axis(7919, 1009), axis(104_729, 997), axis(1_299_709, 991)]
}

/// Sixteen spheres of radius 0.2 centred on a 4 × 4 grid at ±0.25 and ±0.75 in the z = 0 plane.
pub fn sixteen_spheres() -> CompiledScene {
    scene! {
        union(
            sphere(0.2).translate(vec3(-0.75, -0.75, 0.0)), sphere(0.2).translate(vec3(-0.25, -0.75, 0.0)),
            sphere(0.2).translate(vec3(0.25, -0.75, 0.0)), sphere(0.2).translate(vec3(0.75, -0.75, 0.0)),
            sphere(0.2).translate(vec3(-0.75, -0.25, 0.0)), sphere(0.2).translate(vec3(-0.25, -0.25, 0.0)),
            sphere(0.2).translate(vec3(0.25, -0.25, 0.0)), sphere(0.2).translate(vec3(0.75, -0.25, 0.0)),
            sphere(0.2).translate(vec3(-0.75, 0.25, 0.0)), sphere(0.2).translate(vec3(-0.25, 0.25, 0.0)),
            sphere(0.2).translate(vec3(0.25, 0.25, 0.0)), sphere(0.2).translate(vec3(0.75, 0.25, 0.0)),
            sphere(0.2).translate(vec3(-0.75, 0.75, 0.0)), sphere(0.2).translate(vec3(-0.25, 0.75, 0.0)),
            sphere(0.2).translate(vec3(0.25, 0.75, 0.0)), sphere(0.2).translate(vec3(0.75, 0.75, 0.0)),
        )
    }
}
