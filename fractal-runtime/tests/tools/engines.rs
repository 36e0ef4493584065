//! Engine packages of every built-in scene, each checked by the nearest thing to its engine this machine has:
//! - WGSL (plain and Bevy): the library validates with naga; Bevy's material validates with its imports replaced by
//!   what they name (Bevy itself runs it in `tests/engines/bevy`); the library runs on wgpu and agrees with the
//!   scene's own probe kernel.
//! - GLSL (plain, Godot, Shadertoy): glslang, as GLSL 4.50 and GLSL ES 3.00 behind a thin wrapper that calls every
//!   function; Godot's files after removing its own syntax (`hint_range`, `shader_type`, built-ins as uniforms).
//!   Godot itself is not run: its shading language's own rules stay unchecked.
//! - HLSL (plain, Unity, Unreal): glslang's HLSL front end (DXC is not packaged for Debian), with stand-ins for the
//!   few Unity and Unreal symbols the materials read.
//!
//! External validators are skipped with a note when missing, unless FRACTAL_REQUIRE_GPU_BACKENDS=1.

use std::path::PathBuf;

use fractal_dsl::back::{wgsl, Entry};
use fractal_render::{Frame, KernelSources, RenderJob, Renderer, WgpuRenderer};
use fractal_runtime::package::{package, Engine, Package};

use crate::common::{available, run_validator, tool_available};

fn packaged(name: &str, scene: &fractal_dsl::Scene, engine: Engine) -> Package {
    package(scene, name, engine).unwrap_or_else(|e| panic!("{name} for {engine}: {e}"))
}

fn file<'a>(p: &'a Package, name: &str) -> &'a str {
    p.file(name).unwrap_or_else(|| {
        let names: Vec<&str> = p.files.iter().map(|f| f.name.as_str()).collect();
        panic!("{} package has no {name} (it has {names:?})", p.engine)
    })
}

/// Writes `text` to a file of this process (concurrent runs cannot overwrite each other's files).
fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("engines-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create the directory");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write the file");
    path
}

fn validate_wgsl(label: &str, module: &naga::Module, source: &str) {
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
        .validate(module)
        .unwrap_or_else(|e| panic!("{label}: {}\n{source}", e.emit_to_string(source)));
}

#[test]
fn every_scene_packages_for_every_engine_with_the_whole_library() {
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        for engine in Engine::ALL {
            let p = packaged(name, scene, engine);
            let library = &p.files[0].contents;
            for function in ["sdf(", "sdf_normal(", "sdf_material(", "sdf_raymarch(", "SDF_BOUND_RADIUS"] {
                assert!(library.contains(function), "{name} for {engine}: the library lacks {function}");
            }
            // Parameters are the engine's: never the render kernel's frame.
            assert!(!library.contains("frame"), "{name} for {engine}: the library reads a frame");
            for param in scene.params() {
                let ident = param.name.to_ascii_lowercase();
                assert!(library.contains(&ident), "{name} for {engine}: parameter {} is not declared", param.name);
            }
            if engine != Engine::Shadertoy {
                assert!(p.file("README.md").is_some(), "{name} for {engine}: no README");
            }
        }
    }
}

/// Only what the scene needs: a sphere's library has no fractal, noise or shadow code.
#[test]
fn a_sphere_library_holds_only_the_sphere() {
    let scene = fractal_dsl::parse::parse_str("scene(sphere(1.0)).no_shadows()").expect("scene");
    let library = &packaged("ball", &scene, Engine::Glsl).files[0].contents;
    for absent in ["mandelbulb", "noise", "scene_shadow", "scene_ao", "menger"] {
        assert!(!library.contains(absent), "a sphere's library contains {absent}:\n{library}");
    }
}

/// The Bevy material with its WESL imports replaced by what they name: `VertexOutput` and `view` as Bevy 0.20.1
/// declares them (the fields the material reads), the scene's module inlined, `constants::MATERIAL_BIND_GROUP` as
/// Bevy sets it (3). Bevy itself composes it in `tests/engines/bevy` (its own command: it needs Bevy's toolchain).
fn bevy_material_as_wgsl(material: &str, module: &str, name: &str) -> String {
    const BEVY: &str = "struct VertexOutput {\n    @builtin(position) position: vec4<f32>,\n    @location(0) world_position: vec4<f32>,\n    @location(1) world_normal: vec3<f32>,\n}\n\n\
        struct View {\n    clip_from_world: mat4x4<f32>,\n    clip_from_view: mat4x4<f32>,\n    world_position: vec3<f32>,\n    viewport: vec4<f32>,\n}\n\n\
        @group(0) @binding(0) var<uniform> view: View;\n";
    let imports = [
        "import bevy_pbr::render::forward_io::VertexOutput;\n".to_string(),
        "import bevy_pbr::render::mesh_view_bindings::view;\n".to_string(),
        format!("import super::{name} as scene;\n"),
    ];
    let mut body = material.to_string();
    for import in &imports {
        assert!(body.contains(import.as_str()), "{name}: the Bevy material lacks `{}`", import.trim());
        body = body.replace(import.as_str(), "");
    }
    let body = body.replace("constants::MATERIAL_BIND_GROUP", "3").replace("scene::", "");
    format!("{BEVY}{module}{body}")
}

#[test]
fn wgsl_libraries_and_bevy_materials_validate() {
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let plain = packaged(name, scene, Engine::Wgsl);
        let source = file(&plain, &format!("{name}.wgsl"));
        let module =
            naga::front::wgsl::parse_str(source).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
        validate_wgsl(name, &module, source);

        let bevy = packaged(name, scene, Engine::Bevy);
        let composed = bevy_material_as_wgsl(
            file(&bevy, &format!("{name}_material.wesl")),
            file(&bevy, &format!("{name}.wesl")),
            name,
        );
        let module = naga::front::wgsl::parse_str(&composed)
            .unwrap_or_else(|e| panic!("{name}: the Bevy material: {}", e.emit_to_string(&composed)));
        validate_wgsl(&format!("{name}: the Bevy material"), &module, &composed);
        let fragment = module.entry_points.iter().find(|e| e.name == "fragment");
        assert_eq!(fragment.map(|e| e.stage), Some(naga::ShaderStage::Fragment), "{name}: no fragment entry");
    }
}

/// The WGSL library's `sdf`, `sdf_material` and sample terms against the scene's own probe kernel, on the same
/// device at the same points (at the parameters' defaults, t = 0). Both are the same lowered code, with parameters
/// read from the library's globals instead of the frame ([`DISTANCE_ULPS`], [`COLOUR_DIFFERENCE`]); a scene with a
/// perturbed pattern differs in albedo only (the library iterates it plainly), so its albedo is not compared.
#[test]
fn the_wgsl_library_agrees_with_the_probe_kernel_on_wgpu() {
    let Some(mut gpu) = available("wgpu", WgpuRenderer::new()) else { return };
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let library = &packaged(name, scene, Engine::Wgsl).files[0].contents;
        let probe = format!(
            "{library}\n\
             struct ProbeFrame {{\n    origin: vec4<f32>,\n}}\n\n\
             @group(0) @binding(0) var<storage, read_write> probe_out: array<vec4<f32>>;\n\
             @group(0) @binding(1) var<uniform> frame: ProbeFrame;\n\
             @group(0) @binding(2) var<storage, read> points: array<vec4<f32>>;\n\n\
             @compute @workgroup_size(64, 1, 1)\n\
             fn probe(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
             \x20   sdf_params.time = frame.origin.w;\n\
             \x20   let i = gid.x;\n\
             \x20   if (i >= arrayLength(&points)) {{\n        return;\n    }}\n\
             \x20   let p = points[i].xyz;\n\
             \x20   let s = scene_sample(p);\n\
             \x20   probe_out[2u * i] = vec4<f32>(sdf(p), s.ambient, s.diffuse, s.specular);\n\
             \x20   probe_out[2u * i + 1u] = vec4<f32>(sdf_material(p), s.shininess);\n\
             }}\n"
        );
        let frame = Frame::default_view(scene, 0.0, 8, 8).expect("frame");
        let (min, max) = scene_box(scene);
        let points: Vec<[f32; 4]> = (0..256)
            .map(|i| {
                let u = |k: f64| (0.5 + 0.5 * (k * (i as f64 + 1.0)).sin()) as f32;
                let at = |axis: usize, k: f64| min[axis] + (max[axis] - min[axis]) * u(k);
                [at(0, 12.9898), at(1, 78.233), at(2, 37.719), 0.0]
            })
            .collect();
        let program = fractal_dsl::lower::lower(scene);
        let f32 = fractal_dsl::back::Scalar::F32;
        let got =
            gpu.probe((probe.as_str(), f32), &frame, &points).unwrap_or_else(|e| panic!("{name}: the library: {e}"));
        let kernel = wgsl::write(&program, Entry::Probe);
        let want = gpu.probe((kernel.as_str(), f32), &frame, &points).expect("the probe kernel");
        let perturbed = program.reference.is_some();
        let (mut worst_distance, mut worst_colour) = (0.0f64, 0.0f32);
        for (i, (g, w)) in got.iter().zip(&want).enumerate() {
            let size = points[i][..3].iter().fold(1.0f32, |m, c| m.max(c.abs()));
            let scale = f64::from(size.max(w[0].abs()));
            let ulps = f64::from((g[0] - w[0]).abs()) / (scale * UNIT_ROUNDOFF);
            worst_distance = worst_distance.max(ulps);
            assert!(
                ulps <= DISTANCE_ULPS,
                "{name}: point {i} {:?}: distance {} from the library, {} from the probe kernel ({ulps:.1} ulps of {scale})",
                points[i],
                g[0],
                w[0]
            );
            let terms = if perturbed { &[1, 2, 3, 7][..] } else { &[1, 2, 3, 4, 5, 6, 7][..] };
            for &k in terms {
                let difference = (g[k] - w[k]).abs();
                worst_colour = worst_colour.max(difference);
                assert!(
                    difference <= COLOUR_DIFFERENCE,
                    "{name}: point {i} {:?}, material term {k}: {} from the library, {} from the probe kernel",
                    points[i],
                    g[k],
                    w[k]
                );
            }
        }
        println!("{name}: library vs probe kernel: distance within {worst_distance:.2} ulps, material within {worst_colour:.1e}");
    }
}

/// The f32 unit roundoff, 2^-24.
const UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;
/// How far the library's distance may differ from the probe kernel's, in f32 roundoffs of max(1, |p|, |d|). The
/// arithmetic is the same; the driver's compiler may still contract or reorder the two programs differently.
const DISTANCE_ULPS: f64 = 16.0;
/// How far a material term may differ: a quarter of an 8-bit colour step. Orbit-trap colours are steep near the set,
/// so a last-bit difference in an orbit can move them by far more ulps than the distance.
const COLOUR_DIFFERENCE: f32 = 1e-3;

/// The box the probe points fill: the scene's bound grown by a quarter, or ±4 for an unbounded scene.
fn scene_box(scene: &fractal_dsl::Scene) -> ([f32; 3], [f32; 3]) {
    match fractal_dsl::lower::lower(scene).bound {
        Some(b) => {
            let grow = |i: usize| 0.25 * (b.max[i] - b.min[i]);
            (std::array::from_fn(|i| (b.min[i] - grow(i)) as f32), std::array::from_fn(|i| (b.max[i] + grow(i)) as f32))
        }
        None => ([-4.0; 3], [4.0; 3]),
    }
}

/// A GLSL fragment `main` that calls every library function, so the validator type-checks each.
const GLSL_MAIN: &str = "\nout vec4 validator_out;\n\nvoid main() {\n\
    \x20   vec4 hit = sdf_raymarch(vec3(0.0, 0.0, -3.0), vec3(0.0, 0.0, 1.0), 0.001);\n\
    \x20   validator_out = vec4(sdf_display(hit.rgb), hit.w) + vec4(sdf_normal(SDF_BOUND_CENTER), sdf(vec3(0.5)))\n\
    \x20       + vec4(sdf_material(vec3(0.1)), 0.0);\n}\n";

fn glslang(file_name: &str, text: &str, args: &[&str]) {
    let path = temp_file(file_name, text);
    run_validator("glslangValidator", args, &path);
    let _ = std::fs::remove_file(&path);
}

#[test]
fn glsl_libraries_pass_glslang_as_glsl_450_and_es_300() {
    if !tool_available("glslangValidator") {
        return;
    }
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let library = packaged(name, scene, Engine::Glsl).files[0].contents.clone();
        glslang(&format!("{name}.450.frag"), &format!("#version 450\n{library}{GLSL_MAIN}"), &[]);
        let es = format!("#version 300 es\nprecision highp float;\nprecision highp int;\n{library}{GLSL_MAIN}");
        glslang(&format!("{name}.es.frag"), &es, &[]);
    }
}

#[test]
fn shadertoy_packages_pass_glslang_with_the_shadertoy_prelude() {
    if !tool_available("glslangValidator") {
        return;
    }
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let p = packaged(name, scene, Engine::Shadertoy);
        let text = file(&p, &format!("{name}.glsl"));
        assert!(text.contains("void mainImage(out vec4 fragColor, in vec2 fragCoord)"), "{name}: no mainImage");
        let wrapped = format!(
            "#version 300 es\nprecision highp float;\nprecision highp int;\n\
             uniform vec3 iResolution;\nuniform float iTime;\nuniform vec4 iMouse;\nout vec4 shadertoy_out;\n\n{text}\n\
             void main() {{\n    mainImage(shadertoy_out, gl_FragCoord.xy);\n}}\n"
        );
        glslang(&format!("{name}.shadertoy.frag"), &wrapped, &[]);
    }
}

/// Godot's syntax that GLSL lacks, removed: `: hint_range(..)` after a uniform; `TIME` becomes a uniform.
fn godot_include_as_glsl(include: &str) -> String {
    let mut out = String::from("uniform float godot_time;\n#define TIME godot_time\n");
    for line in include.lines() {
        match (line.find(" : hint_range("), line.find(" = ")) {
            (Some(hint), Some(value)) if hint < value => {
                out.push_str(&line[..hint]);
                out.push_str(&line[value..]);
            }
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

#[test]
fn godot_packages_pass_glslang_after_a_thin_wrapper() {
    if !tool_available("glslangValidator") {
        return;
    }
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let p = packaged(name, scene, Engine::Godot);
        let include_name = format!("{name}.gdshaderinc");
        let include = godot_include_as_glsl(file(&p, &include_name));
        glslang(&format!("{name}.godot.frag"), &format!("#version 450\n{include}{GLSL_MAIN}"), &[]);

        // The spatial shader's fragment function, with Godot's built-ins as uniforms and outputs as globals.
        let shader = file(&p, &format!("{name}.gdshader"));
        assert!(shader.starts_with("// fractal") && shader.contains("shader_type spatial;"), "{name}: not spatial");
        assert!(
            shader.contains(&format!("#include \"{include_name}\"")),
            "{name}: the shader does not include {include_name}"
        );
        assert!(shader.contains("DEPTH = "), "{name}: the Godot material writes no depth");
        let vertex = shader.find("void vertex() {").expect("a vertex function");
        let vertex_end = vertex + shader[vertex..].find("\n}\n").expect("the vertex function's end") + 3;
        let fragment: String = shader[vertex_end..].to_string();
        let globals =
            "uniform vec3 CAMERA_POSITION_WORLD;\nuniform mat4 PROJECTION_MATRIX;\nuniform mat4 VIEW_MATRIX;\n\
                       uniform vec2 VIEWPORT_SIZE;\nfloat DEPTH;\nvec3 ALBEDO;\nin vec3 world_position;\n\
                       const vec3 MIRROR = vec3(1.0, 1.0, -1.0);\n";
        // Both sides of the renderer test (Godot's own values of its renderer macros).
        for (renderer, current) in [("forward_plus", 0), ("compatibility", 2)] {
            let macros = format!(
                "#define RENDERER_FORWARD_PLUS 0\n#define RENDERER_MOBILE 1\n#define RENDERER_COMPATIBILITY 2\n#define CURRENT_RENDERER {current}\n"
            );
            let wrapped = format!(
                "#version 450\n{macros}{include}{globals}{fragment}\nout vec4 godot_out;\n\nvoid main() {{\n    fragment();\n    godot_out = vec4(ALBEDO, DEPTH);\n}}\n"
            );
            glslang(&format!("{name}.{renderer}.gdshader.frag"), &wrapped, &[]);
        }
    }
}

/// An HLSL pixel shader `main` calling every library function.
const HLSL_MAIN: &str = "\nfloat4 main(float4 position : SV_Position) : SV_Target {\n\
    \x20   float4 hit = sdf_raymarch(float3(0.0, 0.0, -3.0), float3(0.0, 0.0, 1.0), 0.001);\n\
    \x20   return float4(sdf_display(hit.rgb), hit.w) + float4(sdf_normal(SDF_BOUND_CENTER), sdf(position.xyz))\n\
    \x20       + float4(sdf_material(position.xyz), 0.0);\n}\n";

fn glslang_hlsl(file_name: &str, text: &str, entry: &str) {
    let spirv =
        std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("{file_name}.{}.spv", std::process::id()));
    let spirv_arg = spirv.to_str().expect("a UTF-8 temporary path").to_string();
    glslang(file_name, text, &["-D", "-V", "-S", "frag", "-e", entry, "-o", &spirv_arg]);
    let _ = std::fs::remove_file(spirv);
}

#[test]
fn hlsl_libraries_pass_glslang_hlsl_front_end() {
    if !tool_available("glslangValidator") {
        return;
    }
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let library = packaged(name, scene, Engine::Hlsl).files[0].contents.clone();
        glslang_hlsl(&format!("{name}.hlsl"), &format!("{library}{HLSL_MAIN}"), "main");
    }
}

#[test]
fn unity_packages_pass_glslang_hlsl_front_end() {
    if !tool_available("glslangValidator") {
        return;
    }
    const UNITY_CG: &str = "#define CBUFFER_START(name) cbuffer name {\n#define CBUFFER_END };\n\
        float4 _Time;\nfloat3 _WorldSpaceCameraPos;\nfloat4 _ScreenParams;\n\
        float4x4 unity_ObjectToWorld;\nfloat4x4 UNITY_MATRIX_P;\nfloat4x4 UNITY_MATRIX_VP;\n\
        float4 UnityObjectToClipPos(float4 v) { return mul(UNITY_MATRIX_VP, mul(unity_ObjectToWorld, v)); }\n";
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let p = packaged(name, scene, Engine::Unity);
        let include_name = format!("{name}.hlsl");
        let library = file(&p, &include_name);
        // The Custom Function entry points, called as Shader Graph would.
        let params: String = scene.params().iter().map(|d| format!(", {:?}", d.default as f32)).collect();
        let graph = format!(
            "{library}\nfloat4 main(float4 position : SV_Position) : SV_Target {{\n\
             \x20   float d; float3 n; float3 a; float3 c; float t;\n\
             \x20   FractalSdf_float(position.xyz, 1.0{params}, d);\n\
             \x20   FractalSdfNormal_float(position.xyz, 1.0{params}, n);\n\
             \x20   FractalSdfMaterial_float(position.xyz, 1.0{params}, a);\n\
             \x20   FractalRaymarch_float(float3(0.0, 0.0, -3.0), float3(0.0, 0.0, 1.0), 0.001, 1.0{params}, c, t);\n\
             \x20   half hd; half3 hn; half3 ha; half3 hc; half ht;\n\
             \x20   FractalSdf_half(position.xyz, 1.0{params}, hd);\n\
             \x20   FractalSdfNormal_half(position.xyz, 1.0{params}, hn);\n\
             \x20   FractalSdfMaterial_half(position.xyz, 1.0{params}, ha);\n\
             \x20   FractalRaymarch_half(half3(0.0, 0.0, -3.0), half3(0.0, 0.0, 1.0), 0.001, 1.0{params}, hc, ht);\n\
             \x20   return float4(n + a + c + hn + ha + hc, d + t + hd + ht);\n}}\n"
        );
        glslang_hlsl(&format!("{name}.graph.hlsl"), &graph, "main");

        let shader = file(&p, &format!("{name}.shader"));
        let start = shader.find("HLSLPROGRAM").expect("an HLSL program") + "HLSLPROGRAM".len();
        let end = shader.find("ENDHLSL").expect("ENDHLSL");
        let program = shader[start..end]
            .replace("#include \"UnityCG.cginc\"", UNITY_CG)
            .replace(&format!("#include \"{include_name}\""), library);
        assert!(program.contains("SV_Depth"), "{name}: the Unity material writes no depth");
        glslang_hlsl(&format!("{name}.shader.hlsl"), &program, "frag");
    }
}

#[test]
fn unreal_packages_pass_glslang_hlsl_front_end() {
    if !tool_available("glslangValidator") {
        return;
    }
    const VIEW: &str = "struct ViewParameters {\n    float4x4 ViewToClip;\n    float4 ViewSizeAndInvSize;\n    float3 ViewForward;\n};\n\
        cbuffer View_ { ViewParameters ResolvedView; };\n";
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let p = packaged(name, scene, Engine::Unreal);
        let library = file(&p, &format!("{name}.ush"));
        let body = file(&p, &format!("{name}_custom_node.hlsl"));
        // Unreal wraps a Custom node's code in a function of its inputs and additional outputs.
        let params: Vec<String> = scene.params().iter().map(|d| d.name.to_ascii_lowercase()).collect();
        let declared: String = params.iter().map(|p| format!(", float {p}")).collect();
        let passed: String = scene.params().iter().map(|d| format!(", {:?}", d.default as f32)).collect();
        let wrapped = format!(
            "{VIEW}{library}\nfloat3 CustomExpression0(float3 PixelFromCamera, float3 CameraFromObject, \
             float Scale, float Time{declared}, out float DepthOffset) {{\n{body}}}\n\n\
             float4 main(float4 position : SV_Position) : SV_Target {{\n    float depth_offset;\n\
             \x20   float3 c = CustomExpression0(position.xyz, float3(0.0, 100.0, -300.0), 100.0, 1.0{passed}, depth_offset);\n\
             \x20   return float4(c, depth_offset);\n}}\n"
        );
        glslang_hlsl(&format!("{name}.unreal.hlsl"), &wrapped, "main");
    }
}

/// The WGSL library's `sdf_raymarch` and `sdf_display`, driven per pixel by the render kernel's camera rays, against
/// the scene's own render kernel on the same device: the library's march and shading are the kernel's, with the
/// lights as constants (their values at t = 0, the frame's time here). Pixels may differ by a colour step where the
/// two programs' last-bit differences move a hit: at least 99.9 % must be within one step (measured 100 %). A scene
/// whose Mandelbrot pattern the kernel perturbs and the library iterates plainly differs at the set's boundary too:
/// 99 % there (measured 99.75 % on `mandelbrot` at its first key).
#[test]
fn the_wgsl_library_renders_the_kernels_image_on_wgpu() {
    let Some(mut gpu) = available("wgpu", WgpuRenderer::new()) else { return };
    for (name, scene) in scenes::ALL.iter().map(|(n, c)| (*n, c.scene())) {
        let library = &packaged(name, scene, Engine::Wgsl).files[0].contents;
        let render = format!(
            "{library}\n\
             struct CameraFrame {{\n    origin: vec4<f32>,\n    right: vec4<f32>,\n    up: vec4<f32>,\n    forward: vec4<f32>,\n}}\n\n\
             @group(0) @binding(0) var<storage, read_write> out_px: array<u32>;\n\
             @group(0) @binding(1) var<uniform> frame: CameraFrame;\n\n\
             @compute @workgroup_size(8, 8, 1)\n\
             fn render(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
             \x20   let w = u32(frame.right.w);\n    let h = u32(frame.up.w);\n\
             \x20   if (gid.x >= w || gid.y >= h) {{\n        return;\n    }}\n\
             \x20   sdf_params.time = frame.origin.w;\n\
             \x20   let u = (2.0 * (f32(gid.x) + 0.5) - f32(w)) / f32(h);\n\
             \x20   let v = -(2.0 * (f32(gid.y) + 0.5) - f32(h)) / f32(h);\n\
             \x20   let rd = normalize(frame.forward.xyz + u * frame.right.xyz + v * frame.up.xyz);\n\
             \x20   let hit = sdf_raymarch(frame.origin.xyz, rd, frame.forward.w);\n\
             \x20   let c = vec3<u32>(sdf_display(hit.xyz) * 255.0 + 0.5);\n\
             \x20   out_px[gid.y * w + gid.x] = c.x | (c.y << 8u) | (c.z << 16u) | (255u << 24u);\n\
             }}\n"
        );
        let frame = Frame::default_view(scene, 0.0, 96, 54).expect("frame");
        // A library marches one ray a pixel (the engine's fragment): against the kernel's one-sample image.
        let kernels = fractal_dsl::compile(&scene.clone().samples(1)).expect("compile");
        let job = |wgsl| RenderJob::new(KernelSources::default().with_wgsl(wgsl), &frame);
        let got = gpu.render(&job(&render)).unwrap_or_else(|e| panic!("{name}: the library: {e}"));
        let want = gpu.render(&job(&kernels.wgsl)).expect("the render kernel");
        let (mut alike, mut total) = (0usize, 0usize);
        for y in 0..frame.height() {
            for x in 0..frame.width() {
                let (g, w) = (got.rgba(x, y).expect("pixel"), want.rgba(x, y).expect("pixel"));
                total += 1;
                alike += usize::from(g.iter().zip(&w).all(|(a, b)| a.abs_diff(*b) <= 1));
            }
        }
        let share = alike as f64 / total as f64;
        let needed = if kernels.program.reference.is_some() { 0.99 } else { 0.999 };
        println!("{name}: the library's image matches the render kernel's on {:.2} % of pixels", 100.0 * share);
        assert!(
            share >= needed,
            "{name}: the library's image matches the kernel's on only {:.2} % of pixels",
            100.0 * share
        );
    }
}
