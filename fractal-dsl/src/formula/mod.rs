//! The leaf functions: distance to each primitive, each fractal estimator, and the smooth CSG blends, each written
//! once, generic over [`Num`]. `f32` and `f64` run them directly (interpreter, native evaluator, reference); the
//! tracer records them into the kernels' named functions (`sd_box`, `de_mandelbulb8`, …) and a lane type runs them a
//! packet at a time. So they branch with [`select`] and loop with [`Num::iterate`] (see [`crate::number`]), and the
//! guard constants below reach every kernel as traced literals. The table just below lists them with their
//! signatures.

mod common;
pub mod dual;
mod estimate;
pub mod lang;
pub mod leaf;
pub mod mandelbrot;
mod membership;
pub mod noise;
mod shapes;
pub mod user;

pub use common::{DR_MAX, POW_LOG2_MAX, TINY};
pub use estimate::*;
pub use membership::*;
pub use shapes::*;

use crate::formula::leaf::{leaves, LeafArg, LeafOut};
pub use crate::formula::mandelbrot::{mandelbrot, mandelbrot_perturbed};
pub use crate::formula::noise::{fbm2, fbm3, noise2, noise3};
use crate::number::lanes::{has_avx2, F32x8};
use crate::number::math::*;

// The leaf table: every function below with its parameters' kinds and its result ([`crate::formula::leaf`]).
leaves! {
    SdSphere => sd_sphere(p: V3, r: F) -> F;
    SdBox => sd_box(p: V3, b: V3) -> F;
    SdRoundBox => sd_round_box(p: V3, b: V3, r: F) -> F;
    SdTorus => sd_torus(p: V3, major: F, minor: F) -> F;
    SdCapsule => sd_capsule(p: V3, a: V3, b: V3, r: F) -> F;
    SdCylinder => sd_cylinder(p: V3, r: F, h: F) -> F;
    SdCone => sd_cone(p: V3, h: F, r1: F, r2: F) -> F;
    SdPlane => sd_plane(p: V3, n: V3, offset: F) -> F;
    SdOctahedron => sd_octahedron(p: V3, s: F) -> F;
    SdHexPrism => sd_hex_prism(p: V3, r: F, h: F) -> F;
    SdEllipsoid => sd_ellipsoid(p: V3, r: V3) -> F;
    SmoothMin => smooth_min(a: F, b: F, k: F) -> F;
    SmoothMax => smooth_max(a: F, b: F, k: F) -> F;
    BlendWeight => blend_weight(a: F, b: F, k: F) -> F;
    Noise2 => noise2(x: F, y: F) -> F;
    Noise3 => noise3(p: V3) -> F;
    Fbm2 => fbm2(x: F, y: F, octaves: Count) -> F;
    Fbm3 => fbm3(p: V3, octaves: Count) -> F;
    Mandelbrot => mandelbrot(cx: F, cy: F, iterations: Count, inverse: F) -> F;
    MandelbrotPerturbed => mandelbrot_perturbed(dcx: F, dcy: F, iterations: Count, inverse: F, orbit: Orbit) -> F;
    DeMandelbulb => de_mandelbulb(p: V3, power: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbulbStretched => de_mandelbulb_stretched(p: V3, power: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbulb8 => de_mandelbulb8(p: V3, iterations: Count, bailout: F) -> Pair;
    DeMenger => de_menger(p: V3, levels: Count) -> Pair;
    DeSierpinski => de_sierpinski(p: V3, levels: Count) -> Pair;
    DeJulia => de_julia(p: V3, cx: F, cy: F, cz: F, cw: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbox => de_mandelbox(p: V3, scale: F, iterations: Count, min_radius: F, fold_limit: F) -> Pair;
    DeJuliabulb => de_juliabulb(p: V3, cx: F, cy: F, cz: F, power: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbulbSigned => de_mandelbulb_signed(p: V3, power: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbulbStretchedSigned => de_mandelbulb_stretched_signed(p: V3, power: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbulb8Signed => de_mandelbulb8_signed(p: V3, iterations: Count, bailout: F) -> Pair;
    DeJuliaSigned => de_julia_signed(p: V3, cx: F, cy: F, cz: F, cw: F, iterations: Count, bailout: F) -> Pair;
    DeJuliabulbSigned => de_juliabulb_signed(p: V3, cx: F, cy: F, cz: F, power: F, iterations: Count, bailout: F) -> Pair;
    DeOctahedralKifs => de_octahedral_kifs(p: V3, scale: F, angle: F, iterations: Count) -> Pair;
    DeIcosahedralKifs => de_icosahedral_kifs(p: V3, scale: F, angle: F, iterations: Count) -> Pair;
    InMandelbulb => in_mandelbulb(p: V3, power: F, iterations: Count, bailout: F) -> F;
    InMandelbulb8 => in_mandelbulb8(p: V3, iterations: Count, bailout: F) -> F;
    InMenger => in_menger(p: V3, levels: Count) -> F;
    InSierpinski => in_sierpinski(p: V3, levels: Count) -> F;
    InJulia => in_julia(p: V3, cx: F, cy: F, cz: F, cw: F, iterations: Count, bailout: F) -> F;
    InMandelbox => in_mandelbox(p: V3, scale: F, iterations: Count, min_radius: F, fold_limit: F) -> F;
    InJuliabulb => in_juliabulb(p: V3, cx: F, cy: F, cz: F, power: F, iterations: Count, bailout: F) -> F;
    InOctahedralKifs => in_octahedral_kifs(p: V3, scale: F, angle: F, iterations: Count) -> F;
    InIcosahedralKifs => in_icosahedral_kifs(p: V3, scale: F, angle: F, iterations: Count) -> F;
}

/// How a number type calls a leaf function: directly (the default), or — when tracing — as a call of the named
/// function the kernel defines once.
pub trait CallLeaf: Num {
    #[inline(always)]
    fn leaf(leaf: Leaf, args: &[LeafArg<Self>]) -> LeafOut<Self> {
        leaf.eval(args)
    }
    /// A fractal written in the scene language at `p`: its estimate and orbit trap ([`user::estimate`]), or — for a
    /// number type that answers membership instead — its membership test. `nums` are its scene numbers.
    #[inline(always)]
    fn formula(ready: &user::Ready, nums: &[Self], p: V3<Self>, bailout: Self, signed: bool) -> LeafOut<Self> {
        LeafOut::Pair(user::estimate(ready, nums, p, bailout, signed))
    }
}

impl CallLeaf for f32 {}
/// f64 runs a formula's host code where it has been compiled ([`user::Ready::host`]).
impl CallLeaf for f64 {
    #[inline]
    fn formula(ready: &user::Ready, nums: &[Self], p: V3<Self>, bailout: Self, signed: bool) -> LeafOut<Self> {
        let host = ready.host.as_ref().and_then(|h| h.estimate(nums, [p.x, p.y, p.z], bailout, signed));
        LeafOut::Pair(host.unwrap_or_else(|| user::estimate(ready, nums, p, bailout, signed)))
    }
}

/// A scene run in dual numbers gives its gradient ([`crate::eval::walk::Walk::gradient`]): a leaf is differentiated
/// through its own arithmetic; a formula's estimate with its divisor held constant, its gradient the potential's
/// direction ([`user::estimate_and_gradient`]) carried back through the point's derivatives. A formula whose maps give
/// their own scale carries no Jacobian: its estimate is differentiated through as it is.
impl<F: Num> CallLeaf for dual::Dual<F> {
    #[inline]
    fn formula(ready: &user::Ready, nums: &[Self], p: V3<Self>, bailout: Self, signed: bool) -> LeafOut<Self> {
        if ready.formula.own_scale() {
            return LeafOut::Pair(user::estimate(ready, nums, p, bailout, signed));
        }
        let values: Vec<F> = nums.iter().map(|n| n.v).collect();
        let ([e, trap], g) = user::estimate_and_gradient(ready, &values, v3(p.x.v, p.y.v, p.z.v), bailout.v, signed);
        let d = [0, 1, 2].map(|i| g.x * p.x.d[i] + g.y * p.y.d[i] + g.z * p.z.d[i]);
        LeafOut::Pair([dual::Dual { v: e, d }, dual::Dual::constant(trap)])
    }
}

/// The interpreter's packets call leaves through here (the native evaluator calls its leaves directly, inside its
/// own AVX2 copy): the leaf's formula runs in an AVX2 copy where the CPU has one. The walker around it stays baseline
/// code: it recurses, so no AVX2 function can inline it whole.
impl CallLeaf for F32x8 {
    #[inline]
    fn leaf(leaf: Leaf, args: &[leaf::LeafArg<Self>]) -> leaf::LeafOut<Self> {
        #[cfg(target_arch = "x86_64")]
        if has_avx2() {
            // SAFETY: the CPU has AVX2.
            return unsafe { leaf_avx2(leaf, args) };
        }
        leaf.eval(args)
    }
}

/// A leaf on packets compiled for AVX2; callers check [`has_avx2`].
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn leaf_avx2(leaf: Leaf, args: &[leaf::LeafArg<F32x8>]) -> leaf::LeafOut<F32x8> {
    leaf.eval(args)
}
impl HostNum for F32x8 {}

/// A number type the host evaluates in — f32, f64 and the packet [`crate::number::lanes::F32x8`] — whose masks it can
/// inspect: the native evaluator the `scene!` macro compiles is generic over it.
pub trait HostNum: CallLeaf + Num<Mask: AnyLane, Count = u32> + Send + Sync {}

impl HostNum for f32 {}
impl HostNum for f64 {}
