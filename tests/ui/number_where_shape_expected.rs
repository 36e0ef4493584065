use fractal::prelude::*;

fn main() {
    let _s = scene! { union(sphere(1.0), 2.0) };
}
