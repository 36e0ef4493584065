//! The built-in scene library. Each scene is a `.fractal` file in `scenes/fractal/`, compiled at build time by
//! `scene_file!` (kernels and native evaluator) and loadable at run time from the same file; the list below names
//! each once.

use fractal_dsl::CompiledScene;
use fractal_macros::scene_file;

/// Declares every scene once: its static, its name (the file `fractal/<name>.fractal`) and its doc line; writes
/// [`ALL`] and [`source_file`] from the same list.
macro_rules! library {
    ($($(#[doc = $doc:literal])* $static:ident = $name:literal;)*) => {
        $(
            $(#[doc = $doc])*
            pub static $static: CompiledScene = scene_file!(concat!("fractal/", $name, ".fractal"));
        )*

        /// Every built-in scene with its name, in the order the gallery shows them.
        pub static ALL: &[(&str, &CompiledScene)] = &[$(($name, &$static),)*];

        /// The `.fractal` source file of a built-in scene, as shipped in this crate.
        pub fn source_file(name: &str) -> Option<&'static str> {
            match name {
                $($name => Some(include_str!(concat!("../fractal/", $name, ".fractal"))),)*
                _ => None,
            }
        }
    };
}

library! {
    /// The showcase Mandelbulb: animated power, orbit-trap colour, soft shadows, glow and a camera flight.
    MANDELBULB = "mandelbulb";
    /// The power-8 Mandelbulb set up exactly like the hand-written baseline: the benchmark scene.
    MANDELBULB_BENCH = "mandelbulb_bench";
    /// Mandelbulbs of power 2, 3 and 8 side by side.
    MANDELBULB_POWERS = "mandelbulb_powers";
    /// A quaternion Julia set with an animated constant.
    JULIA = "julia";
    /// The Julia set of the Mandelbulb's map, with a drifting constant.
    JULIABULB = "juliabulb";
    /// Kaleidoscopic IFS with octahedral and icosahedral folds, turning each iteration.
    KIFS = "kifs";
    /// The Mandelbox of scale 2, from outside.
    MANDELBOX = "mandelbox";
    /// A Mandelbox of negative scale (the Amazing Box), from inside its shell.
    AMAZING_BOX = "amazing_box";
    /// The Menger sponge on its own.
    SIERPINSKI_CUBE = "sierpinski_cube";
    /// The Sierpinski tetrahedron on its own.
    SIERPINSKI_TETRAHEDRON = "sierpinski_tetrahedron";
    /// A Menger sponge and a Sierpinski tetrahedron side by side.
    SIERPINSKI_COLLECTION = "sierpinski_collection";
    /// The quadratic White–Nylander bulb, a formula written in the scene language (triplex z² + c).
    QUADRATIC_BULB = "quadratic_bulb";
    /// A Julia set of the quadratic White–Nylander map, written as a formula.
    QUADRATIC_JULIA_BULB = "quadratic_julia_bulb";
    /// The cosine Mandelbulb (latitude from the equator), written as a formula.
    COSINE_BULB = "cosine_bulb";
    /// The Mandelbar bulb, a 3D tricorn (the azimuth turned backwards), written as a formula.
    MANDELBAR_BULB = "mandelbar_bulb";
    /// The quaternion Mandelbrot set, written as a formula with quaternion products.
    QUATERNION_MANDELBROT = "quaternion_mandelbrot";
    /// The Bristorbrot, Doug Bristor's quadratic 3D map, written as a formula.
    BRISTORBROT = "bristorbrot";
    /// Kali's box, a fold written in the scene language.
    KALIBOX = "kalibox";
    /// The Burning Ship bulb, the power-8 map of |z|, written as a formula.
    BURNING_BULB = "burning_bulb";
    /// The Menger sponge as an IFS with smooth folds, written as a fold.
    MENGER_SMOOTH = "menger_smooth";
    /// The Amazing Surf, a Mandelbox variant folding only x and y, written as a fold.
    AMAZING_SURF = "amazing_surf";
    /// Makin3D-2, David Makin's quadratic map with cross terms turning the axes in a cycle, written as a formula.
    MAKIN_BULB = "makin_bulb";
    /// Quickdudley, a quadratic map whose squares and cross terms trade places (a stack of sheets), as a formula.
    QUICKDUDLEY_BULB = "quickdudley_bulb";
    /// Xenodreambuie, the power-9 bulb with its polar angle folded onto the upper half, written as a formula.
    XENODREAMBUIE = "xenodreambuie";
    /// The 2D Mandelbrot set as the material of a plane.
    MANDELBROT = "mandelbrot";
    /// A camera path zooming into the Mandelbrot set to the f32 limit.
    MANDELBROT_ZOOM = "mandelbrot_zoom";
    /// A dive from the whole power-8 Mandelbulb to 1e-9 from its surface, each frame in the precision it needs.
    MANDELBULB_DIVE = "mandelbulb_dive";
    /// A noise heightfield with haze.
    TERRAIN = "terrain";
    /// A noise-displaced sphere with an ocean and an atmosphere.
    PLANET = "planet";
    /// One sphere repeated forever, in fog.
    INFINITE_SPHERES = "infinite_spheres";
    /// Union, subtraction and smooth union of a sphere and a box.
    SPHERE_BOX = "sphere_box";
    /// One lit sphere.
    HELLO_WORLD = "hello_world";
    /// One sphere and nothing else.
    TRIVIAL = "trivial";
}

/// The built-in scene called `name`.
pub fn by_name(name: &str) -> Option<&'static CompiledScene> {
    ALL.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}

/// The names of the built-in scenes.
pub fn names() -> impl Iterator<Item = &'static str> {
    ALL.iter().map(|(n, _)| *n)
}
