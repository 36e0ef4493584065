//! Gradient noise: its range, its slope (the displacement's Lipschitz bound reads the declared slopes, so a slope
//! above them would let a march step through a displaced surface), and its variety (not a constant, not periodic at
//! small scales). The measured values are printed; the declared constants in `fractal_dsl::formula::noise` must stay
//! above.

use fractal_dsl::formula::noise::{fbm2, fbm3, noise2, noise3, NOISE2_SLOPE, NOISE3_SLOPE};
use fractal_dsl::number::math::v3;

use crate::common::Rng;

impl Rng {
    /// Uniform in [−half, half).
    fn signed(&mut self, half: f64) -> f64 {
        (2.0 * self.unit() - 1.0) * half
    }
}

const SAMPLES: usize = 400_000;
/// Finite-difference step: small against the lattice (1), large against f64 rounding.
const H: f64 = 1e-6;

#[test]
fn noise_stays_in_range_and_below_its_declared_slope() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut slope2, mut slope3, mut lo, mut hi, mut sum2) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for _ in 0..SAMPLES {
        let (x, y, z) = (rng.signed(300.0), rng.signed(300.0), rng.signed(300.0));
        let n2 = noise2(x, y);
        let g2 = [(noise2(x + H, y) - n2) / H, (noise2(x, y + H) - n2) / H];
        slope2 = slope2.max(g2[0].hypot(g2[1]));
        let n3 = noise3(v3(x, y, z));
        let g3 = [
            (noise3(v3(x + H, y, z)) - n3) / H,
            (noise3(v3(x, y + H, z)) - n3) / H,
            (noise3(v3(x, y, z + H)) - n3) / H,
        ];
        slope3 = slope3.max((g3[0] * g3[0] + g3[1] * g3[1] + g3[2] * g3[2]).sqrt());
        lo = lo.min(n2.min(n3));
        hi = hi.max(n2.max(n3));
        sum2 += n3 * n3;
    }
    let rms = (sum2 / SAMPLES as f64).sqrt();
    eprintln!("noise2 slope {slope2:.3} (declared {NOISE2_SLOPE}), noise3 slope {slope3:.3} (declared {NOISE3_SLOPE})");
    eprintln!("range [{lo:.3}, {hi:.3}], noise3 rms {rms:.3}");
    assert!(slope2 < NOISE2_SLOPE && slope3 < NOISE3_SLOPE);
    assert!((-1.0..=1.0).contains(&lo) && (-1.0..=1.0).contains(&hi));
    // Real variation: values spread over most of the range.
    assert!(lo < -0.5 && hi > 0.5 && rms > 0.15, "noise barely varies: [{lo}, {hi}], rms {rms}");
}

#[test]
fn noise_is_zero_on_the_lattice_and_fbm_adds_octaves() {
    // Gradient noise vanishes at lattice points, for negative coordinates and far ones too.
    for p in [[0.0, 0.0, 0.0], [3.0, -7.0, 12.0], [-288.0, 289.0, 5000.0]] {
        assert_eq!(noise3(v3(p[0], p[1], p[2])), 0.0);
        assert_eq!(noise2(p[0], p[1]), 0.0);
    }
    // One octave is the noise itself; more octaves add detail of half the amplitude each.
    let (x, y, z) = (0.37f64, 1.61f64, -2.2f64);
    assert_eq!(fbm2(x, y, 1), noise2(x, y));
    assert_eq!(fbm3(v3(x, y, z), 1), noise3(v3(x, y, z)));
    assert!((fbm3(v3(x, y, z), 5) - fbm3(v3(x, y, z), 4)).abs() <= 1.0 / 16.0 + 1e-12);
    // f32 and f64 agree to f32 rounding: the hash picks the same gradients in both.
    let mut rng = Rng(7);
    for _ in 0..10_000 {
        let (x, y, z) = (rng.signed(1000.0), rng.signed(1000.0), rng.signed(1000.0));
        let (xf, yf, zf) = (x as f32, y as f32, z as f32);
        let exact = noise3(v3(xf as f64, yf as f64, zf as f64));
        let single = noise3(v3(xf, yf, zf)) as f64;
        assert!((exact - single).abs() < 1e-3, "at ({x}, {y}, {z}): f64 {exact}, f32 {single}");
    }
}
