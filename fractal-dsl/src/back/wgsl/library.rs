//! The WGSL spelling of each leaf function ([`Helper`]): the formulas of [`crate::sdf`] in `f32`, `vec2<f32>`,
//! `vec3<f32>` and `vec4<f32>`, operation for operation, with the same guards and constants (`TINY` = 1e-30,
//! `DR_MAX` = 1e17, `POW_LOG2_MAX` = 60). Escape-time fractals return `vec2<f32>(distance, trap)`; counts are `i32`.
//!
//! Each text is one function ending in a newline; a kernel holds the helpers it uses and their dependencies
//! ([`crate::back::with_dependencies`]) in [`Helper`] order. WGSL's `%` truncates, so the floored modulo of
//! [`crate::math::fmod_floor`] is spelled out.
//!
//! One deliberate respelling: `de_mandelbulb` takes acos(c) as atan2(√(1 − c²), c), the same function of c. Vulkan
//! only promises acos the accuracy of that very expression, and lavapipe's acos misses it by far (absolute error
//! 1.6e-4 against 3e-6 for its atan2), which moved Mandelbulb distances by 1.3e-4 instead of 2e-6.

use crate::back::{with_dependencies, Helper};

/// The WGSL definition of `helper`.
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
fn sd_sphere(p: vec3<f32>, r: f32) -> f32 {
    return length(p) - r;
}
";

const SD_BOX: &str = "\
fn sd_box(p: vec3<f32>, b: vec3<f32>) -> f32 {
    let q = abs(p) - b;
    return length(max(q, vec3<f32>(0.0))) + min(max(max(q.x, q.y), q.z), 0.0);
}
";

const SD_ROUND_BOX: &str = "\
fn sd_round_box(p: vec3<f32>, b: vec3<f32>, r: f32) -> f32 {
    return sd_box(p, b - vec3<f32>(r)) - r;
}
";

const SD_TORUS: &str = "\
fn sd_torus(p: vec3<f32>, major: f32, minor: f32) -> f32 {
    let qx = sqrt(p.x * p.x + p.z * p.z) - major;
    return sqrt(qx * qx + p.y * p.y) - minor;
}
";

const SD_CAPSULE: &str = "\
fn sd_capsule(p: vec3<f32>, a: vec3<f32>, b: vec3<f32>, r: f32) -> f32 {
    let pa = p - a;
    let ba = b - a;
    let h = clamp(dot(pa, ba) / max(dot(ba, ba), 1e-30), 0.0, 1.0);
    return length(pa - ba * h) - r;
}
";

const SD_CYLINDER: &str = "\
fn sd_cylinder(p: vec3<f32>, r: f32, h: f32) -> f32 {
    let dx = sqrt(p.x * p.x + p.z * p.z) - r;
    let dy = abs(p.y) - h;
    let ox = max(dx, 0.0);
    let oy = max(dy, 0.0);
    return min(max(dx, dy), 0.0) + sqrt(ox * ox + oy * oy);
}
";

const SD_CONE: &str = "\
fn sd_cone(p: vec3<f32>, h: f32, r1: f32, r2: f32) -> f32 {
    let qx = sqrt(p.x * p.x + p.z * p.z);
    let qy = p.y;
    let k2x = r2 - r1;
    let k2y = h + h;
    let cax = qx - min(qx, select(r2, r1, qy < 0.0));
    let cay = abs(qy) - h;
    let t = clamp(((r2 - qx) * k2x + (h - qy) * k2y) / (k2x * k2x + k2y * k2y), 0.0, 1.0);
    let cbx = qx - r2 + k2x * t;
    let cby = qy - h + k2y * t;
    let s = select(1.0, -1.0, cbx < 0.0 && cay < 0.0);
    return s * sqrt(min(cax * cax + cay * cay, cbx * cbx + cby * cby));
}
";

const SD_PLANE: &str = "\
fn sd_plane(p: vec3<f32>, n: vec3<f32>, offset: f32) -> f32 {
    return dot(p, n) + offset;
}
";

const SD_OCTAHEDRON: &str = "\
fn sd_octahedron(p: vec3<f32>, s: f32) -> f32 {
    let a = abs(p);
    let m = a.x + a.y + a.z - s;
    var q: vec3<f32>;
    if 3.0 * a.x < m {
        q = a;
    } else if 3.0 * a.y < m {
        q = vec3<f32>(a.y, a.z, a.x);
    } else if 3.0 * a.z < m {
        q = vec3<f32>(a.z, a.x, a.y);
    } else {
        return m * 0.57735026;
    }
    let k = clamp(0.5 * (q.z - q.y + s), 0.0, s);
    return length(vec3<f32>(q.x, q.y - s + k, q.z - k));
}
";

const SD_ELLIPSOID: &str = "\
fn sd_ellipsoid(p: vec3<f32>, r: vec3<f32>) -> f32 {
    let k0 = length(vec3<f32>(p.x / r.x, p.y / r.y, p.z / r.z));
    let k1 = length(vec3<f32>(p.x / (r.x * r.x), p.y / (r.y * r.y), p.z / (r.z * r.z)));
    if k1 > 0.0 {
        return k0 * (k0 - 1.0) / k1;
    }
    return -min(min(r.x, r.y), r.z);
}
";

const SMOOTH_MIN: &str = "\
fn smooth_min(a: f32, b: f32, k: f32) -> f32 {
    let h = max(k - abs(a - b), 0.0) / max(k, 1e-30);
    return min(a, b) - h * h * k * 0.25;
}
";

const SMOOTH_MAX: &str = "\
fn smooth_max(a: f32, b: f32, k: f32) -> f32 {
    return -smooth_min(-a, -b, k);
}
";

const BLEND_WEIGHT: &str = "\
fn blend_weight(a: f32, b: f32, k: f32) -> f32 {
    return clamp(0.5 + 0.5 * (a - b) / max(k, 1e-30), 0.0, 1.0);
}
";

const DE_MANDELBULB: &str = "\
fn de_mandelbulb(p: vec3<f32>, power: f32, iterations: i32, bailout: f32) -> vec2<f32> {
    let escape = min(bailout, exp2(60.0 / power));
    var z = p;
    var dr = 1.0;
    var r = length(z);
    var trap = r;
    for (var i = 0; i < iterations; i++) {
        if r > escape || dr > 1e17 {
            break;
        }
        let cos_theta = clamp(z.z / max(r, 1e-30), -1.0, 1.0);
        let theta = atan2(sqrt(1.0 - cos_theta * cos_theta), cos_theta) * power;
        let phi = atan2(z.y, z.x) * power;
        dr = power * pow(r, power - 1.0) * dr + 1.0;
        let zr = pow(r, power);
        let st = sin(theta);
        let ct = cos(theta);
        let sp = sin(phi);
        let cp = cos(phi);
        z = vec3<f32>(st * cp, sp * st, ct) * zr + p;
        r = length(z);
        trap = min(trap, r);
    }
    return vec2<f32>(0.5 * log(max(r, 1e-30)) * r / dr, min(trap, 1.0));
}
";

const DE_MANDELBULB8: &str = "\
fn de_mandelbulb8(p: vec3<f32>, iterations: i32, bailout: f32) -> vec2<f32> {
    let escape = min(bailout, exp2(60.0 / 8.0));
    var z = p;
    var dr = 1.0;
    var r = length(z);
    var trap = r;
    for (var i = 0; i < iterations; i++) {
        if r > escape || dr > 1e17 {
            break;
        }
        let x2 = z.x * z.x;
        let y2 = z.y * z.y;
        let a = z.z * z.z;
        let b = x2 + y2;
        let r2 = a + b;
        dr = 8.0 * r2 * r2 * r2 * r * dr + 1.0;
        let a2 = a * a;
        let b2 = b * b;
        let cos_part = a2 * a2 - 28.0 * a2 * a * b + 70.0 * a2 * b2 - 28.0 * a * b2 * b + b2 * b2;
        let sin_part = 8.0 * z.z * (a2 * a - 7.0 * a2 * b + 7.0 * a * b2 - b2 * b);
        let inv_rho = select(0.0, 1.0 / sqrt(b), b > 1e-30);
        let ux = z.x * inv_rho;
        let uy = z.y * inv_rho;
        let u2x = ux * ux - uy * uy;
        let u2y = 2.0 * ux * uy;
        let u4x = u2x * u2x - u2y * u2y;
        let u4y = 2.0 * u2x * u2y;
        let u8x = u4x * u4x - u4y * u4y;
        let u8y = 2.0 * u4x * u4y;
        let rho_sin = b * inv_rho * sin_part;
        z = vec3<f32>(rho_sin * u8x, rho_sin * u8y, cos_part) + p;
        r = length(z);
        trap = min(trap, r);
    }
    return vec2<f32>(0.5 * log(max(r, 1e-30)) * r / dr, min(trap, 1.0));
}
";

const DE_MENGER: &str = "\
fn de_menger(p: vec3<f32>, levels: i32) -> vec2<f32> {
    var d = sd_box(p, vec3<f32>(1.0));
    var s = 1.0;
    var trap = 1.0;
    for (var i = 0; i < levels; i++) {
        let ps = p * s;
        let a = ps - 2.0 * floor(ps / 2.0) - 1.0;
        s = s * 3.0;
        let r = abs(1.0 - 3.0 * abs(a));
        let da = max(r.x, r.y);
        let db = max(r.y, r.z);
        let dc = max(r.z, r.x);
        let cut = (min(min(da, db), dc) - 1.0) / s;
        d = max(d, cut);
        trap = min(trap, dot(a, a) * 0.5);
    }
    return vec2<f32>(d, trap);
}
";

const DE_SIERPINSKI: &str = "\
fn de_sierpinski(p: vec3<f32>, levels: i32) -> vec2<f32> {
    var z = p;
    var trap = 1.0;
    for (var i = 0; i < levels; i++) {
        if z.x + z.y < 0.0 {
            z = vec3<f32>(-z.y, -z.x, z.z);
        }
        if z.x + z.z < 0.0 {
            z = vec3<f32>(-z.z, z.y, -z.x);
        }
        if z.y + z.z < 0.0 {
            z = vec3<f32>(z.x, -z.z, -z.y);
        }
        z = z * 2.0 - 1.0;
        trap = min(trap, dot(z, z) * 0.25);
    }
    let face = max(max(-z.x - z.y - z.z, z.x + z.y - z.z), max(-z.x + z.y + z.z, z.x - z.y + z.z));
    return vec2<f32>((face - 1.0) * 0.57735026 * pow(0.5, f32(levels)), trap);
}
";

const DE_JULIA: &str = "\
fn de_julia(p: vec3<f32>, c: vec4<f32>, iterations: i32, bailout: f32) -> vec2<f32> {
    var z = vec4<f32>(p, 0.0);
    var dz = vec4<f32>(1.0, 0.0, 0.0, 0.0);
    var m = dot(z, z);
    var trap = m;
    let escape2 = bailout * bailout;
    for (var i = 0; i < iterations; i++) {
        if m > escape2 || dot(dz, dz) > 1e17 {
            break;
        }
        dz = 2.0 * vec4<f32>(
            z.x * dz.x - z.y * dz.y - z.z * dz.z - z.w * dz.w,
            z.x * dz.y + z.y * dz.x + z.z * dz.w - z.w * dz.z,
            z.x * dz.z + z.z * dz.x + z.w * dz.y - z.y * dz.w,
            z.x * dz.w + z.w * dz.x + z.y * dz.z - z.z * dz.y,
        );
        z = vec4<f32>(
            z.x * z.x - z.y * z.y - z.z * z.z - z.w * z.w + c.x,
            2.0 * z.x * z.y + c.y,
            2.0 * z.x * z.z + c.z,
            2.0 * z.x * z.w + c.w,
        );
        m = dot(z, z);
        trap = min(trap, m);
    }
    return vec2<f32>(0.25 * log(max(m, 1e-30)) * sqrt(m / max(dot(dz, dz), 1e-30)), min(trap, 1.0));
}
";

const DE_MANDELBOX: &str = "\
fn de_mandelbox(p: vec3<f32>, scale: f32, iterations: i32, min_radius: f32, fold_limit: f32) -> vec2<f32> {
    var z = p;
    var dr = 1.0;
    let min_r2 = min_radius * min_radius;
    var trap = 1.0;
    for (var i = 0; i < iterations; i++) {
        z = clamp(z, vec3<f32>(-fold_limit), vec3<f32>(fold_limit)) * 2.0 - z;
        let r2 = dot(z, z);
        if r2 < min_r2 {
            let f = 1.0 / min_r2;
            z = z * f;
            dr = dr * f;
        } else if r2 < 1.0 {
            let f = 1.0 / r2;
            z = z * f;
            dr = dr * f;
        }
        z = z * scale + p;
        dr = dr * abs(scale) + 1.0;
        trap = min(trap, r2);
    }
    return vec2<f32>(length(z) / abs(dr), trap);
}
";
