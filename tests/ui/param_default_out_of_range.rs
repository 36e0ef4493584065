use fractal::prelude::*;

fn main() {
    let _s = scene! { sphere(param("r", 5.0, 0.1..2.0)) };
}
