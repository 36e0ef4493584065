//! The Godot 4 package: `<scene>.gdshaderinc`, the GLSL library with the parameters as `uniform`s with
//! `hint_range` (the time is Godot's `TIME`), and a `spatial` `<scene>.gdshader` that includes it, marches from the
//! camera through its mesh (a box around the bound) and writes `DEPTH`.

use fractal_dsl::back;

use super::source::{float, HostParam, PackageFile, Source};

/// Godot's global time built-in, which custom functions may read.
const GODOT_TIME: &str = "TIME";

pub(super) fn files(s: &Source) -> Vec<PackageFile> {
    let name = &s.name;
    let include = format!("{name}.gdshaderinc");
    let shader = format!("{name}.gdshader");
    let mut uniforms = String::from("// The scene's parameters, as material properties; the time is Godot's TIME.\n");
    for p in &s.params {
        let d = &p.decl;
        uniforms.push_str(&format!(
            "uniform float {} : hint_range({}, {}) = {};\n",
            p.global(),
            float(d.min),
            float(d.max),
            float(d.default)
        ));
    }
    uniforms.push('\n');
    let library = back::glsl::library(&s.program, &s.library(GODOT_TIME, HostParam::global, uniforms));
    let material = format!(
        "// fractal: the Godot material of `{name}`: marches the scene from the camera through the mesh and writes the\n\
         // hit's depth. Put it on a box covering SDF_BOUND_MIN … SDF_BOUND_MAX (z mirrored).\n\
         shader_type spatial;\n\
         // Back faces: the march starts at the camera, so the box may be entered.\n\
         render_mode unshaded, cull_front;\n\n\
         #include \"{include}\"\n\n\
         varying vec3 world_position;\n\n\
         // Godot is right-handed and the scene left-handed (both y up): z is mirrored on the way in.\n\
         const vec3 MIRROR = vec3(1.0, 1.0, -1.0);\n\n\
         void vertex() {{\n\
         \x20   world_position = (MODEL_MATRIX * vec4(VERTEX, 1.0)).xyz;\n\
         }}\n\n\
         void fragment() {{\n\
         \x20   vec3 ro = CAMERA_POSITION_WORLD;\n\
         \x20   vec3 rd = normalize(world_position - ro);\n\
         \x20   // The pixel's angle: 2·tan(fov/2)/height, from the projection's y scale (negative where Godot draws\n\
         \x20   // y flipped, as the Compatibility renderer does).\n\
         \x20   float footprint = 2.0 / abs(PROJECTION_MATRIX[1][1] * VIEWPORT_SIZE.y);\n\
         \x20   vec4 hit = sdf_raymarch(ro * MIRROR, rd * MIRROR, footprint);\n\
         \x20   if (hit.w < 0.0) {{\n\
         \x20       discard;\n\
         \x20   }}\n\
         \x20   vec4 clip = PROJECTION_MATRIX * VIEW_MATRIX * vec4(ro + rd * hit.w, 1.0);\n\
         #if CURRENT_RENDERER == RENDERER_COMPATIBILITY\n\
         \x20   // OpenGL's clip z runs -1..1; DEPTH is 0..1.\n\
         \x20   DEPTH = clip.z / clip.w * 0.5 + 0.5;\n\
         #else\n\
         \x20   // Forward+ and Mobile: clip z is already the 0..1 (reversed) depth.\n\
         \x20   DEPTH = clip.z / clip.w;\n\
         #endif\n\
         #if CURRENT_RENDERER == RENDERER_COMPATIBILITY\n\
         \x20   // Compatibility shows an unshaded ALBEDO as it is: give it the displayed colour.\n\
         \x20   ALBEDO = sdf_display(hit.rgb);\n\
         #else\n\
         \x20   // Forward+ and Mobile encode to sRGB at the end: give them the linear colour that encodes to it.\n\
         \x20   ALBEDO = sdf_display_linear(hit.rgb);\n\
         #endif\n\
         }}\n"
    );
    let readme = format!(
        "{}\n## Use\n\nCopy both files into the project (same folder), create a `MeshInstance3D` with a `BoxMesh` around the\n\
         bound, and give it a `ShaderMaterial` with `{shader}`. The parameters show in the inspector as shader\n\
         parameters. In your own shaders, `#include \"res://…/{include}\"` and call the functions.\n\n\
         ```glsl\nshader_type spatial;\n#include \"res://fractals/{include}\"\n\nvoid fragment() {{\n    float d = sdf(vec3(0.0));\n    ALBEDO = sdf_material(vec3(0.0));\n}}\n```\n\n\
         ## What was tested, and how\n\n\
         Written for **Godot 4.6**; it tests `CURRENT_RENDERER`, which older 4.x releases may lack. Run in the real Godot web\n\
         build (Compatibility renderer, WebGL2, in headless Chromium: `tests/engines/godot/run.sh` in the fractal\n\
         repository): the scene's view against the project's own render of it (no pixel missing, colours within a few\n\
         steps), an opaque cube in front hides it and one behind is hidden by it; the figures and a picture are in the\n\
         repository's `docs/engines.md`. Forward+ and Mobile do not run there: their depth (clip z already 0..1) and\n\
         colour (linear, encoded by Godot) follow Godot's documentation.\n\n{}",
        s.readme_head(
            "Godot 4",
            &format!("`{include}`: the library, with the parameters as uniforms.\n`{shader}`: a spatial material using it."),
            "vec3"
        ),
        s.param_table(HostParam::global)
    );
    vec![
        PackageFile { name: include, contents: library },
        PackageFile { name: shader, contents: material },
        PackageFile { name: "README.md".into(), contents: readme },
    ]
}
