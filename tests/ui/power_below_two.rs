use fractal::prelude::*;

fn main() {
    let _s = scene! { mandelbulb(1.5) };
}
