//! The Unity package: `<scene>.hlsl`, the HLSL library with Shader Graph Custom Function entry points
//! (`FractalSdf_float` and friends, taking the time and parameters as inputs), and `<scene>.shader`, a ready
//! unlit material that marches from the camera through its mesh and writes `SV_Depth`. Unity is left-handed with
//! y up, like the scene: no change of axes.

use super::plain::hlsl_library;
use super::source::{float, PackageFile, Source, TIME_GLOBAL};

/// A Custom Function entry point: `name_float(inputs…, Time, params…, out outputs…)` assigning the globals, then
/// `body`.
fn custom_function(s: &Source, name: &str, inputs: &str, outputs: &str, body: &str) -> String {
    let params: String = s.params.iter().map(|p| format!(", float {}", p.ident)).collect();
    let assign: String = s.params.iter().map(|p| format!("    {} = {};\n", p.global(), p.ident)).collect();
    format!("void {name}_float({inputs}, float Time{params}, {outputs}) {{\n    {TIME_GLOBAL} = Time;\n{assign}{body}}}\n\n")
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
        "float3 Position",
        "out float Distance",
        "    Distance = sdf(Position);\n",
    ));
    library.push_str(&custom_function(
        s,
        "FractalSdfNormal",
        "float3 Position",
        "out float3 Normal",
        "    Normal = sdf_normal(Position);\n",
    ));
    library.push_str(&custom_function(
        s,
        "FractalSdfMaterial",
        "float3 Position",
        "out float3 Albedo",
        "    Albedo = sdf_material(Position);\n",
    ));
    library.push_str(&custom_function(
        s,
        "FractalRaymarch",
        "float3 Origin, float3 Direction, float Footprint",
        "out float3 Colour, out float Distance",
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
    let declarations: String = s.params.iter().map(|p| format!("            float _{};\n", p.ident)).collect();
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
         \x20               float footprint = 2.0 / (UNITY_MATRIX_P[1][1] * _ScreenParams.y);\n\
         \x20               float4 hit = sdf_raymarch(ro, rd, footprint);\n\
         \x20               clip(hit.w);\n\
         \x20               float4 hit_clip = mul(UNITY_MATRIX_VP, float4(ro + rd * hit.w, 1.0));\n\
         \x20               depth = hit_clip.z / hit_clip.w;\n\
         \x20               return float4(hit.xyz, 1.0);\n            }}\n\
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
         ```hlsl\nvoid FractalSdf_float(float3 Position, float Time{}, out float Distance)\n```\n\n{}",
        s.readme_head(
            "Unity",
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
