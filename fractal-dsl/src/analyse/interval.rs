//! Interval arithmetic over expressions: the range a value can take for any time t ≥ 0 and any parameter value
//! within its declared range. Bounds use it so an animated radius is bounded by its largest value.
//!
//! Every operation is conservative: the value of the expression lies in the interval for every time and every
//! parameter setting. Where an operation can produce NaN or has no useful limit (division by an interval containing
//! zero, the square root of a possibly negative value, a fractional power of a possibly negative base), the answer is
//! [`Interval::ENTIRE`]. NaN itself is no value: an expression that produces one somewhere (and then perhaps loses it
//! in a `min`, which each shading language treats differently) is outside what a range promises.

pub use crate::geom::Interval;
use crate::ir::{BinOp, Expr, Func};

/// The range of `e`.
pub fn range(e: &Expr) -> Interval {
    match e {
        Expr::Lit(v) => Interval::point(*v),
        Expr::Time => Interval::TIME,
        // The point can be anywhere.
        Expr::Point(_) => Interval::ENTIRE,
        // The default is included so a declaration whose default lies outside its range stays covered.
        Expr::Param(p) => Interval::new(p.min, p.max).hull(Interval::point(p.default)),
        Expr::Neg(a) => -range(a),
        Expr::Bin(op, a, b) => {
            let (a, b) = (range(a), range(b));
            match op {
                BinOp::Add => a + b,
                BinOp::Sub => a - b,
                BinOp::Mul => a * b,
                BinOp::Div => a / b,
            }
        }
        Expr::Call(f, args) => {
            let arg = |i: usize| args.get(i).map(range).unwrap_or(Interval::ENTIRE);
            match f {
                Func::Sin => arg(0).sin(),
                Func::Cos => arg(0).cos(),
                Func::Abs => arg(0).abs(),
                Func::Sqrt => arg(0).sqrt(),
                Func::Min => arg(0).min(arg(1)),
                Func::Max => arg(0).max(arg(1)),
                Func::Pow => arg(0).pow(arg(1)),
                Func::Clamp => arg(0).clamp(arg(1), arg(2)),
                Func::Mix => arg(0).mix(arg(1), arg(2)),
                Func::Noise2 | Func::Noise3 => Interval::new(-1.0, 1.0),
                Func::Fbm2 | Func::Fbm3 => {
                    Interval::new(-crate::formula::noise::FBM_RANGE, crate::formula::noise::FBM_RANGE)
                }
                Func::Mandelbrot => Interval::new(0.0, 1.0),
            }
        }
    }
}

/// The range of a declared argument's value.
pub fn arg_range(a: &crate::ir::ArgValue) -> crate::ir::arg::ArgRange {
    use crate::ir::{arg::ArgRange, ArgValue};
    match a {
        ArgValue::Num(e) => ArgRange::Num(range(e)),
        ArgValue::Vec3(v) => ArgRange::Vec3([0, 1, 2].map(|i| range(&v.0[i]))),
    }
}
