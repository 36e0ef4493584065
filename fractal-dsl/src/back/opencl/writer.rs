//! The OpenCL C writer: frames the lowered bodies with the uniform struct, the helpers, and the `render` or `probe`
//! kernel that implements [`crate::back::render`].

use std::fmt::Write;

use super::library;
use crate::back::render::*;
use crate::back::syntax::{self, group_julia, Syntax};
use crate::back::{f32_literal, Entry, Helper, Level};
use crate::ir::{HitEpsilon, Shadows};
use crate::lower::code::{MathFn, Ty};
use crate::lower::{LightShape, Program};

struct OpenCl;

const COMPONENTS: [&str; 4] = ["x", "y", "z", "w"];

fn lit(v: f64) -> String {
    format!("{}f", f32_literal(v))
}

fn vec3_lit(c: [f64; 3]) -> String {
    format!("(float3)({}, {}, {})", lit(c[0]), lit(c[1]), lit(c[2]))
}

impl Syntax for OpenCl {
    fn type_name(&self, ty: Ty) -> &'static str {
        match ty {
            Ty::F => "float",
            Ty::V3 => "float3",
            Ty::Pair => "float2",
            Ty::Bool => "int",
        }
    }
    fn declare(&self, name: &str, ty: Ty, value: &str, mutable: bool) -> String {
        let konst = if mutable { "" } else { "const " };
        format!("{konst}{} {name} = {value};", self.type_name(ty))
    }
    fn lit(&self, v: f64) -> String {
        lit(v)
    }
    fn int(&self, v: u32) -> String {
        v.to_string()
    }
    fn time(&self) -> String {
        "frame->origin.w".to_string()
    }
    fn param(&self, slot: usize) -> String {
        format!("frame->params[{}].{}", slot / 4, COMPONENTS[slot % 4])
    }
    fn make_v3(&self, x: &str, y: &str, z: &str) -> String {
        if x == y && y == z {
            format!("(float3)({x})")
        } else {
            format!("(float3)({x}, {y}, {z})")
        }
    }
    fn comp(&self, v: &str, _ty: Ty, i: u8) -> String {
        format!("{v}.{}", COMPONENTS[i as usize])
    }
    fn math(&self, f: MathFn, a: &[String]) -> String {
        let name = match f {
            MathFn::Sin => "sin",
            MathFn::Cos => "cos",
            MathFn::Abs => "fabs",
            MathFn::Sqrt => "sqrt",
            MathFn::Floor => "floor",
            MathFn::Min => "fmin",
            MathFn::Max => "fmax",
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
            group_julia(args, |c| format!("(float4)({})", c.join(", ")))
        } else {
            args.to_vec()
        };
        format!("{}({})", h.name(), args.join(", "))
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        format!("{cond} ? {if_true} : {if_false}")
    }
    fn less(&self, a: &str, b: &str) -> String {
        format!("({a} < {b})")
    }
    fn if_open(&self, cond: &str) -> String {
        format!("if {cond} {{")
    }
}

/// Writes the complete OpenCL C program for `entry`.
pub fn write(program: &Program, entry: Entry) -> String {
    let mut w = Writer { p: program, out: String::new() };
    w.header(entry);
    w.structs();
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

    /// `frame` as an extra argument of a scene function that reads it.
    fn frame_param(reads: bool) -> &'static str {
        if reads {
            ", __constant const Frame* frame"
        } else {
            ""
        }
    }
    fn frame_arg(reads: bool) -> &'static str {
        if reads {
            ", frame"
        } else {
            ""
        }
    }
    /// Whether functions built on scene_de / scene_sample need the frame.
    fn de(&self, p: &str) -> String {
        format!("scene_de({p}{})", Self::frame_arg(self.p.distance_reads_frame))
    }

    fn header(&mut self, entry: Entry) {
        let what = match entry {
            Entry::Render => "render kernel",
            Entry::Probe => "probe kernel",
        };
        let _ = writeln!(
            self.out,
            "// fractal: OpenCL C {what}, generated from a scene description. Edit the scene, not this file.\n"
        );
    }

    fn structs(&mut self) {
        let layout = self.p.layout();
        self.out
            .push_str("typedef struct {\n    float4 origin;\n    float4 right;\n    float4 up;\n    float4 forward;\n");
        let _ = writeln!(self.out, "    float4 lights[{}];", 2 * layout.lights);
        if layout.params > 0 {
            let _ = writeln!(self.out, "    float4 params[{}];", layout.param_slots());
        }
        self.out.push_str("} Frame;\n\n");
        self.out.push_str(
            "typedef struct {\n    float distance;\n    float3 albedo;\n    float ambient;\n    float diffuse;\n    float specular;\n    float shininess;\n} Sample;\n\n",
        );
    }

    fn scene_functions(&mut self) {
        let p = self.p;
        let _ = writeln!(self.out, "float scene_de(float3 p{}) {{", Self::frame_param(p.distance_reads_frame));
        syntax::write_body(&mut self.out, &p.distance, &OpenCl, Level(1));
        let result = syntax::atom(&p.distance, &OpenCl, p.distance_result);
        self.line(Level(1), &format!("return {result};"));
        self.out.push_str("}\n\n");

        let _ = writeln!(self.out, "Sample scene_sample(float3 p{}) {{", Self::frame_param(p.sample_reads_frame));
        syntax::write_body(&mut self.out, &p.sample, &OpenCl, Level(1));
        let r = p.sample_result;
        self.line(Level(1), "Sample s;");
        for (field, v) in [
            ("distance", r.distance),
            ("albedo", r.albedo),
            ("ambient", r.ambient),
            ("diffuse", r.diffuse),
            ("specular", r.specular),
            ("shininess", r.shininess),
        ] {
            let value = syntax::atom(&p.sample, &OpenCl, v);
            self.line(Level(1), &format!("s.{field} = {value};"));
        }
        self.line(Level(1), "return s;");
        self.out.push_str("}\n\n");
    }

    fn normal(&mut self) {
        let fp = Self::frame_param(self.p.distance_reads_frame);
        let _ = writeln!(self.out, "float3 scene_normal(float3 p, float e{fp}) {{");
        let k = [
            "(float3)(1.0f, -1.0f, -1.0f)",
            "(float3)(-1.0f, -1.0f, 1.0f)",
            "(float3)(-1.0f, 1.0f, -1.0f)",
            "(float3)(1.0f, 1.0f, 1.0f)",
        ];
        for (i, ki) in k.iter().enumerate() {
            self.line(Level(1), &format!("const float3 k{i} = {ki};"));
        }
        let terms: Vec<String> = (0..4).map(|i| format!("k{i} * {}", self.de(&format!("p + k{i} * e")))).collect();
        self.line(Level(1), &format!("const float3 g = {};", terms.join(" + ")));
        self.line(Level(1), "const float len = length(g);");
        self.line(Level(1), "return len > 0.0f ? g / len : (float3)(0.0f, 1.0f, 0.0f);");
        self.out.push_str("}\n\n");
    }

    fn ambient_occlusion(&mut self, strength: f64) {
        let fp = Self::frame_param(self.p.distance_reads_frame);
        let _ = writeln!(self.out, "float scene_ao(float3 p, float3 n{fp}) {{");
        self.line(Level(1), "float occ = 0.0f;");
        self.line(Level(1), "float weight = 1.0f;");
        self.line(Level(1), &format!("for (int i = 0; i < {AO_SAMPLES}; i++) {{"));
        self.line(
            Level(2),
            &format!(
                "const float h = {} + {} * (float)i / {};",
                lit(AO_START),
                lit(AO_SPAN),
                lit((AO_SAMPLES - 1) as f64)
            ),
        );
        self.line(Level(2), &format!("occ += (h - {}) * weight;", self.de("p + n * h")));
        self.line(Level(2), "weight *= 0.95f;");
        self.line(Level(1), "}");
        self.line(Level(1), &format!("return clamp(1.0f - {} * occ, 0.0f, 1.0f);", lit(3.0 * strength)));
        self.out.push_str("}\n\n");
    }

    fn shadow(&mut self) {
        let fp = Self::frame_param(self.p.distance_reads_frame);
        let steps = self.p.settings.max_steps;
        let _ = writeln!(self.out, "float scene_shadow(float3 ro, float3 rd, float limit, float eps{fp}) {{");
        match self.p.settings.shadows {
            Shadows::Soft(k) => {
                self.line(Level(1), "float res = 1.0f;");
                self.line(Level(1), "float t = 2.0f * eps;");
                self.line(Level(1), &format!("for (int i = 0; i < {steps} && t < limit; i++) {{"));
                self.line(Level(2), &format!("const float d = {};", self.de("ro + rd * t")));
                self.line(Level(2), "if (d < eps) {");
                self.line(Level(3), "return 0.0f;");
                self.line(Level(2), "}");
                self.line(Level(2), &format!("res = fmin(res, {} * d / t);", lit(k)));
                self.line(Level(2), "t += d;");
                self.line(Level(1), "}");
                self.line(Level(1), "return res * res * (3.0f - 2.0f * res);");
            }
            _ => {
                self.line(Level(1), "float t = 0.0f;");
                self.line(Level(1), &format!("for (int i = 0; i < {steps} && t < limit; i++) {{"));
                self.line(Level(2), &format!("const float d = {};", self.de("ro + rd * t")));
                self.line(Level(2), "if (d < eps) {");
                self.line(Level(3), "return 0.0f;");
                self.line(Level(2), "}");
                self.line(Level(2), "t += d;");
                self.line(Level(1), "}");
                self.line(Level(1), "return 1.0f;");
            }
        }
        self.out.push_str("}\n\n");
    }

    fn render(&mut self) {
        let s = &self.p.settings;
        let l1 = Level(1);
        let l2 = Level(2);
        let l3 = Level(3);
        self.out.push_str("__kernel void render(__global uint* out, __constant const Frame* frame) {\n");
        for text in [
            "const int x = (int)get_global_id(0);",
            "const int y = (int)get_global_id(1);",
            "const int w = (int)frame->right.w;",
            "const int h = (int)frame->up.w;",
            "if (x >= w || y >= h) {",
            "    return;",
            "}",
            "const float u = (2.0f * ((float)x + 0.5f) - (float)w) / (float)h;",
            "const float v = -(2.0f * ((float)y + 0.5f) - (float)h) / (float)h;",
            "const float3 ro = frame->origin.xyz;",
            "const float3 rd = normalize(frame->forward.xyz + u * frame->right.xyz + v * frame->up.xyz);",
            "float t = 0.0f;",
        ] {
            self.line(l1, text);
        }
        self.line(l1, &format!("float t_far = {};", lit(s.max_distance)));
        if let Some(b) = self.p.bound {
            self.line(l1, "{");
            self.line(l2, "// Clip the ray to the scene's bound: no marching through empty space.");
            self.line(l2, &format!("const float3 m = fmax(fabs(rd), (float3)({}));", lit(MIN_DIRECTION)));
            self.line(l2, "const float3 safe = select(-m, m, rd >= (float3)(0.0f));");
            self.line(l2, &format!("const float3 t0 = ({} - ro) / safe;", vec3_lit(b.min)));
            self.line(l2, &format!("const float3 t1 = ({} - ro) / safe;", vec3_lit(b.max)));
            self.line(l2, "const float3 tn = fmin(t0, t1);");
            self.line(l2, "const float3 tf = fmax(t0, t1);");
            self.line(l2, "t = fmax(fmax(fmax(tn.x, tn.y), tn.z), 0.0f);");
            self.line(l2, "t_far = fmin(fmin(fmin(tf.x, tf.y), tf.z), t_far);");
            self.line(l1, "}");
        }
        self.line(l1, "int hit = 0;");
        self.line(l1, "float eps = 0.0f;");
        let glow = s.glow;
        if glow.is_some() {
            self.line(l1, "float glow = 0.0f;");
        }
        let eps_expr = match s.epsilon {
            HitEpsilon::Fixed(e) => lit(e),
            HitEpsilon::Pixel(k) => format!("{} * frame->forward.w * t", lit(k)),
        };
        self.line(l1, &format!("for (int i = 0; i < {} && t <= t_far; i++) {{", s.max_steps));
        self.line(l2, &format!("const float d = {};", self.de("ro + rd * t")));
        self.line(l2, &format!("eps = fmax({eps_expr}, {} * t);", lit(T_SPACING)));
        self.line(l2, "if (d < eps) {");
        self.line(l3, "hit = 1;");
        self.line(l3, "break;");
        self.line(l2, "}");
        if glow.is_some() {
            self.line(l2, &format!("glow += 1.0f / (1.0f + {} * d * d);", lit(GLOW_FALLOFF)));
        }
        self.line(l2, "t += d;");
        self.line(l1, "}");
        self.line(l1, "float3 col;");
        self.line(l1, "if (hit) {");
        self.line(l2, "const float3 p = ro + rd * t;");
        let fa = Self::frame_arg(self.p.distance_reads_frame);
        self.line(l2, &format!("const float3 n = scene_normal(p, eps{fa});"));
        let fs = Self::frame_arg(self.p.sample_reads_frame);
        self.line(l2, &format!("const Sample m = scene_sample(p{fs});"));
        if s.ambient_occlusion.is_some() {
            self.line(l2, &format!("col = m.albedo * (m.ambient * scene_ao(p, n{fa}));"));
        } else {
            self.line(l2, "col = m.albedo * m.ambient;");
        }
        let shadows = s.shadows != Shadows::None;
        for (i, shape) in self.p.lights.iter().enumerate() {
            let (dir_slot, color_slot) = (2 * i, 2 * i + 1);
            self.line(l2, "{");
            match shape {
                LightShape::Directional => {
                    self.line(l3, &format!("const float3 l = frame->lights[{dir_slot}].xyz;"));
                    self.line(l3, &format!("const float3 radiance = frame->lights[{color_slot}].xyz;"));
                    self.line(l3, &format!("const float limit = {};", lit(s.max_distance)));
                }
                LightShape::Point => {
                    self.line(l3, &format!("const float3 to_light = frame->lights[{dir_slot}].xyz - p;"));
                    self.line(l3, "const float limit = length(to_light);");
                    self.line(l3, "const float3 l = to_light / limit;");
                    self.line(
                        l3,
                        &format!("const float3 radiance = frame->lights[{color_slot}].xyz / (limit * limit);"),
                    );
                }
            }
            self.line(l3, "const float ndl = fmax(dot(n, l), 0.0f);");
            let shade = if shadows {
                self.line(l3, "float shadow = 1.0f;");
                self.line(l3, "if (ndl > 0.0f) {");
                self.line(Level(4), &format!("shadow = scene_shadow(p + n * (2.0f * eps), l, limit, eps{fa});"));
                self.line(l3, "}");
                " * shadow"
            } else {
                ""
            };
            self.line(l3, &format!("col += m.albedo * (m.diffuse * ndl) * radiance{shade};"));
            if self.p.specular {
                self.line(l3, "const float3 hv = normalize(l - rd);");
                self.line(
                    l3,
                    &format!("col += (m.specular * pow(fmax(dot(n, hv), 0.0f), m.shininess)) * radiance{shade};"),
                );
            }
            self.line(l2, "}");
        }
        if let Some(fog) = &s.fog {
            self.line(l2, &format!("col = mix(col, {}, 1.0f - exp({} * t));", vec3_lit(fog.color), lit(-fog.density)));
        }
        self.line(l1, "} else {");
        self.line(l2, &format!("col = {};", vec3_lit(s.background)));
        self.line(l1, "}");
        if let Some(g) = glow {
            self.line(l1, &format!("col += {} * fmin(glow / {}, 1.0f);", vec3_lit(g), lit(GLOW_NORM)));
        }
        self.line(l1, "col = clamp(col, 0.0f, 1.0f);");
        if s.gamma == 2.0 {
            self.line(l1, "col = sqrt(col);");
        } else if s.gamma != 1.0 {
            self.line(l1, &format!("col = pow(col, (float3)({}));", lit(1.0 / s.gamma)));
        }
        for text in [
            "const uint r = (uint)(col.x * 255.0f + 0.5f);",
            "const uint g = (uint)(col.y * 255.0f + 0.5f);",
            "const uint b = (uint)(col.z * 255.0f + 0.5f);",
            "out[y * w + x] = r | (g << 8) | (b << 16) | (255u << 24);",
        ] {
            self.line(l1, text);
        }
        self.out.push_str("}\n");
    }

    fn probe(&mut self) {
        let fa = Self::frame_arg(self.p.distance_reads_frame);
        let fs = Self::frame_arg(self.p.sample_reads_frame);
        self.out.push_str(
            "__kernel void probe(__global const float4* points, __global float4* out, __constant const Frame* frame, uint n) {\n",
        );
        for text in [
            "const uint i = (uint)get_global_id(0);".to_string(),
            "if (i >= n) {".to_string(),
            "    return;".to_string(),
            "}".to_string(),
            "const float3 p = points[i].xyz;".to_string(),
            format!("const Sample s = scene_sample(p{fs});"),
            format!("out[2 * i] = (float4)(scene_de(p{fa}), s.ambient, s.diffuse, s.specular);"),
            "out[2 * i + 1] = (float4)(s.albedo, s.shininess);".to_string(),
        ] {
            self.line(Level(1), &text);
        }
        self.out.push_str("}\n");
    }
}
