//! The hand-written baseline the generated kernels are timed against: the Mandelbulb kernel in OpenCL C and WGSL
//! (`baseline/`, compiled into the program for the GPU dispatchers), and its port line for line to scalar Rust (f32,
//! one rayon task per row), so the CPU backend has a baseline on its own device too. The port has the same
//! constants and the same operations in the same order as `baseline/mandelbulb.cl`; only the vector helpers are
//! spelled out.

use fractal_render::image::Image;
use rayon::prelude::*;

/// The hand-written baseline in OpenCL C: kernel `render(__global uint* out, int w, int h)`.
pub const BASELINE_OPENCL: &str = include_str!("../../baseline/mandelbulb.cl");
/// The hand-written baseline in WGSL: entry `main`, 8×8 workgroups, binding 0 pixels, binding 1 `{w, h}`.
pub const BASELINE_WGSL: &str = include_str!("../../baseline/mandelbulb.wgsl");

const MAX_STEPS: i32 = 128;
const ITERS: i32 = 8;
const POWER: f32 = 8.0;
const EPS: f32 = 0.0005;
const TMAX: f32 = 6.0;

type V = [f32; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn mul(a: V, s: f32) -> V {
    [a[0] * s, a[1] * s, a[2] * s]
}
fn dot(a: V, b: V) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn length(a: V) -> f32 {
    dot(a, a).sqrt()
}
fn normalize(a: V) -> V {
    mul(a, 1.0 / length(a))
}
fn cross(a: V, b: V) -> V {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn de(p: V) -> f32 {
    let mut z = p;
    let mut dr = 1.0f32;
    let mut r = 0.0f32;
    for _ in 0..ITERS {
        r = length(z);
        if r > 2.0 {
            break;
        }
        let mut theta = (z[2] / r).acos();
        let mut phi = z[1].atan2(z[0]);
        dr = r.powf(POWER - 1.0) * POWER * dr + 1.0;
        let zr = r.powf(POWER);
        theta *= POWER;
        phi *= POWER;
        z = add(mul([theta.sin() * phi.cos(), phi.sin() * theta.sin(), theta.cos()], zr), p);
    }
    0.5 * r.ln() * r / dr
}

fn pixel(x: u32, y: u32, w: u32, h: u32) -> u32 {
    let u = (2.0 * (x as f32 + 0.5) - w as f32) / h as f32;
    let v = -(2.0 * (y as f32 + 0.5) - h as f32) / h as f32;
    let ro: V = [1.2, 1.0, -2.2];
    let ww = normalize(mul(ro, -1.0));
    let uu = normalize(cross([0.0, 1.0, 0.0], ww));
    let vv = cross(ww, uu);
    let rd = normalize(add(add(mul(uu, u), mul(vv, v)), mul(ww, 1.8)));

    let mut t = 0.0f32;
    let mut steps = 0;
    let mut hit = false;
    while steps < MAX_STEPS {
        let d = de(add(ro, mul(rd, t)));
        if d < EPS {
            hit = true;
            break;
        }
        t += d;
        if t > TMAX {
            break;
        }
        steps += 1;
    }
    let mut col = add([0.08, 0.09, 0.12], [0.08 * v; 3]);
    if hit {
        let p = add(ro, mul(rd, t));
        let e = 0.0005f32;
        let taps: [V; 4] = [[1.0, -1.0, -1.0], [-1.0, -1.0, 1.0], [-1.0, 1.0, -1.0], [1.0, 1.0, 1.0]];
        let n = normalize(taps.iter().fold([0.0; 3], |acc, &k| add(acc, mul(k, de(add(p, mul(k, e)))))));
        let l = normalize([0.6, 0.8, -0.4]);
        let diff = dot(n, l).max(0.0);
        let ao = 1.0 - steps as f32 / MAX_STEPS as f32;
        col = mul(mul([0.95, 0.75, 0.55], 0.15 + 0.85 * diff), ao);
    }
    let channel = |c: f32| (c.clamp(0.0, 1.0).sqrt() * 255.0 + 0.5) as u32;
    channel(col[0]) | (channel(col[1]) << 8) | (channel(col[2]) << 16) | (255 << 24)
}

/// Renders the baseline's Mandelbulb at `width`×`height`.
pub fn render(width: u32, height: u32) -> Image {
    let mut pixels = vec![0u32; width as usize * height as usize];
    pixels.par_chunks_mut(width.max(1) as usize).enumerate().for_each(|(y, row)| {
        for (x, px) in row.iter_mut().enumerate() {
            *px = pixel(x as u32, y as u32, width, height);
        }
    });
    Image { width, height, pixels }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_the_bulb_in_the_middle_and_background_in_the_corner() {
        let image = render(48, 32);
        let corner = image.rgba(0, 0).unwrap();
        let middle = image.rgba(24, 16).unwrap();
        // Background at the top row: (0.08, 0.09, 0.12) + 0.08·v with v = 31/32, gamma by sqrt.
        let v = 31.0f32 / 32.0;
        let want = [0.08f32, 0.09, 0.12].map(|c| ((c + 0.08 * v).sqrt() * 255.0 + 0.5) as u8);
        assert_eq!(&corner[..3], &want);
        assert!(middle.iter().zip(&want).any(|(a, b)| a.abs_diff(*b) > 10), "no bulb at the centre: {middle:?}");
    }
}
