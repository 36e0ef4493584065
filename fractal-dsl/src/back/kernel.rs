//! The GPU program, written once for every GPU language: the order of its sections, the framing of the lowered scene
//! functions, the functions built on them (normal, ambient occlusion, shadow) and the `render` and `probe` kernels
//! ([`super::Entry`]) that implement [`super::render`]. What differs between the languages is a [`Dialect`]; each GPU
//! writer (`back/opencl/writer.rs`, `back/wgsl/writer.rs`) is one `Dialect` impl, and the [`Syntax`] the shared body
//! walker needs follows from it.

use std::fmt::Write;

use super::render::*;
use super::syntax::{self, Prec, Spelling, Syntax};
use super::{Entry, FrameLayout, Level};
use crate::ir::{HitEpsilon, Shadows};
use crate::lower::code::{MathFn, Ty};
use crate::lower::trace::Function;
use crate::lower::{LightShape, Program};

/// Vector component names, by index.
const COMPONENTS: [&str; 4] = ["x", "y", "z", "w"];

/// What one GPU language spells its own way. Statements are returned without indentation and with their `;`.
pub trait Dialect {
    /// The language's name in the generated file's first line.
    fn language(&self) -> &'static str;
    /// Type definitions and resource bindings, written before the helpers.
    fn declarations(&self, out: &mut String, layout: FrameLayout, entry: Entry);

    fn type_name(&self, ty: Ty) -> &'static str;
    fn vec4_type(&self) -> &'static str;
    /// A float constant.
    fn lit(&self, v: f64) -> String;
    fn bool_lit(&self, v: bool) -> &'static str;
    /// An integer constant in arithmetic on an unsigned index.
    fn index_lit(&self, v: u32) -> String;
    /// `v` (an atom) converted to the scalar type `ty`.
    fn cast(&self, ty: &str, v: &str) -> String;
    /// A value of vector type `ty` from its comma-separated `components` (one of them fills every component).
    fn construct(&self, ty: &str, components: &str) -> String;
    /// A scalar passed where a built-in takes a vector of the other operand's size (`clamp`'s bounds).
    fn vector_operand(&self, scalar: &str) -> String;
    /// The name of a math built-in.
    fn math_name(&self, f: MathFn) -> &'static str;
    /// A call of a math function in lowered code: the built-in, or the language's polyfill for it.
    fn math_call(&self, f: MathFn, args: &[String]) -> String {
        format!("{}({})", self.math_name(f), args.join(", "))
    }
    /// The conditional expression on a scalar condition.
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String;
    /// How tightly [`Dialect::select`]'s spelling binds.
    fn select_prec(&self) -> Prec {
        Prec::Atom
    }
    /// A field of the frame uniform ([`FrameLayout`]), e.g. `origin.xyz` or `lights[2].xyz`.
    fn frame_field(&self, field: &str) -> String;

    /// A declaration with its type spelled out.
    fn declare(&self, name: &str, ty: &str, value: &str, mutable: bool) -> String;
    /// A declaration whose type the language may infer from `value`.
    fn local(&self, name: &str, ty: &str, value: &str, mutable: bool) -> String {
        self.declare(name, ty, value, mutable)
    }
    /// A mutable declaration without a value.
    fn uninitialised(&self, name: &str, ty: &str) -> String;
    /// The opening line of `for` over `i` from 0 while `i < {bound}` (the bound may carry `&& …`).
    fn counted_loop(&self, bound: &str) -> String;
    /// The opening line of `for` over the unsigned `index` from 0 while `index < count`.
    fn counted_loop_over(&self, index: &str, count: &str) -> String;

    /// The type of the frame where functions take it as their last argument `frame`; `None` where they read the
    /// frame as a global.
    fn frame_parameter(&self) -> Option<&'static str>;
    /// A function's first line, up to and including its `{`; `params` are (name, type) pairs.
    fn function_open(&self, ret: &str, name: &str, params: &[(&str, &str)]) -> String;
    /// The statements ending `scene_sample`: return a `Sample` of the named fields' values, in `Sample`'s order.
    fn sample_return(&self, fields: &[(&str, String)]) -> Vec<String>;
    /// Writes the `render` entry point's first lines, through its `{` and the statements naming the invocation's
    /// pixel; returns the pixel's x and y, whose type is [`Self::pixel_index_type`].
    fn render_open(&self, out: &mut String) -> [&'static str; 2];
    fn pixel_index_type(&self) -> &'static str;
    /// The statements that pack `col` into RGBA8 and store it at the pixel.
    fn pack_pixel(&self) -> &'static [&'static str];
    /// Writes the `probe` entry point's first lines, through its `{` and the statement declaring the point index
    /// `i`; returns the expression for the number of points.
    fn probe_open(&self, out: &mut String) -> &'static str;
    /// The name of the `probe` output array.
    fn probe_output(&self) -> &'static str;
}

/// The [`Syntax`] of the lowered bodies in a GPU language.
struct GpuSyntax<'a, D>(&'a D);

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
        self.0.frame_field("origin.w")
    }
    fn param(&self, slot: usize) -> String {
        self.0.frame_field(&format!("params[{}].{}", slot / 4, COMPONENTS[slot % 4]))
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
    let syn = GpuSyntax(dialect);
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
pub fn write<D: Dialect>(program: &Program, entry: Entry, dialect: &D) -> String {
    let mut k = Kernel { p: program, d: dialect, out: String::new() };
    let what = match entry {
        Entry::Render => "render kernel",
        Entry::Probe => "probe kernel",
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
        Entry::Render => {
            k.normal();
            if let Some(strength) = program.settings.ambient_occlusion {
                k.ambient_occlusion(strength);
            }
            if program.settings.shadows != Shadows::None {
                k.shadow();
            }
            k.render();
        }
        Entry::Probe => k.probe(),
    }
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
    out: String,
}

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

    /// A call of a function that reads the frame when `reads_frame`.
    fn call(&self, name: &str, args: &str, reads_frame: bool) -> String {
        let frame = if reads_frame && self.d.frame_parameter().is_some() { ", frame" } else { "" };
        format!("{name}({args}{frame})")
    }
    fn de(&self, p: &str) -> String {
        self.call("scene_de", p, self.p.distance_reads_frame)
    }
    /// Writes the first line of a function that reads the frame when `reads_frame`.
    fn function_open(&mut self, ret: &str, name: &str, params: &[(&str, &str)], reads_frame: bool) {
        let mut params = params.to_vec();
        if let Some(frame) = self.d.frame_parameter().filter(|_| reads_frame) {
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
        let (p, syn) = (self.p, GpuSyntax(self.d));
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

    fn render(&mut self) {
        let (d, p) = (self.d, self.p);
        let s = &p.settings;
        let (float, vec3) = (self.float(), self.vec3());
        let (l1, l2, l3) = (Level(1), Level(2), Level(3));
        let (zero, one, two) = (self.lit(0.0), self.lit(1.0), self.lit(2.0));

        // 1. The ray through the pixel's centre.
        let [px, py] = d.render_open(&mut self.out);
        let index = d.pixel_index_type();
        self.line(l1, &self.constant("w", index, &d.cast(index, &d.frame_field("right.w"))));
        self.line(l1, &self.constant("h", index, &d.cast(index, &d.frame_field("up.w"))));
        self.line(l1, &format!("if ({px} >= w || {py} >= h) {{"));
        self.line(l2, "return;");
        self.line(l1, "}");
        let (half, w, h) = (self.lit(0.5), d.cast(float, "w"), d.cast(float, "h"));
        let u = format!("({two} * ({} + {half}) - {w}) / {h}", d.cast(float, px));
        let v = format!("-({two} * ({} + {half}) - {h}) / {h}", d.cast(float, py));
        self.line(l1, &self.constant("u", float, &u));
        self.line(l1, &self.constant("v", float, &v));
        self.line(l1, &self.constant("ro", vec3, &d.frame_field("origin.xyz")));
        let rd = format!(
            "normalize({} + u * {} + v * {})",
            d.frame_field("forward.xyz"),
            d.frame_field("right.xyz"),
            d.frame_field("up.xyz")
        );
        self.line(l1, &self.constant("rd", vec3, &rd));

        // 2. Clip to the scene's bound.
        self.line(l1, &self.variable("t", float, &zero));
        self.line(l1, &self.variable("t_far", float, &self.lit(s.max_distance)));
        if let Some(b) = p.bound {
            self.line(l1, "{");
            self.line(l2, "// Clip the ray to the scene's bound: no marching through empty space.");
            let min_direction = d.construct(vec3, &self.lit(MIN_DIRECTION));
            let m = self.math(MathFn::Max, &[&self.math(MathFn::Abs, &["rd"]), &min_direction]);
            self.line(l2, &self.constant("m", vec3, &m));
            // Both languages' vector `select` takes (if false, if true, condition).
            let safe = format!("select(-m, m, rd >= {})", d.construct(vec3, &zero));
            self.line(l2, &self.constant("safe", vec3, &safe));
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
            HitEpsilon::Pixel(k) => format!("{} * {} * t", self.lit(k), d.frame_field("forward.w")),
        };
        self.line(l1, &d.counted_loop(&format!("{} && t <= t_far", s.max_steps)));
        self.line(l2, &self.constant("d", float, &self.de("ro + rd * t")));
        let spacing = format!("{} * t", self.lit(T_SPACING));
        self.line(l2, &format!("eps = {};", self.math(MathFn::Max, &[&eps, &spacing])));
        self.line(l2, "if (d < eps) {");
        self.line(l3, &format!("hit = {};", d.bool_lit(true)));
        self.line(l3, "break;");
        self.line(l2, "}");
        if s.glow.is_some() {
            self.line(l2, &format!("glow += {one} / ({one} + {} * d * d);", self.lit(GLOW_FALLOFF)));
        }
        self.line(l2, "t += d;");
        self.line(l1, "}");

        // 4. Hit shading.
        self.line(l1, &d.uninitialised("col", vec3));
        self.line(l1, "if (hit) {");
        self.line(l2, &self.constant("p", vec3, "ro + rd * t"));
        let n = self.call("scene_normal", "p, eps", p.distance_reads_frame);
        self.line(l2, &self.constant("n", vec3, &n));
        // A perturbed pattern reads the hit relative to the camera, rd·t: exact to t's precision at any zoom.
        let sample_args = if p.reference.is_some() { "p, rd * t" } else { "p" };
        self.line(l2, &self.constant("m", "Sample", &self.call("scene_sample", sample_args, p.sample_reads_frame)));
        if s.ambient_occlusion.is_some() {
            let ao = self.call("scene_ao", "p, n", p.distance_reads_frame);
            self.line(l2, &format!("col = m.albedo * (m.ambient * {ao});"));
        } else {
            self.line(l2, "col = m.albedo * m.ambient;");
        }
        for (i, shape) in p.lights.iter().enumerate() {
            let position = d.frame_field(&format!("lights[{}].xyz", 2 * i));
            let color = d.frame_field(&format!("lights[{}].xyz", 2 * i + 1));
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
                    self.call("scene_shadow", &format!("p + n * ({two} * eps), l, limit, eps"), p.distance_reads_frame);
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
            let fogged = builtin("mix", &["col", &self.vec3_lit(fog.color), &attenuation]);
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

        // 7. Output.
        let clamped = builtin("clamp", &["col", &d.vector_operand(&zero), &d.vector_operand(&one)]);
        self.line(l1, &format!("col = {clamped};"));
        if s.gamma == 2.0 {
            self.line(l1, &format!("col = {};", self.math(MathFn::Sqrt, &["col"])));
        } else if s.gamma != 1.0 {
            let exponent = d.construct(vec3, &self.lit(1.0 / s.gamma));
            self.line(l1, &format!("col = {};", self.math(MathFn::Pow, &["col", &exponent])));
        }
        for statement in d.pack_pixel() {
            self.line(l1, statement);
        }
        self.out.push_str("}\n");
    }

    fn probe(&mut self) {
        let (d, p) = (self.d, self.p);
        let (l1, l2) = (Level(1), Level(2));
        let count = d.probe_open(&mut self.out);
        self.line(l1, &format!("if (i >= {count}) {{"));
        self.line(l2, "return;");
        self.line(l1, "}");
        self.line(l1, &self.constant("p", self.vec3(), "points[i].xyz"));
        let sample_args =
            if p.reference.is_some() { format!("p, p - {}", d.frame_field("origin.xyz")) } else { "p".to_string() };
        self.line(l1, &self.constant("s", "Sample", &self.call("scene_sample", &sample_args, p.sample_reads_frame)));
        let (out, two, one, vec4) = (d.probe_output(), d.index_lit(2), d.index_lit(1), d.vec4_type());
        let lighting = d.construct(vec4, &format!("{}, s.ambient, s.diffuse, s.specular", self.de("p")));
        self.line(l1, &format!("{out}[{two} * i] = {lighting};"));
        let albedo = d.construct(vec4, "s.albedo, s.shininess");
        self.line(l1, &format!("{out}[{two} * i + {one}] = {albedo};"));
        self.out.push_str("}\n");
    }
}
