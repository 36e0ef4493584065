//! The generated kernel text: snapshots of the OpenCL C and WGSL of every built-in scene (one file per scene per
//! language), naga validation of every WGSL module, and checks that a kernel holds only what its scene needs.

use fractal::dsl::back::{opencl, wgsl, Entry};
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
        snapshot("wgsl", name, scene.wgsl());
    }
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
        let probe = wgsl::write(&lower(scene.scene()), Entry::Probe);
        validate_wgsl(&format!("{name} probe"), &probe);
    }
}

#[test]
fn a_sphere_only_kernel_has_no_fractal_shadow_or_effect_code() {
    let s = parse_str("sphere(1.0)").unwrap();
    let k = compile(&s);
    for text in [&k.opencl, &k.wgsl] {
        for absent in ["de_", "smooth_", "scene_shadow", "scene_ao", "glow", "noise", "sd_box", "pow("] {
            assert!(!text.contains(absent), "sphere-only kernel contains `{absent}`:\n{text}");
        }
        assert!(text.contains("sd_sphere"));
    }
}

#[test]
fn literals_fold_and_params_become_uniforms() {
    let k = compile(&parse_str("sphere(0.25 + 0.75).translate(vec3(2.0 * 0.5, 0.0, 0.0))").unwrap());
    assert!(k.opencl.contains("sd_sphere(v1, 1.0f)") || k.opencl.contains(", 1.0f)"), "{}", k.opencl);
    assert!(!k.opencl.contains("0.25"), "unfolded literal in:\n{}", k.opencl);
    let k = compile(&parse_str(r#"sphere(param("radius", 1.0, 0.5..2.0))"#).unwrap());
    assert!(k.opencl.contains("frame->params[0].x"), "{}", k.opencl);
    assert!(k.wgsl.contains("frame.params[0].x"), "{}", k.wgsl);
    assert!(k.wgsl.contains("params: array<vec4<f32>, 1>"), "{}", k.wgsl);
}

#[test]
fn power_eight_mandelbulb_is_trig_free_and_other_powers_are_not() {
    let k = compile(&parse_str("mandelbulb(8)").unwrap());
    assert!(k.opencl.contains("de_mandelbulb8(") && !k.opencl.contains("acos"), "{}", k.opencl);
    let k = compile(&parse_str("mandelbulb(8.0 + sin(t))").unwrap());
    assert!(k.opencl.contains("de_mandelbulb(") && !k.opencl.contains("de_mandelbulb8("), "{}", k.opencl);
    // The animated power reaches the estimator (and so its derivative) as the same value.
    assert!(k.opencl.contains("frame->origin.w"), "{}", k.opencl);
}

#[test]
fn effects_appear_only_when_enabled() {
    let plain = compile(&parse_str("scene(sphere(1.0))").unwrap());
    let all = compile(
        &parse_str("scene(sphere(1.0)).soft_shadows(8.0).ambient_occlusion(1.0).glow(rgb(0.2, 0.3, 0.9)).fog(rgb(0.5, 0.5, 0.5), 0.1)")
            .unwrap(),
    );
    for marker in ["scene_shadow", "scene_ao", "glow", "exp("] {
        assert!(!plain.wgsl.contains(marker), "plain kernel has `{marker}`");
        assert!(all.wgsl.contains(marker), "kernel with every effect lacks `{marker}`");
    }
}

#[test]
fn opencl_render_and_probe_kernels_exist_for_every_scene() {
    for (name, scene) in scenes::ALL {
        assert!(scene.opencl().contains("__kernel void render(__global uint* out, __constant const Frame* frame)"));
        let probe = opencl::write(&lower(scene.scene()), Entry::Probe);
        assert!(probe.contains("__kernel void probe("), "{name}");
    }
}
