// Test fixture (hand-written, not generated): the Mandelbulb sphere tracer of the hand-written baseline, reading the
// camera, image size and key light from the frame uniform (layout: 1 light, 0 params) like a generated `render`.
const MAX_STEPS: i32 = 128;
const ITERS: i32 = 8;
const POWER: f32 = 8.0;
const EPS: f32 = 0.0005;
const TMAX: f32 = 6.0;

struct Frame {
    camera_position: vec4<f32>,
    camera_right: vec4<f32>,
    camera_up: vec4<f32>,
    camera_forward: vec4<f32>,
    lights: array<vec4<f32>, 2>,
}

@group(0) @binding(0) var<storage, read_write> out_px: array<u32>;
@group(0) @binding(1) var<uniform> frame: Frame;

fn de(p: vec3<f32>) -> f32 {
    var z = p;
    var dr = 1.0;
    var r = 0.0;
    for (var i = 0; i < ITERS; i++) {
        r = length(z);
        if (r > 2.0) { break; }
        var theta = acos(z.z / r);
        var phi = atan2(z.y, z.x);
        dr = pow(r, POWER - 1.0) * POWER * dr + 1.0;
        let zr = pow(r, POWER);
        theta = theta * POWER;
        phi = phi * POWER;
        z = zr * vec3<f32>(sin(theta) * cos(phi), sin(phi) * sin(theta), cos(theta)) + p;
    }
    return 0.5 * log(r) * r / dr;
}

@compute @workgroup_size(8, 8, 1)
fn render(@builtin(global_invocation_id) gid: vec3<u32>) {
    let w = u32(frame.camera_right.w);
    let h = u32(frame.camera_up.w);
    if (gid.x >= w || gid.y >= h) { return; }
    let u = (2.0 * (f32(gid.x) + 0.5) - f32(w)) / f32(h);
    let v = -(2.0 * (f32(gid.y) + 0.5) - f32(h)) / f32(h);
    let ro = frame.camera_position.xyz;
    let rd = normalize(frame.camera_forward.xyz + u * frame.camera_right.xyz + v * frame.camera_up.xyz);

    var t = 0.0;
    var steps = 0;
    var hit = false;
    for (steps = 0; steps < MAX_STEPS; steps++) {
        let d = de(ro + rd * t);
        if (d < EPS) { hit = true; break; }
        t += d;
        if (t > TMAX) { break; }
    }
    var col = vec3<f32>(0.08, 0.09, 0.12) + 0.08 * v;
    if (hit) {
        let p = ro + rd * t;
        let e = 0.0005;
        let k0 = vec3<f32>(1.0, -1.0, -1.0);
        let k1 = vec3<f32>(-1.0, -1.0, 1.0);
        let k2 = vec3<f32>(-1.0, 1.0, -1.0);
        let k3 = vec3<f32>(1.0, 1.0, 1.0);
        let n = normalize(k0 * de(p + k0 * e) + k1 * de(p + k1 * e) + k2 * de(p + k2 * e) + k3 * de(p + k3 * e));
        let l = frame.lights[0].xyz;
        let diff = max(dot(n, l), 0.0);
        let ao = 1.0 - f32(steps) / f32(MAX_STEPS);
        col = vec3<f32>(0.95, 0.75, 0.55) * (0.15 + 0.85 * diff) * ao * frame.lights[1].xyz;
    }
    col = sqrt(clamp(col, vec3<f32>(0.0), vec3<f32>(1.0)));
    let c = vec3<u32>(col * 255.0 + 0.5);
    out_px[gid.y * w + gid.x] = c.x | (c.y << 8u) | (c.z << 16u) | (255u << 24u);
}
