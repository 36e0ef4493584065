//! The plain function libraries (`--target glsl|hlsl|wgsl`), and the host-value declarations the engine packages
//! build on: GLSL uniforms, HLSL static globals, a WGSL private struct.

use fractal_dsl::back;

use super::source::{float, HostParam, PackageFile, Source, TIME_GLOBAL};

/// The comment naming a parameter's default and range, after its declaration.
fn range_comment(p: &HostParam) -> String {
    let d = &p.decl;
    format!(" // `{}`: default {}, range {} … {}", d.name, d.default, d.min, d.max)
}

/// GLSL: the time and parameters as uniforms, unless the includer defines `SDF_NO_UNIFORMS` and declares them.
pub(super) fn glsl_uniforms(s: &Source) -> String {
    let mut text = String::from(
        "// The host's values: the time in seconds and the scene's parameters. Define SDF_NO_UNIFORMS before\n\
         // including this file to declare them yourself (Vulkan GLSL wants them in a uniform block).\n\
         #ifndef SDF_NO_UNIFORMS\n",
    );
    text.push_str(&format!("uniform float {TIME_GLOBAL};\n"));
    for p in &s.params {
        text.push_str(&format!("uniform float {};{}\n", p.global(), range_comment(p)));
    }
    text.push_str("#endif\n\n");
    text
}

/// HLSL: the time and parameters as static globals at their defaults, which the caller assigns before calling (from
/// its constant buffer or a node's inputs), unless it defines `SDF_NO_GLOBALS` and declares them itself.
pub(super) fn hlsl_globals(s: &Source) -> String {
    let mut text = String::from(
        "// The host's values: the time in seconds and the scene's parameters, at their defaults. Assign them before\n\
         // calling (from your constant buffer), or define SDF_NO_GLOBALS and declare them yourself.\n\
         #ifndef SDF_NO_GLOBALS\n",
    );
    text.push_str(&format!("static float {TIME_GLOBAL} = 0.0;\n"));
    for p in &s.params {
        text.push_str(&format!("static float {} = {};{}\n", p.global(), float(p.decl.default), range_comment(p)));
    }
    text.push_str("#endif\n\n");
    text
}

/// The HLSL library, reading the globals of [`hlsl_globals`].
pub(super) fn hlsl_library(s: &Source) -> String {
    back::hlsl::library(&s.program, &s.library(TIME_GLOBAL, HostParam::global, hlsl_globals(s)))
}

/// The WGSL struct of the host's values.
pub(super) const WGSL_PARAMS: &str = "SdfParams";
/// The private global of that struct the library reads.
pub(super) const WGSL_PARAMS_GLOBAL: &str = "sdf_params";

/// WGSL: the time and parameters as the fields of a private global, at their defaults; the caller assigns it from
/// its uniform buffer before calling.
pub(super) fn wgsl_library(s: &Source, header: &str) -> String {
    let mut prologue = format!(
        "{header}// The host's values: the time in seconds and the scene's parameters. Assign `{WGSL_PARAMS_GLOBAL}` before\n\
         // calling (e.g. from a uniform buffer holding a `{WGSL_PARAMS}`).\n\
         struct {WGSL_PARAMS} {{\n    time: f32,\n"
    );
    for p in &s.params {
        prologue.push_str(&format!("    {}: f32,{}\n", p.ident, range_comment(p)));
    }
    let defaults: Vec<String> =
        std::iter::once(float(0.0)).chain(s.params.iter().map(|p| float(p.decl.default))).collect();
    prologue.push_str(&format!(
        "}}\n\nvar<private> {WGSL_PARAMS_GLOBAL}: {WGSL_PARAMS} = {WGSL_PARAMS}({});\n\n",
        defaults.join(", ")
    ));
    let time = format!("{WGSL_PARAMS_GLOBAL}.time");
    back::wgsl::library(&s.program, &s.library(&time, |p| format!("{WGSL_PARAMS_GLOBAL}.{}", p.ident), prologue))
}

pub(super) fn glsl(s: &Source) -> Vec<PackageFile> {
    let library = back::glsl::library(&s.program, &s.library(TIME_GLOBAL, HostParam::global, glsl_uniforms(s)));
    let file = format!("{}.glsl", s.name);
    let readme = format!(
        "{}\n## Use\n\nPaste or `#include` `{file}` after your `#version` line (GLSL 4.50, or GLSL ES 3.00 with\n\
         `precision highp float;`), set the uniforms, and call the functions:\n\n\
         ```glsl\nvec4 hit = sdf_raymarch(camera_position, ray_direction, 2.0 * tan(0.5 * fov) / height);\n\
         if (hit.w < 0.0) discard;\ncolour = vec4(sdf_display(hit.rgb), 1.0);\n```\n\n\
         Tested in a real WebGL2 context (headless Chromium, `tests/engines/webgl/run.sh` in the fractal repository):\n\
         every built-in scene's library, driven with the scene's camera, matches the project's own render of it.\n\n{}",
        s.readme_head("GLSL", &format!("`{file}`: the function library."), "vec3"),
        s.param_table(HostParam::global)
    );
    vec![PackageFile { name: file, contents: library }, PackageFile { name: "README.md".into(), contents: readme }]
}

pub(super) fn hlsl(s: &Source) -> Vec<PackageFile> {
    let file = format!("{}.hlsl", s.name);
    let readme = format!(
        "{}\n## Use\n\n`#include \"{file}\"`, assign the globals, and call the functions:\n\n\
         ```hlsl\nsdf_time = time;\nfloat4 hit = sdf_raymarch(camera_position, ray_direction, 2.0 * tan(0.5 * fov) / height);\n\
         clip(hit.w);\n```\n\n{}",
        s.readme_head("HLSL", &format!("`{file}`: the function library."), "float3"),
        s.param_table(HostParam::global)
    );
    vec![
        PackageFile { name: file, contents: hlsl_library(s) },
        PackageFile { name: "README.md".into(), contents: readme },
    ]
}

pub(super) fn wgsl(s: &Source) -> Vec<PackageFile> {
    let file = format!("{}.wgsl", s.name);
    let readme = format!(
        "{}\n## Use\n\nConcatenate `{file}` with your module (WGSL has no include), assign `{WGSL_PARAMS_GLOBAL}`, and call\n\
         the functions:\n\n\
         ```wgsl\n{WGSL_PARAMS_GLOBAL} = my_uniforms.scene;\nlet hit = sdf_raymarch(camera_position, ray_direction, 2.0 * tan(0.5 * fov) / height);\n\
         if (hit.w < 0.0) {{ discard; }}\n```\n\n{}",
        s.readme_head("WGSL", &format!("`{file}`: the function library."), "vec3<f32>"),
        s.param_table(|p| format!("{WGSL_PARAMS_GLOBAL}.{}", p.ident))
    );
    vec![
        PackageFile { name: file, contents: wgsl_library(s, "") },
        PackageFile { name: "README.md".into(), contents: readme },
    ]
}
