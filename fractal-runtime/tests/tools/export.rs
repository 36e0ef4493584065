//! Export of every built-in scene (read from `scenes/fractal/*.fractal`) to every target, each export checked for
//! validity: SPIR-V by `spirv-val` (Vulkan 1.0 rules), GLSL by `glslangValidator` (OpenGL and Vulkan rules), HLSL by
//! glslang's HLSL front end (DXC is not packaged for Linux), WGSL by naga's validator. MSL has no validator on Linux,
//! so it only has to be a non-empty Metal program declaring the `render` kernel. The external validators are skipped
//! with a printed note when missing, unless FRACTAL_REQUIRE_GPU_BACKENDS=1 demands them (CI installs Debian's
//! spirv-tools and glslang-tools).
//!
//! The built-in scenes and their kernels change as the compiler does, so nothing here pins kernel text.

use std::path::{Path, PathBuf};

use fractal_dsl::builder::{scene, sphere};
use fractal_dsl::eval::{Env, Sample};
use fractal_dsl::number::lanes::F32x8;
use fractal_dsl::number::math::{v3, Num, V3};
use fractal_dsl::{compile, CompiledScene, DefaultParams, Kernels, NativeFns, Scene};
use fractal_runtime::export::{export, export_compiled, export_scene, ExportError, Exported, Target, ENTRY_POINT};

use crate::common::{run_validator, tool_available};

/// Every built-in scene's file name (without extension), scene and compiled kernels.
fn builtin_scenes() -> Vec<(String, Scene, Kernels)> {
    scenes::ALL
        .iter()
        .map(|(name, compiled)| {
            let scene = compiled.scene().clone();
            let kernels = compile(&scene).unwrap();
            (name.to_string(), scene, kernels)
        })
        .collect()
}

/// Writes an export to a file of its own, in a directory of its own (per process, so concurrent runs cannot overwrite
/// each other's files; per file, so a check that removes its directory cannot take another's from under it).
fn write_export(scene: &str, target: Target, exported: &Exported) -> PathBuf {
    let name = format!("export-{}-{scene}-{}", std::process::id(), target.extension());
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).expect("create the export directory");
    let path = dir.join(format!("{scene}.{}", target.extension()));
    std::fs::write(&path, exported.as_bytes()).expect("write the export");
    path
}

/// Removes the files of a check that passed (one that failed leaves them for inspection).
fn remove(files: &[&Path]) {
    for file in files {
        // At worst a leftover in the build's temporary directory.
        let _ = std::fs::remove_file(file);
        // The file's directory goes with it.
        if let Some(dir) = file.parent() {
            let _ = std::fs::remove_dir(dir);
        }
    }
}

fn exported(name: &str, kernels: &Kernels, target: Target) -> Exported {
    export(kernels, target).unwrap_or_else(|e| panic!("{name} to {target}: {e}"))
}

fn text<'a>(name: &str, target: Target, exported: &'a Exported) -> &'a str {
    let text = exported.as_text().unwrap_or_else(|| panic!("{name} to {target}: binary, expected text"));
    assert!(!text.trim().is_empty(), "{name} to {target}: empty");
    text
}

#[test]
fn every_scene_exports_to_every_target() {
    let scenes = builtin_scenes();
    for (name, _, kernels) in &scenes {
        for target in Target::ALL {
            let out = exported(name, kernels, target);
            assert!(!out.is_empty(), "{name} to {target}: empty export");
            assert_eq!(out.as_text().is_none(), target.is_binary(), "{name} to {target}: text/binary mix-up");
        }
    }
}

#[test]
fn opencl_and_wgsl_are_the_writers_own_text() {
    for (name, _, kernels) in builtin_scenes() {
        assert_eq!(exported(&name, &kernels, Target::OpenCl), Exported::Text(kernels.opencl.clone()));
        assert_eq!(exported(&name, &kernels, Target::Wgsl), Exported::Text(kernels.wgsl.clone()));
    }
}

#[test]
fn wgsl_export_validates_in_naga() {
    for (name, _, kernels) in builtin_scenes() {
        let out = exported(&name, &kernels, Target::Wgsl);
        let wgsl = text(&name, Target::Wgsl, &out);
        let module =
            naga::front::wgsl::parse_str(wgsl).unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(wgsl)));
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::default())
            .validate(&module)
            .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(wgsl)));
        let entry = module.entry_points.iter().find(|ep| ep.name == ENTRY_POINT);
        assert_eq!(entry.map(|ep| ep.stage), Some(naga::ShaderStage::Compute), "{name}: no compute `render`");
    }
}

#[test]
fn spirv_export_passes_spirv_val() {
    let scenes = builtin_scenes();
    let validate = tool_available("spirv-val");
    for (name, _, kernels) in &scenes {
        let out = exported(name, kernels, Target::SpirV);
        let Exported::Binary(bytes) = &out else { panic!("{name}: SPIR-V export is not binary") };
        assert_eq!(bytes.len() % 4, 0, "{name}: SPIR-V is not whole words");
        assert_eq!(bytes.get(..4), Some(&0x0723_0203u32.to_le_bytes()[..]), "{name}: no little-endian SPIR-V magic");
        if validate {
            let file = write_export(name, Target::SpirV, &out);
            run_validator("spirv-val", &["--target-env", "vulkan1.0"], &file);
            remove(&[&file]);
        }
    }
}

#[test]
fn glsl_export_passes_glslang() {
    let scenes = builtin_scenes();
    let validate = tool_available("glslangValidator");
    for (name, _, kernels) in &scenes {
        let out = exported(name, kernels, Target::Glsl);
        let glsl = text(name, Target::Glsl, &out);
        assert!(glsl.starts_with("#version 450 core"), "{name}: GLSL does not start with `#version 450 core`");
        if validate {
            // The `.comp` extension tells glslang the stage; checked as OpenGL GLSL and as Vulkan GLSL.
            let file = write_export(name, Target::Glsl, &out);
            let spirv = file.with_extension("comp.spv");
            let spirv_arg = spirv.to_str().expect("a UTF-8 temporary path");
            run_validator("glslangValidator", &[], &file);
            run_validator("glslangValidator", &["-V", "--target-env", "vulkan1.0", "-o", spirv_arg], &file);
            remove(&[&file, &spirv]);
        }
    }
}

/// DXC is not packaged for Linux, so HLSL goes through glslang's HLSL front end instead: it parses and type-checks
/// the program and compiles the entry point to SPIR-V, which catches what naga could get wrong in syntax or types;
/// rules only DXC applies (shader model 6.0 specifics) stay unchecked.
#[test]
fn hlsl_export_passes_glslang_hlsl_front_end() {
    let scenes = builtin_scenes();
    let validate = tool_available("glslangValidator");
    for (name, _, kernels) in &scenes {
        let out = exported(name, kernels, Target::Hlsl);
        let hlsl = text(name, Target::Hlsl, &out);
        assert!(hlsl.contains("[numthreads("), "{name}: HLSL has no compute entry point:\n{hlsl}");
        assert!(hlsl.contains(&format!(" {ENTRY_POINT}(")), "{name}: HLSL has no `{ENTRY_POINT}`:\n{hlsl}");
        if validate {
            let file = write_export(name, Target::Hlsl, &out);
            let spirv = file.with_extension("hlsl.spv");
            let spirv_arg = spirv.to_str().expect("a UTF-8 temporary path");
            run_validator("glslangValidator", &["-D", "-V", "-S", "comp", "-e", ENTRY_POINT, "-o", spirv_arg], &file);
            remove(&[&file, &spirv]);
        }
    }
}

/// No Metal compiler runs on Linux (Apple's `metal` exists only for macOS and Windows), so the MSL export only has to
/// be a non-empty Metal program declaring the `render` kernel.
#[test]
fn msl_export_declares_the_kernel() {
    for (name, _, kernels) in builtin_scenes() {
        let out = exported(&name, &kernels, Target::Msl);
        let msl = text(&name, Target::Msl, &out);
        assert!(msl.contains("#include <metal_stdlib>"), "{name}: MSL lacks the Metal standard library");
        assert!(
            msl.contains(&format!("kernel void {ENTRY_POINT}(")),
            "{name}: MSL has no `{ENTRY_POINT}` kernel:\n{msl}"
        );
    }
}

#[test]
fn export_scene_compiles_and_exports() {
    let (_, scene, kernels) = builtin_scenes().into_iter().next().expect("a built-in scene");
    for target in Target::ALL {
        let direct = export_scene(&scene, target).unwrap_or_else(|e| panic!("{target}: {e}"));
        assert_eq!(direct, exported("first scene", &kernels, target), "{target}: export_scene differs from export");
    }
}

/// Stand-ins for the native evaluator and the IR constructor a `scene!` expansion carries: export calls neither.
fn unused_distance<F: Num>(_: V3<F>, _: &Env<F>) -> F {
    F::lit(f64::NAN)
}
fn unused_sample<F: Num>(p: V3<F>, env: &Env<F>) -> Sample<F> {
    let nan = unused_distance(p, env);
    Sample { distance: nan, albedo: v3(nan, nan, nan), ambient: nan, diffuse: nan, specular: nan, shininess: nan }
}
fn unused_scene() -> Scene {
    unreachable!("export never reads the IR")
}

#[test]
fn export_compiled_exports_the_build_time_kernels() {
    let (name, _, kernels) = builtin_scenes().into_iter().next().expect("a built-in scene");
    let native = NativeFns {
        distance_f32: unused_distance::<f32>,
        distance_f64: unused_distance::<f64>,
        sample_f32: unused_sample::<f32>,
        sample_f64: unused_sample::<f64>,
        distance_x8: unused_distance::<F32x8>,
        sample_x8: unused_sample::<F32x8>,
        distance_slice_x8: |_, _, _, _, _| unreachable!("export never evaluates"),
        normal: None,
    };
    let leak = |s: &str| -> &'static str { Box::leak(s.to_owned().into_boxed_str()) };
    let compiled = CompiledScene::new(
        leak(&kernels.source),
        (leak(&kernels.opencl), leak(&kernels.opencl_f64)),
        (leak(&kernels.wgsl), leak(&kernels.wgsl_f64)),
        native,
        unused_scene,
        DefaultParams::NONE,
    );
    for target in Target::ALL {
        let out = export_compiled(&compiled, target).unwrap_or_else(|e| panic!("{name} to {target}: {e}"));
        assert_eq!(out, exported(&name, &kernels, target), "{target}: export_compiled differs from export");
    }
}

#[test]
fn invalid_scene_is_refused_with_the_rule_it_breaks() {
    let err = export_scene(&scene(sphere(-1.0)), Target::Glsl).expect_err("a negative radius must be refused");
    assert!(matches!(err, ExportError::InvalidScene(_)), "{err:?}");
    assert!(err.to_string().contains("radius"), "message does not name the radius: {err}");
}

#[test]
fn broken_wgsl_is_an_error_not_a_panic() {
    let mut kernels = compile(&scene(sphere(1.0))).unwrap();
    kernels.wgsl.push_str("\nfn broken( {\n");
    for target in [Target::Glsl, Target::Hlsl, Target::Msl, Target::SpirV] {
        let err = export(&kernels, target).expect_err("broken WGSL must be refused");
        assert!(matches!(err, ExportError::WgslParse(_)), "{target}: {err:?}");
    }
    // The writers' own text is passed through untouched, whatever it holds.
    assert!(export(&kernels, Target::Wgsl).is_ok());
}

#[test]
fn wgsl_without_the_render_entry_point_is_refused() {
    let mut kernels = compile(&scene(sphere(1.0))).unwrap();
    kernels.wgsl = kernels.wgsl.replace("fn render(", "fn not_render(");
    let err = export(&kernels, Target::SpirV).expect_err("no entry point");
    assert_eq!(err, ExportError::NoEntryPoint);
}

#[test]
fn target_names_round_trip_and_extensions_are_distinct() {
    for target in Target::ALL {
        assert_eq!(target.to_string().parse::<Target>(), Ok(target));
        assert_eq!(target.name().to_uppercase().parse::<Target>(), Ok(target));
    }
    let names: Vec<&str> = Target::ALL.iter().map(|t| t.name()).collect();
    assert_eq!(names, ["opencl", "wgsl-kernel", "glsl-kernel", "hlsl-kernel", "msl", "spirv"]);
    let extensions: Vec<&str> = Target::ALL.iter().map(|t| t.extension()).collect();
    assert_eq!(extensions, ["cl", "wgsl", "comp", "hlsl", "metal", "spv"]);
    let err = "vulkan".parse::<Target>().expect_err("unknown target");
    assert!(err.to_string().contains("vulkan") && err.to_string().contains("spirv"), "{err}");
}
