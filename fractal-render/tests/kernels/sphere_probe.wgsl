// Test fixture (hand-written, not generated): a `probe` entry for a sphere whose radius is param 0
// (layout: 1 light, 1 param), with the default surface material.
struct Frame {
    camera: array<vec4<f32>, 5>,
    lights: array<vec4<f32>, 2>,
    params: array<vec4<f32>, 1>,
}

@group(0) @binding(0) var<storage, read_write> probe_out: array<vec4<f32>>;
@group(0) @binding(1) var<uniform> frame: Frame;
@group(0) @binding(2) var<storage, read> points: array<vec4<f32>>;

@compute @workgroup_size(64)
fn probe(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= arrayLength(&points)) { return; }
    let d = length(points[i].xyz) - frame.params[0].x;
    probe_out[2u * i] = vec4<f32>(d, 0.15, 0.85, 0.0);
    probe_out[2u * i + 1u] = vec4<f32>(0.95, 0.75, 0.55, 32.0);
}
