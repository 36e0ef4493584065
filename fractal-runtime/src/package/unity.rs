//! The Unity package: `<scene>.hlsl`, the HLSL library with Shader Graph Custom Function entry points
//! (`FractalSdf_float` and friends, taking the time and parameters as inputs), and `<scene>.shader`, a ready
//! unlit material that marches from the camera through its mesh and writes `SV_Depth`. Unity is left-handed with
//! y up, like the scene: no change of axes.

use super::plain::hlsl_library;
use super::source::{float, PackageFile, Source, TIME_GLOBAL};

/// A Custom Function entry point: `name_float(inputs…, Time, params…, out outputs…)` assigning the globals, then
/// `body`.
/// Shader Graph picks `_float` or `_half` by the node's precision; the `_half` one widens its inputs, calls the
/// `_float` one and narrows its outputs.
fn custom_function(s: &Source, name: &str, inputs: &[(&str, &str)], outputs: &[(&str, &str)], body: &str) -> String {
    let params: String = s.params.iter().map(|p| format!(", float {}", p.ident)).collect();
    let assign: String = s.params.iter().map(|p| format!("    {} = {};\n", p.global(), p.ident)).collect();
    let signature = |precision: &str| {
        let ins: Vec<String> = inputs.iter().map(|(ty, n)| format!("{precision}{ty} {n}")).collect();
        let outs: Vec<String> = outputs.iter().map(|(ty, n)| format!("out {precision}{ty} {n}")).collect();
        let half_params: String = s.params.iter().map(|p| format!(", {precision} {}", p.ident)).collect();
        let params = if precision == "float" { params.clone() } else { half_params };
        format!("void {name}_{precision}({}, {precision} Time{params}, {})", ins.join(", "), outs.join(", "))
    };
    let locals: String = outputs.iter().map(|(ty, n)| format!("    float{ty} {n}_float;\n")).collect();
    let args: String = inputs
        .iter()
        .map(|(_, n)| n.to_string())
        .chain(std::iter::once("Time".to_string()))
        .chain(s.params.iter().map(|p| p.ident.clone()))
        .chain(outputs.iter().map(|(_, n)| format!("{n}_float")))
        .collect::<Vec<_>>()
        .join(", ");
    let narrow: String = outputs.iter().map(|(_, n)| format!("    {n} = {n}_float;\n")).collect();
    format!(
        "{} {{\n    {TIME_GLOBAL} = Time;\n{assign}{body}}}\n\n{} {{\n{locals}    {name}_float({args});\n{narrow}}}\n\n",
        signature("float"),
        signature("half")
    )
}

pub(super) fn files(s: &Source) -> Vec<PackageFile> {
    let name = &s.name;
    let include = format!("{name}.hlsl");
    let shader = format!("{name}.shader");
    let mut library = hlsl_library(s);
    library.push_str("// Shader Graph Custom Function entry points (File mode): wire the time and parameters in.\n");
    library.push_str(&custom_function(
        s,
        "FractalSdf",
        &[("3", "Position")],
        &[("", "Distance")],
        "    Distance = sdf(Position);\n",
    ));
    library.push_str(&custom_function(
        s,
        "FractalSdfNormal",
        &[("3", "Position")],
        &[("3", "Normal")],
        "    Normal = sdf_normal(Position);\n",
    ));
    library.push_str(&custom_function(
        s,
        "FractalSdfMaterial",
        &[("3", "Position")],
        &[("3", "Albedo")],
        "    Albedo = sdf_material(Position);\n",
    ));
    library.push_str(&custom_function(
        s,
        "FractalRaymarch",
        &[("3", "Origin"), ("3", "Direction"), ("", "Footprint")],
        &[("3", "Colour"), ("", "Distance")],
        "    float4 hit = sdf_raymarch(Origin, Direction, Footprint);\n    Colour = hit.xyz;\n    Distance = hit.w;\n",
    ));

    let properties: String = s
        .params
        .iter()
        .map(|p| {
            let d = &p.decl;
            format!(
                "        _{} (\"{}\", Range({}, {})) = {}\n",
                p.ident,
                d.name,
                float(d.min),
                float(d.max),
                float(d.default)
            )
        })
        .collect();
    // The properties in the SRP Batcher's per-material constant buffer.
    let declarations: String = if s.params.is_empty() {
        String::new()
    } else {
        let fields: String = s.params.iter().map(|p| format!("                float _{};\n", p.ident)).collect();
        format!("            CBUFFER_START(UnityPerMaterial)\n{fields}            CBUFFER_END\n")
    };
    let assignments: String =
        s.params.iter().map(|p| format!("                {} = _{};\n", p.global(), p.ident)).collect();
    let material = format!(
        "// fractal: the Unity material of `{name}`: marches the scene from the camera through the mesh and writes the\n\
         // hit's depth. Put it on a cube covering SDF_BOUND_MIN … SDF_BOUND_MAX.\n\
         Shader \"Fractal/{name}\"\n{{\n    Properties\n    {{\n{properties}    }}\n    SubShader\n    {{\n\
         \x20       Tags {{ \"RenderType\" = \"Opaque\" \"Queue\" = \"Geometry\" }}\n\
         \x20       // Back faces: the march starts at the camera, so the cube may be entered.\n\
         \x20       Cull Front\n\
         \x20       Pass\n        {{\n\
         \x20           HLSLPROGRAM\n\
         \x20           #pragma vertex vert\n\
         \x20           #pragma fragment frag\n\
         \x20           #include \"UnityCG.cginc\"\n\
         \x20           #include \"{include}\"\n\n\
         {declarations}\n\
         \x20           struct appdata {{ float4 vertex : POSITION; }};\n\
         \x20           struct v2f {{ float4 pos : SV_POSITION; float3 world : TEXCOORD0; }};\n\n\
         \x20           v2f vert(appdata v)\n            {{\n\
         \x20               v2f o;\n\
         \x20               o.pos = UnityObjectToClipPos(v.vertex);\n\
         \x20               o.world = mul(unity_ObjectToWorld, v.vertex).xyz;\n\
         \x20               return o;\n            }}\n\n\
         \x20           float4 frag(v2f i, out float depth : SV_Depth) : SV_Target\n            {{\n\
         \x20               {TIME_GLOBAL} = _Time.y;\n{assignments}\
         \x20               float3 ro = _WorldSpaceCameraPos;\n\
         \x20               float3 rd = normalize(i.world - ro);\n\
         \x20               // The pixel's angle: 2·tan(fov/2)/height, from the projection's y scale.\n\
         \x20               // (negative when Unity flips y to render into a texture: the footprint takes its size)\n\
         \x20               float footprint = 2.0 / abs(UNITY_MATRIX_P[1][1] * _ScreenParams.y);\n\
         \x20               float4 hit = sdf_raymarch(ro, rd, footprint);\n\
         \x20               clip(hit.w);\n\
         \x20               float4 hit_clip = mul(UNITY_MATRIX_VP, float4(ro + rd * hit.w, 1.0));\n\
         \x20               depth = hit_clip.z / hit_clip.w;\n\
         \x20               // Reversed-z and Direct3D-like targets keep clip z in 0..1 already; OpenGL-like ones in -1..1.\n\
         \x20           #if !defined(UNITY_REVERSED_Z) && (defined(SHADER_API_GLCORE) || defined(SHADER_API_GLES3) || defined(SHADER_API_GLES))\n\
         \x20               depth = depth * 0.5 + 0.5;\n\
         \x20           #endif\n\
         \x20               // The linear colour an sRGB target (Linear colour space) encodes back to the project's pixel.\n\
         \x20               return float4(sdf_display_linear(hit.xyz), 1.0);\n            }}\n\
         \x20           ENDHLSL\n        }}\n    }}\n}}\n"
    );
    let inputs: String =
        s.params.iter().map(|p| format!(", `{}` (the parameter `{}`)", p.ident, p.decl.name)).collect();
    let readme = format!(
        "{}\n## Use\n\n**Ready material:** copy both files into `Assets/`, create a material with the shader\n\
         `Fractal/{name}` and put it on a cube around the bound. The parameters are its properties.\n\n\
         **Shader Graph:** add a Custom Function node, Type *File*, Source `{include}`, Name `FractalSdf` (or\n\
         `FractalSdfNormal`, `FractalSdfMaterial`, `FractalRaymarch`); its inputs are the position (or ray), `Time`{inputs};\n\
         outputs as in the signature:\n\n\
         ```hlsl\nvoid FractalSdf_float(float3 Position, float Time{}, out float Distance)\n```\n\n\
         Each entry point has a `_half` twin for nodes set to half precision (it computes in float).\n\n\
         The ready material returns `sdf_display_linear(colour)`, which a project in the Linear colour space (Unity's\n\
         default) shows as the project's own pixel; in a Gamma-space project return `sdf_display(colour)` instead.\n\
         `FractalRaymarch`'s `Colour` is the raw linear colour.\n\n\
         ## What was tested, and how\n\n\
         Written for **Unity 6** (built-in pipeline and URP). No Unity editor runs where this package is made: the\n\
         library, the entry points and the material's program compile with glslang's HLSL front end, with Unity's\n\
         few symbols stood in; the rest was checked against Unity's documentation only: the depth (clip z / w on\n\
         reversed-z and Direct3D-like targets, remapped from -1..1 on OpenGL-like ones), the footprint's sign (the\n\
         projection's y scale turns negative when Unity renders into a texture), the properties in\n\
         `UnityPerMaterial` (SRP Batcher), and the `_half` entry points Shader Graph looks for.\n\n{}",
        s.readme_head(
            "Unity 6",
            &format!("`{include}`: the library and Shader Graph Custom Function entry points.\n`{shader}`: a ready unlit material (built-in pipeline; URP draws it as an unlit pass)."),
            "float3"
        ),
        s.params.iter().map(|p| format!(", float {}", p.ident)).collect::<String>(),
        s.param_table(|p| format!("_{}", p.ident))
    );
    vec![
        PackageFile { name: include, contents: library },
        PackageFile { name: shader, contents: material },
        PackageFile { name: "README.md".into(), contents: readme },
    ]
}
