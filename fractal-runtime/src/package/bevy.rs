//! The Bevy package (Bevy 0.20): the WGSL library as a WESL module (`<scene>.wesl`) and a `Material` fragment shader
//! (`<scene>_material.wesl`) that imports it as `super::<scene>`, marches from the camera through a proxy mesh (a cube
//! around the bound) and writes `@builtin(frag_depth)`. It imports `bevy_pbr::render::forward_io::VertexOutput` and
//! `bevy_pbr::render::mesh_view_bindings::view`, and binds its uniform at `constants::MATERIAL_BIND_GROUP`, binding
//! 0: the names Bevy 0.20 gives its own WESL modules and its material bind group.

use super::plain::{wgsl_library, WGSL_PARAMS, WGSL_PARAMS_GLOBAL};
use super::source::{PackageFile, Source};

/// The Bevy release the package is written for (its WESL module paths, its `Material` trait).
pub const BEVY_VERSION: &str = "0.20";

pub(super) fn files(s: &Source) -> Vec<PackageFile> {
    let name = &s.name;
    let module = format!("{name}.wesl");
    let material = format!("{name}_material.wesl");
    let library = wgsl_library(
        s,
        &format!("// A WESL module for Bevy {BEVY_VERSION}: `{material}` imports it as `super::{name}`.\n\n"),
    );
    let shader = format!(
        "// fractal: the Bevy {BEVY_VERSION} material of `{name}`: marches the scene from the camera through the material's\n\
         // mesh and writes the hit's depth. Put it on a cube covering SDF_BOUND_MIN … SDF_BOUND_MAX with culling off.\n\
         import bevy_pbr::render::forward_io::VertexOutput;\n\
         import bevy_pbr::render::mesh_view_bindings::view;\n\
         import super::{name} as scene;\n\n\
         @group(constants::MATERIAL_BIND_GROUP) @binding(0) var<uniform> material: scene::{WGSL_PARAMS};\n\n\
         struct FragmentOutput {{\n    @location(0) color: vec4<f32>,\n    @builtin(frag_depth) depth: f32,\n}}\n\n\
         // Bevy is right-handed and the scene left-handed (both y up): z is mirrored on the way in.\n\
         const MIRROR: vec3<f32> = vec3<f32>(1.0, 1.0, -1.0);\n\n\
         @fragment\n\
         fn fragment(in: VertexOutput) -> FragmentOutput {{\n\
         \x20   scene::{WGSL_PARAMS_GLOBAL} = material;\n\
         \x20   let ro = view.world_position;\n\
         \x20   let rd = normalize(in.world_position.xyz - ro);\n\
         \x20   // The pixel's angle: 2·tan(fov/2)/height, from the projection's y scale (its sign is the target's y\n\
         \x20   // direction, which the footprint does not care about).\n\
         \x20   let footprint = 2.0 / abs(view.clip_from_view[1][1] * view.viewport.w);\n\
         \x20   let hit = scene::sdf_raymarch(ro * MIRROR, rd * MIRROR, footprint);\n\
         \x20   if (hit.w < 0.0) {{\n\
         \x20       discard;\n\
         \x20   }}\n\
         \x20   // wgpu's clip z is already the 0..1 depth (Bevy's reversed, infinite-far projection).\n\
         \x20   let clip = view.clip_from_world * vec4<f32>(ro + rd * hit.w, 1.0);\n\
         \x20   var out: FragmentOutput;\n\
         \x20   // The linear colour Bevy's sRGB target encodes back to the project's pixel (or its tonemapper takes).\n\
         \x20   out.color = vec4<f32>(scene::sdf_display_linear(hit.xyz), 1.0);\n\
         \x20   out.depth = clip.z / clip.w;\n\
         \x20   return out;\n\
         }}\n"
    );
    let fields: String = s.params.iter().map(|p| format!("    pub {}: f32,\n", p.ident)).collect();
    let values: String = s.params.iter().map(|p| format!(", {}: {:?}", p.ident, p.decl.default as f32)).collect();
    // The cube around the bound, z mirrored into Bevy's frame.
    let (min, max) = s.bound();
    let corner = |v: [f64; 3]| format!("Vec3::new({:?}, {:?}, {:?})", v[0] as f32, v[1] as f32, v[2] as f32);
    let (cube_min, cube_max) = (corner([min[0], min[1], -max[2]]), corner([max[0], max[1], -min[2]]));
    // The Rust side, one module: the engine test builds it as it stands against the Bevy release named above.
    let rust = format!(
        "//! The Rust side of the `{name}` material (Bevy {BEVY_VERSION}).\n\
         use bevy::mesh::MeshVertexBufferLayoutRef;\n\
         use bevy::pbr::{{MaterialPipeline, MaterialPipelineKey}};\n\
         use bevy::prelude::*;\n\
         use bevy::render::render_resource::{{\n\
         \x20   AsBindGroup, RenderPipelineDescriptor, ShaderType, SpecializedMeshPipelineError,\n\
         }};\n\
         use bevy::shader::ShaderRef;\n\n\
         /// The scene's time and parameters: `{WGSL_PARAMS}` in `{module}`, field for field.\n\
         #[derive(Clone, Copy, Debug, ShaderType)]\n\
         pub struct {WGSL_PARAMS} {{\n    pub time: f32,\n{fields}}}\n\n\
         impl Default for {WGSL_PARAMS} {{\n\
         \x20   /// The parameters' defaults, at t = 0.\n\
         \x20   fn default() -> Self {{\n\
         \x20       {WGSL_PARAMS} {{ time: 0.0{values} }}\n\
         \x20   }}\n\
         }}\n\n\
         #[derive(Asset, TypePath, AsBindGroup, Clone, Debug, Default)]\n\
         pub struct FractalMaterial {{\n    #[uniform(0)]\n    pub params: {WGSL_PARAMS},\n}}\n\n\
         impl Material for FractalMaterial {{\n\
         \x20   fn fragment_shader() -> ShaderRef {{\n\
         \x20       \"shaders/{material}\".into()\n\
         \x20   }}\n\n\
         \x20   // The cube only carries the march: its own depth and shadow would be the cube's, not the fractal's.\n\
         \x20   fn enable_prepass() -> bool {{\n\
         \x20       false\n\
         \x20   }}\n\n\
         \x20   fn enable_shadows() -> bool {{\n\
         \x20       false\n\
         \x20   }}\n\n\
         \x20   // No culling: the march starts at the camera, so the cube may be entered.\n\
         \x20   fn specialize(\n\
         \x20       _pipeline: &MaterialPipeline,\n\
         \x20       descriptor: &mut RenderPipelineDescriptor,\n\
         \x20       _layout: &MeshVertexBufferLayoutRef,\n\
         \x20       _key: MaterialPipelineKey<Self>,\n\
         \x20   ) -> Result<(), SpecializedMeshPipelineError> {{\n\
         \x20       descriptor.primitive.cull_mode = None;\n\
         \x20       Ok(())\n\
         \x20   }}\n\
         }}\n\n\
         /// The cube around the scene's bound, in Bevy's frame (the scene's z mirrored).\n\
         pub fn fractal_cube() -> Cuboid {{\n\
         \x20   Cuboid::from_corners({cube_min}, {cube_max})\n\
         }}\n\n\
         /// Keeps every fractal material's time on Bevy's clock (for animated scenes).\n\
         pub fn tick_fractal_time(time: Res<Time>, mut materials: ResMut<Assets<FractalMaterial>>) {{\n\
         \x20   for (_, material) in materials.iter_mut() {{\n\
         \x20       material.params.time = time.elapsed_secs();\n\
         \x20   }}\n\
         }}\n"
    );
    let readme = format!(
        "{}\n## Use\n\nThe package is written for **Bevy {BEVY_VERSION}** (its WESL shader modules and `Material` trait). Copy both\n\
         `.wesl` files into `assets/shaders/` (the material imports the library as `super::{name}`, and Bevy loads it\n\
         with the material). The material's Rust side, as a module of your app:\n\n\
         ```rust\n{rust}```\n\n\
         Register it and put it on the cube:\n\n\
         ```rust\n\
         app.add_plugins(MaterialPlugin::<FractalMaterial>::default())\n\
         \x20   .add_systems(Update, tick_fractal_time);\n\n\
         fn setup(mut commands: Commands, mut meshes: ResMut<Assets<Mesh>>, mut materials: ResMut<Assets<FractalMaterial>>) {{\n\
         \x20   commands.spawn((Mesh3d(meshes.add(fractal_cube())), MeshMaterial3d(materials.add(FractalMaterial::default()))));\n\
         }}\n\
         ```\n\n\
         The colour written is `sdf_display_linear`'s: Bevy's sRGB target encodes it back to the project's pixel\n\
         (with `Tonemapping::None`; Bevy's tonemappers change it as they change any colour).\n\n\
         ## What was tested, and how\n\n\
         Run in a real Bevy {BEVY_VERSION}.1 app (`tests/engines/bevy/run.sh` in the fractal repository: Vulkan on Mesa's\n\
         lavapipe, the Rust module above compiled as it stands): the scene's view against the project's own render of it\n\
         (no pixel missing, colours within a step), an opaque cube in front hides it and one behind is hidden by it, and\n\
         the scene's `fractal mesh` `.glb` imports; the figures and a picture are in the repository's `docs/engines.md`.\n\n{}",
        s.readme_head(
            &format!("Bevy {BEVY_VERSION}"),
            &format!(
                "`{module}`: the library, a WESL module.\n\
                 `{material}`: the material's fragment shader (imports `bevy_pbr::render::forward_io::VertexOutput`\n\
                 and `bevy_pbr::render::mesh_view_bindings::view`; its uniform is at `constants::MATERIAL_BIND_GROUP`,\n\
                 binding 0)."
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
