//! The Unreal Engine package: `<scene>.ush`, the HLSL library with `FractalRaymarch`, which takes the time and
//! parameters as arguments, and `<scene>_custom_node.hlsl`, the body of a material Custom node that marches from the
//! camera through its mesh and returns the colour, with the hit's pixel depth offset as an additional output.
//! Unreal is left-handed with z up and measures centimetres: the node turns the axes (scene x, y, z = Unreal
//! Y, Z, X, a rotation, so handedness is kept) and divides by `Scale`, Unreal units per scene unit.

use super::plain::hlsl_library;
use super::source::{PackageFile, Source, TIME_GLOBAL};

/// The Custom node's inputs, in order, before the parameters.
pub const CUSTOM_NODE_INPUTS: [&str; 5] = ["WorldPosition", "CameraPosition", "ObjectPosition", "Scale", "Time"];

pub(super) fn files(s: &Source) -> Vec<PackageFile> {
    let name = &s.name;
    let include = format!("{name}.ush");
    let node = format!("{name}_custom_node.hlsl");
    let mut library = hlsl_library(s);
    let params: String = s.params.iter().map(|p| format!(", float {}", p.ident)).collect();
    let assign: String = s.params.iter().map(|p| format!("    {} = {};\n", p.global(), p.ident)).collect();
    library.push_str(&format!(
        "// The raymarch with the host's values as arguments, for a Custom node (see {node}).\n\
         float4 FractalRaymarch(float3 ro, float3 rd, float footprint, float time{params}) {{\n\
         \x20   {TIME_GLOBAL} = time;\n{assign}    return sdf_raymarch(ro, rd, footprint);\n}}\n"
    ));
    let args: String = s.params.iter().map(|p| format!(", {}", p.ident)).collect();
    let body = format!(
        "// fractal: the body of an Unreal material Custom node for `{name}` (Output Type: CMOT Float 3).\n\
         // Inputs: WorldPosition (Absolute World Position), CameraPosition (Camera Position), ObjectPosition (Object\n\
         // Position), Scale (Unreal units per scene unit, e.g. 100), Time{}.\n\
         // Additional output: DepthOffset (float), into the material's Pixel Depth Offset.\n\
         // Include File Paths: /Project/…/{include}\n\
         // Scene x, y, z are Unreal's Y, Z, X (both left-handed).\n\
         float3 to_pixel = WorldPosition - CameraPosition;\n\
         float3 ro = (CameraPosition - ObjectPosition).yzx / Scale;\n\
         float3 rd = normalize(to_pixel.yzx);\n\
         // The pixel's angle: 2·tan(fov/2)/height, from the projection's y scale.\n\
         float footprint = 2.0 / (View.ViewToClip[1][1] * View.ViewSizeAndInvSize.y);\n\
         float4 hit = FractalRaymarch(ro, rd, footprint, Time{args});\n\
         clip(hit.w);\n\
         DepthOffset = max(hit.w * Scale - length(to_pixel), 0.0);\n\
         return hit.xyz;\n",
        s.params.iter().map(|p| format!(", {}", p.ident)).collect::<String>()
    );
    let readme = format!(
        "{}\n## Use\n\nPut `{include}` in a shader directory of the project (a module's `Shaders/` mapped with\n\
         `AddShaderSourceDirectoryMapping`). In an unlit material (two-sided, masked or opaque, Pixel Depth Offset on), add\n\
         a Custom node: Include File Paths `{include}`, Code = the body in `{node}`, inputs {} and the\n\
         parameters, and an additional float output `DepthOffset`; wire its result to Emissive Color and DepthOffset to\n\
         Pixel Depth Offset. Put the material on a cube around the bound, scaled by `Scale`.\n\n{}",
        s.readme_head(
            "Unreal Engine",
            &format!("`{include}`: the library and `FractalRaymarch`.\n`{node}`: the body of a material Custom node."),
            "float3"
        ),
        CUSTOM_NODE_INPUTS.map(|i| format!("`{i}`")).join(", "),
        s.param_table(|p| p.ident.clone())
    );
    vec![
        PackageFile { name: include, contents: library },
        PackageFile { name: node, contents: body },
        PackageFile { name: "README.md".into(), contents: readme },
    ]
}
