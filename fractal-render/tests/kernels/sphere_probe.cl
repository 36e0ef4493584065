// Test fixture (hand-written, not generated): a `probe` kernel for a sphere whose radius is param 0
// (layout: 1 light, 1 param), with the default surface material.
typedef struct {
    float4 camera[5];
    float4 lights[2];
    float4 params[1];
} Frame;

__kernel void probe(__global const float4* points, __global float4* out, __constant Frame* frame, uint n) {
    uint i = get_global_id(0);
    if (i >= n) return;
    float d = length(points[i].xyz) - frame->params[0].x;
    out[2 * i] = (float4)(d, 0.15f, 0.85f, 0.0f);
    out[2 * i + 1] = (float4)(0.95f, 0.75f, 0.55f, 32.0f);
}
