//! The GLSL writer: the GLSL [`Dialect`] of the shared GPU program ([`crate::back::kernel`]), for function
//! libraries. It keeps to what GLSL 4.50, GLSL ES 3.00 and Godot's shading language share: no `const` on values
//! computed at run time (ES allows `const` only on constant expressions), vector comparisons by
//! `greaterThanEqual`, `atan(y, x)` for atan2.

use crate::back::kernel::{self, Dialect};
use crate::back::syntax::common_math_name;
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
            Ty::Sample => "Sample",
        }
    }
    fn vec4_type(&self) -> &'static str {
        "vec4"
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        match f {
            MathFn::Atan2 => "atan",
            MathFn::Ln => "log",
            _ => common_math_name(f),
        }
    }

    fn declare(&self, name: &str, ty: &str, value: &str, _mutable: bool) -> String {
        format!("{ty} {name} = {value};")
    }

    fn sample_return(&self, fields: &[(&str, String)]) -> Vec<String> {
        let values: Vec<&str> = fields.iter().map(|(_, value)| value.as_str()).collect();
        vec![format!("return Sample({});", values.join(", "))]
    }
    fn global_constant(&self, name: &str, ty: &str, value: &str) -> String {
        format!("const {ty} {name} = {value};")
    }
}
