use fractal::prelude::*;

fn main() {
    let _s = scene! { sphere(1.0).translat(vec3(1.0, 0.0, 0.0)) };
}
