use fractal::prelude::*;

fn main() {
    let _s = scene! { spher(1.0) };
}
