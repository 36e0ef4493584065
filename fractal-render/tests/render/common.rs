//! What the renderer's tests share: fixture kernels, frames for them, and the rule for backends
//! that are missing (skip with a note, or fail when FRACTAL_REQUIRE_GPU_BACKENDS=1).

use std::path::Path;

use fractal_dsl::builder::{mandelbulb, param, scene, sphere};
use fractal_dsl::Scene;
pub use fractal_render::device::backends_required;
use fractal_render::{Frame, Image, ParamValues, Pose, RenderError};

/// The opened backend, or `None` with a printed note when it is missing and not required.
pub fn available<T>(backend: &str, opened: Result<T, RenderError>) -> Option<T> {
    match opened {
        Ok(renderer) => Some(renderer),
        Err(e) if backends_required() => {
            panic!("{backend} is required (FRACTAL_REQUIRE_GPU_BACKENDS=1) but could not be opened: {e}")
        }
        Err(e) => {
            eprintln!("note: skipping {backend} test, backend unavailable: {e}");
            None
        }
    }
}

/// A hand-written test kernel from `tests/kernels`.
pub fn fixture(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/kernels").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("reading {}: {e}", path.display()))
}

/// The hand-written baseline's Mandelbulb tracer (`fractal-runtime/baseline/`, the kernel `fractal bench --baseline`
/// times) made a fixture: its formulas as they are, its entry point reading the image size, the camera and the key
/// light from the frame uniform (layout: 1 light, 0 params) as a generated `render` does. Each replaced line must be
/// found, so a change to the baseline that this does not follow fails here rather than testing something else.
pub fn mandelbulb_fixture(language: &str) -> String {
    let baseline =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../fractal-runtime/baseline/mandelbulb").with_extension(language);
    let mut text = std::fs::read_to_string(&baseline).unwrap_or_else(|e| panic!("reading {}: {e}", baseline.display()));
    let replacements: &[(&str, &str)] = match language {
        "wgsl" => &[
            (
                "struct Params { w: u32, h: u32 }",
                "struct Frame {\n    camera_position: vec4<f32>,\n    camera_right: vec4<f32>,\n    camera_up: vec4<f32>,\n    \
                 camera_forward: vec4<f32>,\n    camera_anchor: vec4<f32>,\n    lights: array<vec4<f32>, 2>,\n}",
            ),
            ("var<uniform> params: Params;", "var<uniform> frame: Frame;"),
            ("fn main(", "fn render("),
            ("let w = params.w;", "let w = u32(frame.camera_right.w);"),
            ("let h = params.h;", "let h = u32(frame.camera_up.w);"),
            ("let ro = vec3<f32>(1.2, 1.0, -2.2);", "let ro = frame.camera_position.xyz;"),
            ("let ww = normalize(-ro);", ""),
            ("let uu = normalize(cross(vec3<f32>(0.0, 1.0, 0.0), ww));", ""),
            ("let vv = cross(ww, uu);", ""),
            (
                "let rd = normalize(u * uu + v * vv + 1.8 * ww);",
                "let rd = normalize(frame.camera_forward.xyz + u * frame.camera_right.xyz + v * frame.camera_up.xyz);",
            ),
            ("let l = normalize(vec3<f32>(0.6, 0.8, -0.4));", "let l = frame.lights[0].xyz;"),
            ("* (0.15 + 0.85 * diff) * ao;", "* (0.15 + 0.85 * diff) * ao * frame.lights[1].xyz;"),
        ],
        "cl" => &[
            (
                "__kernel void render(__global uint* out, int w, int h) {",
                "typedef struct {\n    float4 camera_position;\n    float4 camera_right;\n    float4 camera_up;\n    \
                 float4 camera_forward;\n    float4 camera_anchor;\n    float4 lights[2];\n} Frame;\n\n\
                 __kernel void render(__global uint* out, __constant Frame* frame) {\n    \
                 int w = (int)frame->camera_right.w;\n    int h = (int)frame->camera_up.w;",
            ),
            ("float3 ro = (float3)(1.2f, 1.0f, -2.2f);", "float3 ro = frame->camera_position.xyz;"),
            ("float3 ww = normalize(-ro);", ""),
            ("float3 uu = normalize(cross((float3)(0.0f, 1.0f, 0.0f), ww));", ""),
            ("float3 vv = cross(ww, uu);", ""),
            (
                "float3 rd = normalize(u * uu + v * vv + 1.8f * ww);",
                "float3 rd = normalize(frame->camera_forward.xyz + u * frame->camera_right.xyz + v * frame->camera_up.xyz);",
            ),
            ("float3 l = normalize((float3)(0.6f, 0.8f, -0.4f));", "float3 l = frame->lights[0].xyz;"),
            ("* (0.15f + 0.85f * diff) * ao;", "* (0.15f + 0.85f * diff) * ao * frame->lights[1].xyz;"),
        ],
        other => panic!("no baseline in {other}"),
    };
    for (from, to) in replacements {
        assert_eq!(text.matches(from).count(), 1, "`{from}` is not once in {}", baseline.display());
        text = text.replace(from, to);
    }
    text
}

/// The scene the Mandelbulb fixture kernels draw (their frame layout: 1 light, 0 params), with the default camera.
pub fn mandelbulb_scene() -> Scene {
    scene(mandelbulb(8))
}

/// A frame of the scene's camera at t = 0 with these parameter values.
fn frame_for(s: &Scene, width: u32, height: u32, params: &ParamValues) -> Frame {
    let pose = Pose::from_camera(&s.camera, 0.0, &|p| params.lookup(p)).expect("camera");
    Frame::new(s, &pose, 0.0, width, height, params).expect("frame")
}

pub fn mandelbulb_frame(width: u32, height: u32) -> Frame {
    let s = mandelbulb_scene();
    Frame::default_view(&s, 0.0, width, height).expect("frame")
}

/// The scene the sphere probe fixtures evaluate: a sphere whose radius is param 0.
pub fn sphere_probe_scene() -> Scene {
    scene(sphere(param("radius", 1.0, 0.1..2.0)))
}

/// A frame for the sphere probe with the given radius.
pub fn sphere_probe_frame(radius: f64) -> Frame {
    let s = sphere_probe_scene();
    let params = ParamValues::from_values(&s, &[radius]).expect("radius in range");
    frame_for(&s, 8, 8, &params)
}

/// Points spread over and around a sphere of radius ~1, more than two workgroups of 64 so partial groups run too.
pub fn probe_points() -> Vec<[f32; 4]> {
    (0..150)
        .map(|i| {
            let i = i as f32;
            let r = 0.1 + 0.023 * i;
            let (theta, phi) = (0.37 * i, 0.91 * i);
            [r * theta.sin() * phi.cos(), r * theta.sin() * phi.sin(), r * theta.cos(), 0.0]
        })
        .collect()
}

/// The analytic sphere distance in f64.
pub fn sphere_distance(p: [f32; 4], radius: f64) -> f64 {
    let [x, y, z, _] = p.map(f64::from);
    (x * x + y * y + z * z).sqrt() - radius
}

/// Checks probe output of the sphere fixture: distances within f32 rounding, the default surface material.
pub fn check_sphere_probe(samples: &[[f32; 8]], points: &[[f32; 4]], radius: f64) {
    assert_eq!(samples.len(), points.len());
    for (s, p) in samples.iter().zip(points) {
        let want = sphere_distance(*p, radius);
        assert!((s[0] as f64 - want).abs() < 1e-5, "distance at {p:?}: got {}, want {want}", s[0]);
        assert_eq!(&s[1..], &[0.15, 0.85, 0.0, 0.95, 0.75, 0.55, 32.0], "material at {p:?}");
    }
}

/// Fraction of pixels whose channels differ by more than `tolerance` levels.
pub fn fraction_different(a: &Image, b: &Image, tolerance: u8) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let differing = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(x, y)| x.to_le_bytes().iter().zip(y.to_le_bytes()).any(|(p, q)| p.abs_diff(q) > tolerance))
        .count();
    differing as f64 / a.pixels.len() as f64
}
