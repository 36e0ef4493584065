//! The HLSL writer: the HLSL [`Dialect`] of the shared GPU program ([`crate::back::kernel`]), for function
//! libraries. HLSL has no one-argument vector constructor (a scalar is cast to splat), calls `mix` `lerp`, and its
//! compilers warn about reading a variable no path may have set, so `col` starts at zero.

use crate::back::kernel::{self, Dialect};
use crate::back::syntax::common_math_name;
use crate::lower::code::{MathFn, Ty};
use crate::lower::Program;

struct Hlsl;

/// Writes `program` as an HLSL function library ([`kernel::write_library`]).
pub fn library(program: &Program, lib: &kernel::Library) -> String {
    kernel::write_library(program, lib, &Hlsl)
}

impl Dialect for Hlsl {
    fn language(&self) -> &'static str {
        "HLSL"
    }
    fn sample_struct(&self) -> String {
        "struct Sample {\n    float distance;\n    float3 albedo;\n    float ambient;\n    float diffuse;\n    float specular;\n    float shininess;\n};\n\n".to_string()
    }

    fn type_name(&self, ty: Ty) -> &'static str {
        match ty {
            Ty::F => "float",
            Ty::V3 => "float3",
            Ty::Pair => "float2",
            Ty::Bool => "bool",
            Ty::Int => "uint",
            // Never declared: a library has no frame, so no perturbed pattern reads an orbit.
            Ty::Orbit => "float2",
            Ty::Sample => "Sample",
        }
    }
    fn vec4_type(&self) -> &'static str {
        "float4"
    }
    fn construct(&self, ty: &str, components: &str) -> String {
        if components.contains(',') {
            format!("{ty}({components})")
        } else {
            format!("(({ty})({components}))")
        }
    }
    fn math_name(&self, f: MathFn) -> &'static str {
        match f {
            MathFn::Ln => "log",
            _ => common_math_name(f),
        }
    }

    fn global_constant(&self, name: &str, ty: &str, value: &str) -> String {
        format!("static const {ty} {name} = {value};")
    }
}
