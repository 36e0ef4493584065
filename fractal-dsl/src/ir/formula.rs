//! Fractals written in the scene language, in the IR: the formula language ([`crate::formula::lang`]) with the
//! scene's own expressions as its numbers.

pub use crate::formula::lang::{
    FBin, FCmp, FExpr, FFunc, FLogic, FTy, FormulaKind, FormulaMap, Swizzle, MAX_FORMULA_NODES, MAX_HYBRID_MAPS,
    MAX_LETS,
};

/// A formula of a scene: its numbers are expressions of the scene (`t`, `param(..)`, literals).
pub type Formula = crate::formula::lang::Formula<super::Expr>;
