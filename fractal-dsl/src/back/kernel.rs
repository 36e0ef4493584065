//! The GPU program, written once for every GPU language: the order of its sections, the framing of the lowered scene
//! functions, the functions built on them (normal, ambient occlusion, shadow) and the `render` and `probe` kernels
//! ([`super::Entry`]) that implement [`crate::ray`], or, for another engine, the same functions as a library
//! ([`write_library`]: `sdf`, `sdf_normal`, `sdf_material`, the bound as constants and `sdf_raymarch`, whose march
//! and shading are the `render` kernel's statements). What differs between the languages is a [`Dialect`] (and,
//! for the kernels, a [`KernelDialect`]); each GPU writer (`back/<lang>/writer.rs`) is one impl, and the [`Syntax`]
//! the shared body walker needs follows from it.

use std::fmt::Write;

use super::syntax::{self, Prec, Spelling, Syntax};
use super::{f32_literal, Entry, FrameLayout, Level};
use crate::analyse::SignRefinement;
use crate::ir::{HitEpsilon, Shadows};
use crate::lower::code::{MathFn, Ty};
use crate::lower::trace::Function;
use crate::lower::{LightShape, Program};
use crate::ray::*;

/// Vector component names, by index.
const COMPONENTS: [&str; 4] = ["x", "y", "z", "w"];

/// What one GPU language spells its own way. Statements are returned without indentation and with their `;`.
/// The provided spellings are the C family's (OpenCL C, GLSL, HLSL); a language overrides where it differs.
pub trait Dialect {
    /// The language's name in the generated file's first line.
    fn language(&self) -> &'static str;
    /// The definition of the `Sample` struct (the sample function's result), with a blank line after it.
    fn sample_struct(&self) -> String;

    fn type_name(&self, ty: Ty) -> &'static str;
    fn vec4_type(&self) -> &'static str;
    /// A float constant.
    fn lit(&self, v: f64) -> String {
        f32_literal(v)
    }
    fn bool_lit(&self, v: bool) -> &'static str {
        if v {
            "true"
        } else {
            "false"
        }
    }
    /// An integer constant in arithmetic on an unsigned index.
    fn index_lit(&self, v: u32) -> String {
        format!("{v}u")
    }
    /// `v` (an atom) converted to the scalar type `ty`.
    fn cast(&self, ty: &str, v: &str) -> String {
        format!("{ty}({v})")
    }
    /// A value of vector type `ty` from its comma-separated `components` (one of them fills every component).
    fn construct(&self, ty: &str, components: &str) -> String {
        format!("{ty}({components})")
    }
    /// A scalar passed where a built-in takes a vector of the other operand's size (`clamp`'s bounds).
    fn vector_operand(&self, scalar: &str) -> String {
        scalar.to_string()
    }
    /// Per component of the 3-vector `v`: `if_nonnegative` where it is ≥ 0 (−0 included), else `if_negative`.
    fn select_nonnegative(&self, v: &str, if_nonnegative: &str, if_negative: &str) -> String {
        // OpenCL's and WGSL's vector `select` take (if false, if true, condition).
        let zero = self.construct(self.type_name(Ty::V3), &self.lit(0.0));
        format!("select({if_negative}, {if_nonnegative}, {v} >= {zero})")
    }
    /// The name of linear interpolation, `mix(a, b, t)`.
    fn mix_name(&self) -> &'static str {
        "mix"
    }
    /// The name of a math built-in.
    fn math_name(&self, f: MathFn) -> &'static str;
    /// A call of a math function in lowered code: the built-in, or the language's polyfill for it.
    fn math_call(&self, f: MathFn, args: &[String]) -> String {
        format!("{}({})", self.math_name(f), args.join(", "))
    }
    /// The conditional expression on a scalar condition.
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        format!("{cond} ? {if_true} : {if_false}")
    }
    /// How tightly [`Dialect::select`]'s spelling binds.
    fn select_prec(&self) -> Prec {
        Prec::Ternary
    }
    /// A field of the frame uniform ([`FrameLayout`]), e.g. `origin.xyz` or `lights[2].xyz`.
    fn frame_field(&self, field: &str) -> String {
        format!("frame.{field}")
    }

    /// A declaration with its type spelled out.
    fn declare(&self, name: &str, ty: &str, value: &str, mutable: bool) -> String {
        let konst = if mutable { "" } else { "const " };
        format!("{konst}{ty} {name} = {value};")
    }
    /// A declaration whose type the language may infer from `value`.
    fn local(&self, name: &str, ty: &str, value: &str, mutable: bool) -> String {
        self.declare(name, ty, value, mutable)
    }
    /// A mutable declaration whose value every path assigns later.
    fn uninitialised(&self, name: &str, ty: &str) -> String {
        format!("{ty} {name};")
    }
    /// The opening line of `for` over `i` from 0 while `i < {bound}` (the bound may carry `&& …`).
    fn counted_loop(&self, bound: &str) -> String {
        format!("for (int i = 0; i < {bound}; i++) {{")
    }
    /// The opening line of `for` over the unsigned `index` from 0 while `index < count`.
    fn counted_loop_over(&self, index: &str, count: &str) -> String {
        format!("for (uint {index} = 0u; {index} < {count}; {index}++) {{")
    }

    /// The type of the frame where functions take it as their last argument `frame`; `None` where they read the
    /// frame as a global.
    fn frame_parameter(&self) -> Option<&'static str> {
        None
    }
    /// A function's first line, up to and including its `{`; `params` are (name, type) pairs.
    fn function_open(&self, ret: &str, name: &str, params: &[(&str, &str)]) -> String {
        let params: Vec<String> = params.iter().map(|(name, ty)| format!("{ty} {name}")).collect();
        format!("{ret} {name}({}) {{", params.join(", "))
    }
    /// The statements ending `scene_sample`: return a `Sample` of the named fields' values, in `Sample`'s order.
    fn sample_return(&self, fields: &[(&str, String)]) -> Vec<String> {
        let assignments = fields.iter().map(|(field, value)| format!("s.{field} = {value};"));
        std::iter::once("Sample s;".to_string()).chain(assignments).chain(["return s;".to_string()]).collect()
    }
    /// A module-scope constant.
    fn global_constant(&self, name: &str, ty: &str, value: &str) -> String;
}

/// What a language's compute kernels spell their own way ([`write()`]): resources, entry points and pixel output.
pub trait KernelDialect: Dialect {
    /// Type definitions and resource bindings, written before the helpers.
    fn declarations(&self, out: &mut String, layout: FrameLayout, entry: Entry);
    /// Writes the `render` or `trace` entry point's first lines, through its `{` and the statements naming the
    /// invocation's pixel; returns the pixel's x and y, whose type is [`Self::pixel_index_type`].
    fn render_open(&self, out: &mut String, entry: Entry) -> [&'static str; 2];
    fn pixel_index_type(&self) -> &'static str;
    /// The statements that pack `col` into RGBA8 and store it at the pixel.
    fn pack_pixel(&self) -> &'static [&'static str];
    /// Writes the `probe` entry point's first lines, through its `{` and the statement declaring the point index
    /// `i`; returns the expression for the number of points.
    fn probe_open(&self, out: &mut String) -> &'static str;
    /// The name of the `probe` output array.
    fn probe_output(&self) -> &'static str;
}

/// The [`Syntax`] of the lowered bodies in a GPU language; time and parameters come from the frame, or from the
/// host's globals in a library.
struct GpuSyntax<'a, D>(&'a D, Option<&'a Library>);

impl<D: Dialect> Syntax for GpuSyntax<'_, D> {
    fn type_name(&self, ty: Ty) -> &'static str {
        self.0.type_name(ty)
    }
    fn declare(&self, name: &str, ty: Ty, value: &str, mutable: bool) -> String {
        self.0.declare(name, self.0.type_name(ty), value, mutable)
    }
    fn lit(&self, v: f64) -> String {
        self.0.lit(v)
    }
    fn bool_lit(&self, v: bool) -> String {
        self.0.bool_lit(v).to_string()
    }
    fn int(&self, v: u32) -> String {
        self.0.index_lit(v)
    }
    fn time(&self) -> String {
        match self.1 {
            Some(lib) => lib.time.clone(),
            None => self.0.frame_field("origin.w"),
        }
    }
    fn param(&self, slot: usize) -> String {
        match self.1 {
            Some(lib) => lib.params[slot].clone(),
            None => self.0.frame_field(&format!("params[{}].{}", slot / 4, COMPONENTS[slot % 4])),
        }
    }
    fn orbit(&self) -> Option<String> {
        self.0.frame_parameter().map(|_| "frame".to_string())
    }
    fn orbit_entry(&self, index: &str) -> String {
        // Two entries per slot: entry i is the xy (even i) or zw (odd i) of slot i / 2.
        let d = self.0;
        let i = d.cast(d.type_name(Ty::Int), index);
        let (two, one) = (d.index_lit(2), d.index_lit(1));
        let slot = d.frame_field(&format!("orbit[{i} / {two}]"));
        d.select(&format!("({i} % {two} == {one})"), &format!("{slot}.zw"), &format!("{slot}.xy"))
    }
    fn orbit_last(&self) -> String {
        self.0.frame_field("reference.x")
    }
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String {
        let components = if x == y && y == z { x.to_string() } else { format!("{x}, {y}, {z}") };
        self.0.construct(self.0.type_name(Ty::V3), &components)
    }
    fn make_pair(&self, distance: &str, trap: &str) -> String {
        self.0.construct(self.0.type_name(Ty::Pair), &format!("{distance}, {trap}"))
    }
    fn comp(&self, v: &str, _ty: Ty, i: u8) -> String {
        format!("{v}.{}", COMPONENTS[i as usize])
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        self.0.math_name(f)
    }
    fn math(&self, f: MathFn, args: &[String]) -> String {
        self.0.math_call(f, args)
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        self.0.select(cond, if_true, if_false)
    }
    fn select_prec(&self) -> Prec {
        self.0.select_prec()
    }
    fn if_open(&self, cond: &str) -> String {
        format!("if {} {{", parenthesized(cond))
    }
    fn break_if(&self, cond: &str) -> String {
        format!("if {} {{ break; }}", parenthesized(cond))
    }
    fn loop_open(&self, count: &str, depth: usize) -> String {
        self.0.counted_loop_over(&format!("i{depth}"), count)
    }
}

/// Writes traced leaf functions in `dialect`, each followed by a blank line.
pub fn write_functions<D: Dialect>(functions: &[Function], dialect: &D) -> String {
    let syn = GpuSyntax(dialect, None);
    let mut out = String::new();
    for f in functions {
        // An orbit parameter is the frame, where the language passes it (see `Syntax::orbit`).
        let params: Vec<(&str, &str)> = f
            .params
            .iter()
            .filter_map(|&(name, ty)| match ty {
                Ty::Orbit => dialect.frame_parameter().map(|frame| ("frame", frame)),
                _ => Some((name, dialect.type_name(ty))),
            })
            .collect();
        let _ = writeln!(out, "{}", dialect.function_open(dialect.type_name(f.returns), f.name(), &params));
        let spelling = Spelling::new(&f.body, &syn, &[f.result]);
        spelling.write(&mut out, Level(1));
        let _ = writeln!(out, "{}return {};", Level(1), spelling.value(f.result));
        out.push_str("}\n\n");
    }
    out
}

/// Writes the complete GPU program for `entry` in `dialect`.
pub fn write<D: KernelDialect>(program: &Program, entry: Entry, dialect: &D) -> String {
    let mut k = Kernel { p: program, d: dialect, lib: None, traced: entry == Entry::Trace, out: String::new() };
    let what = match entry {
        Entry::Render => "render kernel",
        Entry::Probe => "probe kernel",
        Entry::Trace => "trace kernel",
    };
    let _ = writeln!(
        k.out,
        "// fractal: {} {what}, generated from a scene description. Edit the scene, not this file.\n",
        dialect.language()
    );
    dialect.declarations(&mut k.out, program.layout(), entry);
    k.leaf_functions();
    k.scene_functions();
    match entry {
        Entry::Render | Entry::Trace => {
            k.normal();
            if let Some(strength) = program.settings.ambient_occlusion {
                k.ambient_occlusion(strength);
            }
            if program.settings.shadows != Shadows::None {
                k.shadow();
            }
            k.render(dialect, entry);
        }
        Entry::Probe => k.probe(dialect),
    }
    k.out
}

/// What a library's host provides in place of the frame: the expressions reading its time and parameters (globals
/// the host sets) and the lights' values, constant in a library.
#[derive(Clone, Debug, PartialEq)]
pub struct Library {
    /// The time in seconds.
    pub time: String,
    /// Each parameter, in slot order.
    pub params: Vec<String>,
    /// The value of each of the program's lights, in order.
    pub lights: Vec<LightValue>,
    /// Text written after the first comment line and before the `Sample` struct: the host's declarations.
    pub prologue: String,
}

/// A light's value in a library, as the frame would hold it ([`FrameLayout`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightValue {
    /// Unit direction towards a directional light, or a point light's position.
    pub position: [f64; 3],
    /// Colour · intensity.
    pub radiance: [f64; 3],
}

/// The functions of a library ([`write_library`]) an engine calls, by name.
pub mod library {
    /// `float sdf(vec3 p)`: the scene's distance estimate.
    pub const SDF: &str = "sdf";
    /// `vec3 sdf_normal(vec3 p)`: the unit surface normal (tetrahedral central differences of [`SDF`] at
    /// [`NORMAL_EPSILON`]).
    pub const NORMAL: &str = "sdf_normal";
    /// `vec3 sdf_material(vec3 p)`: the albedo of the surface at p.
    pub const MATERIAL: &str = "sdf_material";
    /// `vec4 sdf_raymarch(vec3 ro, vec3 rd, float footprint)`: the viewer's march and shading along the unit ray
    /// (ro, rd) whose pixel spans `footprint` radians (2·tan(fov/2)/height); xyz = the linear colour before clamping
    /// and gamma, w = the hit's ray distance t, or −1 for a miss.
    pub const RAYMARCH: &str = "sdf_raymarch";
    /// `vec3 sdf_display(vec3 col)`: clamps a linear colour and encodes it with the scene's gamma, as the viewer
    /// does before writing a pixel (for targets that are not sRGB).
    pub const DISPLAY: &str = "sdf_display";
    /// Constant: the scene's bound, min corner (a box of ±max distance for an unbounded scene).
    pub const BOUND_MIN: &str = "SDF_BOUND_MIN";
    /// Constant: the bound's max corner.
    pub const BOUND_MAX: &str = "SDF_BOUND_MAX";
    /// Constant: the centre of the bounding sphere (the box's centre).
    pub const BOUND_CENTER: &str = "SDF_BOUND_CENTER";
    /// Constant: the radius of the bounding sphere (half the box's diagonal).
    pub const BOUND_RADIUS: &str = "SDF_BOUND_RADIUS";
    /// Constant: the offset [`NORMAL`] differences over.
    pub const NORMAL_EPSILON: &str = "SDF_NORMAL_EPSILON";
    /// Constant: the largest ray distance [`RAYMARCH`] marches.
    pub const MAX_DISTANCE: &str = "SDF_MAX_DISTANCE";

    /// The corners [`BOUND_MIN`] and [`BOUND_MAX`] hold: the program's bound, or ±max distance for an unbounded
    /// scene.
    pub fn bound(program: &crate::lower::Program) -> ([f64; 3], [f64; 3]) {
        let reach = program.settings.max_distance;
        program.bound.map_or(([-reach; 3], [reach; 3]), |b| (b.min, b.max))
    }
}

/// Writes `program` as a function library in `dialect` ([`library`] names its functions and constants), with the
/// host values `lib` names. The program should be lowered without a perturbation reference (a library has no frame
/// to hold its orbit).
pub fn write_library<D: Dialect>(program: &Program, lib: &Library, dialect: &D) -> String {
    let mut k = Kernel { p: program, d: dialect, lib: Some(lib), traced: false, out: String::new() };
    let _ = writeln!(
        k.out,
        "// fractal: {} SDF library, generated from a scene description. Edit the scene, not this file.\n",
        dialect.language()
    );
    k.out.push_str(&lib.prologue);
    k.out.push_str(&dialect.sample_struct());
    k.library_constants();
    k.leaf_functions();
    k.scene_functions();
    k.normal();
    if let Some(strength) = program.settings.ambient_occlusion {
        k.ambient_occlusion(strength);
    }
    if program.settings.shadows != Shadows::None {
        k.shadow();
    }
    k.library_functions();
    k.out
}

/// A condition as C-like `if`s need it: in parentheses (a comparison spelled in place already is).
fn parenthesized(cond: &str) -> String {
    // Already wrapped when the opening parenthesis closes at the very end (not `(a) || (b)`).
    let mut depth = 0usize;
    let wrapped = cond.starts_with('(')
        && cond.char_indices().all(|(i, ch)| {
            match ch {
                '(' => depth += 1,
                ')' => depth = depth.saturating_sub(1),
                _ => {}
            }
            depth > 0 || i == cond.len() - 1
        });
    if wrapped {
        cond.to_string()
    } else {
        format!("({cond})")
    }
}

/// A call of a built-in every GPU language spells alike (`clamp`, `mix`).
fn builtin(name: &str, args: &[&str]) -> String {
    format!("{name}({})", args.join(", "))
}

struct Kernel<'a, D> {
    p: &'a Program,
    d: &'a D,
    /// Where the program's host values come from in a library; `None` in a kernel (the frame).
    lib: Option<&'a Library>,
    /// Whether the render kernel also writes each pixel's march to [`TRACES`] ([`Entry::Trace`]).
    traced: bool,
    out: String,
}

/// The `trace` kernel's per-pixel output array ([`Entry::Trace`]).
const TRACES: &str = "traces";

impl<D: Dialect> Kernel<'_, D> {
    fn line(&mut self, level: Level, text: &str) {
        let _ = writeln!(self.out, "{level}{text}");
    }
    fn lit(&self, v: f64) -> String {
        self.d.lit(v)
    }
    fn float(&self) -> &'static str {
        self.d.type_name(Ty::F)
    }
    fn vec3(&self) -> &'static str {
        self.d.type_name(Ty::V3)
    }
    /// A 3-vector constant, every component spelled.
    fn vec3_lit(&self, c: [f64; 3]) -> String {
        self.d.construct(self.vec3(), &format!("{}, {}, {}", self.lit(c[0]), self.lit(c[1]), self.lit(c[2])))
    }
    fn math(&self, f: MathFn, args: &[&str]) -> String {
        format!("{}({})", self.d.math_name(f), args.join(", "))
    }
    fn constant(&self, name: &str, ty: &str, value: &str) -> String {
        self.d.local(name, ty, value, false)
    }
    fn variable(&self, name: &str, ty: &str, value: &str) -> String {
        self.d.local(name, ty, value, true)
    }

    /// Whether a function that reads the frame when `reads_frame` takes it as an argument (never in a library,
    /// which reads the host's globals instead).
    fn passes_frame(&self, reads_frame: bool) -> bool {
        reads_frame && self.lib.is_none() && self.d.frame_parameter().is_some()
    }
    /// A call of a function that reads the frame when `reads_frame`.
    fn call(&self, name: &str, args: &str, reads_frame: bool) -> String {
        let frame = if self.passes_frame(reads_frame) { ", frame" } else { "" };
        format!("{name}({args}{frame})")
    }
    fn de(&self, p: &str) -> String {
        self.call("scene_de", p, self.p.distance_reads_frame)
    }
    /// Writes the first line of a function that reads the frame when `reads_frame`.
    fn function_open(&mut self, ret: &str, name: &str, params: &[(&str, &str)], reads_frame: bool) {
        let mut params = params.to_vec();
        if let Some(frame) = self.d.frame_parameter().filter(|_| self.passes_frame(reads_frame)) {
            params.push(("frame", frame));
        }
        let open = self.d.function_open(ret, name, &params);
        self.line(Level(0), &open);
    }
    fn function_close(&mut self) {
        self.out.push_str("}\n\n");
    }

    /// The traced leaf functions the scene calls, each once.
    fn leaf_functions(&mut self) {
        self.out.push_str(&write_functions(&self.p.functions, self.d));
    }

    fn scene_functions(&mut self) {
        let (p, syn) = (self.p, GpuSyntax(self.d, self.lib));
        let (float, vec3) = (self.float(), self.vec3());
        self.function_open(float, "scene_de", &[("p", vec3)], p.distance_reads_frame);
        let spelling = Spelling::new(&p.distance, &syn, &[p.distance_result]);
        spelling.write(&mut self.out, Level(1));
        let result = spelling.value(p.distance_result);
        self.line(Level(1), &format!("return {result};"));
        self.function_close();

        let mut params = vec![("p", vec3)];
        if p.reference.is_some() {
            params.push((crate::lower::REFERENCE_OFFSET, vec3));
        }
        self.function_open("Sample", "scene_sample", &params, p.sample_reads_frame);
        let spelling = Spelling::new(&p.sample, &syn, &p.sample_result.all());
        spelling.write(&mut self.out, Level(1));
        let fields: Vec<(&str, String)> =
            syntax::sample_fields(&p.sample_result).into_iter().map(|(field, v)| (field, spelling.value(v))).collect();
        for statement in self.d.sample_return(&fields) {
            self.line(Level(1), &statement);
        }
        self.function_close();
    }

    fn normal(&mut self) {
        let (float, vec3) = (self.float(), self.vec3());
        let l1 = Level(1);
        self.function_open(vec3, "scene_normal", &[("p", vec3), ("e", float)], self.p.distance_reads_frame);
        let k = [[1.0, -1.0, -1.0], [-1.0, -1.0, 1.0], [-1.0, 1.0, -1.0], [1.0, 1.0, 1.0]];
        for (i, ki) in k.into_iter().enumerate() {
            self.line(l1, &self.constant(&format!("k{i}"), vec3, &self.vec3_lit(ki)));
        }
        let terms: Vec<String> = (0..4).map(|i| format!("k{i} * {}", self.de(&format!("p + k{i} * e")))).collect();
        self.line(l1, &self.constant("g", vec3, &terms.join(" + ")));
        self.line(l1, &self.constant("len", float, "length(g)"));
        let up = self.vec3_lit([0.0, 1.0, 0.0]);
        let normal = self.d.select(&format!("len > {}", self.lit(0.0)), "g / len", &up);
        self.line(l1, &format!("return {normal};"));
        self.function_close();
    }

    fn ambient_occlusion(&mut self, strength: f64) {
        let (float, vec3) = (self.float(), self.vec3());
        let (l1, l2) = (Level(1), Level(2));
        self.function_open(float, "scene_ao", &[("p", vec3), ("n", vec3)], self.p.distance_reads_frame);
        self.line(l1, &self.variable("occ", float, &self.lit(0.0)));
        self.line(l1, &self.variable("weight", float, &self.lit(1.0)));
        self.line(l1, &self.d.counted_loop(&AO_SAMPLES.to_string()));
        let h = format!(
            "{} + {} * {} / {}",
            self.lit(AO_START),
            self.lit(AO_SPAN),
            self.d.cast(float, "i"),
            self.lit((AO_SAMPLES - 1) as f64)
        );
        self.line(l2, &self.constant("h", float, &h));
        self.line(l2, &format!("occ += (h - {}) * weight;", self.de("p + n * h")));
        self.line(l2, &format!("weight *= {};", self.lit(0.95)));
        self.line(l1, "}");
        let occlusion = format!("{} - {} * occ", self.lit(1.0), self.lit(3.0 * strength));
        let clamped = builtin("clamp", &[&occlusion, &self.lit(0.0), &self.lit(1.0)]);
        self.line(l1, &format!("return {clamped};"));
        self.function_close();
    }

    fn shadow(&mut self) {
        let (float, vec3) = (self.float(), self.vec3());
        let (l1, l2, l3) = (Level(1), Level(2), Level(3));
        let params = [("ro", vec3), ("rd", vec3), ("limit", float), ("eps", float)];
        self.function_open(float, "scene_shadow", &params, self.p.distance_reads_frame);
        let soft = match self.p.settings.shadows {
            Shadows::Soft(k) => Some(k),
            _ => None,
        };
        if soft.is_some() {
            self.line(l1, &self.variable("res", float, &self.lit(1.0)));
            self.line(l1, &self.variable("t", float, &format!("{} * eps", self.lit(2.0))));
        } else {
            self.line(l1, &self.variable("t", float, &self.lit(0.0)));
        }
        self.line(l1, &self.d.counted_loop(&format!("{} && t < limit", self.p.settings.max_steps)));
        self.line(l2, &self.constant("d", float, &self.de("ro + rd * t")));
        self.line(l2, "if (d < eps) {");
        self.line(l3, &format!("return {};", self.lit(0.0)));
        self.line(l2, "}");
        if let Some(k) = soft {
            let penumbra = format!("{} * d / t", self.lit(k));
            self.line(l2, &format!("res = {};", self.math(MathFn::Min, &["res", &penumbra])));
        }
        self.line(l2, "t += d;");
        self.line(l1, "}");
        if soft.is_some() {
            self.line(l1, &format!("return res * res * ({} - {} * res);", self.lit(3.0), self.lit(2.0)));
        } else {
            self.line(l1, &format!("return {};", self.lit(1.0)));
        }
        self.function_close();
    }

    /// Whether the march used all its steps without hitting or leaving the ray: the trace kernel's flag.
    fn out_of_steps(&self) -> String {
        format!("!hit && steps_taken >= {} && t <= t_far", self.lit(f64::from(self.p.settings.max_steps)))
    }

    /// Pixel footprint per unit distance: the frame's, or a library function's argument `footprint`.
    fn footprint(&self) -> String {
        match self.lib {
            Some(_) => "footprint".to_string(),
            None => self.d.frame_field("forward.w"),
        }
    }
    /// Light i's direction or position, and its colour · intensity: the frame's, or a library's constants.
    fn light(&self, i: usize) -> (String, String) {
        match self.lib {
            Some(lib) => (self.vec3_lit(lib.lights[i].position), self.vec3_lit(lib.lights[i].radiance)),
            None => (
                self.d.frame_field(&format!("lights[{}].xyz", 2 * i)),
                self.d.frame_field(&format!("lights[{}].xyz", 2 * i + 1)),
            ),
        }
    }

    fn render<K: KernelDialect>(&mut self, kernel: &K, entry: Entry) {
        let d = self.d;
        let float = self.float();
        let (l1, l2) = (Level(1), Level(2));
        let (two, half) = (self.lit(2.0), self.lit(0.5));

        // 1. The ray through the pixel's centre.
        let [px, py] = kernel.render_open(&mut self.out, entry);
        let index = kernel.pixel_index_type();
        self.line(l1, &self.constant("w", index, &d.cast(index, &d.frame_field("right.w"))));
        self.line(l1, &self.constant("h", index, &d.cast(index, &d.frame_field("up.w"))));
        self.line(l1, &format!("if ({px} >= w || {py} >= h) {{"));
        self.line(l2, "return;");
        self.line(l1, "}");
        if self.traced {
            self.line(l1, &self.constant("pixel", index, &format!("{} * ({py} * w + {px})", d.index_lit(3))));
        }
        let (w, h) = (d.cast(float, "w"), d.cast(float, "h"));
        let u = format!("({two} * ({} + {half}) - {w}) / {h}", d.cast(float, px));
        let v = format!("-({two} * ({} + {half}) - {h}) / {h}", d.cast(float, py));
        self.line(l1, &self.constant("u", float, &u));
        self.line(l1, &self.constant("v", float, &v));
        self.line(l1, &self.constant("ro", self.vec3(), &d.frame_field("origin.xyz")));
        let rd = format!(
            "normalize({} + u * {} + v * {})",
            d.frame_field("forward.xyz"),
            d.frame_field("right.xyz"),
            d.frame_field("up.xyz")
        );
        self.line(l1, &self.constant("rd", self.vec3(), &rd));

        // 2.–6. March and shade.
        self.march();
        if self.traced {
            let (zero, one) = (self.lit(0.0), self.lit(1.0));
            let flag = |cond: &str| d.select(cond, &one, &zero);
            let vec4 = d.vec4_type();
            let position = d.construct(vec4, &format!("{}, t", d.construct(self.vec3(), &zero)));
            self.line(l1, &format!("{TRACES}[pixel] = {position};"));
            let march = format!("steps_taken, {}, {}, {zero}", flag("hit"), flag(&self.out_of_steps()));
            self.line(l1, &format!("{TRACES}[pixel + {}] = {};", d.index_lit(1), d.construct(vec4, &march)));
        }
        self.shade();
        if self.traced {
            let colour = d.construct(d.vec4_type(), &format!("col, {}", self.lit(0.0)));
            self.line(l1, &format!("{TRACES}[pixel + {}] = {colour};", d.index_lit(2)));
        }

        // 7. Output.
        self.display();
        for statement in kernel.pack_pixel() {
            self.line(l1, statement);
        }
        self.out.push_str("}\n");
    }

    /// Steps 2 and 3 of [`crate::ray`] from `ro` along the unit `rd`: declares and sets `t`, `t_far`, `hit`,
    /// `eps` and (with glow) `glow`.
    fn march(&mut self) {
        let (d, p) = (self.d, self.p);
        let s = &p.settings;
        let (float, vec3) = (self.float(), self.vec3());
        let (l1, l2, l3) = (Level(1), Level(2), Level(3));
        let (zero, one) = (self.lit(0.0), self.lit(1.0));

        // 2. Clip to the scene's bound.
        self.line(l1, &self.variable("t", float, &zero));
        self.line(l1, &self.variable("t_far", float, &self.lit(s.max_distance)));
        if let Some(b) = p.bound {
            self.line(l1, "{");
            self.line(l2, "// Clip the ray to the scene's bound: no marching through empty space.");
            let min_direction = d.construct(vec3, &self.lit(MIN_DIRECTION));
            let m = self.math(MathFn::Max, &[&self.math(MathFn::Abs, &["rd"]), &min_direction]);
            self.line(l2, &self.constant("m", vec3, &m));
            self.line(l2, &self.constant("safe", vec3, &d.select_nonnegative("rd", "m", "-m")));
            self.line(l2, &self.constant("t0", vec3, &format!("({} - ro) / safe", self.vec3_lit(b.min))));
            self.line(l2, &self.constant("t1", vec3, &format!("({} - ro) / safe", self.vec3_lit(b.max))));
            self.line(l2, &self.constant("tn", vec3, &self.math(MathFn::Min, &["t0", "t1"])));
            self.line(l2, &self.constant("tf", vec3, &self.math(MathFn::Max, &["t0", "t1"])));
            let fold = |f: MathFn, v: &str, last: &str| {
                let xy = self.math(f, &[&format!("{v}.x"), &format!("{v}.y")]);
                let xyz = self.math(f, &[&xy, &format!("{v}.z")]);
                self.math(f, &[&xyz, last])
            };
            let (near, far) = (fold(MathFn::Max, "tn", &zero), fold(MathFn::Min, "tf", "t_far"));
            self.line(l2, &format!("t = {near};"));
            self.line(l2, &format!("t_far = {far};"));
            self.line(l1, "}");
        }

        // 3. March.
        self.line(l1, &self.variable("hit", d.type_name(Ty::Bool), d.bool_lit(false)));
        self.line(l1, &self.variable("eps", float, &zero));
        if s.glow.is_some() {
            self.line(l1, &self.variable("glow", float, &zero));
        }
        let eps = match s.epsilon {
            HitEpsilon::Fixed(e) => self.lit(e),
            HitEpsilon::Pixel(k) => format!("{} * {} * t", self.lit(k), self.footprint()),
        };
        // Over-relaxation only where the scene asks for it: a plain march is the loop below without it.
        let relaxed = s.over_relaxation > 1.0;
        if relaxed {
            self.line(l1, &self.variable("omega", float, &self.lit(s.over_relaxation)));
            self.line(l1, &self.variable("previous", float, &zero));
            self.line(l1, &self.variable("stride", float, &zero));
        }
        if p.refine.is_some() {
            self.line(l1, &self.variable("t_last", float, "t"));
            self.line(l1, &self.variable("d_last", float, &zero));
        }
        if self.traced {
            self.line(l1, &self.variable("steps_taken", float, &zero));
        }
        self.line(l1, &d.counted_loop(&format!("{} && t <= t_far", s.max_steps)));
        self.line(l2, &self.constant("d", float, &self.de("ro + rd * t")));
        if self.traced {
            self.line(l2, &format!("steps_taken = steps_taken + {one};"));
        }
        let spacing = format!("{} * t", self.lit(T_SPACING));
        self.line(l2, &format!("eps = {};", self.math(MathFn::Max, &[&eps, &spacing])));
        let abs_d = self.math(MathFn::Abs, &["d"]);
        // The step this iteration takes once the hit test has passed over it.
        let step = if relaxed { "stride" } else { "advance" };
        if p.refine.is_some() && !relaxed {
            self.line(l2, &self.variable("advance", float, "d"));
        }
        let hit_test = |w: &mut Self, level: Level| {
            w.line(level, "if (d < eps) {");
            if p.refine.is_some() {
                w.refine(level.next(), step);
                if relaxed {
                    w.line(level, "} else {");
                    w.line(level.next(), "stride = d * omega;");
                }
            } else {
                w.line(level.next(), &format!("hit = {};", d.bool_lit(true)));
                w.line(level.next(), "break;");
            }
            w.line(level, "}");
        };
        if relaxed {
            // The unbounding spheres of this point and the last do not overlap: the relaxed step may have passed
            // the surface, so take back its excess and go on with plain steps.
            self.line(l2, &format!("if (omega > {one} && {abs_d} + previous < stride) {{"));
            self.line(l3, "stride = stride - omega * stride;");
            self.line(l3, &format!("omega = {one};"));
            self.line(l2, "} else {");
            hit_test(self, l3);
            if p.refine.is_none() {
                self.line(l3, "stride = d * omega;");
            }
            self.line(l2, "}");
            self.line(l2, &format!("previous = {abs_d};"));
        } else {
            hit_test(self, l2);
        }
        if s.glow.is_some() {
            self.line(l2, &format!("glow += {one} / ({one} + {} * d * d);", self.lit(GLOW_FALLOFF)));
        }
        if p.refine.is_some() {
            self.line(l2, "t_last = t;");
            self.line(l2, "d_last = d;");
        }
        let advance = if p.refine.is_some() || relaxed { format!("t += {step};") } else { "t += d;".to_string() };
        self.line(l2, &advance);
        self.line(l1, "}");
    }

    /// Step 3b of [`crate::ray`], the sign refinement, where `d < eps` (inside the march's loop): the hit where
    /// `d ≤ 0`, refined on its bracket; otherwise the sign step, into `step`.
    fn refine(&mut self, l1: Level, step: &str) {
        let d = self.d;
        let float = self.float();
        let (l2, l3, l4, l5) = (l1.next(), l1.next().next(), Level(l1.0 + 3), Level(l1.0 + 4));
        let (zero, one, half) = (self.lit(0.0), self.lit(1.0), self.lit(0.5));
        let false_position = "a + (b - a) * (fa / (fa - fb))";
        let why = match self.p.refine {
            Some(SignRefinement::Membership) => {
                "// Hits on the fractals' drawn sets: the estimate's sign is membership."
            }
            _ => "// A displaced distance is divided by its slope bound, but its sign is exact: a hit is a crossing.",
        };
        self.line(l1, why);
        self.line(l1, &format!("if (d <= {zero}) {{"));
        self.line(l2, &format!("if (d_last > {zero}) {{"));
        for (name, value) in [("a", "t_last"), ("fa", "d_last"), ("b", "t"), ("fb", "d"), ("side", &zero)] {
            self.line(l3, &self.variable(name, float, value));
        }
        self.line(l3, &d.counted_loop_over("k", &d.index_lit(REFINE_STEPS)));
        self.line(l4, &self.constant("m", float, false_position));
        self.line(l4, &self.constant("fm", float, &self.de("ro + rd * m")));
        self.line(l4, &format!("if (fm <= {zero}) {{"));
        self.line(l5, "b = m;");
        self.line(l5, "fb = fm;");
        self.line(l5, &format!("if (side < {zero}) {{"));
        self.line(l5.next(), &format!("fa = fa * {half};"));
        self.line(l5, "}");
        self.line(l5, &format!("side = -{one};"));
        self.line(l4, "} else {");
        self.line(l5, "a = m;");
        self.line(l5, "fa = fm;");
        self.line(l5, &format!("if (side > {zero}) {{"));
        self.line(l5.next(), &format!("fb = fb * {half};"));
        self.line(l5, "}");
        self.line(l5, &format!("side = {one};"));
        self.line(l4, "}");
        self.line(l3, "}");
        self.line(l3, &format!("t = {false_position};"));
        self.line(l2, "}");
        self.line(l2, &format!("hit = {};", d.bool_lit(true)));
        self.line(l2, "break;");
        self.line(l1, "}");
        if self.p.refine == Some(SignRefinement::Membership) {
            self.line(l1, &format!("{step} = {} * eps;", self.lit(MEMBERSHIP_STEP)));
        } else {
            self.line(l1, &format!("{step} = eps;"));
            self.line(l1, "if (d_last > d) {");
            let toward = format!("{} * d * (t - t_last) / (d_last - d)", self.lit(PROBE_SHARE));
            self.line(l2, &format!("{step} = {};", self.math(MathFn::Max, &[step, &toward])));
            self.line(l1, "}");
            let reach = format!("{} * eps", self.lit(PROBE_REACH));
            self.line(l1, &format!("{step} = {};", self.math(MathFn::Min, &[step, &reach])));
        }
        if self.p.settings.over_relaxation > 1.0 {
            self.line(l1, &format!("omega = {one};"));
        }
    }

    /// Steps 4 to 6 of [`crate::ray`] after [`Self::march`]: declares and sets `col`, the linear colour.
    fn shade(&mut self) {
        let (d, p) = (self.d, self.p);
        let s = &p.settings;
        let (float, vec3) = (self.float(), self.vec3());
        let (l1, l2, l3) = (Level(1), Level(2), Level(3));
        let (zero, one, two) = (self.lit(0.0), self.lit(1.0), self.lit(2.0));

        // 4. Hit shading.
        self.line(l1, &d.uninitialised("col", vec3));
        self.line(l1, "if (hit) {");
        self.line(l2, &self.constant("p", vec3, "ro + rd * t"));
        let distance_frame = p.distance_reads_frame;
        let tap = match s.normal_epsilon {
            Some(k) => format!("{} * {} * t", self.lit(k), self.footprint()),
            None if p.refine.is_some() => format!("eps * {}", self.lit(REFINED_NORMAL_SHARE)),
            None => "eps".to_string(),
        };
        let n = self.call("scene_normal", &format!("p, {tap}"), distance_frame);
        self.line(l2, &self.constant("n", vec3, &n));
        if self.traced {
            let normal = d.construct(d.vec4_type(), "n, t");
            self.line(l2, &format!("{TRACES}[pixel] = {normal};"));
        }
        // A perturbed pattern reads the hit relative to the camera, rd·t: exact to t's precision at any zoom.
        let sample_args = if p.reference.is_some() { "p, rd * t" } else { "p" };
        let sample = self.call("scene_sample", sample_args, p.sample_reads_frame);
        self.line(l2, &self.constant("m", "Sample", &sample));
        if s.ambient_occlusion.is_some() {
            let ao = self.call("scene_ao", "p, n", distance_frame);
            self.line(l2, &format!("col = m.albedo * (m.ambient * {ao});"));
        } else {
            self.line(l2, "col = m.albedo * m.ambient;");
        }
        for (i, shape) in p.lights.iter().enumerate() {
            let (position, color) = self.light(i);
            self.line(l2, "{");
            match shape {
                LightShape::Directional => {
                    self.line(l3, &self.constant("l", vec3, &position));
                    self.line(l3, &self.constant("radiance", vec3, &color));
                    self.line(l3, &self.constant("limit", float, &self.lit(s.max_distance)));
                }
                LightShape::Point => {
                    self.line(l3, &self.constant("to_light", vec3, &format!("{position} - p")));
                    self.line(l3, &self.constant("limit", float, "length(to_light)"));
                    self.line(l3, &self.constant("l", vec3, "to_light / limit"));
                    self.line(l3, &self.constant("radiance", vec3, &format!("{color} / (limit * limit)")));
                }
            }
            self.line(l3, &self.constant("ndl", float, &self.math(MathFn::Max, &["dot(n, l)", &zero])));
            let shade = if s.shadows != Shadows::None {
                self.line(l3, &self.variable("shadow", float, &one));
                self.line(l3, &format!("if (ndl > {zero}) {{"));
                let shadow =
                    self.call("scene_shadow", &format!("p + n * ({two} * eps), l, limit, eps"), distance_frame);
                self.line(Level(4), &format!("shadow = {shadow};"));
                self.line(l3, "}");
                " * shadow"
            } else {
                ""
            };
            self.line(l3, &format!("col += m.albedo * (m.diffuse * ndl) * radiance{shade};"));
            if p.specular {
                self.line(l3, &self.constant("hv", vec3, "normalize(l - rd)"));
                let highlight =
                    self.math(MathFn::Pow, &[&self.math(MathFn::Max, &["dot(n, hv)", &zero]), "m.shininess"]);
                self.line(l3, &format!("col += (m.specular * {highlight}) * radiance{shade};"));
            }
            self.line(l2, "}");
        }
        if let Some(fog) = &s.fog {
            let attenuation = format!("{one} - exp({} * t)", self.lit(-fog.density));
            let fogged = format!("{}(col, {}, {attenuation})", d.mix_name(), self.vec3_lit(fog.color));
            self.line(l2, &format!("col = {fogged};"));
        }

        // 5. Miss.
        self.line(l1, "} else {");
        self.line(l2, &format!("col = {};", self.vec3_lit(s.background)));
        self.line(l1, "}");

        // 6. Glow.
        if let Some(g) = s.glow {
            let saturation = self.math(MathFn::Min, &[&format!("glow / {}", self.lit(GLOW_NORM)), &one]);
            self.line(l1, &format!("col += {} * {saturation};", self.vec3_lit(g)));
        }
    }

    /// Step 7 of [`crate::ray`] up to packing: `col` clamped to [0, 1] and gamma-encoded in place.
    fn display(&mut self) {
        let d = self.d;
        let s = &self.p.settings;
        let (zero, one) = (self.lit(0.0), self.lit(1.0));
        let clamped = builtin("clamp", &["col", &d.vector_operand(&zero), &d.vector_operand(&one)]);
        self.line(Level(1), &format!("col = {clamped};"));
        if s.gamma == 2.0 {
            self.line(Level(1), &format!("col = {};", self.math(MathFn::Sqrt, &["col"])));
        } else if s.gamma != 1.0 {
            let exponent = self.d.construct(self.vec3(), &self.lit(1.0 / s.gamma));
            self.line(Level(1), &format!("col = {};", self.math(MathFn::Pow, &["col", &exponent])));
        }
    }

    /// The bound and the constants the library's functions use ([`library`]).
    fn library_constants(&mut self) {
        let (p, d) = (self.p, self.d);
        let (float, vec3) = (self.float(), self.vec3());
        let reach = p.settings.max_distance;
        let (min, max) = library::bound(p);
        let center: [f64; 3] = std::array::from_fn(|i| 0.5 * (min[i] + max[i]));
        let radius = (0..3).map(|i| 0.5 * (max[i] - min[i])).map(|h| h * h).sum::<f64>().sqrt();
        let normal_epsilon = match p.settings.epsilon {
            HitEpsilon::Fixed(e) => e,
            // A pixel epsilon has no fixed size: a thousandth of the bound's radius resolves the surface's shape.
            HitEpsilon::Pixel(_) => 1e-3 * radius.min(reach),
        };
        for (name, ty, value) in [
            (library::BOUND_MIN, vec3, self.vec3_lit(min)),
            (library::BOUND_MAX, vec3, self.vec3_lit(max)),
            (library::BOUND_CENTER, vec3, self.vec3_lit(center)),
            (library::BOUND_RADIUS, float, self.lit(radius)),
            (library::NORMAL_EPSILON, float, self.lit(normal_epsilon)),
            (library::MAX_DISTANCE, float, self.lit(reach)),
        ] {
            self.line(Level(0), &d.global_constant(name, ty, &value));
        }
        self.out.push('\n');
    }

    /// The functions an engine calls ([`library`]), on the scene functions.
    fn library_functions(&mut self) {
        let (float, vec3, vec4) = (self.float(), self.vec3(), self.d.vec4_type());
        let l1 = Level(1);
        self.function_open(float, library::SDF, &[("p", vec3)], false);
        self.line(l1, &format!("return {};", self.de("p")));
        self.function_close();

        self.function_open(vec3, library::NORMAL, &[("p", vec3)], false);
        let normal = self.call("scene_normal", &format!("p, {}", library::NORMAL_EPSILON), false);
        self.line(l1, &format!("return {normal};"));
        self.function_close();

        self.function_open(vec3, library::MATERIAL, &[("p", vec3)], false);
        self.line(l1, &format!("return {}.albedo;", self.call("scene_sample", "p", false)));
        self.function_close();

        self.function_open(vec4, library::RAYMARCH, &[("ro", vec3), ("rd", vec3), ("footprint", float)], false);
        self.march();
        self.shade();
        let t = self.d.select("hit", "t", &self.lit(-1.0));
        let t = if self.d.select_prec() == Prec::Atom { t } else { format!("({t})") };
        self.line(l1, &format!("return {};", self.d.construct(vec4, &format!("col, {t}"))));
        self.function_close();

        self.function_open(vec3, library::DISPLAY, &[("colour", vec3)], false);
        self.line(l1, &self.variable("col", vec3, "colour"));
        self.display();
        self.line(l1, "return col;");
        self.function_close();
    }

    fn probe<K: KernelDialect>(&mut self, kernel: &K) {
        let (d, p) = (self.d, self.p);
        let (l1, l2) = (Level(1), Level(2));
        let count = kernel.probe_open(&mut self.out);
        self.line(l1, &format!("if (i >= {count}) {{"));
        self.line(l2, "return;");
        self.line(l1, "}");
        self.line(l1, &self.constant("p", self.vec3(), "points[i].xyz"));
        let sample_args =
            if p.reference.is_some() { format!("p, p - {}", d.frame_field("origin.xyz")) } else { "p".to_string() };
        self.line(l1, &self.constant("s", "Sample", &self.call("scene_sample", &sample_args, p.sample_reads_frame)));
        let (out, two, one, vec4) = (kernel.probe_output(), d.index_lit(2), d.index_lit(1), d.vec4_type());
        let lighting = d.construct(vec4, &format!("{}, s.ambient, s.diffuse, s.specular", self.de("p")));
        self.line(l1, &format!("{out}[{two} * i] = {lighting};"));
        let albedo = d.construct(vec4, "s.albedo, s.shininess");
        self.line(l1, &format!("{out}[{two} * i + {one}] = {albedo};"));
        self.out.push_str("}\n");
    }
}
