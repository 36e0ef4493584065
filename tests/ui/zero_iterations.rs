use fractal::prelude::*;

fn main() {
    let _s = scene! { mandelbulb(8).iterations(0) };
}
