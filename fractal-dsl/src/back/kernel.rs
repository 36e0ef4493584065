//! The GPU program, written once for every GPU language: the order of its sections, the framing of the lowered scene
//! functions and the `render`, `trace` and `probe` kernels ([`super::Entry`]), or, for another engine, the same
//! functions as a library ([`write_library`]: `sdf`, `sdf_normal`, `sdf_material`, the bound as constants and
//! `sdf_raymarch`). The ray itself is not written here: the render kernel's body and the library's functions are the
//! ray program of [`crate::ray`] traced ([`crate::lower::ray`]), the one the CPU renderer runs. What differs between
//! the languages is a [`Dialect`] (and, for the kernels, a [`KernelDialect`]); each GPU writer
//! (`back/<lang>/writer.rs`) is one impl, and the [`Syntax`] the shared body walker needs follows from it.

use std::fmt::Write;

use super::syntax::{self, Prec, Spelling, Syntax};
use super::{f32_literal, Entry, FrameLayout, Level, Pass, REFINE_MARK};
use crate::ir::HitEpsilon;
use crate::lower::code::{Body, FrameField, MathFn, SceneFn, Ty, Val};
use crate::lower::ray;
use crate::lower::trace::Function;
use crate::lower::Program;

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
    /// Whether the kernel computes in a type whose `sin`, `cos`, `acos`, `atan2`, `exp2`, `log` and `pow` the
    /// language leaves undefined (WGSL's f64): then [`Dialect::math_call`] calls the traced functions of
    /// [`crate::lower::portable`] for them, and the program writes those it calls.
    fn portable_math(&self) -> bool {
        false
    }
    /// `v`, a 4-vector of the kernel's number type, as the f32 4-vector an output buffer holds (the trace and probe
    /// outputs are f32 whatever the kernel computes in).
    fn to_f32x4(&self, v: &str) -> String {
        v.to_string()
    }
    /// `v`, a scalar of the kernel's number type, as the f32 an output buffer holds.
    fn to_f32(&self, v: &str) -> String {
        v.to_string()
    }
    /// `v`, an f32 3-vector read from an input buffer (the probe's points), as the kernel's V3.
    fn read_f32x3(&self, v: &str) -> String {
        v.to_string()
    }
}

/// What a language's compute kernels spell their own way ([`write()`]): resources, entry points and pixel output.
pub trait KernelDialect: Dialect {
    /// Type definitions and resource bindings, written before the helpers; `refine` where the kernel has the
    /// second pass ([`Pass::Refine`]).
    fn declarations(&self, out: &mut String, layout: FrameLayout, entry: Entry, refine: bool);
    /// Writes the first lines of the `render` or `trace` kernel's entry point for `pass` (the refine pass also takes
    /// the first pass's pixels), through its `{` and the statements naming the invocation's pixel; returns the
    /// pixel's x and y, whose type is [`Self::pixel_index_type`].
    fn render_open(&self, out: &mut String, entry: Entry, pass: Pass) -> [&'static str; 2];
    fn pixel_index_type(&self) -> &'static str;
    /// The statements that pack `col` into RGBA8 and store it at the pixel.
    fn pack_pixel(&self) -> &'static [&'static str];
    /// The pixel index `i` moved by `step` (−1 or 1) and kept within 0..`size`.
    fn clamp_index(&self, i: &str, step: i32, size: &str) -> String;
    /// The first pass's displayed colour at pixel index `index` of the refine pass's input, as a 3-vector in [0, 1].
    fn first_shown(&self, index: &str) -> String;
    /// Writes the `probe` entry point's first lines, through its `{` and the statement declaring the point index
    /// `i`; returns the expression for the number of points.
    fn probe_open(&self, out: &mut String) -> &'static str;
    /// The name of the `probe` output array.
    fn probe_output(&self) -> &'static str;
}

/// The [`Syntax`] of the lowered bodies in a GPU language; time and parameters come from the frame, or from the
/// host's globals in a library.
struct GpuSyntax<'a, D> {
    d: &'a D,
    lib: Option<&'a Library>,
    /// Whether `scene_de` and `scene_sample` take the frame as an argument.
    passes_frame: [bool; 2],
}

impl<D: Dialect> Syntax for GpuSyntax<'_, D> {
    fn type_name(&self, ty: Ty) -> &'static str {
        self.d.type_name(ty)
    }
    fn declare(&self, name: &str, ty: Ty, value: &str, mutable: bool) -> String {
        self.d.declare(name, self.d.type_name(ty), value, mutable)
    }
    fn lit(&self, v: f64) -> String {
        self.d.lit(v)
    }
    fn bool_lit(&self, v: bool) -> String {
        self.d.bool_lit(v).to_string()
    }
    fn int(&self, v: u32) -> String {
        self.d.index_lit(v)
    }
    fn time(&self) -> String {
        match self.lib {
            Some(lib) => lib.time.clone(),
            None => self.d.frame_field("origin.w"),
        }
    }
    fn param(&self, slot: usize) -> String {
        match self.lib {
            Some(lib) => lib.params[slot].clone(),
            None => self.d.frame_field(&format!("params[{}].{}", slot / 4, COMPONENTS[slot % 4])),
        }
    }
    fn orbit(&self) -> Option<String> {
        self.d.frame_parameter().map(|_| "frame".to_string())
    }
    fn orbit_entry(&self, index: &str) -> String {
        // Two entries per slot: entry i is the xy (even i) or zw (odd i) of slot i / 2.
        let d = self.d;
        let i = d.cast(d.type_name(Ty::Int), index);
        let (two, one) = (d.index_lit(2), d.index_lit(1));
        let slot = d.frame_field(&format!("orbit[{i} / {two}]"));
        d.select(&format!("({i} % {two} == {one})"), &format!("{slot}.zw"), &format!("{slot}.xy"))
    }
    fn orbit_last(&self) -> String {
        self.d.frame_field("reference.x")
    }
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String {
        let components = if x == y && y == z { x.to_string() } else { format!("{x}, {y}, {z}") };
        self.d.construct(self.d.type_name(Ty::V3), &components)
    }
    fn make_pair(&self, distance: &str, trap: &str) -> String {
        self.d.construct(self.d.type_name(Ty::Pair), &format!("{distance}, {trap}"))
    }
    fn comp(&self, v: &str, _ty: Ty, i: u8) -> String {
        format!("{v}.{}", COMPONENTS[i as usize])
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        self.d.math_name(f)
    }
    fn math(&self, f: MathFn, args: &[String]) -> String {
        self.d.math_call(f, args)
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        self.d.select(cond, if_true, if_false)
    }
    fn select_prec(&self) -> Prec {
        self.d.select_prec()
    }
    fn if_open(&self, cond: &str) -> String {
        format!("if {} {{", parenthesized(cond))
    }
    fn break_if(&self, cond: &str) -> String {
        format!("if {} {{ break; }}", parenthesized(cond))
    }
    fn scene_call(&self, f: SceneFn, args: &[String]) -> String {
        let frame = match f {
            SceneFn::Sample => self.passes_frame[1],
            SceneFn::Distance | SceneFn::Normal | SceneFn::Occlusion | SceneFn::Shadow => self.passes_frame[0],
        };
        let frame = if frame { ", frame" } else { "" };
        format!("{}({}{frame})", f.name(), args.join(", "))
    }
    fn frame(&self, field: FrameField) -> String {
        self.d.frame_field(&field.path())
    }
    fn loop_open(&self, count: &str, depth: usize) -> String {
        self.d.counted_loop_over(&format!("i{depth}"), count)
    }
}

/// Writes traced leaf functions in `dialect`, each followed by a blank line.
pub fn write_functions<D: Dialect>(functions: &[Function], dialect: &D) -> String {
    let syn = GpuSyntax { d: dialect, lib: None, passes_frame: [false; 2] };
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
    let refine = entry != Entry::Probe && program.settings.samples > 1;
    dialect.declarations(&mut k.out, program.layout(), entry, refine);
    // Where the elementary functions go, once the program shows which it calls: before every function that may.
    let helpers_at = k.out.len();
    k.leaf_functions();
    k.scene_functions();
    match entry {
        Entry::Render | Entry::Trace => {
            k.ray_functions();
            k.render(dialect, entry);
            if refine {
                k.refine(dialect, entry);
            }
        }
        Entry::Probe => k.probe(dialect),
    }
    if dialect.portable_math() {
        let helpers = k.portable_functions();
        k.out.insert_str(helpers_at, &helpers);
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
    /// `vec3 sdf_display_linear(vec3 col)`: the linear colour whose sRGB encoding is `sdf_display(col)`, for sRGB
    /// targets and engines' tonemappers: the pixel then shows as the viewer's does.
    pub const DISPLAY_LINEAR: &str = "sdf_display_linear";
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
    k.ray_functions();
    k.library_functions(lib);
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

impl<'a, D: Dialect> Kernel<'a, D> {
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
    fn constant(&self, name: &str, ty: &str, value: &str) -> String {
        self.d.local(name, ty, value, false)
    }

    /// The spelling of lowered bodies in this program.
    fn syntax(&self) -> GpuSyntax<'a, D> {
        let passes_frame =
            [self.passes_frame(self.p.distance_reads_frame), self.passes_frame(self.p.sample_reads_frame)];
        GpuSyntax { d: self.d, lib: self.lib, passes_frame }
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
        let (p, syn) = (self.p, self.syntax());
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

    /// The ray program's named functions the scene needs ([`ray::functions`]).
    fn ray_functions(&mut self) {
        for f in ray::functions(self.p) {
            let params: Vec<(&str, &str)> = f.params.iter().map(|&(name, ty)| (name, self.d.type_name(ty))).collect();
            let reads_frame = self.p.distance_reads_frame;
            self.traced_function(
                self.d.type_name(f.f.returns()),
                f.f.name(),
                &params,
                &f.body,
                &[f.result],
                reads_frame,
            );
        }
    }

    /// The statements after a pixel entry point's opening: the image size `w` and `h`, the bounds check, and the
    /// pixel's column and row as floats ([`ray::PIXEL_ARGS`]). Returns the pixel index type.
    fn pixel_preamble<K: KernelDialect>(&mut self, kernel: &K, [px, py]: [&str; 2]) -> &'static str {
        let (d, float, (l1, l2)) = (self.d, self.float(), (Level(1), Level(2)));
        let index = kernel.pixel_index_type();
        self.line(l1, &self.constant("w", index, &d.cast(index, &d.frame_field("right.w"))));
        self.line(l1, &self.constant("h", index, &d.cast(index, &d.frame_field("up.w"))));
        self.line(l1, &format!("if ({px} >= w || {py} >= h) {{"));
        self.line(l2, "return;");
        self.line(l1, "}");
        for (name, i) in ray::PIXEL_ARGS.into_iter().zip([px, py]) {
            self.line(l1, &self.constant(name, float, &d.cast(float, i)));
        }
        index
    }

    /// The `render` or `trace` entry point: the pixel's ray program ([`crate::lower::ray::pixel`]), then what the
    /// entry writes of it.
    fn render<K: KernelDialect>(&mut self, kernel: &K, entry: Entry) {
        let d = self.d;
        let l1 = Level(1);
        let [px, py] = kernel.render_open(&mut self.out, entry, Pass::First);
        let index = self.pixel_preamble(kernel, [px, py]);
        let (body, vals) = ray::pixel(self.p);
        let (all, shown) = (vals.all(), [vals.display]);
        let body = body.pruned(if self.traced { &all } else { &shown });
        let syn = self.syntax();
        let spelling = Spelling::new(&body, &syn, &vals.all());
        spelling.write(&mut self.out, l1);
        if self.traced {
            let vec4 = d.vec4_type();
            let v = |x| spelling.value(x);
            self.line(l1, &self.constant("pixel", index, &format!("{} * ({py} * w + {px})", d.index_lit(3))));
            let rows = [
                format!("{}, {}", v(vals.normal), v(vals.t)),
                format!("{}, {}, {}, {}", v(vals.steps), v(vals.hit), v(vals.out_of_steps), v(vals.samples)),
                format!("{}, {}", v(vals.colour), self.lit(0.0)),
            ];
            for (k, row) in rows.iter().enumerate() {
                let at = if k == 0 { "pixel".to_string() } else { format!("pixel + {}", d.index_lit(k as u32)) };
                self.line(l1, &format!("{TRACES}[{at}] = {};", d.to_f32x4(&d.construct(vec4, row))));
            }
        }
        self.line(l1, &self.constant("col", self.vec3(), &spelling.value(vals.display)));
        for statement in kernel.pack_pixel() {
            self.line(l1, statement);
        }
        self.out.push_str("}\n");
    }

    /// The `refine` entry point ([`Pass::Refine`]): the ray program's second pass ([`crate::lower::ray::refine`]) from
    /// the first pass's pixels around this one, then what it writes where the pixel took more samples.
    fn refine<K: KernelDialect>(&mut self, kernel: &K, entry: Entry) {
        let d = self.d;
        let (l1, l2) = (Level(1), Level(2));
        let _ = writeln!(self.out, "\n{REFINE_MARK}");
        let [px, py] = kernel.render_open(&mut self.out, entry, Pass::Refine);
        let index = self.pixel_preamble(kernel, [px, py]);
        let rows = [kernel.clamp_index(py, -1, "h"), py.to_string(), kernel.clamp_index(py, 1, "h")];
        let columns = [kernel.clamp_index(px, -1, "w"), px.to_string(), kernel.clamp_index(px, 1, "w")];
        for (name, value) in ["y0", "y2"].into_iter().zip([&rows[0], &rows[2]]) {
            self.line(l1, &self.constant(name, index, value));
        }
        for (name, value) in ["x0", "x2"].into_iter().zip([&columns[0], &columns[2]]) {
            self.line(l1, &self.constant(name, index, value));
        }
        let (ys, xs) = (["y0", py, "y2"], ["x0", px, "x2"]);
        let around = ys.iter().flat_map(|y| xs.iter().map(move |x| (*y, *x)));
        let (centre, neighbours): (Vec<_>, Vec<_>) = around.enumerate().partition(|(i, _)| *i == 4);
        for (name, (_, (y, x))) in ray::SHOWN_ARGS.into_iter().zip(centre.into_iter().chain(neighbours)) {
            self.line(l1, &self.constant(name, self.vec3(), &kernel.first_shown(&format!("{y} * w + {x}"))));
        }
        let (body, vals) = ray::refine(self.p);
        let written = [vals.refined, vals.display, vals.colour, vals.samples];
        let body = body.pruned(if self.traced { &written } else { &written[..2] });
        let syn = self.syntax();
        let spelling = Spelling::new(&body, &syn, &written);
        spelling.write(&mut self.out, l1);
        if self.traced {
            let v = |x| spelling.value(x);
            self.line(l1, &self.constant("pixel", index, &format!("{} * ({py} * w + {px})", d.index_lit(3))));
            self.line(l1, &format!("if ({} > {}) {{", v(vals.refined), self.lit(0.5)));
            let one = d.index_lit(1);
            self.line(l2, &format!("{TRACES}[pixel + {one}].w = {};", d.to_f32(&v(vals.samples))));
            let colour = d.construct(d.vec4_type(), &format!("{}, {}", v(vals.colour), self.lit(0.0)));
            self.line(l2, &format!("{TRACES}[pixel + {}] = {};", d.index_lit(2), d.to_f32x4(&colour)));
            self.line(l1, "}");
        }
        self.line(l1, &self.constant("col", self.vec3(), &spelling.value(vals.display)));
        for statement in kernel.pack_pixel() {
            self.line(l1, statement);
        }
        self.out.push_str("}\n");
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

    /// The functions an engine calls ([`library`]), on the scene functions: `sdf` and `sdf_material` call them, the
    /// others are the ray program traced ([`crate::lower::ray`]).
    fn library_functions(&mut self, lib: &Library) {
        let (float, vec3, vec4) = (self.float(), self.vec3(), self.d.vec4_type());
        let l1 = Level(1);
        self.function_open(float, library::SDF, &[("p", vec3)], false);
        self.line(l1, &format!("return {};", self.call("scene_de", "p", self.p.distance_reads_frame)));
        self.function_close();

        let (body, normal) = ray::normal(self.p, library::NORMAL_EPSILON);
        self.traced_function(vec3, library::NORMAL, &[("p", vec3)], &body, &[normal], false);

        self.function_open(vec3, library::MATERIAL, &[("p", vec3)], false);
        self.line(l1, &format!("return {}.albedo;", self.call("scene_sample", "p", false)));
        self.function_close();

        let lights: Vec<([f64; 3], [f64; 3])> = lib.lights.iter().map(|l| (l.position, l.radiance)).collect();
        let (body, [colour, t]) = ray::raymarch(self.p, &lights);
        let params = ray::RAYMARCH_ARGS.map(|(name, ty)| (name, self.d.type_name(ty)));
        let hit = |s: &Spelling| self.d.construct(vec4, &format!("{}, {}", s.value(colour), s.value(t)));
        self.traced_function_with(vec4, library::RAYMARCH, (&params, false), &body, &[colour, t], hit);

        let (body, shown) = ray::display(self.p, false);
        self.traced_function(vec3, library::DISPLAY, &[("colour", vec3)], &body, &[shown], false);
        let (body, shown) = ray::display(self.p, true);
        self.traced_function(vec3, library::DISPLAY_LINEAR, &[("colour", vec3)], &body, &[shown], false);
    }

    /// A function whose body is `body`, returning its one result; it takes the frame where it `reads_frame`.
    fn traced_function(
        &mut self,
        ret: &str,
        name: &str,
        params: &[(&str, &str)],
        body: &Body,
        results: &[Val],
        reads_frame: bool,
    ) {
        self.traced_function_with(ret, name, (params, reads_frame), body, results, |s| s.value(results[0]));
    }

    /// A function whose body is `body`, returning `value` of its spelling; it takes the frame where it reads it.
    fn traced_function_with(
        &mut self,
        ret: &str,
        name: &str,
        (params, reads_frame): (&[(&str, &str)], bool),
        body: &Body,
        results: &[Val],
        value: impl Fn(&Spelling) -> String,
    ) {
        self.function_open(ret, name, params, reads_frame);
        let syn = self.syntax();
        let spelling = Spelling::new(body, &syn, results);
        spelling.write(&mut self.out, Level(1));
        let returned = value(&spelling);
        self.line(Level(1), &format!("return {returned};"));
        self.function_close();
    }

    /// The text of the traced elementary functions ([`crate::lower::portable`]) the program written so far calls.
    fn portable_functions(&self) -> String {
        let called: Vec<_> = crate::lower::portable::functions()
            .into_iter()
            .filter(|f| self.out.contains(&format!("{}(", crate::lower::portable::name(f.f))))
            .collect();
        let mut helpers = Kernel { out: String::new(), ..*self };
        if !called.is_empty() {
            helpers.out.push_str(
                "// Elementary functions from arithmetic, sqrt and floor (the language defines them for f32 only).\n\n",
            );
        }
        let float = self.float();
        for f in called {
            let params: Vec<(&str, &str)> = f.params.iter().map(|&(name, ty)| (name, self.d.type_name(ty))).collect();
            let name = crate::lower::portable::name(f.f);
            helpers.traced_function(float, name, &params, &f.body, &[f.result], false);
        }
        helpers.out
    }

    fn probe<K: KernelDialect>(&mut self, kernel: &K) {
        let (d, p) = (self.d, self.p);
        let (l1, l2) = (Level(1), Level(2));
        let count = kernel.probe_open(&mut self.out);
        self.line(l1, &format!("if (i >= {count}) {{"));
        self.line(l2, "return;");
        self.line(l1, "}");
        self.line(l1, &self.constant("p", self.vec3(), &d.read_f32x3("points[i].xyz")));
        let sample_args =
            if p.reference.is_some() { format!("p, p - {}", d.frame_field("origin.xyz")) } else { "p".to_string() };
        self.line(l1, &self.constant("s", "Sample", &self.call("scene_sample", &sample_args, p.sample_reads_frame)));
        let (out, two, one, vec4) = (kernel.probe_output(), d.index_lit(2), d.index_lit(1), d.vec4_type());
        let lighting = d.construct(vec4, &format!("{}, s.ambient, s.diffuse, s.specular", self.de("p")));
        self.line(l1, &format!("{out}[{two} * i] = {};", d.to_f32x4(&lighting)));
        let albedo = d.construct(vec4, "s.albedo, s.shininess");
        self.line(l1, &format!("{out}[{two} * i + {one}] = {};", d.to_f32x4(&albedo)));
        self.out.push_str("}\n");
    }
}
