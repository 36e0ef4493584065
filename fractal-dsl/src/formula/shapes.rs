//! The primitives' exact distances and the smooth CSG blends.

use super::common::*;
use crate::number::math::*;
use crate::number::Num;

#[inline(always)]
pub fn sd_sphere<F: Num>(p: V3<F>, r: F) -> F {
    length(p) - r
}

#[inline(always)]
pub fn sd_box<F: Num>(p: V3<F>, b: V3<F>) -> F {
    let q = abs3(p) - b;
    length(max3(q, c(0.0))) + min(q.max_element(), c(0.0))
}

#[inline(always)]
pub fn sd_round_box<F: Num>(p: V3<F>, b: V3<F>, r: F) -> F {
    sd_box(p, b - V3::splat(r)) - r
}

#[inline(always)]
pub fn sd_torus<F: Num>(p: V3<F>, major: F, minor: F) -> F {
    let qx = sqrt(p.x * p.x + p.z * p.z) - major;
    sqrt(qx * qx + p.y * p.y) - minor
}

#[inline(always)]
pub fn sd_capsule<F: Num>(p: V3<F>, a: V3<F>, b: V3<F>, r: F) -> F {
    let pa = p - a;
    let ba = b - a;
    let h = clamp(dot(pa, ba) / max(dot(ba, ba), c(TINY)), c(0.0), c(1.0));
    length(pa - ba * h) - r
}

#[inline(always)]
pub fn sd_cylinder<F: Num>(p: V3<F>, r: F, h: F) -> F {
    let dx = sqrt(p.x * p.x + p.z * p.z) - r;
    let dy = abs(p.y) - h;
    let ox = max(dx, c(0.0));
    let oy = max(dy, c(0.0));
    min(max(dx, dy), c(0.0)) + sqrt(ox * ox + oy * oy)
}

/// IQ's exact capped cone.
#[inline(always)]
pub fn sd_cone<F: Num>(p: V3<F>, h: F, r1: F, r2: F) -> F {
    let qx = sqrt(p.x * p.x + p.z * p.z);
    let qy = p.y;
    let k2x = r2 - r1;
    let k2y = h + h;
    let cax = qx - min(qx, select(lt(qy, c(0.0)), r1, r2));
    let cay = abs(qy) - h;
    let t = clamp(((r2 - qx) * k2x + (h - qy) * k2y) / (k2x * k2x + k2y * k2y), c(0.0), c(1.0));
    let cbx = qx - r2 + k2x * t;
    let cby = qy - h + k2y * t;
    let s = select::<F>(lt(cbx, c(0.0)) & lt(cay, c(0.0)), c(-1.0), c(1.0));
    s * sqrt(min(cax * cax + cay * cay, cbx * cbx + cby * cby))
}

#[inline(always)]
pub fn sd_plane<F: Num>(p: V3<F>, n: V3<F>, offset: F) -> F {
    dot(p, n) + offset
}

/// IQ's exact octahedron: near a face the distance to the face plane, elsewhere to the nearest edge, found in the
/// rotation of the coordinates that puts the relevant axis first.
#[inline(always)]
pub fn sd_octahedron<F: Num>(p: V3<F>, s: F) -> F {
    let a = abs3(p);
    let m = a.x + a.y + a.z - s;
    let three = c::<F>(3.0);
    let (in_x, in_y, in_z) = (lt(three * a.x, m), lt(three * a.y, m), lt(three * a.z, m));
    let q = select3(in_x, a, select3(in_y, v3(a.y, a.z, a.x), v3(a.z, a.x, a.y)));
    let k = clamp(c::<F>(0.5) * (q.z - q.y + s), c(0.0), s);
    let to_edge = length(v3(q.x, q.y - s + k, q.z - k));
    select(in_x | in_y | in_z, to_edge, m * c(INV_SQRT3))
}

/// IQ's exact hexagonal prism along y: the hexagon in the xz plane has inradius `r` (its flat sides face ±z), the
/// prism extends `h` above and below.
#[inline(always)]
pub fn sd_hex_prism<F: Num>(p: V3<F>, r: F, h: F) -> F {
    // The edge normal of the 30° sector and tan(30°).
    let (kx, kz, tan30) = (c::<F>(-0.866_025_403_784_438_6), c::<F>(0.5), c::<F>(INV_SQRT3));
    let a = abs3(p);
    // Fold the 60° wedge onto the sector whose flat side is z = r.
    let fold = c::<F>(2.0) * min(kx * a.x + kz * a.z, c(0.0));
    let (x, z) = (a.x - fold * kx, a.z - fold * kz);
    let ex = x - clamp(x, -tan30 * r, tan30 * r);
    let ez = z - r;
    let across = sqrt(ex * ex + ez * ez) * select(lt(ez, c(0.0)), c(-1.0), c(1.0));
    let along = a.y - h;
    let (ox, oy) = (max(across, c(0.0)), max(along, c(0.0)));
    min(max(across, along), c(0.0)) + sqrt(ox * ox + oy * oy)
}

/// IQ's ellipsoid bound; at the centre, minus the smallest radius.
#[inline(always)]
pub fn sd_ellipsoid<F: Num>(p: V3<F>, r: V3<F>) -> F {
    let k0 = length(v3(p.x / r.x, p.y / r.y, p.z / r.z));
    let k1 = length(v3(p.x / (r.x * r.x), p.y / (r.y * r.y), p.z / (r.z * r.z)));
    select(gt(k1, c(0.0)), k0 * (k0 - c(1.0)) / max(k1, c(TINY)), -r.min_element())
}

// ---- smooth CSG -----------------------------------------------------------------------------------------------------

/// Polynomial smooth minimum (IQ) with blend radius k; k = 0 is the plain minimum (no division by zero).
#[inline(always)]
pub fn smooth_min<F: Num>(a: F, b: F, k: F) -> F {
    let h = max(k - abs(a - b), c(0.0)) / max(k, c(TINY));
    min(a, b) - h * h * k * c(0.25)
}

#[inline(always)]
pub fn smooth_max<F: Num>(a: F, b: F, k: F) -> F {
    -smooth_min(-a, -b, k)
}

/// How far a smooth blend of `a` and `b` leans towards `b` (0 = all `a`, 1 = all `b`): mixes materials.
#[inline(always)]
pub fn blend_weight<F: Num>(a: F, b: F, k: F) -> F {
    clamp(c::<F>(0.5) + c::<F>(0.5) * (a - b) / max(k, c(TINY)), c(0.0), c(1.0))
}
