//! The WGSL writer: frames the lowered bodies with the uniform struct, the bindings, the helpers, and the `render` or
//! `probe` entry point that implements [`crate::back::render`].

use std::fmt::Write;

use super::library;
use crate::back::render::*;
use crate::back::syntax::{self, group_julia, Syntax};
use crate::back::{f32_literal, Entry, Helper, Level};
use crate::ir::{HitEpsilon, Shadows};
use crate::lower::code::{MathFn, Ty};
use crate::lower::{LightShape, Program};

struct Wgsl;

const COMPONENTS: [&str; 4] = ["x", "y", "z", "w"];

fn lit(v: f64) -> String {
    f32_literal(v)
}

fn vec3_lit(c: [f64; 3]) -> String {
    format!("vec3<f32>({}, {}, {})", lit(c[0]), lit(c[1]), lit(c[2]))
}

impl Syntax for Wgsl {
    fn type_name(&self, ty: Ty) -> &'static str {
        match ty {
            Ty::F => "f32",
            Ty::V3 => "vec3<f32>",
            Ty::Pair => "vec2<f32>",
            Ty::Bool => "bool",
        }
    }
    fn declare(&self, name: &str, ty: Ty, value: &str, mutable: bool) -> String {
        let kw = if mutable { "var" } else { "let" };
        format!("{kw} {name}: {} = {value};", self.type_name(ty))
    }
    fn lit(&self, v: f64) -> String {
        lit(v)
    }
    fn int(&self, v: u32) -> String {
        v.to_string()
    }
    fn time(&self) -> String {
        "frame.origin.w".to_string()
    }
    fn param(&self, slot: usize) -> String {
        format!("frame.params[{}].{}", slot / 4, COMPONENTS[slot % 4])
    }
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String {
        if x == y && y == z {
            format!("vec3<f32>({x})")
        } else {
            format!("vec3<f32>({x}, {y}, {z})")
        }
    }
    fn comp(&self, v: &str, _ty: Ty, i: u8) -> String {
        format!("{v}.{}", COMPONENTS[i as usize])
    }
    fn math(&self, f: MathFn, a: &[String]) -> String {
        let name = match f {
            MathFn::Sin => "sin",
            MathFn::Cos => "cos",
            MathFn::Abs => "abs",
            MathFn::Sqrt => "sqrt",
            MathFn::Floor => "floor",
            MathFn::Min => "min",
            MathFn::Max => "max",
            MathFn::Pow => "pow",
            MathFn::Clamp => "clamp",
            MathFn::Mix => "mix",
        };
        format!("{name}({})", a.join(", "))
    }
    fn length(&self, v: &str) -> String {
        format!("length({v})")
    }
    fn call(&self, h: Helper, args: &[String]) -> String {
        let args = if h == Helper::DeJulia {
            group_julia(args, |c| format!("vec4<f32>({})", c.join(", ")))
        } else {
            args.to_vec()
        };
        format!("{}({})", h.name(), args.join(", "))
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        format!("select({if_false}, {if_true}, {cond})")
    }
    fn less(&self, a: &str, b: &str) -> String {
        format!("({a} < {b})")
    }
    fn if_open(&self, cond: &str) -> String {
        format!("if {cond} {{")
    }
}

/// Writes the complete WGSL module for `entry`.
pub fn write(program: &Program, entry: Entry) -> String {
    let mut w = Writer { p: program, out: String::new() };
    w.header(entry);
    w.structs(entry);
    w.out.push_str(&library::helpers_source(program.helpers.iter().copied()));
    w.scene_functions();
    match entry {
        Entry::Render => {
            w.normal();
            if let Some(strength) = program.settings.ambient_occlusion {
                w.ambient_occlusion(strength);
            }
            if program.settings.shadows != Shadows::None {
                w.shadow();
            }
            w.render();
        }
        Entry::Probe => w.probe(),
    }
    w.out
}

struct Writer<'a> {
    p: &'a Program,
    out: String,
}

impl Writer<'_> {
    fn line(&mut self, level: Level, text: &str) {
        let _ = writeln!(self.out, "{level}{text}");
    }

    fn header(&mut self, entry: Entry) {
        let what = match entry {
            Entry::Render => "render kernel",
            Entry::Probe => "probe kernel",
        };
        let _ = writeln!(
            self.out,
            "// fractal: WGSL {what}, generated from a scene description. Edit the scene, not this file.\n"
        );
    }

    fn structs(&mut self, entry: Entry) {
        let layout = self.p.layout();
        self.out.push_str(
            "struct Frame {\n    origin: vec4<f32>,\n    right: vec4<f32>,\n    up: vec4<f32>,\n    forward: vec4<f32>,\n",
        );
        let _ = writeln!(self.out, "    lights: array<vec4<f32>, {}>,", 2 * layout.lights);
        if layout.params > 0 {
            let _ = writeln!(self.out, "    params: array<vec4<f32>, {}>,", layout.param_slots());
        }
        self.out.push_str("}\n\n");
        self.out.push_str(
            "struct Sample {\n    distance: f32,\n    albedo: vec3<f32>,\n    ambient: f32,\n    diffuse: f32,\n    specular: f32,\n    shininess: f32,\n}\n\n",
        );
        match entry {
            Entry::Render => {
                self.out.push_str("@group(0) @binding(0) var<storage, read_write> out_px: array<u32>;\n");
                self.out.push_str("@group(0) @binding(1) var<uniform> frame: Frame;\n\n");
            }
            Entry::Probe => {
                self.out.push_str("@group(0) @binding(0) var<storage, read_write> probe_out: array<vec4<f32>>;\n");
                self.out.push_str("@group(0) @binding(1) var<uniform> frame: Frame;\n");
                self.out.push_str("@group(0) @binding(2) var<storage, read> points: array<vec4<f32>>;\n\n");
            }
        }
    }

    fn scene_functions(&mut self) {
        let p = self.p;
        self.out.push_str("fn scene_de(p: vec3<f32>) -> f32 {\n");
        syntax::write_body(&mut self.out, &p.distance, &Wgsl, Level(1));
        let result = syntax::atom(&p.distance, &Wgsl, p.distance_result);
        self.line(Level(1), &format!("return {result};"));
        self.out.push_str("}\n\n");

        self.out.push_str("fn scene_sample(p: vec3<f32>) -> Sample {\n");
        syntax::write_body(&mut self.out, &p.sample, &Wgsl, Level(1));
        let r = p.sample_result;
        let fields: Vec<String> = [r.distance, r.albedo, r.ambient, r.diffuse, r.specular, r.shininess]
            .iter()
            .map(|v| syntax::atom(&p.sample, &Wgsl, *v))
            .collect();
        self.line(Level(1), &format!("return Sample({});", fields.join(", ")));
        self.out.push_str("}\n\n");
    }

    fn normal(&mut self) {
        self.out.push_str("fn scene_normal(p: vec3<f32>, e: f32) -> vec3<f32> {\n");
        let k = [
            "vec3<f32>(1.0, -1.0, -1.0)",
            "vec3<f32>(-1.0, -1.0, 1.0)",
            "vec3<f32>(-1.0, 1.0, -1.0)",
            "vec3<f32>(1.0, 1.0, 1.0)",
        ];
        for (i, ki) in k.iter().enumerate() {
            self.line(Level(1), &format!("let k{i} = {ki};"));
        }
        let terms: Vec<String> = (0..4).map(|i| format!("k{i} * scene_de(p + k{i} * e)")).collect();
        self.line(Level(1), &format!("let g = {};", terms.join(" + ")));
        self.line(Level(1), "let len = length(g);");
        self.line(Level(1), "return select(vec3<f32>(0.0, 1.0, 0.0), g / len, len > 0.0);");
        self.out.push_str("}\n\n");
    }

    fn ambient_occlusion(&mut self, strength: f64) {
        self.out.push_str("fn scene_ao(p: vec3<f32>, n: vec3<f32>) -> f32 {\n");
        self.line(Level(1), "var occ = 0.0;");
        self.line(Level(1), "var weight = 1.0;");
        self.line(Level(1), &format!("for (var i = 0; i < {AO_SAMPLES}; i++) {{"));
        self.line(
            Level(2),
            &format!("let h = {} + {} * f32(i) / {};", lit(AO_START), lit(AO_SPAN), lit((AO_SAMPLES - 1) as f64)),
        );
        self.line(Level(2), "occ += (h - scene_de(p + n * h)) * weight;");
        self.line(Level(2), "weight *= 0.95;");
        self.line(Level(1), "}");
        self.line(Level(1), &format!("return clamp(1.0 - {} * occ, 0.0, 1.0);", lit(3.0 * strength)));
        self.out.push_str("}\n\n");
    }

    fn shadow(&mut self) {
        let steps = self.p.settings.max_steps;
        self.out.push_str("fn scene_shadow(ro: vec3<f32>, rd: vec3<f32>, limit: f32, eps: f32) -> f32 {\n");
        let soft = if let Shadows::Soft(k) = self.p.settings.shadows { Some(k) } else { None };
        if soft.is_some() {
            self.line(Level(1), "var res = 1.0;");
            self.line(Level(1), "var t = 2.0 * eps;");
        } else {
            self.line(Level(1), "var t = 0.0;");
        }
        self.line(Level(1), &format!("for (var i = 0; i < {steps} && t < limit; i++) {{"));
        self.line(Level(2), "let d = scene_de(ro + rd * t);");
        self.line(Level(2), "if (d < eps) {");
        self.line(Level(3), "return 0.0;");
        self.line(Level(2), "}");
        if let Some(k) = soft {
            self.line(Level(2), &format!("res = min(res, {} * d / t);", lit(k)));
        }
        self.line(Level(2), "t += d;");
        self.line(Level(1), "}");
        if soft.is_some() {
            self.line(Level(1), "return res * res * (3.0 - 2.0 * res);");
        } else {
            self.line(Level(1), "return 1.0;");
        }
        self.out.push_str("}\n\n");
    }

    fn render(&mut self) {
        let s = &self.p.settings;
        let (l1, l2, l3) = (Level(1), Level(2), Level(3));
        self.out.push_str("@compute @workgroup_size(8, 8, 1)\n");
        self.out.push_str("fn render(@builtin(global_invocation_id) gid: vec3<u32>) {\n");
        for text in [
            "let w = u32(frame.right.w);",
            "let h = u32(frame.up.w);",
            "if (gid.x >= w || gid.y >= h) {",
            "    return;",
            "}",
            "let u = (2.0 * (f32(gid.x) + 0.5) - f32(w)) / f32(h);",
            "let v = -(2.0 * (f32(gid.y) + 0.5) - f32(h)) / f32(h);",
            "let ro = frame.origin.xyz;",
            "let rd = normalize(frame.forward.xyz + u * frame.right.xyz + v * frame.up.xyz);",
            "var t = 0.0;",
        ] {
            self.line(l1, text);
        }
        self.line(l1, &format!("var t_far = {};", lit(s.max_distance)));
        if let Some(b) = self.p.bound {
            self.line(l1, "{");
            self.line(l2, "// Clip the ray to the scene's bound: no marching through empty space.");
            self.line(l2, &format!("let m = max(abs(rd), vec3<f32>({}));", lit(MIN_DIRECTION)));
            self.line(l2, "let safe = select(-m, m, rd >= vec3<f32>(0.0));");
            self.line(l2, &format!("let t0 = ({} - ro) / safe;", vec3_lit(b.min)));
            self.line(l2, &format!("let t1 = ({} - ro) / safe;", vec3_lit(b.max)));
            self.line(l2, "let tn = min(t0, t1);");
            self.line(l2, "let tf = max(t0, t1);");
            self.line(l2, "t = max(max(max(tn.x, tn.y), tn.z), 0.0);");
            self.line(l2, "t_far = min(min(min(tf.x, tf.y), tf.z), t_far);");
            self.line(l1, "}");
        }
        self.line(l1, "var hit = false;");
        self.line(l1, "var eps = 0.0;");
        if s.glow.is_some() {
            self.line(l1, "var glow = 0.0;");
        }
        let eps_expr = match s.epsilon {
            HitEpsilon::Fixed(e) => lit(e),
            HitEpsilon::Pixel(k) => format!("{} * frame.forward.w * t", lit(k)),
        };
        self.line(l1, &format!("for (var i = 0; i < {} && t <= t_far; i++) {{", s.max_steps));
        self.line(l2, "let d = scene_de(ro + rd * t);");
        self.line(l2, &format!("eps = max({eps_expr}, {} * t);", lit(T_SPACING)));
        self.line(l2, "if (d < eps) {");
        self.line(l3, "hit = true;");
        self.line(l3, "break;");
        self.line(l2, "}");
        if s.glow.is_some() {
            self.line(l2, &format!("glow += 1.0 / (1.0 + {} * d * d);", lit(GLOW_FALLOFF)));
        }
        self.line(l2, "t += d;");
        self.line(l1, "}");
        self.line(l1, "var col: vec3<f32>;");
        self.line(l1, "if (hit) {");
        self.line(l2, "let p = ro + rd * t;");
        self.line(l2, "let n = scene_normal(p, eps);");
        self.line(l2, "let m = scene_sample(p);");
        if s.ambient_occlusion.is_some() {
            self.line(l2, "col = m.albedo * (m.ambient * scene_ao(p, n));");
        } else {
            self.line(l2, "col = m.albedo * m.ambient;");
        }
        let shadows = s.shadows != Shadows::None;
        for (i, shape) in self.p.lights.iter().enumerate() {
            let (dir_slot, color_slot) = (2 * i, 2 * i + 1);
            self.line(l2, "{");
            match shape {
                LightShape::Directional => {
                    self.line(l3, &format!("let l = frame.lights[{dir_slot}].xyz;"));
                    self.line(l3, &format!("let radiance = frame.lights[{color_slot}].xyz;"));
                    self.line(l3, &format!("let limit = {};", lit(s.max_distance)));
                }
                LightShape::Point => {
                    self.line(l3, &format!("let to_light = frame.lights[{dir_slot}].xyz - p;"));
                    self.line(l3, "let limit = length(to_light);");
                    self.line(l3, "let l = to_light / limit;");
                    self.line(l3, &format!("let radiance = frame.lights[{color_slot}].xyz / (limit * limit);"));
                }
            }
            self.line(l3, "let ndl = max(dot(n, l), 0.0);");
            let shade = if shadows {
                self.line(l3, "var shadow = 1.0;");
                self.line(l3, "if (ndl > 0.0) {");
                self.line(Level(4), "shadow = scene_shadow(p + n * (2.0 * eps), l, limit, eps);");
                self.line(l3, "}");
                " * shadow"
            } else {
                ""
            };
            self.line(l3, &format!("col += m.albedo * (m.diffuse * ndl) * radiance{shade};"));
            if self.p.specular {
                self.line(l3, "let hv = normalize(l - rd);");
                self.line(
                    l3,
                    &format!("col += (m.specular * pow(max(dot(n, hv), 0.0), m.shininess)) * radiance{shade};"),
                );
            }
            self.line(l2, "}");
        }
        if let Some(fog) = &s.fog {
            self.line(l2, &format!("col = mix(col, {}, 1.0 - exp({} * t));", vec3_lit(fog.color), lit(-fog.density)));
        }
        self.line(l1, "} else {");
        self.line(l2, &format!("col = {};", vec3_lit(s.background)));
        self.line(l1, "}");
        if let Some(g) = s.glow {
            self.line(l1, &format!("col += {} * min(glow / {}, 1.0);", vec3_lit(g), lit(GLOW_NORM)));
        }
        self.line(l1, "col = clamp(col, vec3<f32>(0.0), vec3<f32>(1.0));");
        if s.gamma == 2.0 {
            self.line(l1, "col = sqrt(col);");
        } else if s.gamma != 1.0 {
            self.line(l1, &format!("col = pow(col, vec3<f32>({}));", lit(1.0 / s.gamma)));
        }
        self.line(l1, "let c = vec3<u32>(col * 255.0 + 0.5);");
        self.line(l1, "out_px[gid.y * w + gid.x] = c.x | (c.y << 8u) | (c.z << 16u) | (255u << 24u);");
        self.out.push_str("}\n");
    }

    fn probe(&mut self) {
        self.out.push_str("@compute @workgroup_size(64, 1, 1)\n");
        self.out.push_str("fn probe(@builtin(global_invocation_id) gid: vec3<u32>) {\n");
        for text in [
            "// Keeps the frame binding in the pipeline's layout even when the scene reads nothing from it.",
            "_ = frame.origin;",
            "let i = gid.x;",
            "if (i >= arrayLength(&points)) {",
            "    return;",
            "}",
            "let p = points[i].xyz;",
            "let s = scene_sample(p);",
            "probe_out[2u * i] = vec4<f32>(scene_de(p), s.ambient, s.diffuse, s.specular);",
            "probe_out[2u * i + 1u] = vec4<f32>(s.albedo, s.shininess);",
        ] {
            self.line(Level(1), text);
        }
        self.out.push_str("}\n");
    }
}
