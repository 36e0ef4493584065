//! One syntax, one compiler: a scene written with `scene!`, the same text in a `.fractal` file compiled by
//! `scene_file!`, and that file loaded at run time all produce byte-identical kernels.

use fractal::dsl::{compile, parse::parse_str};
use fractal::prelude::*;
use fractal::scenes;

#[test]
fn macro_file_and_runtime_load_write_identical_kernels() {
    let inline = scene! {
        // One lit sphere: the smallest complete scene.
        scene(sphere(1.0).material(rgb(0.9, 0.2, 0.1)))
            .light(directional(vec3(0.6, 0.8, -0.4), rgb(1.0, 1.0, 1.0)))
            .camera(camera(vec3(0.0, 0.6, -3.2), vec3(0.0, 0.0, 0.0)).fov(50.0))
            // At the default 128 steps one ray grazing the silhouette runs out of steps before it leaves (`fractal
            // accuracy hello_world`); 256 cost nothing measurable.
            .max_steps(256)
            // Up to 5 rays a pixel where it differs from a neighbour: the best image within 3x the one-ray time, if it
            // buys 3 dB (`docs/image-accuracy.md`; `docs/settings.md`, “Samples per pixel”).
            .samples(5)
    };
    let from_file = &scenes::HELLO_WORLD;
    let loaded = compile(&parse_str(scenes::source_file("hello_world").unwrap()).unwrap()).unwrap();
    assert_eq!(inline.opencl(), from_file.opencl());
    assert_eq!(inline.wgsl(), from_file.wgsl());
    assert_eq!(inline.opencl(), loaded.opencl);
    assert_eq!(inline.wgsl(), loaded.wgsl);
}

#[test]
fn every_built_in_scene_loads_at_run_time_to_the_same_kernels() {
    for (name, compiled) in scenes::ALL {
        let loaded = compile(&parse_str(scenes::source_file(name).unwrap()).unwrap()).unwrap();
        assert_eq!(compiled.opencl(), loaded.opencl, "{name}");
        assert_eq!(compiled.wgsl(), loaded.wgsl, "{name}");
        // The canonical source the macro embeds reads back to the same scene.
        assert_eq!(compiled.scene(), &parse_str(compiled.source()).unwrap(), "{name}");
    }
}

#[test]
fn builder_and_macro_build_the_same_scene() {
    let built = fractal::dsl::builder::scene(union(mandelbulb(8), sphere(1.0).translate(vec3(1.5, 0.0, 0.0))));
    let compiled = scene! { union(mandelbulb(8), sphere(1.0).translate(vec3(1.5, 0.0, 0.0))) };
    assert_eq!(compiled.scene(), &built);
    assert_eq!(compiled.opencl(), compile(&built).unwrap().opencl);
}
