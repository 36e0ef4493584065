//! The Shadertoy package: one GLSL ES 3.00 file to paste into a Shadertoy tab. The parameters are constants at
//! their defaults, the time is `iTime`, and `mainImage` looks from the scene's camera at t = 0, orbiting with the
//! mouse (`iMouse`) about the point of the view axis nearest the bound's centre.

use fractal_dsl::back;
use fractal_render::Pose;

use super::source::{float, PackageError, PackageFile, Source};

/// Shadertoy's time uniform.
const SHADERTOY_TIME: &str = "iTime";

fn vec3(v: [f64; 3]) -> String {
    format!("vec3({}, {}, {})", float(v[0]), float(v[1]), float(v[2]))
}

pub(super) fn files(s: &Source) -> Result<Vec<PackageFile>, PackageError> {
    let name = &s.name;
    let file = format!("{name}.glsl");
    let mut constants = String::from("// The scene's parameters, at their defaults: edit them here.\n");
    for p in &s.params {
        let d = &p.decl;
        constants.push_str(&format!(
            "const float {} = {}; // range {} … {}\n",
            p.global(),
            float(d.default),
            d.min,
            d.max
        ));
    }
    constants.push('\n');
    let mut text = back::glsl::library(&s.program, &s.library(SHADERTOY_TIME, |p| p.global(), constants));

    let pose = Pose::from_camera(&s.scene.camera, 0.0, &|p| p.default)?;
    let (eye, forward) = (pose.position, pose.forward.normalize());
    let (min, max) = s.bound();
    let centre = glam::DVec3::from_array(std::array::from_fn(|i| 0.5 * (min[i] + max[i])));
    let along = if s.program.bound.is_some() { forward.dot(centre - eye).max(1e-3) } else { 1.0 };
    let pivot = eye + forward * along;
    text.push_str(&format!(
        "// The scene's camera at t = 0; drag the mouse to orbit.\n\
         void mainImage(out vec4 fragColor, in vec2 fragCoord) {{\n\
         \x20   vec3 pivot = {pivot};\n\
         \x20   vec3 offset = {offset};\n\
         \x20   if (iMouse.z > 0.0) {{\n\
         \x20       vec2 turn = (iMouse.xy / iResolution.xy - 0.5) * vec2(6.2831853, 3.0);\n\
         \x20       float c = cos(turn.x), s = sin(turn.x);\n\
         \x20       offset = vec3(c * offset.x + s * offset.z, offset.y, -s * offset.x + c * offset.z);\n\
         \x20       float r = length(offset);\n\
         \x20       float pitch = clamp(asin(offset.y / r) - turn.y, -1.5, 1.5);\n\
         \x20       float flat_r = r * cos(pitch);\n\
         \x20       vec2 heading = normalize(offset.xz + vec2(1e-9, 0.0));\n\
         \x20       offset = vec3(heading.x * flat_r, r * sin(pitch), heading.y * flat_r);\n\
         \x20   }}\n\
         \x20   vec3 eye = pivot + offset;\n\
         \x20   // Left-handed, y up: right × up = forward.\n\
         \x20   vec3 forward = normalize(pivot - eye);\n\
         \x20   vec3 right = normalize(cross(vec3(0.0, 1.0, 0.0), forward));\n\
         \x20   vec3 up = cross(forward, right);\n\
         \x20   float tan_half = {tan_half};\n\
         \x20   vec2 uv = (2.0 * fragCoord - iResolution.xy) / iResolution.y;\n\
         \x20   vec3 rd = normalize(forward + tan_half * (uv.x * right + uv.y * up));\n\
         \x20   vec4 hit = sdf_raymarch(eye, rd, 2.0 * tan_half / iResolution.y);\n\
         \x20   fragColor = vec4(sdf_display(hit.rgb), 1.0);\n\
         }}\n",
        pivot = vec3(pivot.to_array()),
        offset = vec3((eye - pivot).to_array()),
        tan_half = float((0.5 * pose.fov_degrees.to_radians()).tan()),
    ));
    Ok(vec![PackageFile { name: file, contents: text }])
}
