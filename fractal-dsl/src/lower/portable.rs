//! The f64 elementary functions of [`crate::number::portable`] traced, one function each, for kernels whose language
//! defines `sin`, `cos`, `acos`, `atan2`, `exp2`, `log` and `pow` for f32 only (WGSL on Vulkan): the writer calls
//! them by [`name`] and writes the ones a kernel calls.

use super::code::{Body, MathFn, Ty, Val};
use super::trace::{trace, Sym};
use crate::number::portable;

/// A traced elementary function: its parameters (F each), body and result.
#[derive(Clone, Debug, PartialEq)]
pub struct MathFunction {
    pub f: MathFn,
    pub params: Vec<(&'static str, Ty)>,
    pub body: Body,
    pub result: Val,
}

/// The math functions a device computes correctly in f64 everywhere: the built-ins an f64 kernel keeps.
pub fn exact_in_f64(f: MathFn) -> bool {
    matches!(f, MathFn::Abs | MathFn::Sqrt | MathFn::Floor | MathFn::Min | MathFn::Max)
}

/// The name an f64 kernel calls `f` by, where it is not a built-in there ([`exact_in_f64`]).
pub fn name(f: MathFn) -> &'static str {
    match f {
        MathFn::Sin => "portable_sin",
        MathFn::Cos => "portable_cos",
        MathFn::Acos => "portable_acos",
        MathFn::Atan2 => "portable_atan2",
        MathFn::Exp2 => "portable_exp2",
        MathFn::Ln => "portable_ln",
        MathFn::Pow => "portable_pow",
        MathFn::Abs | MathFn::Sqrt | MathFn::Floor | MathFn::Min | MathFn::Max => "",
    }
}

type Unary = fn(Sym) -> Sym;
type Binary = fn(Sym, Sym) -> Sym;

/// Every function [`name`] names, traced.
pub fn functions() -> Vec<MathFunction> {
    let unary: [(MathFn, Unary); 5] = [
        (MathFn::Sin, portable::sin),
        (MathFn::Cos, portable::cos),
        (MathFn::Acos, portable::acos),
        (MathFn::Exp2, portable::exp2),
        (MathFn::Ln, portable::ln),
    ];
    let binary: [(MathFn, [&'static str; 2], Binary); 2] =
        [(MathFn::Atan2, ["y", "x"], portable::atan2), (MathFn::Pow, ["x", "y"], portable::pow)];
    let one = unary.into_iter().map(|(f, g)| (f, vec!["x"], trace(|| g(Sym::arg("x")).0)));
    let two = binary.into_iter().map(|(f, [a, b], g)| (f, vec![a, b], trace(|| g(Sym::arg(a), Sym::arg(b)).0)));
    one.chain(two)
        .map(|(f, params, (body, result))| MathFunction {
            f,
            params: params.into_iter().map(|p| (p, Ty::F)).collect(),
            body: body.pruned(&[result]),
            result,
        })
        .collect()
}
