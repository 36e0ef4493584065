//! Formulas: a closure `|z, c| { let a = ..; .. }` in syn's tree to a typed [`FormulaMap`]. Every name, call,
//! operator and component is checked here, at its own span, so an error in a formula points at `line:column` inside
//! it; scene numbers (`t`, `PI`, `param(..)`) inside a formula are built as anywhere else in the scene.

use syn::spanned::Spanned;

use super::build::{error, Lower, MAX_EVAL_DEPTH};
use super::names::Value;
use crate::ir::formula::{FBin, FCmp, FExpr, FFunc, FLogic, FTy, FormulaMap, Swizzle, MAX_FORMULA_NODES, MAX_LETS};
use crate::ir::Expr;

type Typed = (FExpr<Expr>, FTy);

/// A name in scope: the closure's argument `index` or the `let` binding `index`.
#[derive(Clone, Copy)]
enum Binding {
    Arg(u8),
    Let(u16, FTy),
}

struct Scope {
    names: Vec<(String, Binding)>,
    /// Expression nodes so far in this formula.
    nodes: usize,
}

impl Scope {
    fn find(&self, name: &str) -> Option<Binding> {
        self.names.iter().rev().find(|(n, _)| n == name).map(|(_, b)| *b)
    }
    fn names(&self) -> String {
        let mut seen: Vec<&str> = Vec::new();
        for (n, _) in &self.names {
            if !seen.contains(&n.as_str()) {
                seen.push(n);
            }
        }
        seen.iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
    }
}

impl Lower {
    /// Parses the closure of `escape_time(..)`, `fold(..)` or `hybrid(..)`; `own_scale` allows a fold's
    /// `(z, scale)` result.
    pub(super) fn formula_map(
        &mut self,
        e: &syn::Expr,
        own_scale: bool,
        depth: usize,
    ) -> syn::Result<FormulaMap<Expr>> {
        let syn::Expr::Closure(closure) = e else {
            return Err(error(e, "a formula is a closure: |z, c| expression, e.g. |z, c| box_fold(z, 1.0) * 2.0 + c"));
        };
        if closure.lifetimes.is_some()
            || closure.constness.is_some()
            || closure.movability.is_some()
            || closure.asyncness.is_some()
            || closure.capture.is_some()
            || !matches!(closure.output, syn::ReturnType::Default)
        {
            return Err(error(closure, "a formula is a plain closure |z, c| ..: no keywords or return type"));
        }
        let mut params = Vec::new();
        for input in &closure.inputs {
            let syn::Pat::Ident(id) = input else {
                return Err(error(input, "a formula's parameters are plain names: |z, c|"));
            };
            if id.by_ref.is_some() || id.mutability.is_some() || id.subpat.is_some() {
                return Err(error(input, "a formula's parameters are plain names: |z, c|"));
            }
            params.push(id.ident.to_string());
        }
        if params.is_empty() || params.len() > 2 {
            return Err(error(
                &closure.inputs,
                format!(
                    "a formula takes z, the orbit's point, and optionally c, the point drawn: |z, c|; found {} \
                         parameters",
                    params.len()
                ),
            ));
        }
        let mut scope = Scope {
            names: params.iter().enumerate().map(|(i, n)| (n.clone(), Binding::Arg(i as u8))).collect(),
            nodes: 0,
        };
        let mut lets = Vec::new();
        let result = match &*closure.body {
            syn::Expr::Block(block) if block.label.is_none() => {
                let stmts = &block.block.stmts;
                let Some((last, body)) = stmts.split_last() else {
                    return Err(error(block, "the formula's block is empty: end it with the next z"));
                };
                for stmt in body {
                    let (name, value) = self.let_binding(stmt, &mut scope, depth)?;
                    if lets.len() >= MAX_LETS {
                        return Err(error(stmt, format!("a formula has at most {MAX_LETS} `let` bindings")));
                    }
                    scope.names.push((name.clone(), Binding::Let(lets.len() as u16, value.1)));
                    lets.push((name, value.0));
                }
                match last {
                    syn::Stmt::Expr(e, None) => e,
                    other => return Err(error(other, "end the formula's block with the next z, without `;`")),
                }
            }
            body => body,
        };
        let (next, scale) = match result {
            syn::Expr::Tuple(t) if own_scale && t.elems.len() == 2 => {
                let next = self.typed(&t.elems[0], &mut scope, depth + 1)?;
                let scale = self.typed(&t.elems[1], &mut scope, depth + 1)?;
                expect(&t.elems[1], &scale, FTy::Num, "the fold's scale")?;
                (next, Some(scale.0))
            }
            syn::Expr::Tuple(t) => {
                let message = if own_scale {
                    "a fold returns the next z, or (z, scale)"
                } else {
                    "a map returns the next z, a vec3 ((z, scale) only in fold(..))"
                };
                return Err(error(t, message));
            }
            e => (self.typed(e, &mut scope, depth + 1)?, None),
        };
        expect(result_expr(result), &next, FTy::Vec(3), "the next z")?;
        Ok(FormulaMap { params, lets, next: next.0, scale })
    }

    fn let_binding(&mut self, stmt: &syn::Stmt, scope: &mut Scope, depth: usize) -> syn::Result<(String, Typed)> {
        let syn::Stmt::Local(local) = stmt else {
            return Err(error(stmt, "a formula's block holds `let name = value;` bindings and ends with the next z"));
        };
        let syn::Pat::Ident(id) = &local.pat else {
            return Err(error(&local.pat, "a `let` binds one plain name: let name = value;"));
        };
        if id.by_ref.is_some() || id.mutability.is_some() || id.subpat.is_some() {
            let message = "a `let` binds one plain name (no `mut`: bind a new name, or the same name again)";
            return Err(error(&local.pat, message));
        }
        let Some(init) = &local.init else {
            return Err(error(local, "a `let` needs a value: let name = value;"));
        };
        if let Some((_, diverge)) = &init.diverge {
            return Err(error(diverge, "`let .. else` is not part of the scene language"));
        }
        let value = self.typed(&init.expr, scope, depth + 1)?;
        if value.1 == FTy::Bool {
            return Err(error(&init.expr, "a `let` holds a number or a vector; use a condition inside `if` directly"));
        }
        Ok((id.ident.to_string(), value))
    }

    /// A formula expression with its type.
    fn typed(&mut self, e: &syn::Expr, scope: &mut Scope, depth: usize) -> syn::Result<Typed> {
        if depth > MAX_EVAL_DEPTH {
            return Err(error(e, format!("the formula nests more than {MAX_EVAL_DEPTH} levels deep")));
        }
        scope.nodes += 1;
        if scope.nodes > MAX_FORMULA_NODES {
            return Err(error(e, format!("the formula has more than {MAX_FORMULA_NODES} nodes")));
        }
        let next = depth + 1;
        match e {
            syn::Expr::Paren(p) => self.typed(&p.expr, scope, next),
            syn::Expr::Group(g) => self.typed(&g.expr, scope, next),
            syn::Expr::Lit(_) => self.scene_number(e, depth),
            syn::Expr::Path(p) => {
                let name = p.path.get_ident().map(|i| i.to_string()).unwrap_or_default();
                match scope.find(&name) {
                    Some(Binding::Arg(i)) => Ok((FExpr::Arg(i), FTy::Vec(3))),
                    Some(Binding::Let(i, ty)) => Ok((FExpr::Let(i), ty)),
                    None if name == "t" || name == "PI" => self.scene_number(e, depth),
                    None => Err(error(
                        e,
                        format!("unknown name `{name}` in the formula (its names: {}, `t` and `PI`)", scope.names()),
                    )),
                }
            }
            syn::Expr::Unary(u) => {
                let a = self.typed(&u.expr, scope, next)?;
                match u.op {
                    syn::UnOp::Neg(_) if a.1 != FTy::Bool => Ok((FExpr::Neg(Box::new(a.0)), a.1)),
                    syn::UnOp::Not(_) if a.1 == FTy::Bool => Ok((FExpr::Not(Box::new(a.0)), FTy::Bool)),
                    syn::UnOp::Neg(_) => Err(error(u, "`-` applies to numbers and vectors, found a truth value")),
                    syn::UnOp::Not(_) => Err(error(u, format!("`!` applies to truth values, found {}", a.1.name()))),
                    _ => Err(error(u, "`*` is not part of the scene language")),
                }
            }
            syn::Expr::Binary(b) => self.formula_binary(b, scope, next),
            syn::Expr::Call(c) => self.formula_call(c, scope, next),
            syn::Expr::Field(f) => {
                let a = self.typed(&f.base, scope, next)?;
                let syn::Member::Named(letters) = &f.member else {
                    return Err(error(&f.member, "components are named x, y, z, w: v.x, v.xy, v.zyx"));
                };
                let FTy::Vec(width) = a.1 else {
                    return Err(error(&f.member, format!("components belong to vectors, found {}", a.1.name())));
                };
                let text = letters.to_string();
                let mut index = [0u8; 4];
                if text.is_empty() || text.len() > 4 {
                    return Err(error(&f.member, "a swizzle picks 1 to 4 components: v.x, v.xy, v.zyx, v.wzyx"));
                }
                for (slot, ch) in index.iter_mut().zip(text.chars()) {
                    match Swizzle::LETTERS.iter().position(|&l| l == ch) {
                        Some(i) if (i as u8) < width => *slot = i as u8,
                        _ => {
                            let allowed: String = Swizzle::LETTERS[..width as usize].iter().collect();
                            let message =
                                format!("`{text}` is not a component of {} (its letters: {allowed})", a.1.name());
                            return Err(error(&f.member, message));
                        }
                    }
                }
                let len = text.len() as u8;
                let ty = if len == 1 { FTy::Num } else { FTy::Vec(len) };
                Ok((FExpr::Swizzle(Box::new(a.0), Swizzle { len, index }), ty))
            }
            syn::Expr::If(i) => {
                let cond = self.typed(&i.cond, scope, next)?;
                expect(&i.cond, &cond, FTy::Bool, "an `if` condition")?;
                let then = self.branch(&i.then_branch, scope, next)?;
                let Some((_, otherwise)) = &i.else_branch else {
                    return Err(error(i, "an `if` in a formula is a value: give it an `else`"));
                };
                let otherwise = match &**otherwise {
                    syn::Expr::Block(b) => self.branch(&b.block, scope, next)?,
                    other => self.typed(other, scope, next)?,
                };
                if then.1 != otherwise.1 {
                    let message = format!("the `if` gives {} and its `else` {}", then.1.name(), otherwise.1.name());
                    return Err(error(i, message));
                }
                Ok((FExpr::If(Box::new(cond.0), Box::new(then.0), Box::new(otherwise.0)), then.1))
            }
            syn::Expr::MethodCall(m) => Err(error(
                &m.method,
                format!("methods are not part of formulas: call the function, e.g. {}(v)", m.method),
            )),
            _ => Err(error(e, "this is not part of a formula (numbers, vectors, `let`, `if`, calls and components)")),
        }
    }

    /// A branch of an `if`: a block of one expression.
    fn branch(&mut self, block: &syn::Block, scope: &mut Scope, depth: usize) -> syn::Result<Typed> {
        match block.stmts.as_slice() {
            [syn::Stmt::Expr(e, None)] => self.typed(e, scope, depth),
            _ => Err(error(block, "an `if` branch is one value, without `let` or `;`")),
        }
    }

    /// A number of the scene (literal, `t`, `PI`, `param(..)`) inside a formula.
    fn scene_number(&mut self, e: &syn::Expr, depth: usize) -> syn::Result<Typed> {
        match self.eval(e, depth)? {
            Value::Number(n) => Ok((FExpr::Num(n), FTy::Num)),
            other => Err(error(e, format!("a formula computes with numbers and vectors, found {}", other.ty().a()))),
        }
    }

    fn formula_binary(&mut self, b: &syn::ExprBinary, scope: &mut Scope, depth: usize) -> syn::Result<Typed> {
        let left = self.typed(&b.left, scope, depth)?;
        let right = self.typed(&b.right, scope, depth)?;
        let arith = match b.op {
            syn::BinOp::Add(_) => Some(FBin::Add),
            syn::BinOp::Sub(_) => Some(FBin::Sub),
            syn::BinOp::Mul(_) => Some(FBin::Mul),
            syn::BinOp::Div(_) => Some(FBin::Div),
            _ => None,
        };
        if let Some(op) = arith {
            let ty = broadcast(&left, &right).ok_or_else(|| {
                error(
                    b,
                    format!(
                        "`{}` applies to numbers and vectors of one size, found {} and {}",
                        op.symbol(),
                        left.1.name(),
                        right.1.name()
                    ),
                )
            })?;
            return Ok((FExpr::Bin(op, Box::new(left.0), Box::new(right.0)), ty));
        }
        let cmp = match b.op {
            syn::BinOp::Lt(_) => Some(FCmp::Lt),
            syn::BinOp::Le(_) => Some(FCmp::Le),
            syn::BinOp::Gt(_) => Some(FCmp::Gt),
            syn::BinOp::Ge(_) => Some(FCmp::Ge),
            _ => None,
        };
        if let Some(op) = cmp {
            if left.1 != FTy::Num || right.1 != FTy::Num {
                let message =
                    format!("`{}` compares numbers, found {} and {}", op.symbol(), left.1.name(), right.1.name());
                return Err(error(b, message));
            }
            return Ok((FExpr::Cmp(op, Box::new(left.0), Box::new(right.0)), FTy::Bool));
        }
        let logic = match b.op {
            syn::BinOp::And(_) => FLogic::And,
            syn::BinOp::Or(_) => FLogic::Or,
            syn::BinOp::Eq(_) | syn::BinOp::Ne(_) => {
                return Err(error(b.op, "floats are compared with < <= > >= in a formula, not == or !="))
            }
            op => {
                let text = quote::ToTokens::to_token_stream(&op).to_string();
                return Err(error(op, format!("`{text}` is not part of formulas (+ - * /, < <= > >=, && ||, !)")));
            }
        };
        if left.1 != FTy::Bool || right.1 != FTy::Bool {
            return Err(error(b, "`&&` and `||` join conditions such as a < b"));
        }
        Ok((FExpr::Logic(logic, Box::new(left.0), Box::new(right.0)), FTy::Bool))
    }

    fn formula_call(&mut self, c: &syn::ExprCall, scope: &mut Scope, depth: usize) -> syn::Result<Typed> {
        let syn::Expr::Path(path) = &*c.func else {
            return Err(error(&c.func, "only the formula functions can be called here"));
        };
        let name = path.path.get_ident().map(|i| i.to_string()).unwrap_or_default();
        if name == "param" {
            return self.scene_number(&syn::Expr::Call(c.clone()), depth);
        }
        let Some(func) = FFunc::from_name(&name) else {
            let known: Vec<&str> = FFunc::ALL.iter().map(|f| f.name()).collect();
            let message = match super::names::suggest(&name, known.iter().copied()) {
                Some(s) => format!("unknown formula function `{name}`; did you mean `{s}`?"),
                None => format!("`{name}` is not a formula function (they are: {})", known.join(", ")),
            };
            return Err(error(&c.func, message));
        };
        let args: Vec<Typed> = c.args.iter().map(|a| self.typed(a, scope, depth)).collect::<syn::Result<_>>()?;
        let vector = matches!(func, FFunc::Vec2 | FFunc::Vec3 | FFunc::Vec4);
        if !vector && args.len() != func.arity() {
            let message = format!("`{name}` takes {} arguments, found {}", func.arity(), args.len());
            return Err(syn::Error::new(c.func.span(), message));
        }
        let ty = call_type(func, &args).map_err(|message| error(c, format!("`{name}`: {message}")))?;
        Ok((FExpr::Call(func, args.into_iter().map(|a| a.0).collect()), ty))
    }
}

/// The expression a result stands for, for messages.
fn result_expr(e: &syn::Expr) -> &syn::Expr {
    match e {
        syn::Expr::Tuple(t) if !t.elems.is_empty() => &t.elems[0],
        e => e,
    }
}

fn expect(at: &syn::Expr, value: &Typed, ty: FTy, what: &str) -> syn::Result<()> {
    if value.1 == ty {
        return Ok(());
    }
    Err(error(at, format!("{what} must be {}, found {}", ty.name(), value.1.name())))
}

/// The type of a per-component operation on `a` and `b`: equal types, or a number with a vector.
fn broadcast(a: &Typed, b: &Typed) -> Option<FTy> {
    match (a.1, b.1) {
        (FTy::Bool, _) | (_, FTy::Bool) => None,
        (x, y) if x == y => Some(x),
        (FTy::Num, v) | (v, FTy::Num) => Some(v),
        _ => None,
    }
}

/// The result type of a call, or why its arguments do not fit.
fn call_type(func: FFunc, args: &[Typed]) -> Result<FTy, String> {
    let ty = |i: usize| args[i].1;
    let number_or_vector = |i: usize| -> Result<FTy, String> {
        match ty(i) {
            FTy::Bool => Err("takes numbers and vectors, found a truth value".into()),
            t => Ok(t),
        }
    };
    let vector_of = |i: usize, n: u8| -> Result<(), String> {
        if ty(i) == FTy::Vec(n) {
            Ok(())
        } else {
            Err(format!("takes {}, found {}", FTy::Vec(n).name(), ty(i).name()))
        }
    };
    let number = |i: usize| -> Result<(), String> {
        if ty(i) == FTy::Num {
            Ok(())
        } else {
            Err(format!("argument {} must be a number, found {}", i + 1, ty(i).name()))
        }
    };
    match func {
        FFunc::Vec2 | FFunc::Vec3 | FFunc::Vec4 => {
            let n = func.arity();
            let mut width = 0;
            for i in 0..args.len() {
                width += number_or_vector(i)?.width();
            }
            if width != n {
                return Err(format!("its arguments give {width} components, not {n}"));
            }
            Ok(FTy::Vec(n as u8))
        }
        FFunc::Length => number_or_vector(0).map(|_| FTy::Num),
        FFunc::Normalize => number_or_vector(0),
        FFunc::Dot => match (ty(0), ty(1)) {
            (FTy::Vec(a), FTy::Vec(b)) if a == b => Ok(FTy::Num),
            (a, b) => Err(format!("takes two vectors of one size, found {} and {}", a.name(), b.name())),
        },
        FFunc::Cross => vector_of(0, 3).and(vector_of(1, 3)).map(|_| FTy::Vec(3)),
        FFunc::Abs
        | FFunc::Sign
        | FFunc::Floor
        | FFunc::Fract
        | FFunc::Sqrt
        | FFunc::Sin
        | FFunc::Cos
        | FFunc::Tan
        | FFunc::Asin
        | FFunc::Acos
        | FFunc::Atan
        | FFunc::Exp
        | FFunc::Ln => number_or_vector(0),
        FFunc::Atan2 | FFunc::Min | FFunc::Max => {
            broadcast(&args[0], &args[1]).ok_or_else(|| "takes numbers or vectors of one size".to_string())
        }
        FFunc::Pow => number(1).and(number_or_vector(0)),
        FFunc::Clamp | FFunc::Mix => {
            let ab = broadcast(&args[0], &args[1]).ok_or_else(|| "takes numbers or vectors of one size".to_string())?;
            let t = (args[2].0.clone(), ab);
            broadcast(&t, &args[2]).ok_or_else(|| "takes numbers or vectors of one size".to_string())
        }
        FFunc::Cmul => vector_of(0, 2).and(vector_of(1, 2)).map(|_| FTy::Vec(2)),
        FFunc::Csqr => vector_of(0, 2).map(|_| FTy::Vec(2)),
        FFunc::Qmul => vector_of(0, 4).and(vector_of(1, 4)).map(|_| FTy::Vec(4)),
        FFunc::Qsqr => vector_of(0, 4).map(|_| FTy::Vec(4)),
        FFunc::BoxFold => match ty(0) {
            FTy::Vec(n) => number(1).map(|_| FTy::Vec(n)),
            t => Err(format!("folds a vector, found {}", t.name())),
        },
        FFunc::SphereFold => match ty(0) {
            FTy::Vec(n) => number(1).and(number(2)).map(|_| FTy::Vec(n)),
            t => Err(format!("folds a vector, found {}", t.name())),
        },
    }
}
