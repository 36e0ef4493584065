//! The builder API: plain functions and chained methods (glam's feel) that construct the IR.
//!
//! The parser lowers source text through these same functions, so `scene! { sphere(1.0).translate(..) }` and
//! `sphere(1.0).translate(..)` in Rust build the same [`Node`]. Building never fails; [`crate::validate`] reports
//! out-of-range values with the parameter's name when the scene is compiled.

use crate::ir::fractal::Setting;
use crate::ir::*;

// ---- numbers and vectors ----------------------------------------------------------------------------------------

/// Scene time in seconds (`t` in scene source).
pub fn time() -> Expr {
    Expr::Time
}

/// The point's coordinates (`x`, `y`, `z` in scene source): only a displacement's amount may read them.
pub fn x() -> Expr {
    Expr::Point(0)
}
pub fn y() -> Expr {
    Expr::Point(1)
}
pub fn z() -> Expr {
    Expr::Point(2)
}

/// 2D gradient noise in [−1, 1] (`noise2(x, y)`; [`crate::formula::noise`]).
pub fn noise2(x: impl Into<Expr>, y: impl Into<Expr>) -> Expr {
    Expr::Call(Func::Noise2, vec![x.into(), y.into()])
}
/// 3D gradient noise in [−1, 1].
pub fn noise3(x: impl Into<Expr>, y: impl Into<Expr>, z: impl Into<Expr>) -> Expr {
    Expr::Call(Func::Noise3, vec![x.into(), y.into(), z.into()])
}
/// `octaves` octaves of 2D noise, in [−2, 2].
pub fn fbm2(x: impl Into<Expr>, y: impl Into<Expr>, octaves: u32) -> Expr {
    Expr::Call(Func::Fbm2, vec![x.into(), y.into(), Expr::Lit(f64::from(octaves))])
}
/// `octaves` octaves of 3D noise, in [−2, 2].
pub fn fbm3(x: impl Into<Expr>, y: impl Into<Expr>, z: impl Into<Expr>, octaves: u32) -> Expr {
    Expr::Call(Func::Fbm3, vec![x.into(), y.into(), z.into(), Expr::Lit(f64::from(octaves))])
}

/// The 2D Mandelbrot set's smooth escape count at c = (x, y) over `iterations`, in (0, 1]; 0 inside the set
/// (`mandelbrot(x, y, iterations)`; a material pattern).
pub fn mandelbrot(x: impl Into<Expr>, y: impl Into<Expr>, iterations: u32) -> Expr {
    Expr::Call(Func::Mandelbrot, vec![x.into(), y.into(), Expr::Lit(f64::from(iterations))])
}

/// A named uniform: changeable at run time without recompiling, `default` within `range`.
pub fn param(name: &str, default: f64, range: core::ops::Range<f64>) -> Expr {
    Expr::Param(Box::new(ParamDecl { name: name.to_string(), default, min: range.start, max: range.end }))
}

macro_rules! unary_fns {
    ($($name:ident $f:ident),*) => {$(
        #[doc = concat!("`", stringify!($name), "(x)` in scene source.")]
        pub fn $name(x: impl Into<Expr>) -> Expr { Expr::Call(Func::$f, vec![x.into()]) }
    )*};
}
unary_fns!(sin Sin, cos Cos, abs Abs, sqrt Sqrt);

/// `min(a, b)` in scene source.
pub fn min(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    Expr::Call(Func::Min, vec![a.into(), b.into()])
}
/// `max(a, b)` in scene source.
pub fn max(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    Expr::Call(Func::Max, vec![a.into(), b.into()])
}
/// `pow(a, b)` in scene source.
pub fn pow(a: impl Into<Expr>, b: impl Into<Expr>) -> Expr {
    Expr::Call(Func::Pow, vec![a.into(), b.into()])
}
/// `clamp(x, lo, hi)` in scene source.
pub fn clamp(x: impl Into<Expr>, lo: impl Into<Expr>, hi: impl Into<Expr>) -> Expr {
    Expr::Call(Func::Clamp, vec![x.into(), lo.into(), hi.into()])
}
/// `mix(a, b, s)` in scene source: a + (b − a)·s.
pub fn mix(a: impl Into<Expr>, b: impl Into<Expr>, s: impl Into<Expr>) -> Expr {
    Expr::Call(Func::Mix, vec![a.into(), b.into(), s.into()])
}

/// A 3-vector whose components may be expressions. glam's `Vec3` converts into the same type.
pub fn vec3(x: impl Into<Expr>, y: impl Into<Expr>, z: impl Into<Expr>) -> Vec3Expr {
    Vec3Expr([x.into(), y.into(), z.into()])
}

/// A 4-vector (the quaternion Julia constant).
pub fn vec4(x: impl Into<Expr>, y: impl Into<Expr>, z: impl Into<Expr>, w: impl Into<Expr>) -> Vec4Expr {
    Vec4Expr([x.into(), y.into(), z.into(), w.into()])
}

// ---- primitives: declared with their builder functions in `crate::vocab::prims` ------------------------------------

pub use crate::vocab::prims::*;

// ---- fractals: declared with their builder functions in `crate::vocab::fractals` ----------------------------------

pub use crate::vocab::fractals::*;

// ---- operators (CSG, transforms, domain operations): declared with their builders in `crate::vocab::ops` -----------

pub use crate::vocab::ops::{
    intersect, intersect_all, smooth_intersect, smooth_intersect_all, smooth_subtract, smooth_union, smooth_union_all,
    subtract, union, union_all, ShapeExt,
};

impl Fractal {
    pub fn iterations(mut self, n: u32) -> Fractal {
        self.iterations = Some(n);
        self
    }
    /// The factor on the distance estimate a march steps by, for this scene, in place of the family's measured
    /// factor: larger is faster and may step through the surface (`fractal accuracy` measures both).
    pub fn step_factor(mut self, k: f64) -> Fractal {
        self.step_factor = Some(k);
        self
    }
    /// Escape-time families: the escape radius.
    pub fn bailout(self, b: impl Into<Expr>) -> Fractal {
        self.with(Setting::Bailout, b)
    }
    /// Mandelbox only: the inner radius of the sphere fold.
    pub fn min_radius(self, r: impl Into<Expr>) -> Fractal {
        self.with(Setting::MinRadius, r)
    }
    /// Mandelbox only: the box fold limit.
    pub fn fold_limit(self, f: impl Into<Expr>) -> Fractal {
        self.with(Setting::FoldLimit, f)
    }
    /// Juliabulb only: the power.
    pub fn power(self, p: impl Into<Expr>) -> Fractal {
        self.with(Setting::Power, p)
    }
    /// KIFS only: the rotation per iteration, radians.
    pub fn angle(self, a: impl Into<Expr>) -> Fractal {
        self.with(Setting::Angle, a)
    }
}

impl From<Fractal> for Node {
    fn from(f: Fractal) -> Node {
        Node::Fractal(Box::new(f))
    }
}

// ---- materials --------------------------------------------------------------------------------------------------

/// A colour; converts into a [`Material`] with default Blinn-Phong terms.
#[derive(Clone, Debug, PartialEq)]
pub struct Color(pub Vec3Expr);

pub fn rgb(r: impl Into<Expr>, g: impl Into<Expr>, b: impl Into<Expr>) -> Color {
    Color(vec3(r, g, b))
}

impl From<Color> for Material {
    fn from(c: Color) -> Material {
        Material::from_albedo(Albedo::Rgb(c.0))
    }
}

/// An explicit Blinn-Phong material.
pub fn phong(
    color: Color,
    ambient: impl Into<Expr>,
    diffuse: impl Into<Expr>,
    specular: impl Into<Expr>,
    shininess: impl Into<Expr>,
) -> Material {
    Material {
        albedo: Albedo::Rgb(color.0),
        ambient: ambient.into(),
        diffuse: diffuse.into(),
        specular: specular.into(),
        shininess: shininess.into(),
    }
}

/// Orbit-trap colouring for fractals: mix(a, b, trap).
pub fn orbit_trap(a: Color, b: Color) -> Material {
    Material::from_albedo(Albedo::OrbitTrap(a.0, b.0))
}

macro_rules! material_setters {
    ($($name:ident),*) => {
        impl Material {$(
            pub fn $name(mut self, v: impl Into<Expr>) -> Material { self.$name = v.into(); self }
        )*}
        impl Color {$(
            pub fn $name(self, v: impl Into<Expr>) -> Material { Material::from(self).$name(v) }
        )*}
    };
}
material_setters!(ambient, diffuse, specular, shininess);

// ---- lights and camera ------------------------------------------------------------------------------------------

/// Light arriving from `direction` (pointing from the scene towards the light).
pub fn directional(direction: impl Into<Vec3Expr>, color: Color) -> Light {
    Light { kind: LightKind::Directional { direction: direction.into() }, color: color.0, intensity: Expr::Lit(1.0) }
}
/// A point light with inverse-square fall-off.
pub fn point_light(position: impl Into<Vec3Expr>, color: Color) -> Light {
    Light { kind: LightKind::Point { position: position.into() }, color: color.0, intensity: Expr::Lit(1.0) }
}
impl Light {
    pub fn intensity(mut self, i: impl Into<Expr>) -> Light {
        self.intensity = i.into();
        self
    }
}

/// A camera at `position` looking at `target`.
pub fn camera(position: impl Into<Vec3Expr>, target: impl Into<Vec3Expr>) -> Camera {
    Camera {
        placement: CameraPlacement::LookAt { position: position.into(), target: target.into() },
        ..Camera::default()
    }
}
/// One key of a camera path: at `time` seconds the camera is at `position` looking at `target`.
pub fn key(time: f64, position: impl Into<glam::DVec3>, target: impl Into<glam::DVec3>) -> CameraKey {
    CameraKey { time, position: position.into().to_array(), target: target.into().to_array() }
}
/// A keyed camera path, Catmull-Rom by default.
pub fn camera_path(keys: impl IntoIterator<Item = CameraKey>) -> Camera {
    Camera {
        placement: CameraPlacement::Path {
            keys: keys.into_iter().collect(),
            interpolation: PathInterpolation::CatmullRom,
            looped: false,
        },
        ..Camera::default()
    }
}
impl Camera {
    /// Vertical field of view in degrees.
    pub fn fov(mut self, degrees: f64) -> Camera {
        self.fov_degrees = degrees;
        self
    }
    /// A thin lens of radius `radius` (scene units): depth of field, with the scene's samples spread over the lens.
    pub fn aperture(mut self, radius: f64) -> Camera {
        self.aperture = radius;
        self
    }
    /// The distance along the view direction a lens holds in focus (default: the distance to the target at t = 0).
    pub fn focus(mut self, distance: f64) -> Camera {
        self.focus = Some(distance);
        self
    }
    pub fn linear(mut self) -> Camera {
        if let CameraPlacement::Path { interpolation, .. } = &mut self.placement {
            *interpolation = PathInterpolation::Linear;
        }
        self
    }
    pub fn looped(mut self) -> Camera {
        if let CameraPlacement::Path { looped, .. } = &mut self.placement {
            *looped = true;
        }
        self
    }
}

// ---- scene --------------------------------------------------------------------------------------------------------

/// A scene of `root` with default lights, camera and settings.
pub fn scene(root: impl Into<Node>) -> Scene {
    Scene { root: root.into(), lights: Vec::new(), camera: Camera::default(), settings: RenderSettings::default() }
}

impl From<Node> for Scene {
    fn from(n: Node) -> Scene {
        scene(n)
    }
}
impl From<Fractal> for Scene {
    fn from(f: Fractal) -> Scene {
        scene(f)
    }
}

fn constant_color(c: &Color) -> [f64; 3] {
    c.0.lits().unwrap_or_else(|| c.0.eval_default(0.0))
}

impl Scene {
    /// Adds a light; the first one replaces the default key light.
    pub fn light(mut self, l: Light) -> Scene {
        self.lights.push(l);
        self
    }
    pub fn camera(mut self, c: Camera) -> Scene {
        self.camera = c;
        self
    }
    pub fn max_steps(mut self, n: u32) -> Scene {
        self.settings.max_steps = n;
        self
    }
    pub fn max_distance(mut self, d: f64) -> Scene {
        self.settings.max_distance = d;
        self
    }
    /// A fixed hit distance.
    pub fn epsilon(mut self, e: f64) -> Scene {
        self.settings.epsilon = HitEpsilon::Fixed(e);
        self
    }
    /// March with over-relaxation factor `omega` in [1, 2]: steps of ω·d, falling back to plain steps (after a step
    /// back) where the distance bounds stop overlapping. Fewer steps on smooth surfaces; 1 is plain sphere tracing.
    pub fn over_relaxation(mut self, omega: f64) -> Scene {
        self.settings.over_relaxation = omega;
        self
    }
    /// A hit distance of `k` pixel footprints at the ray's distance.
    pub fn pixel_epsilon(mut self, k: f64) -> Scene {
        self.settings.epsilon = HitEpsilon::Pixel(k);
        self
    }
    /// The normal's gradient taken with taps `k` pixel footprints apart at the hit, whatever the hit epsilon: a
    /// normal at the pixel's scale, where a fine epsilon would take it from detail far below the pixel.
    pub fn normal_pixel_epsilon(mut self, k: f64) -> Scene {
        self.settings.normal_epsilon = Some(k);
        self
    }
    /// Up to `n` rays per pixel: a first batch, then more only where they disagree (1: one ray through the centre).
    pub fn samples(mut self, n: u32) -> Scene {
        self.settings.samples = n;
        self
    }
    /// The adaptive threshold of [`Scene::samples`]: a pixel stops once the standard error of its mean display luma
    /// is below `e` (display units; smaller is smoother and slower).
    pub fn sample_threshold(mut self, e: f64) -> Scene {
        self.settings.sample_threshold = e;
        self
    }
    /// Take hits on the escape-time fractals' drawn sets themselves: where the estimate falls below the hit epsilon
    /// outside the set, step on by half the epsilon until a point is in the set, then refine the crossing. For sets
    /// whose estimate is far below the true distance near them (the power-2 Mandelbulb), at more steps.
    pub fn membership_hits(mut self) -> Scene {
        self.settings.membership_hits = true;
        self
    }
    pub fn no_shadows(mut self) -> Scene {
        self.settings.shadows = Shadows::None;
        self
    }
    pub fn hard_shadows(mut self) -> Scene {
        self.settings.shadows = Shadows::Hard;
        self
    }
    /// Soft shadows with penumbra sharpness `k`.
    pub fn soft_shadows(mut self, k: f64) -> Scene {
        self.settings.shadows = Shadows::Soft(k);
        self
    }
    pub fn ambient_occlusion(mut self, strength: f64) -> Scene {
        self.settings.ambient_occlusion = Some(strength);
        self
    }
    pub fn glow(mut self, c: Color) -> Scene {
        self.settings.glow = Some(constant_color(&c));
        self
    }
    pub fn fog(mut self, c: Color, density: f64) -> Scene {
        self.settings.fog = Some(Fog { color: constant_color(&c), density });
        self
    }
    pub fn background(mut self, c: Color) -> Scene {
        self.settings.background = constant_color(&c);
        self
    }
    pub fn gamma(mut self, g: f64) -> Scene {
        self.settings.gamma = g;
        self
    }
    /// The lights in effect: the scene's own, or the default key light when it names none.
    pub fn effective_lights(&self) -> Vec<Light> {
        if self.lights.is_empty() {
            vec![Light::default_key()]
        } else {
            self.lights.clone()
        }
    }
}
