//! The OpenCL C spelling of each leaf function ([`Helper`]): the formulas of [`crate::sdf`] in `float`, `float2`,
//! `float3` and `float4`, operation for operation, with the same guards and constants (`TINY` = 1e-30,
//! `DR_MAX` = 1e17, `POW_LOG2_MAX` = 60). Escape-time fractals return `(float2)(distance, trap)`.
//!
//! Each text is one function ending in a newline; a kernel holds the helpers it uses and their dependencies
//! ([`crate::back::with_dependencies`]) in [`Helper`] order, so a function only calls helpers that come before it.

use crate::back::{with_dependencies, Helper};

/// The OpenCL C definition of `helper`.
pub fn helper_source(helper: Helper) -> &'static str {
    match helper {
        Helper::SdSphere => SD_SPHERE,
        Helper::SdBox => SD_BOX,
        Helper::SdRoundBox => SD_ROUND_BOX,
        Helper::SdTorus => SD_TORUS,
        Helper::SdCapsule => SD_CAPSULE,
        Helper::SdCylinder => SD_CYLINDER,
        Helper::SdCone => SD_CONE,
        Helper::SdPlane => SD_PLANE,
        Helper::SdOctahedron => SD_OCTAHEDRON,
        Helper::SdEllipsoid => SD_ELLIPSOID,
        Helper::SmoothMin => SMOOTH_MIN,
        Helper::SmoothMax => SMOOTH_MAX,
        Helper::BlendWeight => BLEND_WEIGHT,
        Helper::DeMandelbulb => DE_MANDELBULB,
        Helper::DeMandelbulb8 => DE_MANDELBULB8,
        Helper::DeMenger => DE_MENGER,
        Helper::DeSierpinski => DE_SIERPINSKI,
        Helper::DeJulia => DE_JULIA,
        Helper::DeMandelbox => DE_MANDELBOX,
    }
}

/// The definitions of `used` and everything they depend on, in emission order, one blank line between functions.
pub fn helpers_source(used: impl IntoIterator<Item = Helper>) -> String {
    with_dependencies(used).into_iter().map(helper_source).collect::<Vec<_>>().join("\n")
}

const SD_SPHERE: &str = "\
float sd_sphere(float3 p, float r) {
    return length(p) - r;
}
";

const SD_BOX: &str = "\
float sd_box(float3 p, float3 b) {
    float3 q = fabs(p) - b;
    return length(fmax(q, 0.0f)) + fmin(fmax(fmax(q.x, q.y), q.z), 0.0f);
}
";

const SD_ROUND_BOX: &str = "\
float sd_round_box(float3 p, float3 b, float r) {
    return sd_box(p, b - (float3)(r)) - r;
}
";

const SD_TORUS: &str = "\
float sd_torus(float3 p, float major, float minor) {
    float qx = sqrt(p.x * p.x + p.z * p.z) - major;
    return sqrt(qx * qx + p.y * p.y) - minor;
}
";

const SD_CAPSULE: &str = "\
float sd_capsule(float3 p, float3 a, float3 b, float r) {
    float3 pa = p - a;
    float3 ba = b - a;
    float h = clamp(dot(pa, ba) / fmax(dot(ba, ba), 1e-30f), 0.0f, 1.0f);
    return length(pa - ba * h) - r;
}
";

const SD_CYLINDER: &str = "\
float sd_cylinder(float3 p, float r, float h) {
    float dx = sqrt(p.x * p.x + p.z * p.z) - r;
    float dy = fabs(p.y) - h;
    float ox = fmax(dx, 0.0f);
    float oy = fmax(dy, 0.0f);
    return fmin(fmax(dx, dy), 0.0f) + sqrt(ox * ox + oy * oy);
}
";

const SD_CONE: &str = "\
float sd_cone(float3 p, float h, float r1, float r2) {
    float qx = sqrt(p.x * p.x + p.z * p.z);
    float qy = p.y;
    float k2x = r2 - r1;
    float k2y = h + h;
    float cax = qx - fmin(qx, qy < 0.0f ? r1 : r2);
    float cay = fabs(qy) - h;
    float t = clamp(((r2 - qx) * k2x + (h - qy) * k2y) / (k2x * k2x + k2y * k2y), 0.0f, 1.0f);
    float cbx = qx - r2 + k2x * t;
    float cby = qy - h + k2y * t;
    float s = cbx < 0.0f && cay < 0.0f ? -1.0f : 1.0f;
    return s * sqrt(fmin(cax * cax + cay * cay, cbx * cbx + cby * cby));
}
";

const SD_PLANE: &str = "\
float sd_plane(float3 p, float3 n, float offset) {
    return dot(p, n) + offset;
}
";

const SD_OCTAHEDRON: &str = "\
float sd_octahedron(float3 p, float s) {
    float3 a = fabs(p);
    float m = a.x + a.y + a.z - s;
    float3 q;
    if (3.0f * a.x < m) {
        q = a;
    } else if (3.0f * a.y < m) {
        q = (float3)(a.y, a.z, a.x);
    } else if (3.0f * a.z < m) {
        q = (float3)(a.z, a.x, a.y);
    } else {
        return m * 0.57735026f;
    }
    float k = clamp(0.5f * (q.z - q.y + s), 0.0f, s);
    return length((float3)(q.x, q.y - s + k, q.z - k));
}
";

const SD_ELLIPSOID: &str = "\
float sd_ellipsoid(float3 p, float3 r) {
    float k0 = length((float3)(p.x / r.x, p.y / r.y, p.z / r.z));
    float k1 = length((float3)(p.x / (r.x * r.x), p.y / (r.y * r.y), p.z / (r.z * r.z)));
    if (k1 > 0.0f) {
        return k0 * (k0 - 1.0f) / k1;
    }
    return -fmin(fmin(r.x, r.y), r.z);
}
";

const SMOOTH_MIN: &str = "\
float smooth_min(float a, float b, float k) {
    float h = fmax(k - fabs(a - b), 0.0f) / fmax(k, 1e-30f);
    return fmin(a, b) - h * h * k * 0.25f;
}
";

const SMOOTH_MAX: &str = "\
float smooth_max(float a, float b, float k) {
    return -smooth_min(-a, -b, k);
}
";

const BLEND_WEIGHT: &str = "\
float blend_weight(float a, float b, float k) {
    return clamp(0.5f + 0.5f * (a - b) / fmax(k, 1e-30f), 0.0f, 1.0f);
}
";

const DE_MANDELBULB: &str = "\
float2 de_mandelbulb(float3 p, float power, int iterations, float bailout) {
    float escape = fmin(bailout, exp2(60.0f / power));
    float3 z = p;
    float dr = 1.0f;
    float r = length(z);
    float trap = r;
    for (int i = 0; i < iterations; i++) {
        if (r > escape || dr > 1e17f) {
            break;
        }
        float theta = acos(clamp(z.z / fmax(r, 1e-30f), -1.0f, 1.0f)) * power;
        float phi = atan2(z.y, z.x) * power;
        dr = power * pow(r, power - 1.0f) * dr + 1.0f;
        float zr = pow(r, power);
        float st = sin(theta);
        float ct = cos(theta);
        float sp = sin(phi);
        float cp = cos(phi);
        z = (float3)(st * cp, sp * st, ct) * zr + p;
        r = length(z);
        trap = fmin(trap, r);
    }
    return (float2)(0.5f * log(fmax(r, 1e-30f)) * r / dr, fmin(trap, 1.0f));
}
";

const DE_MANDELBULB8: &str = "\
float2 de_mandelbulb8(float3 p, int iterations, float bailout) {
    float escape = fmin(bailout, exp2(60.0f / 8.0f));
    float3 z = p;
    float dr = 1.0f;
    float r = length(z);
    float trap = r;
    for (int i = 0; i < iterations; i++) {
        if (r > escape || dr > 1e17f) {
            break;
        }
        float x2 = z.x * z.x;
        float y2 = z.y * z.y;
        float a = z.z * z.z;
        float b = x2 + y2;
        float r2 = a + b;
        dr = 8.0f * r2 * r2 * r2 * r * dr + 1.0f;
        float a2 = a * a;
        float b2 = b * b;
        float cos_part = a2 * a2 - 28.0f * a2 * a * b + 70.0f * a2 * b2 - 28.0f * a * b2 * b + b2 * b2;
        float sin_part = 8.0f * z.z * (a2 * a - 7.0f * a2 * b + 7.0f * a * b2 - b2 * b);
        float inv_rho = b > 1e-30f ? 1.0f / sqrt(b) : 0.0f;
        float ux = z.x * inv_rho;
        float uy = z.y * inv_rho;
        float u2x = ux * ux - uy * uy;
        float u2y = 2.0f * ux * uy;
        float u4x = u2x * u2x - u2y * u2y;
        float u4y = 2.0f * u2x * u2y;
        float u8x = u4x * u4x - u4y * u4y;
        float u8y = 2.0f * u4x * u4y;
        float rho_sin = b * inv_rho * sin_part;
        z = (float3)(rho_sin * u8x, rho_sin * u8y, cos_part) + p;
        r = length(z);
        trap = fmin(trap, r);
    }
    return (float2)(0.5f * log(fmax(r, 1e-30f)) * r / dr, fmin(trap, 1.0f));
}
";

const DE_MENGER: &str = "\
float2 de_menger(float3 p, int levels) {
    float d = sd_box(p, (float3)(1.0f));
    float s = 1.0f;
    float trap = 1.0f;
    for (int i = 0; i < levels; i++) {
        float3 ps = p * s;
        float3 a = ps - 2.0f * floor(ps / 2.0f) - 1.0f;
        s = s * 3.0f;
        float3 r = fabs(1.0f - 3.0f * fabs(a));
        float da = fmax(r.x, r.y);
        float db = fmax(r.y, r.z);
        float dc = fmax(r.z, r.x);
        float cut = (fmin(fmin(da, db), dc) - 1.0f) / s;
        d = fmax(d, cut);
        trap = fmin(trap, dot(a, a) * 0.5f);
    }
    return (float2)(d, trap);
}
";

const DE_SIERPINSKI: &str = "\
float2 de_sierpinski(float3 p, int levels) {
    float3 z = p;
    float trap = 1.0f;
    for (int i = 0; i < levels; i++) {
        if (z.x + z.y < 0.0f) {
            z = (float3)(-z.y, -z.x, z.z);
        }
        if (z.x + z.z < 0.0f) {
            z = (float3)(-z.z, z.y, -z.x);
        }
        if (z.y + z.z < 0.0f) {
            z = (float3)(z.x, -z.z, -z.y);
        }
        z = z * 2.0f - 1.0f;
        trap = fmin(trap, dot(z, z) * 0.25f);
    }
    float face = fmax(fmax(-z.x - z.y - z.z, z.x + z.y - z.z), fmax(-z.x + z.y + z.z, z.x - z.y + z.z));
    return (float2)((face - 1.0f) * 0.57735026f * pown(0.5f, levels), trap);
}
";

const DE_JULIA: &str = "\
float2 de_julia(float3 p, float4 c, int iterations, float bailout) {
    float4 z = (float4)(p, 0.0f);
    float4 dz = (float4)(1.0f, 0.0f, 0.0f, 0.0f);
    float m = dot(z, z);
    float trap = m;
    float escape2 = bailout * bailout;
    for (int i = 0; i < iterations; i++) {
        if (m > escape2 || dot(dz, dz) > 1e17f) {
            break;
        }
        dz = 2.0f * (float4)(
            z.x * dz.x - z.y * dz.y - z.z * dz.z - z.w * dz.w,
            z.x * dz.y + z.y * dz.x + z.z * dz.w - z.w * dz.z,
            z.x * dz.z + z.z * dz.x + z.w * dz.y - z.y * dz.w,
            z.x * dz.w + z.w * dz.x + z.y * dz.z - z.z * dz.y);
        z = (float4)(
            z.x * z.x - z.y * z.y - z.z * z.z - z.w * z.w + c.x,
            2.0f * z.x * z.y + c.y,
            2.0f * z.x * z.z + c.z,
            2.0f * z.x * z.w + c.w);
        m = dot(z, z);
        trap = fmin(trap, m);
    }
    return (float2)(0.25f * log(fmax(m, 1e-30f)) * sqrt(m / fmax(dot(dz, dz), 1e-30f)), fmin(trap, 1.0f));
}
";

const DE_MANDELBOX: &str = "\
float2 de_mandelbox(float3 p, float scale, int iterations, float min_radius, float fold_limit) {
    float3 z = p;
    float dr = 1.0f;
    float min_r2 = min_radius * min_radius;
    float trap = 1.0f;
    for (int i = 0; i < iterations; i++) {
        z = clamp(z, -fold_limit, fold_limit) * 2.0f - z;
        float r2 = dot(z, z);
        if (r2 < min_r2) {
            float f = 1.0f / min_r2;
            z = z * f;
            dr = dr * f;
        } else if (r2 < 1.0f) {
            float f = 1.0f / r2;
            z = z * f;
            dr = dr * f;
        }
        z = z * scale + p;
        dr = dr * fabs(scale) + 1.0f;
        trap = fmin(trap, r2);
    }
    return (float2)(length(z) / fabs(dr), trap);
}
";
