//! Scene numbers as text: literals that read back as the same `f64`, and expressions with the parentheses their
//! operators need. The scene printer and the formula printer both write numbers through here.

use crate::ir::{BinOp, Expr};

/// A number literal that reads back as exactly `v`.
pub(super) fn lit(v: f64) -> String {
    if v.is_finite() {
        format!("{v:?}")
    } else if v.is_nan() {
        // Not a valid scene value (validation refuses it); written so the text still parses as an expression.
        "(0.0 / 0.0)".to_string()
    } else if v > 0.0 {
        "1e999".to_string()
    } else {
        "-1e999".to_string()
    }
}

/// Binding strength of an expression's outermost operator.
fn precedence(e: &Expr) -> u8 {
    match e {
        Expr::Bin(BinOp::Add | BinOp::Sub, ..) => 1,
        Expr::Bin(BinOp::Mul | BinOp::Div, ..) => 2,
        Expr::Neg(_) => 3,
        Expr::Lit(v) if v.is_sign_negative() || !v.is_finite() => 3,
        _ => 4,
    }
}

/// The names of the point's coordinates in scene source.
pub const POINT_NAMES: [&str; 3] = ["x", "y", "z"];

/// Writes a scalar expression.
pub fn expr(e: &Expr) -> String {
    match e {
        Expr::Lit(v) => lit(*v),
        Expr::Time => "t".to_string(),
        Expr::Point(axis) => POINT_NAMES[*axis as usize % 3].to_string(),
        Expr::Param(p) => format!("param({:?}, {}, {}..{})", p.name, lit(p.default), lit(p.min), lit(p.max)),
        // A literal, a negation or an operator under `-` is parenthesised: `-1.0` would read back as one literal,
        // and `--x` would make a run of signs.
        Expr::Neg(a) => match **a {
            Expr::Lit(_) | Expr::Neg(_) | Expr::Bin(..) => format!("-({})", expr(a)),
            _ => format!("-{}", expr(a)),
        },
        Expr::Bin(op, a, c) => {
            let p = precedence(e);
            let left = if precedence(a) < p { format!("({})", expr(a)) } else { expr(a) };
            let right = if precedence(c) <= p { format!("({})", expr(c)) } else { expr(c) };
            format!("{left} {} {right}", op.symbol())
        }
        Expr::Call(f, args) => {
            let written: Vec<String> = args
                .iter()
                .enumerate()
                .map(|(i, a)| match a {
                    // A count is an integer in source (`fbm2(x, z, 4)`), not `4.0`.
                    Expr::Lit(n) if f.takes_count() && i + 1 == args.len() && n.fract() == 0.0 && *n >= 0.0 => {
                        format!("{}", *n as u64)
                    }
                    _ => expr(a),
                })
                .collect();
            format!("{}({})", f.name(), written.join(", "))
        }
    }
}
