//! Writes a formula ([`crate::ir::formula`]) back as the closure it was parsed from, in canonical form: every `let`
//! with its name, operands that are not single terms in parentheses, scene numbers as [`super::expr`] writes them.

use crate::ir::formula::{FExpr, FLogic, Formula, FormulaKind, FormulaMap};
use crate::ir::Expr;

/// The call that makes the fractal: `escape_time(|z, c| ..)`, `hybrid(|z, c| .., |z, c| ..)` or `fold(|z, c| ..)`.
pub fn call(formula: &Formula) -> String {
    let maps: Vec<String> = formula.maps.iter().map(map).collect();
    let name = match (formula.kind, maps.len()) {
        (FormulaKind::Fold, _) => "fold",
        (FormulaKind::EscapeTime, 1) => "escape_time",
        (FormulaKind::EscapeTime, _) => "hybrid",
    };
    format!("{name}({})", maps.join(", "))
}

/// One map as a closure.
pub fn map(m: &FormulaMap<Expr>) -> String {
    let params = m.params.join(", ");
    let names = Names { map: m };
    let result = match &m.scale {
        Some(s) => format!("({}, {})", names.expr(&m.next), names.expr(s)),
        None => names.expr(&m.next),
    };
    if m.lets.is_empty() {
        return format!("|{params}| {result}");
    }
    let lets: String = m.lets.iter().map(|(name, e)| format!("let {name} = {}; ", names.expr(e))).collect();
    format!("|{params}| {{ {lets}{result} }}")
}

struct Names<'a> {
    map: &'a FormulaMap<Expr>,
}

impl Names<'_> {
    /// An operand: in parentheses unless it is a single term.
    fn operand(&self, e: &FExpr<Expr>) -> String {
        let atomic = match e {
            FExpr::Num(n) => matches!(n, Expr::Lit(v) if *v >= 0.0) || matches!(n, Expr::Time | Expr::Param(_)),
            FExpr::Arg(_) | FExpr::Let(_) | FExpr::Call(..) | FExpr::Swizzle(..) => true,
            _ => false,
        };
        if atomic {
            self.expr(e)
        } else {
            format!("({})", self.expr(e))
        }
    }

    fn expr(&self, e: &FExpr<Expr>) -> String {
        match e {
            FExpr::Num(n) => super::number::expr(n),
            FExpr::Arg(i) => self.map.params.get(*i as usize).cloned().unwrap_or_else(|| "z".into()),
            FExpr::Let(i) => self.map.lets.get(*i as usize).map_or_else(|| "z".into(), |(n, _)| n.clone()),
            FExpr::Neg(a) => format!("-{}", self.operand(a)),
            FExpr::Not(a) => format!("!{}", self.operand(a)),
            FExpr::Bin(op, a, b) => format!("{} {} {}", self.operand(a), op.symbol(), self.operand(b)),
            FExpr::Call(f, args) => {
                let args: Vec<String> = args.iter().map(|a| self.expr(a)).collect();
                format!("{}({})", f.name(), args.join(", "))
            }
            FExpr::Swizzle(a, s) => format!("{}.{}", self.operand(a), s.text()),
            FExpr::Cmp(op, a, b) => format!("{} {} {}", self.operand(a), op.symbol(), self.operand(b)),
            FExpr::Logic(op, a, b) => {
                let symbol = if *op == FLogic::And { "&&" } else { "||" };
                format!("{} {symbol} {}", self.operand(a), self.operand(b))
            }
            FExpr::If(c, a, b) => format!("if {} {{ {} }} else {{ {} }}", self.expr(c), self.expr(a), self.expr(b)),
        }
    }
}
