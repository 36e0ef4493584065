//! The vocabulary of the scene language as data: every function and method with its argument names and types, and
//! the builder call that gives it meaning. Arity and type errors are produced from this table, so they read the same
//! for every word; nothing here decides what a word means beyond naming the builder function.

use std::borrow::Cow;
use std::collections::VecDeque;
use std::sync::OnceLock;

use crate::builder::{self as b, Color, ShapeExt};
use crate::ir::arg::{ArgDecl, ArgShape};
use crate::ir::formula::{Formula, FormulaKind, FormulaMap};
use crate::ir::fractal::{FractalArgShape, FractalArgValue, Setting};
use crate::ir::op::Operands;
use crate::ir::*;
use crate::vocab::fractals::families::{FOLD, FRACTALS};
use crate::vocab::ops::decl::OPS;
use crate::vocab::prims::decl::PRIMS;

/// The type of a value or of an argument slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Ty {
    Number,
    /// A number without `t` or `param` (scene settings, camera keys, rotation axes).
    Const,
    /// A non-negative integer literal (iterations, levels, counts, steps).
    Int,
    Vec3,
    ConstVec3,
    /// `vec3(..)` of integer literals (repeat counts).
    IntVec3,
    Vec4,
    Color,
    ConstColor,
    Material,
    Shape,
    Fractal,
    Light,
    Camera,
    Key,
    Scene,
    /// A string literal (the name of a param).
    Str,
    /// `min..max` (the range of a param).
    Range,
    /// An iteration map written as a closure, `|z, c| ..` ([`crate::ir::formula`]).
    Formula,
}

impl Ty {
    /// The short name in signatures: `sphere(radius: number)`.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Ty::Number => "number",
            Ty::Const => "constant",
            Ty::Int => "integer",
            Ty::Vec3 => "vec3",
            Ty::ConstVec3 => "constant vec3",
            Ty::IntVec3 => "vec3 of integers",
            Ty::Vec4 => "vec4",
            Ty::Color => "color",
            Ty::ConstColor => "constant color",
            Ty::Material => "material",
            Ty::Shape => "shape",
            Ty::Fractal => "fractal",
            Ty::Light => "light",
            Ty::Camera => "camera",
            Ty::Key => "camera key",
            Ty::Scene => "scene",
            Ty::Str => "string",
            Ty::Range => "range",
            Ty::Formula => "map",
        }
    }
    /// The name with its article, as messages use it: "must be a number".
    pub(crate) fn a(self) -> &'static str {
        match self {
            Ty::Number => "a number",
            Ty::Const => "a constant number",
            Ty::Int => "a non-negative integer literal",
            Ty::Vec3 => "a vec3",
            Ty::ConstVec3 => "a constant vec3",
            Ty::IntVec3 => "vec3(..) of non-negative integer literals",
            Ty::Vec4 => "a vec4",
            Ty::Color => "a color",
            Ty::ConstColor => "a constant color",
            Ty::Material => "a material",
            Ty::Shape => "a shape",
            Ty::Fractal => "a fractal",
            Ty::Light => "a light",
            Ty::Camera => "a camera",
            Ty::Key => "a camera key",
            Ty::Scene => "a scene",
            Ty::Str => "a string literal",
            Ty::Range => "a range min..max",
            Ty::Formula => "a map |z, c| ..",
        }
    }
}

/// A value while a scene is being built: what an expression evaluates to, or an argument after coercion to its slot.
#[derive(Clone, Debug)]
pub(crate) enum Value {
    Number(Expr),
    Const(f64),
    Int(u32),
    Vec3(Vec3Expr),
    ConstVec3([f64; 3]),
    IntVec3([u32; 3]),
    Vec4(Vec4Expr),
    Color(Color),
    Material(Material),
    Shape(Node),
    Fractal(Fractal),
    Light(Light),
    Camera(Camera),
    Key(CameraKey),
    Scene(Box<Scene>),
    Str(String),
    Range(f64, f64),
    Formula(FormulaMap<Expr>),
}

impl Value {
    pub(crate) fn ty(&self) -> Ty {
        match self {
            Value::Number(_) => Ty::Number,
            Value::Const(_) => Ty::Const,
            Value::Int(_) => Ty::Int,
            Value::Vec3(_) => Ty::Vec3,
            Value::ConstVec3(_) => Ty::ConstVec3,
            Value::IntVec3(_) => Ty::IntVec3,
            Value::Vec4(_) => Ty::Vec4,
            Value::Color(_) => Ty::Color,
            Value::Material(_) => Ty::Material,
            Value::Shape(_) => Ty::Shape,
            Value::Fractal(_) => Ty::Fractal,
            Value::Light(_) => Ty::Light,
            Value::Camera(_) => Ty::Camera,
            Value::Key(_) => Ty::Key,
            Value::Scene(_) => Ty::Scene,
            Value::Str(_) => Ty::Str,
            Value::Range(..) => Ty::Range,
            Value::Formula(_) => Ty::Formula,
        }
    }
}

/// One argument slot of a signature. A `many` slot takes one or more values.
#[derive(Clone)]
pub(crate) struct Param {
    pub name: &'static str,
    pub ty: Ty,
    pub many: bool,
}

const fn p(name: &'static str, ty: Ty) -> Param {
    Param { name, ty, many: false }
}
const fn many(name: &'static str, ty: Ty) -> Param {
    Param { name, ty, many: true }
}

/// Builds the value of a call from its coerced arguments (the receiver first, for methods).
pub(crate) type BuildFn = fn(&mut Args) -> Result<Value, String>;

/// What gives a call its meaning: a builder call, a declared primitive ([`crate::vocab::prims`]), fractal family
/// ([`crate::vocab::fractals`]), fractal setting ([`Setting`]) or operator ([`crate::vocab::ops`]).
pub(crate) enum Build {
    Fn(BuildFn),
    Prim(&'static PrimDecl),
    Fractal(&'static FractalDecl),
    Setting(Setting),
    Op(&'static OpDecl),
}

/// A function (`receiver: None`) or a method of the language.
pub(crate) struct Entry {
    pub name: &'static str,
    pub receiver: Option<Ty>,
    pub params: Cow<'static, [Param]>,
    pub result: Ty,
    pub build: Build,
}

const fn fun(name: &'static str, params: &'static [Param], result: Ty, build: BuildFn) -> Entry {
    Entry { name, receiver: None, params: Cow::Borrowed(params), result, build: Build::Fn(build) }
}
const fn meth(receiver: Ty, name: &'static str, params: &'static [Param], result: Ty, build: BuildFn) -> Entry {
    Entry { name, receiver: Some(receiver), params: Cow::Borrowed(params), result, build: Build::Fn(build) }
}

/// The parameter of a declared argument, typed as the declaration types it.
fn declared_param(a: &ArgDecl) -> Param {
    let ty = match a.shape {
        ArgShape::Number => Ty::Number,
        ArgShape::Vec3 => Ty::Vec3,
        ArgShape::ConstVec3 => Ty::ConstVec3,
        ArgShape::Counts => Ty::IntVec3,
    };
    Param { name: a.name, ty, many: false }
}

/// The signature of a declared primitive: its arguments as the declaration types them.
fn prim_entry(decl: &'static PrimDecl) -> Entry {
    let params = decl.args.iter().map(declared_param).collect();
    Entry { name: decl.name, receiver: None, params: Cow::Owned(params), result: Ty::Shape, build: Build::Prim(decl) }
}

/// The signature of a declared operator: its shapes (the receiver, for a method), then its arguments.
fn op_entry(decl: &'static OpDecl) -> Entry {
    let shapes = match decl.operands {
        Operands::Many => vec![many("shapes", Ty::Shape)],
        Operands::Two => vec![p("a", Ty::Shape), p("b", Ty::Shape)],
        Operands::Receiver => vec![],
    };
    let params = shapes.into_iter().chain(decl.args.iter().map(declared_param)).collect();
    let receiver = (decl.operands == Operands::Receiver).then_some(Ty::Shape);
    Entry { name: decl.name, receiver, params: Cow::Owned(params), result: Ty::Shape, build: Build::Op(decl) }
}

/// The signature of a declared fractal family: its constructor argument as the declaration types it.
fn fractal_entry(decl: &'static FractalDecl) -> Entry {
    let ty = match decl.arg.shape {
        FractalArgShape::Number => Ty::Number,
        FractalArgShape::Vec3 => Ty::Vec3,
        FractalArgShape::Vec4 => Ty::Vec4,
        FractalArgShape::Levels => Ty::Int,
        FractalArgShape::Formula => Ty::Formula,
    };
    let params = vec![Param { name: decl.arg.name, ty, many: false }];
    Entry {
        name: decl.name,
        receiver: None,
        params: Cow::Owned(params),
        result: Ty::Fractal,
        build: Build::Fractal(decl),
    }
}

impl Entry {
    /// Builds the value of a call from its coerced arguments (the receiver first, for methods).
    pub(crate) fn build(&self, args: &mut Args) -> Result<Value, String> {
        match self.build {
            Build::Fn(f) => f(args),
            Build::Prim(decl) => Ok(Value::Shape(decl.node(args.declared(decl.args)?))),
            Build::Op(decl) => {
                let shapes = match decl.operands {
                    Operands::Many => args.shapes(),
                    Operands::Two => vec![args.shape()?, args.shape()?],
                    Operands::Receiver => vec![args.shape()?],
                };
                Ok(Value::Shape(decl.node(shapes, args.declared(decl.args)?)))
            }
            Build::Setting(setting) => Ok(Value::Fractal(args.fractal()?.with(setting, args.num()?))),
            Build::Fractal(decl) => {
                let fractal = match args.0.pop_front() {
                    Some(Value::Number(e)) => Fractal::new(decl, FractalArgValue::Num(e)),
                    Some(Value::Vec3(v)) => Fractal::new(decl, FractalArgValue::Vec3(v)),
                    Some(Value::Vec4(v)) => Fractal::new(decl, FractalArgValue::Vec4(v)),
                    Some(Value::Int(n)) => {
                        Fractal { iterations: Some(n), ..Fractal::new(decl, FractalArgValue::Levels) }
                    }
                    Some(Value::Formula(m)) => {
                        let kind = if decl.name == FOLD.name { FormulaKind::Fold } else { FormulaKind::EscapeTime };
                        let formula = Formula { kind, maps: vec![m] };
                        Fractal::new(decl, FractalArgValue::Formula(Box::new(formula)))
                    }
                    _ => return Err(mismatch()),
                };
                Ok(Value::Fractal(fractal))
            }
        }
    }
}

impl Entry {
    /// `(radius: number)`, `(shapes: shape..., k: number)`.
    pub(crate) fn param_list(&self) -> String {
        let list: Vec<String> = self
            .params
            .iter()
            .map(|p| format!("{}: {}{}", p.name, p.ty.name(), if p.many { "..." } else { "" }))
            .collect();
        format!("({})", list.join(", "))
    }
    /// The signature as documentation shows it: `shape.translate(offset: vec3) -> shape`.
    pub(crate) fn signature(&self) -> String {
        let receiver = self.receiver.map(|r| format!("{}.", r.name())).unwrap_or_default();
        format!("{receiver}{}{} -> {}", self.name, self.param_list(), self.result.name())
    }
    pub(crate) fn many_index(&self) -> Option<usize> {
        self.params.iter().position(|p| p.many)
    }
}

/// The coerced arguments of a call, taken in order by the build function.
pub(crate) struct Args(pub VecDeque<Value>);

fn mismatch() -> String {
    "internal error: an argument does not match its signature".to_string()
}

macro_rules! takers {
    ($($name:ident $variant:ident $t:ty),* $(,)?) => {
        impl Args {$(
            pub(crate) fn $name(&mut self) -> Result<$t, String> {
                match self.0.pop_front() {
                    Some(Value::$variant(v)) => Ok(v),
                    _ => Err(mismatch()),
                }
            }
        )*}
    };
}
takers!(
    num Number Expr,
    konst Const f64,
    int Int u32,
    vec3 Vec3 Vec3Expr,
    const_vec3 ConstVec3 [f64; 3],
    color Color Color,
    material Material Material,
    shape Shape Node,
    fractal Fractal Fractal,
    light Light Light,
    camera Camera Camera,
    string Str String,
);

impl Args {
    /// The values of declared arguments, in the form the IR stores them.
    fn declared(&mut self, decls: &[ArgDecl]) -> Result<Vec<ArgValue>, String> {
        let mut values = Vec::with_capacity(decls.len());
        for _ in decls {
            values.push(match self.0.pop_front() {
                Some(Value::Number(e)) => ArgValue::Num(e),
                Some(Value::Vec3(v)) => ArgValue::Vec3(v),
                Some(Value::ConstVec3(v)) => ArgValue::Vec3(v.into()),
                Some(Value::IntVec3(n)) => ArgValue::Vec3(n.map(f64::from).into()),
                _ => return Err(mismatch()),
            });
        }
        Ok(values)
    }
    fn scene(&mut self) -> Result<Scene, String> {
        match self.0.pop_front() {
            Some(Value::Scene(s)) => Ok(*s),
            _ => Err(mismatch()),
        }
    }
    fn range(&mut self) -> Result<core::ops::Range<f64>, String> {
        match self.0.pop_front() {
            Some(Value::Range(lo, hi)) => Ok(lo..hi),
            _ => Err(mismatch()),
        }
    }
    /// The values of a `many` shape slot.
    fn shapes(&mut self) -> Vec<Node> {
        let mut out = Vec::new();
        while let Some(Value::Shape(_)) = self.0.front() {
            if let Some(Value::Shape(n)) = self.0.pop_front() {
                out.push(n);
            }
        }
        out
    }
    /// The values of a `many` key slot.
    fn keys(&mut self) -> Vec<CameraKey> {
        let mut out = Vec::new();
        while let Some(Value::Key(_)) = self.0.front() {
            if let Some(Value::Key(k)) = self.0.pop_front() {
                out.push(k);
            }
        }
        out
    }
}

fn shape(n: Node) -> Result<Value, String> {
    Ok(Value::Shape(n))
}
fn number(e: Expr) -> Result<Value, String> {
    Ok(Value::Number(e))
}
fn fractal(f: Fractal) -> Result<Value, String> {
    Ok(Value::Fractal(f))
}
fn material(m: Material) -> Result<Value, String> {
    Ok(Value::Material(m))
}
fn scene(s: Scene) -> Result<Value, String> {
    Ok(Value::Scene(Box::new(s)))
}
fn camera(c: Camera) -> Result<Value, String> {
    Ok(Value::Camera(c))
}
fn path_only(c: &Camera, method: &str) -> Result<(), String> {
    match c.placement {
        CameraPlacement::Path { .. } => Ok(()),
        CameraPlacement::LookAt { .. } => Err(format!("`{method}` applies only to cameras made with camera_path(..)")),
    }
}
fn dvec3(v: [f64; 3]) -> glam::DVec3 {
    glam::DVec3::from_array(v)
}

use Ty as T;

/// The free functions of the language.
pub(crate) static FUNCTIONS: &[Entry] = &[
    // ---- formulas (`escape_time` and `fold` are made from their declarations)
    fun("hybrid", &[many("maps", T::Formula)], T::Fractal, |a| {
        let mut maps = Vec::new();
        while let Some(Value::Formula(m)) = a.0.pop_front() {
            maps.push(m);
        }
        fractal(crate::vocab::fractals::escape_time(Formula { kind: FormulaKind::EscapeTime, maps }))
    }),
    // ---- numbers and vectors
    fun("param", &[p("name", T::Str), p("default", T::Const), p("range", T::Range)], T::Number, |a| {
        number(b::param(&a.string()?, a.konst()?, a.range()?))
    }),
    fun("sin", &[p("x", T::Number)], T::Number, |a| number(b::sin(a.num()?))),
    fun("cos", &[p("x", T::Number)], T::Number, |a| number(b::cos(a.num()?))),
    fun("abs", &[p("x", T::Number)], T::Number, |a| number(b::abs(a.num()?))),
    fun("sqrt", &[p("x", T::Number)], T::Number, |a| number(b::sqrt(a.num()?))),
    fun("min", &[p("a", T::Number), p("b", T::Number)], T::Number, |a| number(b::min(a.num()?, a.num()?))),
    fun("max", &[p("a", T::Number), p("b", T::Number)], T::Number, |a| number(b::max(a.num()?, a.num()?))),
    fun("pow", &[p("x", T::Number), p("y", T::Number)], T::Number, |a| number(b::pow(a.num()?, a.num()?))),
    fun("clamp", &[p("x", T::Number), p("lo", T::Number), p("hi", T::Number)], T::Number, |a| {
        number(b::clamp(a.num()?, a.num()?, a.num()?))
    }),
    fun("noise2", &[p("x", T::Number), p("y", T::Number)], T::Number, |a| number(b::noise2(a.num()?, a.num()?))),
    fun("noise3", &[p("x", T::Number), p("y", T::Number), p("z", T::Number)], T::Number, |a| {
        number(b::noise3(a.num()?, a.num()?, a.num()?))
    }),
    fun("fbm2", &[p("x", T::Number), p("y", T::Number), p("octaves", T::Int)], T::Number, |a| {
        number(b::fbm2(a.num()?, a.num()?, a.int()?))
    }),
    fun("fbm3", &[p("x", T::Number), p("y", T::Number), p("z", T::Number), p("octaves", T::Int)], T::Number, |a| {
        number(b::fbm3(a.num()?, a.num()?, a.num()?, a.int()?))
    }),
    fun("mandelbrot", &[p("x", T::Number), p("y", T::Number), p("iterations", T::Int)], T::Number, |a| {
        number(b::mandelbrot(a.num()?, a.num()?, a.int()?))
    }),
    fun("mix", &[p("a", T::Number), p("b", T::Number), p("s", T::Number)], T::Number, |a| {
        number(b::mix(a.num()?, a.num()?, a.num()?))
    }),
    fun("vec3", &[p("x", T::Number), p("y", T::Number), p("z", T::Number)], T::Vec3, |a| {
        Ok(Value::Vec3(b::vec3(a.num()?, a.num()?, a.num()?)))
    }),
    fun("vec4", &[p("x", T::Number), p("y", T::Number), p("z", T::Number), p("w", T::Number)], T::Vec4, |a| {
        Ok(Value::Vec4(b::vec4(a.num()?, a.num()?, a.num()?, a.num()?)))
    }),
    fun("rgb", &[p("r", T::Number), p("g", T::Number), p("b", T::Number)], T::Color, |a| {
        Ok(Value::Color(b::rgb(a.num()?, a.num()?, a.num()?)))
    }),
    // ---- materials
    fun(
        "phong",
        &[
            p("color", T::Color),
            p("ambient", T::Number),
            p("diffuse", T::Number),
            p("specular", T::Number),
            p("shininess", T::Number),
        ],
        T::Material,
        |a| material(b::phong(a.color()?, a.num()?, a.num()?, a.num()?, a.num()?)),
    ),
    fun("orbit_trap", &[p("a", T::Color), p("b", T::Color)], T::Material, |a| {
        material(b::orbit_trap(a.color()?, a.color()?))
    }),
    // ---- lights and camera
    fun("directional", &[p("direction", T::Vec3), p("color", T::Color)], T::Light, |a| {
        Ok(Value::Light(b::directional(a.vec3()?, a.color()?)))
    }),
    fun("point_light", &[p("position", T::Vec3), p("color", T::Color)], T::Light, |a| {
        Ok(Value::Light(b::point_light(a.vec3()?, a.color()?)))
    }),
    fun("camera", &[p("position", T::Vec3), p("target", T::Vec3)], T::Camera, |a| {
        camera(b::camera(a.vec3()?, a.vec3()?))
    }),
    fun("camera_path", &[many("keys", T::Key)], T::Camera, |a| camera(b::camera_path(a.keys()))),
    fun("key", &[p("time", T::Const), p("position", T::ConstVec3), p("target", T::ConstVec3)], T::Key, |a| {
        Ok(Value::Key(b::key(a.konst()?, dvec3(a.const_vec3()?), dvec3(a.const_vec3()?))))
    }),
    // ---- scene
    fun("scene", &[p("shape", T::Shape)], T::Scene, |a| scene(b::scene(a.shape()?))),
];

/// The methods of the language; a method name belongs to exactly one receiver type.
pub(crate) static METHODS: &[Entry] = &[
    // ---- fractal settings
    meth(T::Fractal, "iterations", &[p("iterations", T::Int)], T::Fractal, |a| {
        fractal(a.fractal()?.iterations(a.int()?))
    }),
    meth(T::Fractal, "step_factor", &[p("factor", T::Const)], T::Fractal, |a| {
        fractal(a.fractal()?.step_factor(a.konst()?))
    }),
    // (the settings that take a number, `.bailout(b)` and the rest, are made from [`Setting::ALL`])
    // ---- materials (the operators are declared in `crate::vocab::ops`)
    meth(T::Shape, "material", &[p("material", T::Material)], T::Shape, |a| shape(a.shape()?.material(a.material()?))),
    // ---- material terms (a color becomes a material with default terms first)
    meth(T::Material, "ambient", &[p("ambient", T::Number)], T::Material, |a| {
        material(a.material()?.ambient(a.num()?))
    }),
    meth(T::Material, "diffuse", &[p("diffuse", T::Number)], T::Material, |a| {
        material(a.material()?.diffuse(a.num()?))
    }),
    meth(T::Material, "specular", &[p("specular", T::Number)], T::Material, |a| {
        material(a.material()?.specular(a.num()?))
    }),
    meth(T::Material, "shininess", &[p("shininess", T::Number)], T::Material, |a| {
        material(a.material()?.shininess(a.num()?))
    }),
    // ---- lights and cameras
    meth(T::Light, "intensity", &[p("intensity", T::Number)], T::Light, |a| {
        Ok(Value::Light(a.light()?.intensity(a.num()?)))
    }),
    meth(T::Camera, "fov", &[p("degrees", T::Const)], T::Camera, |a| camera(a.camera()?.fov(a.konst()?))),
    meth(T::Camera, "aperture", &[p("radius", T::Const)], T::Camera, |a| camera(a.camera()?.aperture(a.konst()?))),
    meth(T::Camera, "focus", &[p("distance", T::Const)], T::Camera, |a| camera(a.camera()?.focus(a.konst()?))),
    meth(T::Camera, "linear", &[], T::Camera, |a| {
        let c = a.camera()?;
        path_only(&c, "linear")?;
        camera(c.linear())
    }),
    meth(T::Camera, "looped", &[], T::Camera, |a| {
        let c = a.camera()?;
        path_only(&c, "looped")?;
        camera(c.looped())
    }),
    // ---- scene: lights, camera, render settings (settings are constants: they are compiled into the kernel)
    meth(T::Scene, "light", &[p("light", T::Light)], T::Scene, |a| scene(a.scene()?.light(a.light()?))),
    meth(T::Scene, "camera", &[p("camera", T::Camera)], T::Scene, |a| scene(a.scene()?.camera(a.camera()?))),
    meth(T::Scene, "max_steps", &[p("steps", T::Int)], T::Scene, |a| scene(a.scene()?.max_steps(a.int()?))),
    meth(T::Scene, "max_distance", &[p("distance", T::Const)], T::Scene, |a| {
        scene(a.scene()?.max_distance(a.konst()?))
    }),
    meth(T::Scene, "epsilon", &[p("epsilon", T::Const)], T::Scene, |a| scene(a.scene()?.epsilon(a.konst()?))),
    meth(T::Scene, "pixel_epsilon", &[p("pixels", T::Const)], T::Scene, |a| {
        scene(a.scene()?.pixel_epsilon(a.konst()?))
    }),
    meth(T::Scene, "normal_pixel_epsilon", &[p("pixels", T::Const)], T::Scene, |a| {
        scene(a.scene()?.normal_pixel_epsilon(a.konst()?))
    }),
    meth(T::Scene, "over_relaxation", &[p("omega", T::Const)], T::Scene, |a| {
        scene(a.scene()?.over_relaxation(a.konst()?))
    }),
    meth(T::Scene, "membership_hits", &[], T::Scene, |a| scene(a.scene()?.membership_hits())),
    meth(T::Scene, "no_shadows", &[], T::Scene, |a| scene(a.scene()?.no_shadows())),
    meth(T::Scene, "hard_shadows", &[], T::Scene, |a| scene(a.scene()?.hard_shadows())),
    meth(T::Scene, "soft_shadows", &[p("k", T::Const)], T::Scene, |a| scene(a.scene()?.soft_shadows(a.konst()?))),
    meth(T::Scene, "ambient_occlusion", &[p("strength", T::Const)], T::Scene, |a| {
        scene(a.scene()?.ambient_occlusion(a.konst()?))
    }),
    meth(T::Scene, "glow", &[p("color", T::ConstColor)], T::Scene, |a| scene(a.scene()?.glow(a.color()?))),
    meth(T::Scene, "fog", &[p("color", T::ConstColor), p("density", T::Const)], T::Scene, |a| {
        scene(a.scene()?.fog(a.color()?, a.konst()?))
    }),
    meth(T::Scene, "background", &[p("color", T::ConstColor)], T::Scene, |a| scene(a.scene()?.background(a.color()?))),
    meth(T::Scene, "gamma", &[p("gamma", T::Const)], T::Scene, |a| scene(a.scene()?.gamma(a.konst()?))),
    meth(T::Scene, "samples", &[p("n", T::Int)], T::Scene, |a| scene(a.scene()?.samples(a.int()?))),
    meth(T::Scene, "sample_threshold", &[p("threshold", T::Const)], T::Scene, |a| {
        scene(a.scene()?.sample_threshold(a.konst()?))
    }),
];

/// Names that stand alone (not called).
pub(crate) const NAMES: &[&str] = &["t", "PI", "x", "y", "z"];

/// The entries made from declarations: primitives, fractal families, fractal settings and operators.
fn declared() -> &'static [Entry] {
    static DECLARED: OnceLock<Vec<Entry>> = OnceLock::new();
    DECLARED.get_or_init(|| {
        let prims = PRIMS.iter().copied().map(prim_entry);
        let fractals = FRACTALS.iter().copied().map(fractal_entry);
        let settings = Setting::ALL.into_iter().map(setting_entry);
        prims.chain(fractals).chain(settings).chain(OPS.iter().copied().map(op_entry)).collect()
    })
}

/// `fractal.setting(value)`: a number chained onto a fractal.
fn setting_entry(setting: Setting) -> Entry {
    Entry {
        name: setting.name(),
        receiver: Some(Ty::Fractal),
        params: Cow::Owned(vec![Param { name: setting.name(), ty: Ty::Number, many: false }]),
        result: Ty::Fractal,
        build: Build::Setting(setting),
    }
}

/// Every free function: the table above, then the declared primitives, fractal families and combining operators.
pub(crate) fn functions() -> impl Iterator<Item = &'static Entry> {
    FUNCTIONS.iter().chain(declared().iter().filter(|e| e.receiver.is_none()))
}

/// Every method: the table above, then the declared operators that apply to one shape.
pub(crate) fn methods() -> impl Iterator<Item = &'static Entry> {
    METHODS.iter().chain(declared().iter().filter(|e| e.receiver.is_some()))
}

pub(crate) fn function(name: &str) -> Option<&'static Entry> {
    functions().find(|e| e.name == name)
}

pub(crate) fn method(name: &str) -> Option<&'static Entry> {
    methods().find(|e| e.name == name)
}

/// Edit distance (insertions, deletions, substitutions, adjacent swaps) between two short words.
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (d[i - 1][j] + 1).min(d[i][j - 1] + 1).min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = best;
        }
    }
    d[a.len()][b.len()]
}

/// The closest known word to a misspelt one, if it is close enough to be what was meant.
pub(crate) fn suggest<'a>(word: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let len = word.chars().count();
    if len > 64 {
        return None;
    }
    // One edit in three letters: `spher` finds `sphere`, while a one-letter name suggests nothing.
    let limit = ((len + 1) / 3).min(3);
    candidates
        .into_iter()
        .map(|c| (distance(word, c), c))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}
