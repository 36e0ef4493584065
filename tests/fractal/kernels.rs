//! The generated kernel text: snapshots of the OpenCL C, WGSL and native Rust of every built-in scene (one file per
//! scene per language; the agreement suite pins every row's code the same way) and of its engine libraries (GLSL,
//! HLSL, WGSL), naga validation of every WGSL module, and checks that a kernel holds only what its scene needs.

use fractal::dsl::back::{opencl, rust, wgsl, Entry};
use fractal::dsl::{compile, lower::lower, parse::parse_str};
use fractal::scenes;

fn snapshot(language: &str, name: &str, text: &str) {
    insta::with_settings!({ snapshot_path => format!("snapshots/{language}"), prepend_module_to_snapshot => false }, {
        insta::assert_snapshot!(name.to_string(), text);
    });
}

#[test]
fn every_built_in_scene_has_pinned_kernels() {
    for (name, scene) in scenes::ALL {
        snapshot("opencl", name, scene.opencl());
        snapshot("opencl_f64", name, scene.opencl_f64());
        snapshot("wgsl", name, scene.wgsl());
        snapshot("wgsl_f64", name, scene.wgsl_f64());
        snapshot("rust", name, &rust::write(&lower(scene.scene()), "fractal_dsl"));
    }
}

/// The function libraries of the engine packages, one file per scene per language, and every file of each engine's
/// package for one scene with a parameter (the engine glue around the libraries).
#[test]
fn every_built_in_scene_has_pinned_engine_libraries() {
    use fractal::runtime::package::{package, Engine};
    for (name, scene) in scenes::ALL {
        for (engine, language) in
            [(Engine::Glsl, "library_glsl"), (Engine::Hlsl, "library_hlsl"), (Engine::Wgsl, "library_wgsl")]
        {
            let files = package(scene.scene(), name, engine).unwrap_or_else(|e| panic!("{name} for {engine}: {e}"));
            snapshot(language, name, &files.files[0].contents);
        }
    }
    let name = "amazing_box";
    let scene = scenes::ALL.iter().find(|(n, _)| *n == name).expect("the amazing box").1;
    assert!(!scene.scene().params().is_empty(), "{name} has no parameter to show");
    for engine in Engine::ALL {
        let files = package(scene.scene(), name, engine).unwrap_or_else(|e| panic!("{name} for {engine}: {e}"));
        let all: String = files.files.iter().map(|f| format!("===== {} =====\n{}\n", f.name, f.contents)).collect();
        snapshot("packages", &format!("{name}_{engine}"), &all);
    }
}

/// The functions a kernel defines, by name, in order: `float sd_box(…) {` in OpenCL C, `fn sd_box(…) -> f32 {` in
/// WGSL.
fn defined_functions(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| !l.starts_with(' ') && l.ends_with('{') && l.contains('('))
        .filter_map(|l| {
            let head = l.split('(').next()?;
            Some(head.split_whitespace().last()?.to_string())
        })
        .collect()
}

fn validate_wgsl(label: &str, src: &str) {
    let module = naga::front::wgsl::parse_str(src).unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(src)));
    naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::all())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(src)));
}

#[test]
fn every_wgsl_module_validates_with_naga() {
    for (name, scene) in scenes::ALL {
        validate_wgsl(name, scene.wgsl());
        let program = lower(scene.scene());
        validate_wgsl(&format!("{name} probe"), &wgsl::write(&program, Entry::Probe));
        validate_wgsl(&format!("{name} trace"), &wgsl::write(&program, Entry::Trace));
    }
}

/// An f64 WGSL module validates (WGSL converts nothing implicitly, so a value left in f32 fails here) and calls none
/// of the built-ins Vulkan defines for f32 only: the traced ones of `lower::portable` stand in for them.
#[test]
fn every_wgsl_f64_module_validates_and_calls_no_f32_only_built_in() {
    use fractal::dsl::back::Scalar;
    for (name, scene) in scenes::ALL {
        let program = lower(scene.scene());
        for entry in [Entry::Render, Entry::Trace, Entry::Probe] {
            let text = wgsl::write_in(&program, entry, Scalar::F64);
            validate_wgsl(&format!("{name} {entry:?} in f64"), &text);
            for built_in in ["sin(", "cos(", "acos(", "atan2(", "exp2(", "log(", "pow("] {
                // A call of the built-in itself, not of `portable_sin` or (for `cos(`) of `acos`.
                let bare = text
                    .match_indices(built_in)
                    .any(|(i, _)| !text[..i].ends_with(|c: char| c.is_ascii_alphanumeric() || c == '_'));
                assert!(!bare, "{name} {entry:?}: an f64 module calls the built-in `{built_in}`");
            }
        }
        assert_eq!(scene.wgsl_f64(), wgsl::write_in(&program, Entry::Render, Scalar::F64), "{name}");
    }
}

#[test]
fn a_sphere_only_kernel_has_no_fractal_shadow_or_effect_code() {
    let k = compile(&parse_str("sphere(1.0)").unwrap()).unwrap();
    // Exactly the sphere's distance, the two scene functions, the normal and the entry point: no fractal estimator,
    // blend, shadow, occlusion or glow code, and no loop but the march.
    let expected = ["sd_sphere", "scene_de", "scene_sample", "scene_normal", "render"];
    for text in [&k.opencl, &k.wgsl] {
        assert_eq!(defined_functions(text), expected, "{text}");
        assert_eq!(text.matches("for (").count(), 1, "{text}");
        for absent in ["glow", "pow(", "exp("] {
            assert!(!text.contains(absent), "sphere-only kernel contains `{absent}`:\n{text}");
        }
    }
}

/// The body of `scene_de` in an OpenCL C kernel.
fn opencl_scene_de(text: &str) -> &str {
    let start = text.find("float scene_de(").expect("every kernel defines scene_de");
    let body = &text[start..];
    &body[..body.find("\n}\n").expect("scene_de ends")]
}

#[test]
fn literals_fold_and_params_become_uniforms() {
    let k = compile(&parse_str("sphere(0.25 + 0.75).translate(vec3(2.0 * 0.5, 0.0, 0.0))").unwrap()).unwrap();
    // Radius 0.25 + 0.75 and offset 2.0 · 0.5 arrive as single literals; the zero offsets cost nothing. The offset
    // moves the frame's anchor before the point relative to it is added (a scene far out keeps its precision).
    assert_eq!(
        opencl_scene_de(&k.opencl),
        "float scene_de(float3 p, __constant const Frame* frame) {\n    const float3 v4 = frame->anchor.xyz;\n    \
         return sd_sphere((float3)(v4.x - 1.0f + p.x, v4.y + p.y, v4.z + p.z), 1.0f);",
        "{}",
        k.opencl
    );
    let k = compile(&parse_str(r#"sphere(param("radius", 1.0, 0.5..2.0))"#).unwrap()).unwrap();
    assert!(k.opencl.contains("frame->params[0].x"), "{}", k.opencl);
    assert!(k.wgsl.contains("frame.params[0].x"), "{}", k.wgsl);
    assert!(k.wgsl.contains("params: array<vec4<f32>, 1>"), "{}", k.wgsl);
}

#[test]
fn power_eight_mandelbulb_is_trig_free_and_other_powers_are_not() {
    let k = compile(&parse_str("mandelbulb(8)").unwrap()).unwrap();
    assert!(k.opencl.contains("de_mandelbulb8(") && !k.opencl.contains("acos"), "{}", k.opencl);
    let k = compile(&parse_str("mandelbulb(8.0 + sin(t))").unwrap()).unwrap();
    assert!(k.opencl.contains("de_mandelbulb(") && !k.opencl.contains("de_mandelbulb8("), "{}", k.opencl);
    // The animated power reaches the estimator (and so its derivative) as the same value.
    assert!(k.opencl.contains("frame->origin.w"), "{}", k.opencl);
}

#[test]
fn effects_appear_only_when_enabled() {
    let plain = compile(&parse_str("scene(sphere(1.0))").unwrap()).unwrap();
    // Each effect, and code only it brings: its function, or its constant.
    for (setting, marker) in [
        (".soft_shadows(8.0)", "scene_shadow"),
        (".ambient_occlusion(1.0)", "scene_ao"),
        // Glow's fall-off with the distance of a near miss.
        (".glow(rgb(0.2, 0.3, 0.9))", "256.0"),
        (".fog(rgb(0.5, 0.5, 0.5), 0.1)", "exp2("),
    ] {
        let with = compile(&parse_str(&format!("scene(sphere(1.0)){setting}")).unwrap()).unwrap();
        assert!(!plain.wgsl.contains(marker), "plain kernel has `{marker}`");
        assert!(with.wgsl.contains(marker), "kernel with {setting} lacks `{marker}`:\n{}", with.wgsl);
    }
}

/// Whether `line` has a number with an `f` suffix (`0.5f`).
fn has_f32_literal(line: &str) -> bool {
    let b = line.as_bytes();
    (1..b.len()).any(|i| {
        b[i] == b'f'
            && b[i - 1].is_ascii_digit()
            && b.get(i + 1).is_none_or(|c| !c.is_ascii_alphanumeric() && *c != b'_')
            && !line[..i]
                .rsplit(|c: char| !c.is_ascii_alphanumeric() && c != '_' && c != '.')
                .next()
                .is_some_and(|w| w.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_'))
    })
}

/// An f64 program computes in f64 throughout: it enables `cl_khr_fp64`, reads its frame in f64 and declares no f32
/// value; only its f32 outputs (trace and probe results) and inputs (probe points) are converted at the boundary.
#[test]
fn opencl_f64_kernels_compute_in_f64_only() {
    use fractal::dsl::back::Scalar;
    for (name, scene) in scenes::ALL {
        let program = lower(scene.scene());
        for entry in [Entry::Render, Entry::Trace, Entry::Probe] {
            let text = opencl::write_in(&program, entry, Scalar::F64);
            assert!(text.contains("#pragma OPENCL EXTENSION cl_khr_fp64 : enable"), "{name} {entry:?}");
            assert!(text.contains("    double4 origin;"), "{name} {entry:?}: the frame is not read in f64");
            for f32_type in ["float ", "float2", "float3", "(float4)"] {
                assert!(!text.contains(f32_type), "{name} {entry:?}: an f64 program has `{f32_type}`");
            }
            // The pixel packing (`col.x * 255.0f + 0.5f`, the same lines as the f32 program's) is the only place an
            // f32 literal may stand.
            let literal = text.lines().filter(|l| !l.contains("(uint)(col.")).find(|l| has_f32_literal(l));
            assert_eq!(literal, None, "{name} {entry:?}: an f32 literal in an f64 program");
        }
        assert_eq!(scene.opencl_f64(), opencl::write_in(&program, Entry::Render, Scalar::F64), "{name}");
    }
}

#[test]
fn opencl_render_probe_and_trace_kernels_exist_for_every_scene() {
    for (name, scene) in scenes::ALL {
        assert!(scene.opencl().contains("__kernel void render(__global uint* out, __constant const Frame* frame)"));
        let program = lower(scene.scene());
        assert!(opencl::write(&program, Entry::Probe).contains("__kernel void probe("), "{name}");
        let trace = opencl::write(&program, Entry::Trace);
        assert!(
            trace.contains(
                "__kernel void trace(__global uint* out, __constant const Frame* frame, __global float4* traces)"
            ),
            "{name}"
        );
    }
}

/// A frame's anchor keeps precision only where the scene meets a translation before anything that takes the whole
/// point, so only such a scene's kernels read it (the others compute relative to the origin, as before anchors).
#[test]
fn only_a_scene_that_meets_a_translation_first_reads_the_anchor() {
    let kernels = |text: &str| compile(&parse_str(text).unwrap()).unwrap();
    for (text, reads) in [
        ("sphere(1.0)", false),
        ("sphere(1.0).translate(vec3(1e6, 0.0, 0.0)).scale(2.0)", false),
        ("sphere(1.0).translate(vec3(1e6, 0.0, 0.0))", true),
        ("union(sphere(1.0), box3(vec3(1.0, 1.0, 1.0)).translate(vec3(3.0, 0.0, 0.0)))", true),
    ] {
        let k = kernels(text);
        for code in [&k.opencl, &k.wgsl, &k.opencl_f64, &k.wgsl_f64] {
            assert_eq!(code.contains("anchor.xyz"), reads, "{text}:\n{code}");
        }
    }
}
