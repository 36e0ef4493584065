use fractal::prelude::*;

fn main() {
    let _s = scene! { mandelbulb(8).min_radius(0.5) };
}
