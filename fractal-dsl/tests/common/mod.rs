//! Helpers shared by the integration tests: a deterministic point generator, the random-tree building blocks
//! (coordinate boxes, unit axes, exact bounded primitives) and distance evaluation at rest.
// Each test crate compiles its own copy of this module and uses only part of it.
#![allow(dead_code)]

use fractal_dsl::builder::*;
use fractal_dsl::eval::interp::Interpreter;
use fractal_dsl::eval::Env;
use fractal_dsl::math::v3;
use fractal_dsl::*;
use proptest::prelude::*;

/// A small deterministic xorshift generator for dense point sets, so measured figures are reproducible run to run
/// (proptest drives the shapes). Test files add the samplers they need in their own `impl Rng` blocks.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in [0, 1) from the top 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The f64 distance at `p` at time 0 with every parameter at its default.
pub fn d64(i: &Interpreter, p: [f64; 3]) -> f64 {
    i.distance_in(v3(p[0], p[1], p[2]), &Env::<f64>::still())
}

pub fn vec3_in(lo: f64, hi: f64) -> impl Strategy<Value = [f64; 3]> {
    [lo..hi, lo..hi, lo..hi]
}

pub fn unit_axis() -> impl Strategy<Value = [f64; 3]> {
    vec3_in(-1.0, 1.0).prop_filter_map("a usable axis", |a| {
        let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
        (l > 0.2).then(|| a.map(|c| c / l))
    })
}

/// Primitives whose leaf function is the exact distance (no plane: it would make a child unbounded and unguarded).
pub fn exact_bounded_primitive() -> impl Strategy<Value = Node> {
    prop_oneof![
        (0.1..1.5f64).prop_map(sphere),
        vec3_in(0.05, 1.2).prop_map(box3),
        (0.2..1.2f64, 0.05..0.5f64).prop_map(|(a, b)| torus(a, b)),
        (vec3_in(-1.0, 1.0), vec3_in(-1.0, 1.0), 0.05..0.6f64).prop_map(|(a, b, r)| capsule(a, b, r)),
        (0.1..1.0f64, 0.0..1.0f64, 0.0..1.0f64).prop_map(|(h, a, b)| cone(h, a, b)),
        (0.1..1.5f64).prop_map(octahedron),
    ]
}
