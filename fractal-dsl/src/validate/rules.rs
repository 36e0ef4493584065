//! The rules of one number or vector (its limits, finiteness, the f32 range), checked on constants directly and on
//! values that read `t` or a `param` over the range they can take.

use super::problem::*;
use crate::analyse::fold::fold_expr;
use crate::analyse::interval::{range, Interval};
use crate::ir::*;

/// Allowed values of one number: optional ends, each open or closed.
#[derive(Clone, Copy, Debug)]
pub(super) struct Limits {
    pub(super) lo: Option<(f64, bool)>,
    pub(super) hi: Option<(f64, bool)>,
    /// Describe both ends together ("in (0, 1)") rather than the end that was crossed.
    pub(super) as_interval: bool,
}

pub(super) const fn gt(x: f64) -> Limits {
    Limits { lo: Some((x, false)), hi: None, as_interval: false }
}
pub(super) const fn ge(x: f64) -> Limits {
    Limits { lo: Some((x, true)), hi: None, as_interval: false }
}
/// Both ends, reported one at a time (">= 2", "<= 64").
pub(super) const fn ge_le(lo: f64, hi: f64) -> Limits {
    Limits { lo: Some((lo, true)), hi: Some((hi, true)), as_interval: false }
}
/// Both ends, reported as an interval with the given closedness.
pub(super) const fn within(lo: f64, lo_closed: bool, hi: f64, hi_closed: bool) -> Limits {
    Limits { lo: Some((lo, lo_closed)), hi: Some((hi, hi_closed)), as_interval: true }
}

impl Limits {
    fn lo_ok(&self, v: f64) -> bool {
        self.lo.is_none_or(|(lo, closed)| if closed { v >= lo } else { v > lo })
    }
    fn hi_ok(&self, v: f64) -> bool {
        self.hi.is_none_or(|(hi, closed)| if closed { v <= hi } else { v < hi })
    }
    fn describe_lo(&self) -> String {
        match self.lo {
            Some((lo, closed)) => format!("{} {}", if closed { ">=" } else { ">" }, number_text(lo)),
            None => String::new(),
        }
    }
    fn describe_hi(&self) -> String {
        match self.hi {
            Some((hi, closed)) => format!("{} {}", if closed { "<=" } else { "<" }, number_text(hi)),
            None => String::new(),
        }
    }
    fn describe_interval(&self) -> String {
        match (self.lo, self.hi) {
            (Some((lo, lc)), Some((hi, hc))) => {
                format!(
                    "in {}{}, {}{}",
                    if lc { "[" } else { "(" },
                    number_text(lo),
                    number_text(hi),
                    if hc { "]" } else { ")" }
                )
            }
            _ => format!("{}{}", self.describe_lo(), self.describe_hi()),
        }
    }
    /// The description of the rule a value broke (the crossed end, or the whole interval).
    fn describe(&self, low_side: bool) -> String {
        if self.as_interval {
            self.describe_interval()
        } else if low_side {
            self.describe_lo()
        } else {
            self.describe_hi()
        }
    }
}

/// A number as messages show it: integers without a fraction, very large or small values in exponent form.
pub fn number_text(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Whether an expression depends on nothing (no `t`, no `param`, no point).
pub fn is_constant(e: &Expr) -> bool {
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match e {
            Expr::Lit(_) => {}
            Expr::Time | Expr::Param(_) | Expr::Point(_) => return false,
            Expr::Neg(a) => stack.push(a),
            Expr::Bin(_, a, b) => stack.extend([&**a, &**b]),
            Expr::Call(_, args) => stack.extend(args),
        }
    }
    true
}

/// The value of a constant expression.
pub fn constant_value(e: &Expr) -> Option<f64> {
    is_constant(e).then(|| e.eval_default(0.0))
}

/// Largest magnitude a number of a scene may have: the kernels compute in f32, where anything larger is infinite.
pub const MAX_MAGNITUDE: f64 = f32::MAX as f64;

/// Why `v` cannot be a number of a scene, if it cannot: not finite, or beyond the f32 range the kernels compute in
/// (`1e308` is finite in f64 and `inf` on every GPU).
pub fn value_problem(v: f64) -> Option<String> {
    if !v.is_finite() {
        Some(format!("numbers must be finite, found {}", number_text(v)))
    } else if v.abs() > MAX_MAGNITUDE {
        Some(format!("numbers must lie within ±3.4e38 (the kernels compute in f32), found {}", number_text(v)))
    } else {
        None
    }
}

/// The message for a literal that is not finite or beyond the f32 range, if the expression holds one.
pub fn literal_problem(e: &Expr) -> Option<String> {
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match e {
            Expr::Lit(v) if value_problem(*v).is_some() => return value_problem(*v),
            Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => {}
            Expr::Neg(a) => stack.push(a),
            Expr::Bin(_, a, b) => stack.extend([&**a, &**b]),
            Expr::Call(_, args) => stack.extend(args),
        }
    }
    None
}

/// The values an expression can take: one point for a constant, the interval analysis' range otherwise.
pub(super) fn value_range(e: &Expr) -> (Interval, bool) {
    match constant_value(e) {
        Some(v) => (Interval { lo: v, hi: v }, true),
        None => {
            let r = range(e);
            // A NaN end means the analysis knows nothing: treat it as unbounded.
            let lo = if r.lo.is_nan() { f64::NEG_INFINITY } else { r.lo };
            let hi = if r.hi.is_nan() { f64::INFINITY } else { r.hi };
            (Interval { lo, hi }, false)
        }
    }
}

/// Checks one number against its limits; `what` names it in the message ("sphere radius").
pub(super) fn number(out: &mut Vec<Problem>, arg: &'static str, what: &str, e: &Expr, lim: Limits) {
    if let Some(m) = literal_problem(&fold_expr(e)) {
        out.push(Problem::new(arg, format!("{what}: {m}")));
        return;
    }
    let (r, constant) = value_range(e);
    if constant {
        let v = r.lo;
        if !v.is_finite() {
            out.push(Problem::new(arg, format!("{what} must be finite, found {}", number_text(v))));
        } else if !lim.lo_ok(v) {
            out.push(Problem::new(arg, format!("{what} must be {}, found {}", lim.describe(true), number_text(v))));
        } else if !lim.hi_ok(v) {
            out.push(Problem::new(arg, format!("{what} must be {}, found {}", lim.describe(false), number_text(v))));
        }
        return;
    }
    let unbounded = |end: f64| !end.is_finite();
    let span = format!("{}..{}", number_text(r.lo), number_text(r.hi));
    let low_bad = lim.lo.is_some() && !lim.lo_ok(r.lo);
    let high_bad = lim.hi.is_some() && !lim.hi_ok(r.hi);
    let message = if low_bad {
        let rule = lim.describe(true);
        if unbounded(r.lo) {
            format!("{what} must be {rule}, but no lower bound is known for its value, so it may leave that range")
        } else {
            format!("{what} must be {rule}, but it can go down to {} (its range is {span})", number_text(r.lo))
        }
    } else if high_bad {
        let rule = lim.describe(false);
        if unbounded(r.hi) {
            format!("{what} must be {rule}, but no upper bound is known for its value, so it may leave that range")
        } else {
            format!("{what} must be {rule}, but it can go up to {} (its range is {span})", number_text(r.hi))
        }
    } else {
        return;
    };
    out.push(Problem::new(arg, message));
}

pub(super) const AXES: [&str; 3] = ["x", "y", "z"];

/// Checks each component of a vector against the same limits ("box3 half extent y must be > 0").
pub(super) fn vector(out: &mut Vec<Problem>, arg: &'static str, what: &str, v: &Vec3Expr, lim: Limits) {
    for (e, axis) in v.0.iter().zip(AXES) {
        number(out, arg, &format!("{what} {axis}"), e, lim);
    }
}

/// Checks that each expression holds no non-finite number, written (`1e999`) or computed from literals (`0.0 / 0.0`,
/// `t * (1e300 * 1e300)`): folding makes a computed one a literal first.
pub(super) fn finite(out: &mut Vec<Problem>, arg: &'static str, what: &str, exprs: &[&Expr]) {
    if let Some(m) = exprs.iter().find_map(|e| literal_problem(&fold_expr(e))) {
        out.push(Problem::new(arg, format!("{what}: {m}")));
    }
}

pub(super) fn integer(out: &mut Vec<Problem>, arg: &'static str, what: &str, v: u32, lo: u32, hi: u32) {
    if !(lo..=hi).contains(&v) {
        out.push(Problem::new(arg, format!("{what} must be in {lo}..={hi}, found {v}")));
    }
}

pub(super) fn constant(out: &mut Vec<Problem>, arg: &'static str, what: &str, v: f64, lim: Limits) {
    number(out, arg, what, &Expr::Lit(v), lim)
}

// ---- per-value checks ---------------------------------------------------------------------------------------------
