//! The scene IR: the one description every reader (writers, interpreter, analyses) walks.
//!
//! A [`Scene`] is a distance tree ([`Node`]) plus what is needed to light and look at it. Leaves are primitives
//! ([`Prim`]) and fractals ([`Fractal`]); inner nodes are operators ([`Op`]: CSG, transforms, domain operations) and
//! materials.
//! Numbers are [`Expr`]s so that `t` and `param(..)` can stand wherever a literal can.

/// `PartialEq` and `Debug` for a reference to a vocabulary declaration: equal when the names are, printed as the
/// name.
macro_rules! named_by_declaration {
    ($kind:ident) => {
        impl PartialEq for $kind {
            fn eq(&self, o: &Self) -> bool {
                self.0.name == o.0.name
            }
        }

        impl std::fmt::Debug for $kind {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.0.name)
            }
        }
    };
}
use named_by_declaration;

/// The accessors of an item made from a declaration with arguments (a primitive, an operator): its declaration, name,
/// and arguments with their declarations.
macro_rules! declared_item {
    ($item:ident, $decl:ident) => {
        impl $item {
            pub fn decl(&self) -> &'static $decl {
                self.kind.0
            }
            pub fn name(&self) -> &'static str {
                self.kind.0.name
            }
            /// Every expression of every argument, in order.
            pub fn exprs(&self) -> impl Iterator<Item = &super::Expr> {
                self.args.iter().flat_map(super::ArgValue::exprs)
            }
            /// The declared arguments with their values.
            pub fn declared_args(&self) -> impl Iterator<Item = (&'static super::arg::ArgDecl, &super::ArgValue)> {
                self.kind.0.args.iter().zip(&self.args)
            }
        }
    };
}
use declared_item;

pub mod arg;
mod expr;
pub mod formula;
pub mod fractal;
pub mod op;
pub mod prim;

pub use arg::ArgValue;
pub use expr::{BinOp, Expr, Func, ParamDecl, Vec3Expr, Vec4Expr};
pub use fractal::{Fractal, FractalDecl, FractalKind, MAX_ITERATIONS};
pub use op::{Op, OpDecl, OpKind};
pub use prim::{Prim, PrimDecl, PrimKind};

/// The distance tree.
#[derive(Clone, Debug, PartialEq)]
pub enum Node {
    Prim(Prim),
    Fractal(Box<Fractal>),
    /// CSG, transforms and domain operations ([`crate::vocab::ops`]).
    Op(Op),
    Material(Box<Node>, Box<Material>),
}

impl Node {
    /// The direct children, in order.
    pub fn children(&self) -> &[Node] {
        match self {
            Node::Prim(_) | Node::Fractal(_) => &[],
            Node::Op(op) => &op.shapes,
            Node::Material(c, _) => std::slice::from_ref(&**c),
        }
    }
    /// Number of nodes in the tree.
    pub fn size(&self) -> usize {
        1 + self.children().iter().map(|c| c.size()).sum::<usize>()
    }
    pub fn depth(&self) -> usize {
        1 + self.children().iter().map(|c| c.depth()).max().unwrap_or(0)
    }
    /// Whether this subtree contains a fractal (the expensive leaves the bound guard protects).
    pub fn has_fractal(&self) -> bool {
        matches!(self, Node::Fractal(_)) || self.children().iter().any(|c| c.has_fractal())
    }
    /// The operator at this node, if it is one.
    pub fn op(&self) -> Option<&Op> {
        match self {
            Node::Op(op) => Some(op),
            _ => None,
        }
    }
}

/// How a surface's base colour is chosen.
#[derive(Clone, Debug, PartialEq)]
pub enum Albedo {
    Rgb(Vec3Expr),
    /// For fractals: mix(a, b, trap), where trap is the orbit's closest approach to the origin, clamped to [0, 1].
    /// Non-fractal leaves under it take `a`.
    OrbitTrap(Vec3Expr, Vec3Expr),
}

/// Blinn-Phong material.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub albedo: Albedo,
    pub ambient: Expr,
    pub diffuse: Expr,
    pub specular: Expr,
    pub shininess: Expr,
}

impl Material {
    pub const DEFAULT_AMBIENT: f64 = 0.15;
    pub const DEFAULT_DIFFUSE: f64 = 0.85;
    pub const DEFAULT_SPECULAR: f64 = 0.0;
    pub const DEFAULT_SHININESS: f64 = 32.0;
    pub fn from_albedo(albedo: Albedo) -> Material {
        Material {
            albedo,
            ambient: Expr::Lit(Self::DEFAULT_AMBIENT),
            diffuse: Expr::Lit(Self::DEFAULT_DIFFUSE),
            specular: Expr::Lit(Self::DEFAULT_SPECULAR),
            shininess: Expr::Lit(Self::DEFAULT_SHININESS),
        }
    }
    /// The material of geometry no `.material(..)` covers.
    pub fn default_surface() -> Material {
        Material::from_albedo(Albedo::Rgb([0.95, 0.75, 0.55].into()))
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    /// Light from infinitely far away in `direction` (pointing from the scene towards the light).
    Directional { direction: Vec3Expr },
    /// Light at `position`, falling off with the inverse square of distance.
    Point { position: Vec3Expr },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub kind: LightKind,
    pub color: Vec3Expr,
    pub intensity: Expr,
}

impl Light {
    /// The light of a scene that names none: the baseline's key light.
    pub fn default_key() -> Light {
        Light {
            kind: LightKind::Directional { direction: [0.6, 0.8, -0.4].into() },
            color: [1.0, 1.0, 1.0].into(),
            intensity: Expr::Lit(1.0),
        }
    }
}

/// Interpolation between camera path keys.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathInterpolation {
    Linear,
    CatmullRom,
}

/// One key of a camera path.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraKey {
    pub time: f64,
    pub position: [f64; 3],
    pub target: [f64; 3],
}

#[derive(Clone, Debug, PartialEq)]
pub enum CameraPlacement {
    LookAt { position: Vec3Expr, target: Vec3Expr },
    Path { keys: Vec<CameraKey>, interpolation: PathInterpolation, looped: bool },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub placement: CameraPlacement,
    /// Vertical field of view in degrees.
    pub fov_degrees: f64,
    /// Radius of a thin lens in scene units (0: a pinhole, everything in focus).
    pub aperture: f64,
    /// Distance along the view direction that a lens holds in focus; `None`: the distance from the camera to its
    /// target (the first key's, on a path) at time 0.
    pub focus: Option<f64>,
}

impl Default for Camera {
    fn default() -> Camera {
        Camera {
            placement: CameraPlacement::LookAt { position: [1.2, 1.0, -2.2].into(), target: [0.0, 0.0, 0.0].into() },
            // The baseline's focal length 1.8: fov = 2·atan(1/1.8).
            fov_degrees: 2.0 * (1.0f64 / 1.8).atan().to_degrees(),
            aperture: 0.0,
            focus: None,
        }
    }
}

/// When the march counts as a hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HitEpsilon {
    /// A fixed distance.
    Fixed(f64),
    /// A multiple of the pixel footprint at the ray's distance: detail scales with the view.
    Pixel(f64),
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shadows {
    None,
    Hard,
    /// Penumbra sharpness k (IQ's soft shadows): larger is sharper.
    Soft(f64),
}

#[derive(Clone, Debug, PartialEq)]
pub struct Fog {
    pub color: [f64; 3],
    pub density: f64,
}

/// Everything about how rays are marched and shaded; compiled into the kernel, so a disabled effect costs nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub max_steps: u32,
    pub max_distance: f64,
    pub epsilon: HitEpsilon,
    /// Over-relaxation factor ω of the march, in [1, 2] (Keinert et al. 2014): step ω·d while successive unbounding
    /// spheres overlap, and where they do not, step back and go on with ω = 1. 1 is plain sphere tracing.
    pub over_relaxation: f64,
    /// The normal's taps, in pixel footprints at the hit (k·footprint·t): the scale the surface's normal is taken at.
    /// `None`: the hit epsilon's (step 4 of [`crate::ray`]).
    pub normal_epsilon: Option<f64>,
    /// Hits on escape-time fractals are points of the drawn set: below the hit epsilon the march steps on by a share
    /// of it until the estimate's membership sign turns, and refines the crossing (step 3b of
    /// [`crate::ray`]). For sets whose estimate stops rays far in front of them (the power-2 Mandelbulb).
    pub membership_hits: bool,
    pub shadows: Shadows,
    /// Ambient occlusion strength (5 samples along the normal); None disables it.
    pub ambient_occlusion: Option<f64>,
    pub glow: Option<[f64; 3]>,
    pub fog: Option<Fog>,
    pub background: [f64; 3],
    pub gamma: f64,
    /// The most rays a pixel may take (1: one ray through its centre). A pixel takes more only where its centre's
    /// colour differs from a neighbour's, and then while its samples disagree ([`crate::ray::pixel`]).
    pub samples: u32,
    /// The adaptive threshold: a pixel stops taking samples once the standard error of its mean display luma is
    /// below this (in display units, 1 = full scale); it refines at all where its display luma differs from a
    /// neighbour's by more than [`crate::ray::pixel::CONTRAST`] times this.
    pub sample_threshold: f64,
}

impl Default for RenderSettings {
    fn default() -> Self {
        RenderSettings {
            // A ray grazing a surface at just over the hit epsilon takes steps of about that epsilon along it: even
            // past a unit sphere some rays ran out of 128 steps, none of 256, at the same cost (measured:
            // `docs/settings.md`, “The default step budget”).
            max_steps: 256,
            max_distance: 20.0,
            epsilon: HitEpsilon::Fixed(0.0005),
            over_relaxation: 1.0,
            normal_epsilon: None,
            membership_hits: false,
            shadows: Shadows::None,
            ambient_occlusion: None,
            glow: None,
            fog: None,
            background: [0.08, 0.09, 0.12],
            gamma: 2.0,
            samples: 1,
            sample_threshold: DEFAULT_SAMPLE_THRESHOLD,
        }
    }
}

/// The default adaptive threshold of [`RenderSettings::sample_threshold`] (measured: `docs/settings.md`, “Samples
/// per pixel”).
pub const DEFAULT_SAMPLE_THRESHOLD: f64 = 0.004;

/// A complete scene: geometry, lights, camera and render settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub root: Node,
    /// The scene's lights; empty means the default key light ([`Scene::effective_lights`]).
    pub lights: Vec<Light>,
    pub camera: Camera,
    pub settings: RenderSettings,
}

/// Most nodes a distance tree may have.
pub const MAX_NODES: usize = 10_000;
