//! The built-in scene library, under the seed's names. Each scene is a `.fractal` file in `scenes/fractal/`, compiled
//! at build time by `scene_file!` (kernels and native evaluator) and loadable at run time from the same file.

use fractal_dsl::CompiledScene;
use fractal_macros::scene_file;

/// One lit sphere.
pub static HELLO_WORLD: CompiledScene = scene_file!("fractal/hello_world.fractal");
/// Union, subtraction and smooth union of a sphere and a box.
pub static SPHERE_BOX: CompiledScene = scene_file!("fractal/sphere_box.fractal");
/// The power-8 Mandelbulb, set up like the hand-written baseline.
pub static MANDELBULB: CompiledScene = scene_file!("fractal/mandelbulb.fractal");
/// A Menger sponge and a Sierpinski tetrahedron side by side.
pub static SIERPINSKI_COLLECTION: CompiledScene = scene_file!("fractal/sierpinski_collection.fractal");

/// Every built-in scene with its name.
pub static ALL: &[(&str, &CompiledScene)] = &[
    ("hello_world", &HELLO_WORLD),
    ("sphere_box", &SPHERE_BOX),
    ("mandelbulb", &MANDELBULB),
    ("sierpinski_collection", &SIERPINSKI_COLLECTION),
];

/// The built-in scene called `name`.
pub fn by_name(name: &str) -> Option<&'static CompiledScene> {
    ALL.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// The names of the built-in scenes.
pub fn names() -> impl Iterator<Item = &'static str> {
    ALL.iter().map(|(n, _)| *n)
}

/// The `.fractal` source file of a built-in scene, as shipped in this crate.
pub fn source_file(name: &str) -> Option<&'static str> {
    match name {
        "hello_world" => Some(include_str!("../fractal/hello_world.fractal")),
        "sphere_box" => Some(include_str!("../fractal/sphere_box.fractal")),
        "mandelbulb" => Some(include_str!("../fractal/mandelbulb.fractal")),
        "sierpinski_collection" => Some(include_str!("../fractal/sierpinski_collection.fractal")),
        _ => None,
    }
}
