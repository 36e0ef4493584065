// Test fixture (hand-written, not generated): the Mandelbulb sphere tracer of the hand-written baseline, reading the
// camera, image size and key light from the frame uniform (layout: 1 light, 0 params) like a generated `render`.
#define MAX_STEPS 128
#define ITERS 8
#define POWER 8.0f
#define EPS 0.0005f
#define TMAX 6.0f

typedef struct {
    float4 camera_position;
    float4 camera_right;
    float4 camera_up;
    float4 camera_forward;
    float4 lights[2];
} Frame;

float de(float3 p) {
    float3 z = p;
    float dr = 1.0f;
    float r = 0.0f;
    for (int i = 0; i < ITERS; i++) {
        r = length(z);
        if (r > 2.0f) break;
        float theta = acos(z.z / r);
        float phi = atan2(z.y, z.x);
        dr = pow(r, POWER - 1.0f) * POWER * dr + 1.0f;
        float zr = pow(r, POWER);
        theta *= POWER;
        phi *= POWER;
        z = zr * (float3)(sin(theta) * cos(phi), sin(phi) * sin(theta), cos(theta)) + p;
    }
    return 0.5f * log(r) * r / dr;
}

__kernel void render(__global uint* out, __constant Frame* frame) {
    int x = get_global_id(0);
    int y = get_global_id(1);
    int w = (int)frame->camera_right.w;
    int h = (int)frame->camera_up.w;
    if (x >= w || y >= h) return;
    float u = (2.0f * ((float)x + 0.5f) - (float)w) / (float)h;
    float v = -(2.0f * ((float)y + 0.5f) - (float)h) / (float)h;
    float3 ro = frame->camera_position.xyz;
    float3 rd = normalize(frame->camera_forward.xyz + u * frame->camera_right.xyz + v * frame->camera_up.xyz);

    float t = 0.0f;
    int steps = 0;
    int hit = 0;
    for (steps = 0; steps < MAX_STEPS; steps++) {
        float d = de(ro + rd * t);
        if (d < EPS) { hit = 1; break; }
        t += d;
        if (t > TMAX) break;
    }
    float3 col = (float3)(0.08f, 0.09f, 0.12f) + 0.08f * v;
    if (hit) {
        float3 p = ro + rd * t;
        const float e = 0.0005f;
        float3 k0 = (float3)( 1.0f, -1.0f, -1.0f);
        float3 k1 = (float3)(-1.0f, -1.0f,  1.0f);
        float3 k2 = (float3)(-1.0f,  1.0f, -1.0f);
        float3 k3 = (float3)( 1.0f,  1.0f,  1.0f);
        float3 n = normalize(k0 * de(p + k0 * e) + k1 * de(p + k1 * e) + k2 * de(p + k2 * e) + k3 * de(p + k3 * e));
        float3 l = frame->lights[0].xyz;
        float diff = fmax(dot(n, l), 0.0f);
        float ao = 1.0f - (float)steps / (float)MAX_STEPS;
        col = (float3)(0.95f, 0.75f, 0.55f) * (0.15f + 0.85f * diff) * ao * frame->lights[1].xyz;
    }
    col = sqrt(clamp(col, 0.0f, 1.0f));
    uint r = (uint)(col.x * 255.0f + 0.5f);
    uint g = (uint)(col.y * 255.0f + 0.5f);
    uint b = (uint)(col.z * 255.0f + 0.5f);
    out[y * w + x] = r | (g << 8) | (b << 16) | (255u << 24);
}
