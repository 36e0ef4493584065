//! The GLSL writer: the GLSL [`Dialect`] of the shared GPU program ([`crate::back::kernel`]), for function
//! libraries. It keeps to what GLSL 4.50, GLSL ES 3.00 and Godot's shading language share: no `const` on values
//! computed at run time (ES allows `const` only on constant expressions), vector comparisons by
//! `greaterThanEqual`, `atan(y, x)` for atan2.

use crate::back::f32_literal;
use crate::back::kernel::{self, Dialect};
use crate::back::syntax::{common_math_name, Prec};
use crate::lower::code::{MathFn, Ty};
use crate::lower::Program;

struct Glsl;

/// Writes `program` as a GLSL function library ([`kernel::write_library`]).
pub fn library(program: &Program, lib: &kernel::Library) -> String {
    kernel::write_library(program, lib, &Glsl)
}

impl Dialect for Glsl {
    fn language(&self) -> &'static str {
        "GLSL"
    }
    fn sample_struct(&self) -> String {
        "struct Sample {\n    float distance;\n    vec3 albedo;\n    float ambient;\n    float diffuse;\n    float specular;\n    float shininess;\n};\n\n".to_string()
    }

    fn type_name(&self, ty: Ty) -> &'static str {
        match ty {
            Ty::F => "float",
            Ty::V3 => "vec3",
            Ty::Pair => "vec2",
            Ty::Bool => "bool",
            Ty::Int => "uint",
            // Never declared: a library has no frame, so no perturbed pattern reads an orbit.
            Ty::Orbit => "vec2",
        }
    }
    fn vec4_type(&self) -> &'static str {
        "vec4"
    }
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
    fn index_lit(&self, v: u32) -> String {
        format!("{v}u")
    }
    fn cast(&self, ty: &str, v: &str) -> String {
        format!("{ty}({v})")
    }
    fn construct(&self, ty: &str, components: &str) -> String {
        format!("{ty}({components})")
    }
    fn vector_operand(&self, scalar: &str) -> String {
        scalar.to_string()
    }
    fn select_nonnegative(&self, v: &str, if_nonnegative: &str, if_negative: &str) -> String {
        // mix with a bool vector selects per component, exactly.
        let zero = self.construct("vec3", &self.lit(0.0));
        format!("mix({if_negative}, {if_nonnegative}, greaterThanEqual({v}, {zero}))")
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        match f {
            MathFn::Atan2 => "atan",
            MathFn::Ln => "log",
            _ => common_math_name(f),
        }
    }
    fn select(&self, cond: &str, if_true: &str, if_false: &str) -> String {
        format!("{cond} ? {if_true} : {if_false}")
    }
    fn select_prec(&self) -> Prec {
        Prec::Ternary
    }
    fn frame_field(&self, field: &str) -> String {
        format!("frame.{field}")
    }

    fn declare(&self, name: &str, ty: &str, value: &str, _mutable: bool) -> String {
        format!("{ty} {name} = {value};")
    }
    fn uninitialised(&self, name: &str, ty: &str) -> String {
        format!("{ty} {name};")
    }
    fn counted_loop(&self, bound: &str) -> String {
        format!("for (int i = 0; i < {bound}; i++) {{")
    }
    fn counted_loop_over(&self, index: &str, count: &str) -> String {
        format!("for (uint {index} = 0u; {index} < {count}; {index}++) {{")
    }

    fn frame_parameter(&self) -> Option<&'static str> {
        None
    }
    fn function_open(&self, ret: &str, name: &str, params: &[(&str, &str)]) -> String {
        let params: Vec<String> = params.iter().map(|(name, ty)| format!("{ty} {name}")).collect();
        format!("{ret} {name}({}) {{", params.join(", "))
    }
    fn sample_return(&self, fields: &[(&str, String)]) -> Vec<String> {
        let values: Vec<&str> = fields.iter().map(|(_, value)| value.as_str()).collect();
        vec![format!("return Sample({});", values.join(", "))]
    }
    fn global_constant(&self, name: &str, ty: &str, value: &str) -> String {
        format!("const {ty} {name} = {value};")
    }
}
