//! The Bevy package: the WGSL library as a naga_oil module (`#define_import_path fractal::<scene>`) and a
//! `Material` fragment shader that imports it, marches from the camera through a proxy mesh (a cube around the
//! bound) and writes `@builtin(frag_depth)`. It imports Bevy's `bevy_pbr::forward_io::VertexOutput` and
//! `bevy_pbr::mesh_view_bindings::view`, and binds its uniform at `#{MATERIAL_BIND_GROUP}`, binding 0.

use super::plain::{wgsl_library, WGSL_PARAMS, WGSL_PARAMS_GLOBAL};
use super::source::{PackageFile, Source};

/// The naga_oil import path of a scene's module.
pub fn import_path(scene: &str) -> String {
    format!("fractal::{scene}")
}

pub(super) fn files(s: &Source) -> Vec<PackageFile> {
    let name = &s.name;
    let module = format!("{name}.wgsl");
    let material = format!("{name}_material.wgsl");
    let path = import_path(name);
    let library = wgsl_library(s, &format!("#define_import_path {path}\n\n"));
    let shader = format!(
        "// fractal: the Bevy material of `{name}`: marches the scene from the camera through the material's mesh and\n\
         // writes the hit's depth. Put it on a cube covering SDF_BOUND_MIN … SDF_BOUND_MAX with culling off.\n\
         #import bevy_pbr::forward_io::VertexOutput\n\
         #import bevy_pbr::mesh_view_bindings::view\n\
         #import {path} as scene\n\n\
         @group(#{{MATERIAL_BIND_GROUP}}) @binding(0) var<uniform> material: scene::{WGSL_PARAMS};\n\n\
         struct FragmentOutput {{\n    @location(0) color: vec4<f32>,\n    @builtin(frag_depth) depth: f32,\n}}\n\n\
         // Bevy is right-handed and the scene left-handed (both y up): z is mirrored on the way in.\n\
         const MIRROR: vec3<f32> = vec3<f32>(1.0, 1.0, -1.0);\n\n\
         @fragment\n\
         fn fragment(in: VertexOutput) -> FragmentOutput {{\n\
         \x20   scene::{WGSL_PARAMS_GLOBAL} = material;\n\
         \x20   let ro = view.world_position;\n\
         \x20   let rd = normalize(in.world_position.xyz - ro);\n\
         \x20   // The pixel's angle: 2·tan(fov/2)/height, from the projection's y scale.\n\
         \x20   let footprint = 2.0 / (view.clip_from_view[1][1] * view.viewport.w);\n\
         \x20   let hit = scene::sdf_raymarch(ro * MIRROR, rd * MIRROR, footprint);\n\
         \x20   if (hit.w < 0.0) {{\n\
         \x20       discard;\n\
         \x20   }}\n\
         \x20   let clip = view.clip_from_world * vec4<f32>(ro + rd * hit.w, 1.0);\n\
         \x20   var out: FragmentOutput;\n\
         \x20   out.color = vec4<f32>(hit.xyz, 1.0);\n\
         \x20   out.depth = clip.z / clip.w;\n\
         \x20   return out;\n\
         }}\n"
    );
    let fields: String = s.params.iter().map(|p| format!("    {}: f32,\n", p.ident)).collect();
    let values: String = s.params.iter().map(|p| format!(", {}: {:?}", p.ident, p.decl.default)).collect();
    // The cube around the bound, z mirrored into Bevy's frame.
    let (min, max) = s.bound();
    let corner = |v: [f64; 3]| format!("Vec3::new({:?}, {:?}, {:?})", v[0] as f32, v[1] as f32, v[2] as f32);
    let (cube_min, cube_max) = (corner([min[0], min[1], -max[2]]), corner([max[0], max[1], -min[2]]));
    let readme = format!(
        "{}\n## Use\n\nCopy both files into `assets/shaders/`, keep the module loaded so the material's import finds it,\n\
         and put the material on a cube around the bound:\n\n\
         ```rust\nuse bevy::prelude::*;\nuse bevy::render::render_resource::{{AsBindGroup, ShaderRef, ShaderType}};\n\n\
         #[derive(Clone, Copy, Default, ShaderType)]\nstruct {WGSL_PARAMS} {{\n    time: f32,\n{fields}}}\n\n\
         #[derive(Asset, TypePath, AsBindGroup, Clone)]\nstruct FractalMaterial {{\n    #[uniform(0)]\n    params: {WGSL_PARAMS},\n}}\n\n\
         impl Material for FractalMaterial {{\n    fn fragment_shader() -> ShaderRef {{\n        \"shaders/{material}\".into()\n    }}\n}}\n\n\
         #[derive(Resource)]\nstruct SceneModule(Handle<Shader>);\n\n\
         fn setup(\n    mut commands: Commands,\n    assets: Res<AssetServer>,\n    mut meshes: ResMut<Assets<Mesh>>,\n    mut materials: ResMut<Assets<FractalMaterial>>,\n) {{\n\
         \x20   commands.insert_resource(SceneModule(assets.load(\"shaders/{module}\")));\n\
         \x20   commands.spawn((\n\
         \x20       Mesh3d(meshes.add(Cuboid::from_corners({cube_min}, {cube_max}))),\n\
         \x20       MeshMaterial3d(materials.add(FractalMaterial {{ params: {WGSL_PARAMS} {{ time: 0.0{values} }} }})),\n\
         \x20   ));\n}}\n\n\
         // Register with `MaterialPlugin::<FractalMaterial>::default()`; each frame set `params.time` to\n\
         // `time.elapsed_secs()` for animated scenes. To see it from inside the cube, turn culling off in\n\
         // `Material::specialize` (`descriptor.primitive.cull_mode = None`).\n```\n\n{}",
        s.readme_head(
            "Bevy",
            &format!(
                "`{module}`: the library, a naga_oil module (`#define_import_path {path}`).\n\
                 `{material}`: the material's fragment shader (imports `bevy_pbr::forward_io::VertexOutput` and\n\
                 `bevy_pbr::mesh_view_bindings::view`; its uniform is at `#{{MATERIAL_BIND_GROUP}}`, binding 0)."
            ),
            "vec3<f32>"
        ),
        s.param_table(|p| format!("{WGSL_PARAMS}.{}", p.ident))
    );
    vec![
        PackageFile { name: module, contents: library },
        PackageFile { name: material, contents: shader },
        PackageFile { name: "README.md".into(), contents: readme },
    ]
}
