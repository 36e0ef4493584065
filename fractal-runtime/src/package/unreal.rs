//! The Unreal Engine 5 package: `<scene>.ush`, the HLSL library with `FractalRaymarch`, which takes the time and
//! parameters as arguments, and `<scene>_custom_node.hlsl`, the body of a material Custom node that marches from the
//! camera through its mesh and returns the colour, with the hit's pixel depth offset as an additional output.
//! Unreal is left-handed with z up and measures centimetres: the node turns the axes (scene x, y, z = Unreal
//! Y, Z, X, a rotation, so handedness is kept) and divides by `Scale`, Unreal units per scene unit. Its position
//! inputs are camera-relative (UE5's large world coordinates stay in the graph), and it reads `ResolvedView`, which
//! serves instanced stereo as well.

use super::plain::hlsl_library;
use super::source::{PackageFile, Source, TIME_GLOBAL};

/// The Custom node's inputs, in order, before the parameters.
pub const CUSTOM_NODE_INPUTS: [&str; 4] = ["PixelFromCamera", "CameraFromObject", "Scale", "Time"];

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
         // Inputs: PixelFromCamera (World Position node, Camera Relative World Position), CameraFromObject (Camera\n\
         // Position minus Object Position, subtracted in the graph), Scale (Unreal units per scene unit, e.g. 100),\n\
         // Time{}.\n\
         // Additional output: DepthOffset (float), into the material's Pixel Depth Offset.\n\
         // Include File Paths: /Project/…/{include}\n\
         // Scene x, y, z are Unreal's Y, Z, X (both left-handed).\n\
         float3 ro = CameraFromObject.yzx / Scale;\n\
         float3 rd = normalize(PixelFromCamera.yzx);\n\
         // The pixel's angle: 2·tan(fov/2)/height, from the projection's y scale.\n\
         float footprint = 2.0 / abs(ResolvedView.ViewToClip[1][1] * ResolvedView.ViewSizeAndInvSize.y);\n\
         float4 hit = FractalRaymarch(ro, rd, footprint, Time{args});\n\
         clip(hit.w);\n\
         // Pixel Depth Offset is view depth (along the camera's forward axis), not distance along the ray.\n\
         float along_axis = dot(normalize(PixelFromCamera), ResolvedView.ViewForward);\n\
         DepthOffset = max((hit.w * Scale - length(PixelFromCamera)) * along_axis, 0.0);\n\
         // The linear colour that Unreal's sRGB output encodes back to the project's pixel (before its tonemapper).\n\
         return sdf_display_linear(hit.xyz);\n",
        s.params.iter().map(|p| format!(", {}", p.ident)).collect::<String>()
    );
    let readme = format!(
        "{}\n## Use\n\nPut `{include}` in a shader directory of the project (a module's `Shaders/` mapped with\n\
         `AddShaderSourceDirectoryMapping`). In an unlit material (two-sided, masked or opaque, Pixel Depth Offset on), add\n\
         a Custom node: Include File Paths `{include}`, Code = the body in `{node}`, inputs {} and the\n\
         parameters, and an additional float output `DepthOffset`; wire its result to Emissive Color and DepthOffset to\n\
         Pixel Depth Offset. Put the material on a cube around the bound, scaled by `Scale`.\n\n\
         The node returns `sdf_display_linear(colour)`, the linear colour whose sRGB encoding is the project's pixel;\n\
         Unreal's tonemapper then applies to it as to any emissive surface.\n\n\
         ## What was tested, and how\n\n\
         Written for **Unreal Engine 5.4**. No Unreal editor runs where this package is made: the library and the\n\
         Custom node's body (wrapped in a function as Unreal wraps it) compile with glslang's HLSL front end, with\n\
         `ResolvedView` stood in; the rest was checked against Unreal's documentation only: Pixel Depth Offset as view\n\
         depth (the ray distance times the ray's cosine to the view axis), camera-relative positions (large world\n\
         coordinates are subtracted in the graph, not in the node), and `ResolvedView` (instanced stereo).\n\n{}",
        s.readme_head(
            "Unreal Engine 5",
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
