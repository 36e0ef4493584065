//! Building: syn's expression tree to IR values. Calls and methods are looked up in the parser's name table (`names`),
//! their arguments evaluated and coerced to the declared types, and the builder function named there builds the
//! value; then the validation rules check it while the argument spans are still at hand.
//!
//! Method chains are walked in a loop, not by recursion, so a long chain costs no stack; every other descent counts
//! against [`MAX_EVAL_DEPTH`].

use proc_macro2::Span;
use quote::ToTokens;
use syn::spanned::Spanned;

use super::names::{self, Args, Entry, Ty, Value};
use crate::builder::{self as b, Color};
use crate::ir::*;
use crate::validate::{self as v, Problem};

/// Deepest the lowering descends into the syntax tree.
pub const MAX_EVAL_DEPTH: usize = 256;

/// Lowers the expression of a whole scene.
pub(crate) fn scene(expr: &syn::Expr) -> syn::Result<Scene> {
    let mut lower = Lower::default();
    let value = lower.eval(expr, 0)?;
    let scene = match value {
        Value::Scene(s) => *s,
        Value::Shape(n) => b::scene(n),
        Value::Fractal(f) => b::scene(f),
        other => return Err(error(expr, format!("a scene must be a shape or scene(..), found {}", other.ty().a()))),
    };
    // Every rule was checked where its value was built; this is the net under that, so that a parsed scene always
    // passes validation.
    if let Err(errors) = v::validate(&scene) {
        return Err(error(expr, errors[0].to_string()));
    }
    Ok(scene)
}

pub(super) fn error(at: impl ToTokens, message: impl std::fmt::Display) -> syn::Error {
    syn::Error::new_spanned(at, message)
}

/// Short source text of an expression for messages: the text as written where the span can give it.
fn snippet(e: &syn::Expr) -> String {
    let tokens = e.to_token_stream().to_string();
    let squeeze = |s: &str| s.split_whitespace().collect::<String>();
    let text = match e.span().source_text() {
        Some(src) if squeeze(&src) == squeeze(&tokens) => src,
        _ => tokens,
    };
    if text.chars().count() > 40 {
        format!("{}...", text.chars().take(37).collect::<String>())
    } else {
        text
    }
}

/// Why a value does not fit an argument slot.
enum Misfit {
    Type,
    NotConstant,
    NotFinite(f64),
}

fn constant(e: &Expr) -> Result<f64, Misfit> {
    match v::constant_value(e) {
        Some(x) if x.is_finite() => Ok(x),
        Some(x) => Err(Misfit::NotFinite(x)),
        None => Err(Misfit::NotConstant),
    }
}

fn const_vec3(v: &Vec3Expr) -> Result<[f64; 3], Misfit> {
    Ok([constant(&v.0[0])?, constant(&v.0[1])?, constant(&v.0[2])?])
}

/// Converts a value to the type of a slot: fractals are shapes, colours are materials, shapes and fractals are scenes,
/// and constant numbers, vectors and colours are numbers, vectors and colours without `t` or `param`.
fn coerce(value: Value, ty: Ty) -> Result<Value, Misfit> {
    Ok(match (value, ty) {
        (Value::Number(e), Ty::Number) => Value::Number(e),
        (Value::Number(e), Ty::Const) => Value::Const(constant(&e)?),
        (Value::Vec3(v), Ty::Vec3) => Value::Vec3(v),
        (Value::Vec3(v), Ty::ConstVec3) => Value::ConstVec3(const_vec3(&v)?),
        (Value::Vec4(v), Ty::Vec4) => Value::Vec4(v),
        (Value::Color(c), Ty::Color) => Value::Color(c),
        (Value::Color(c), Ty::ConstColor) => Value::Color(Color(const_vec3(&c.0)?.into())),
        (Value::Color(c), Ty::Material) => Value::Material(c.into()),
        (Value::Material(m), Ty::Material) => Value::Material(m),
        (Value::Shape(n), Ty::Shape) => Value::Shape(n),
        (Value::Fractal(f), Ty::Shape) => Value::Shape(f.into()),
        (Value::Fractal(f), Ty::Fractal) => Value::Fractal(f),
        (Value::Shape(n), Ty::Scene) => Value::Scene(Box::new(b::scene(n))),
        (Value::Fractal(f), Ty::Scene) => Value::Scene(Box::new(b::scene(f))),
        (Value::Scene(s), Ty::Scene) => Value::Scene(s),
        (Value::Light(l), Ty::Light) => Value::Light(l),
        (Value::Camera(c), Ty::Camera) => Value::Camera(c),
        (Value::Key(k), Ty::Key) => Value::Key(k),
        (Value::Formula(m), Ty::Formula) => Value::Formula(m),
        _ => return Err(Misfit::Type),
    })
}

/// Whether a value of type `from` can stand where `to` is expected.
fn accepts(to: Ty, from: Ty) -> bool {
    to == from
        || matches!(
            (from, to),
            (Ty::Number, Ty::Const)
                | (Ty::Vec3, Ty::ConstVec3)
                | (Ty::Color, Ty::ConstColor | Ty::Material)
                | (Ty::Fractal, Ty::Shape | Ty::Scene)
                | (Ty::Shape, Ty::Scene)
        )
}

const INT_SUFFIXES: &[&str] = &["u8", "u16", "u32", "u64", "u128", "usize", "i8", "i16", "i32", "i64", "i128", "isize"];

/// Rust's integer suffixes read as Rust would check them (`300u8` does not fit) or as the bare number would be a
/// different value than the text promises; the language has one number type, so they are refused.
fn int_suffix(digits: &str, suffix: &str) -> String {
    format!("integer suffixes such as `{suffix}` are not part of the scene language: write `{digits}`")
}

/// The value of a number literal, honouring Rust's `f32` suffix the way the builder would see it.
fn number_literal(lit: &syn::Lit) -> Result<f64, String> {
    let (digits, suffix, is_int) = match lit {
        syn::Lit::Float(f) => (f.base10_digits(), f.suffix(), false),
        syn::Lit::Int(i) => (i.base10_digits(), i.suffix(), true),
        syn::Lit::Str(_) => {
            return Err("a string appears only as the name in param(\"name\", default, min..max)".to_string())
        }
        _ => return Err(format!("`{}` is not a number", lit.to_token_stream())),
    };
    let value = match suffix {
        "" | "f64" => digits.parse::<f64>().ok(),
        "f32" => digits.parse::<f32>().ok().map(f64::from),
        s if is_int && INT_SUFFIXES.contains(&s) => return Err(int_suffix(digits, s)),
        s => return Err(format!("unknown number suffix `{s}`")),
    };
    match value {
        Some(v) if v.is_finite() => Ok(v),
        _ => Err(format!("the number `{}` is out of range (numbers must be finite)", lit.to_token_stream())),
    }
}

/// `3` in an integer slot.
fn int_literal(e: &syn::Expr) -> Option<Result<u32, String>> {
    match e {
        syn::Expr::Group(g) => int_literal(&g.expr),
        syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) if INT_SUFFIXES.contains(&i.suffix()) => {
            Some(Err(int_suffix(i.base10_digits(), i.suffix())))
        }
        syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Int(i), .. }) if i.suffix().is_empty() => {
            Some(i.base10_parse::<u32>().map_err(|_| format!("the integer `{i}` is too large")))
        }
        _ => None,
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

#[derive(Default)]
pub(super) struct Lower {
    /// Parameters declared so far, to refuse a second declaration that disagrees.
    params: Vec<ParamDecl>,
    nodes: usize,
    expr_nodes: usize,
}

impl Lower {
    pub(super) fn eval(&mut self, e: &syn::Expr, depth: usize) -> syn::Result<Value> {
        if depth > MAX_EVAL_DEPTH {
            let message = match e {
                // A long sum or product is a chain of binary operators, each one level: say so, or the message
                // reads wrong for text that does not look nested.
                syn::Expr::Binary(_) => format!(
                    "this expression chains more than {MAX_EVAL_DEPTH} operators (each `+`, `-`, `*`, `/` nests one \
                     level): use fewer terms"
                ),
                _ => format!("the scene nests more than {MAX_EVAL_DEPTH} levels deep"),
            };
            return Err(error(e, message));
        }
        match e {
            syn::Expr::Lit(l) => {
                let value = number_literal(&l.lit).map_err(|m| error(e, m))?;
                self.number(e, Expr::Lit(value))
            }
            syn::Expr::Path(p) => self.name(p),
            syn::Expr::Paren(p) => self.eval(&p.expr, depth + 1),
            syn::Expr::Group(g) => self.eval(&g.expr, depth + 1),
            syn::Expr::Unary(u) => self.unary(u, depth),
            syn::Expr::Binary(bin) => self.binary(bin, depth),
            syn::Expr::Call(c) => self.call(c, depth),
            syn::Expr::MethodCall(m) => self.chain(m, depth),
            syn::Expr::Range(_) => Err(error(
                e,
                "a range `min..max` appears only as the last argument of param(\"name\", default, min..max)",
            )),
            syn::Expr::Field(_) => Err(error(e, "fields (`v.x`) are not part of the scene language")),
            syn::Expr::Tuple(_) => Err(error(e, "tuples are not part of the scene language: write vec3(x, y, z)")),
            _ => Err(error(e, format!("`{}` is not part of the scene language", snippet(e)))),
        }
    }

    /// Counts a new expression node and checks the expression caps.
    fn number(&mut self, at: impl ToTokens, e: Expr) -> syn::Result<Value> {
        self.expr_nodes += 1;
        if self.expr_nodes > v::MAX_EXPR_NODES {
            return Err(error(at, format!("the scene's expressions have more than {} nodes", v::MAX_EXPR_NODES)));
        }
        if let Some(m) = v::expr_size_problem(&e) {
            return Err(error(at, m));
        }
        Ok(Value::Number(e))
    }

    fn name(&mut self, p: &syn::ExprPath) -> syn::Result<Value> {
        let Some(ident) = p.path.get_ident().filter(|_| p.qself.is_none()) else {
            return Err(error(p, "paths are not part of the scene language"));
        };
        let name = ident.to_string();
        match name.as_str() {
            "t" => return self.number(p, Expr::Time),
            "PI" => return self.number(p, Expr::Lit(std::f64::consts::PI)),
            "x" | "y" | "z" => {
                let axis = crate::print::POINT_NAMES.iter().position(|n| *n == name).unwrap_or(0) as u8;
                return self.number(p, Expr::Point(axis));
            }
            _ => {}
        }
        let message = if names::function(&name).is_some() {
            format!("`{name}` is a function: call it, e.g. {name}(..)")
        } else if let Some(m) = names::method(&name) {
            let receiver = m.receiver.map(Ty::name).unwrap_or("value");
            format!("`{name}` is a method: write {receiver}.{name}(..)")
        } else {
            let candidates = names::NAMES.iter().copied().chain(names::functions().map(|f| f.name));
            match names::suggest(&name, candidates) {
                Some(s) => format!("unknown name `{name}`; did you mean `{s}`?"),
                None => format!("unknown name `{name}` (the names are `t`, the time in seconds, and `PI`)"),
            }
        };
        Err(error(ident, message))
    }

    fn unary(&mut self, u: &syn::ExprUnary, depth: usize) -> syn::Result<Value> {
        if !matches!(u.op, syn::UnOp::Neg(_)) {
            return Err(error(u.op, format!("`{}` is not part of the scene language", u.op.to_token_stream())));
        }
        // `-2.0` is one negative literal, as it is for the builder; `-(2.0)` stays a negation.
        if let syn::Expr::Lit(l) = &*u.expr {
            let value = number_literal(&l.lit).map_err(|m| error(&u.expr, m))?;
            return self.number(u, Expr::Lit(-value));
        }
        match self.eval(&u.expr, depth + 1)? {
            Value::Number(e) => self.number(u, Expr::Neg(Box::new(e))),
            other => Err(error(&u.expr, format!("`-` applies to numbers, found {}", other.ty().a()))),
        }
    }

    fn binary(&mut self, bin: &syn::ExprBinary, depth: usize) -> syn::Result<Value> {
        let op = match bin.op {
            syn::BinOp::Add(_) => BinOp::Add,
            syn::BinOp::Sub(_) => BinOp::Sub,
            syn::BinOp::Mul(_) => BinOp::Mul,
            syn::BinOp::Div(_) => BinOp::Div,
            op => {
                let message =
                    format!("`{}` is not part of the scene language (operators: + - * /)", op.to_token_stream());
                return Err(error(op, message));
            }
        };
        let mut operand = |side: &syn::Expr| -> syn::Result<Expr> {
            match self.eval(side, depth + 1)? {
                Value::Number(e) => Ok(e),
                other => Err(error(side, format!("`{op}` applies to numbers, found {}", other.ty().a()))),
            }
        };
        let left = operand(&bin.left)?;
        let right = operand(&bin.right)?;
        self.number(bin, Expr::Bin(op, Box::new(left), Box::new(right)))
    }

    fn call(&mut self, c: &syn::ExprCall, depth: usize) -> syn::Result<Value> {
        let ident = match &*c.func {
            syn::Expr::Path(p) if p.qself.is_none() => p.path.get_ident(),
            _ => None,
        };
        let Some(ident) = ident else {
            return Err(error(&c.func, "only the scene language's functions can be called here"));
        };
        let name = ident.to_string();
        let Some(entry) = names::function(&name) else {
            let message = if let Some(m) = names::method(&name) {
                let receiver = m.receiver.map(Ty::name).unwrap_or("value");
                format!("`{name}` is a method, not a function: write {receiver}.{name}(..)")
            } else {
                match names::suggest(&name, names::functions().map(|f| f.name)) {
                    Some(s) => format!("unknown function `{name}`; did you mean `{s}`?"),
                    None => format!("unknown function `{name}`"),
                }
            };
            return Err(error(ident, message));
        };
        let args: Vec<&syn::Expr> = c.args.iter().collect();
        self.apply(entry, ident.span(), None, &args, depth)
    }

    fn chain(&mut self, m: &syn::ExprMethodCall, depth: usize) -> syn::Result<Value> {
        let mut calls = vec![m];
        let mut base = &*m.receiver;
        while let syn::Expr::MethodCall(inner) = base {
            calls.push(inner);
            base = &inner.receiver;
        }
        let mut value = self.eval(base, depth + 1)?;
        for call in calls.into_iter().rev() {
            value = self.method(value, call, depth + 1)?;
        }
        Ok(value)
    }

    fn method(&mut self, receiver: Value, m: &syn::ExprMethodCall, depth: usize) -> syn::Result<Value> {
        let name = m.method.to_string();
        let found = receiver.ty();
        let Some(entry) = names::method(&name) else {
            let message = if names::function(&name).is_some() {
                format!("`{name}` is a function, not a method: call it as {name}(..)")
            } else {
                let fitting = names::methods().filter(|e| e.receiver.is_some_and(|r| accepts(r, found)));
                let any = names::methods();
                match names::suggest(&name, fitting.map(|e| e.name))
                    .or_else(|| names::suggest(&name, any.map(|e| e.name)))
                {
                    Some(s) => format!("unknown method `{name}` on {}; did you mean `{s}`?", found.a()),
                    None => format!("unknown method `{name}` on {}", found.a()),
                }
            };
            return Err(error(&m.method, message));
        };
        if m.turbofish.is_some() {
            return Err(error(&m.turbofish, "type arguments are not part of the scene language"));
        }
        let Some(expected) = entry.receiver else {
            return Err(error(&m.method, "internal error: a method without a receiver type"));
        };
        let receiver = match coerce(receiver, expected) {
            Ok(r) => r,
            Err(_) => {
                return Err(error(&m.method, format!("`{name}` is a method of {}, found {}", expected.a(), found.a())))
            }
        };
        let args: Vec<&syn::Expr> = m.args.iter().collect();
        self.apply(entry, m.method.span(), Some(receiver), &args, depth)
    }

    /// Checks arity, evaluates and coerces the arguments, builds the value and checks it.
    fn apply(
        &mut self,
        entry: &'static Entry,
        name_span: Span,
        receiver: Option<Value>,
        args: &[&syn::Expr],
        depth: usize,
    ) -> syn::Result<Value> {
        let name = entry.name;
        let n = entry.params.len();
        let many = entry.many_index();
        let arity_ok = if many.is_some() { args.len() >= n } else { args.len() == n };
        if !arity_ok {
            let takes = match (many, n) {
                (Some(_), n) => format!("takes at least {n} argument{}", plural(n)),
                (None, 0) => "takes no arguments".to_string(),
                (None, n) => format!("takes {n} argument{}", plural(n)),
            };
            let list = if n == 0 { String::new() } else { format!(" {}", entry.param_list()) };
            let message = format!("`{name}` {takes}{list}, found {}", args.len());
            return Err(match args.get(n) {
                Some(extra) if many.is_none() => error(extra, message),
                _ => syn::Error::new(name_span, message),
            });
        }

        let mut values = std::collections::VecDeque::with_capacity(args.len() + 1);
        values.extend(receiver);
        let repeated = args.len() + 1 - n;
        for (i, arg) in args.iter().enumerate() {
            let param = match many {
                Some(m) if i >= m && i < m + repeated => &entry.params[m],
                Some(m) if i >= m + repeated => &entry.params[i + 1 - repeated],
                _ => &entry.params[i],
            };
            values.push_back(self.argument(entry, param, arg, depth + 1)?);
        }

        let value = entry.build(&mut Args(values)).map_err(|m| syn::Error::new(name_span, m))?;
        let problems = self.check(entry, &value).map_err(|m| syn::Error::new(name_span, m))?;
        match problems.into_iter().next() {
            None => Ok(value),
            Some(p) => Err(syn::Error::new(problem_span(entry, name_span, args, &p), p.message)),
        }
    }

    fn argument(&mut self, entry: &Entry, param: &names::Param, arg: &syn::Expr, depth: usize) -> syn::Result<Value> {
        let slot = format!("`{}` argument `{}`", entry.name, param.name);
        let wrong = |what: &str| error(arg, format!("{slot} must be {what}, found `{}`", snippet(arg)));
        match param.ty {
            Ty::Int => match int_literal(arg) {
                Some(Ok(n)) => Ok(Value::Int(n)),
                Some(Err(m)) => Err(error(arg, m)),
                None => Err(wrong(Ty::Int.a())),
            },
            Ty::IntVec3 => {
                let example = "vec3(..) of non-negative integer literals, e.g. vec3(2, 2, 0)";
                let syn::Expr::Call(c) = arg else { return Err(wrong(example)) };
                let is_vec3 = matches!(&*c.func, syn::Expr::Path(p) if p.path.is_ident("vec3"));
                if !is_vec3 || c.args.len() != 3 {
                    return Err(wrong(example));
                }
                let mut out = [0u32; 3];
                for (slot_value, a) in out.iter_mut().zip(&c.args) {
                    *slot_value = match int_literal(a) {
                        Some(Ok(n)) => n,
                        Some(Err(m)) => return Err(error(a, m)),
                        None => return Err(error(a, format!("{slot} must be {example}, found `{}`", snippet(a)))),
                    };
                }
                Ok(Value::IntVec3(out))
            }
            Ty::Formula => Ok(Value::Formula(self.formula_map(arg, entry.name == "fold", depth)?)),
            Ty::Str => match arg {
                syn::Expr::Lit(syn::ExprLit { lit: syn::Lit::Str(s), .. }) => Ok(Value::Str(s.value())),
                _ => Err(wrong("a string literal such as \"power\"")),
            },
            Ty::Range => {
                let syn::Expr::Range(r) = arg else { return Err(wrong("a range min..max")) };
                let (Some(lo), Some(hi), syn::RangeLimits::HalfOpen(_)) = (&r.start, &r.end, &r.limits) else {
                    return Err(wrong("a range min..max"));
                };
                let lo = self.constant_argument(&slot, lo, depth)?;
                let hi = self.constant_argument(&slot, hi, depth)?;
                Ok(Value::Range(lo, hi))
            }
            ty => {
                let value = self.eval(arg, depth)?;
                let found = value.ty();
                coerce(value, ty).map_err(|misfit| match misfit {
                    // A scene where a shape belongs is almost always a setting written on the shape.
                    Misfit::Type if ty == Ty::Shape && found == Ty::Scene => error(
                        arg,
                        format!(
                            "{slot} must be a shape, found a scene: settings such as max_steps go on scene(..), \
                             e.g. scene(sphere(1.0)).max_steps(200)"
                        ),
                    ),
                    Misfit::Type => error(arg, format!("{slot} must be {}, found {}", ty.a(), found.a())),
                    Misfit::NotConstant => {
                        error(arg, format!("{slot} must be a constant: `t` and `param(..)` cannot be used here"))
                    }
                    Misfit::NotFinite(x) => error(arg, format!("{slot} must be finite, found {}", v::number_text(x))),
                })
            }
        }
    }

    fn constant_argument(&mut self, slot: &str, e: &syn::Expr, depth: usize) -> syn::Result<f64> {
        match self.eval(e, depth)? {
            Value::Number(x) => constant(&x).map_err(|misfit| match misfit {
                Misfit::NotFinite(x) => error(e, format!("{slot} must be finite, found {}", v::number_text(x))),
                _ => error(e, format!("{slot} must be a constant: `t` and `param(..)` cannot be used here")),
            }),
            other => Err(error(e, format!("{slot} must be a number, found {}", other.ty().a()))),
        }
    }

    /// The validation rules of a freshly built value, and the scene-wide caps it may cross.
    fn check(&mut self, entry: &Entry, value: &Value) -> Result<Vec<Problem>, String> {
        Ok(match value {
            Value::Shape(n) => {
                self.count_node()?;
                if v::node_depth(n) > v::MAX_DEPTH {
                    return Err(format!("the shape tree nests more than {} levels deep", v::MAX_DEPTH));
                }
                v::check_node(n)
            }
            Value::Fractal(f) => {
                if entry.receiver.is_none() {
                    self.count_node()?;
                }
                v::check_fractal(f)
            }
            Value::Material(m) => v::check_material(m),
            Value::Light(l) => v::check_light(l),
            Value::Camera(c) => v::check_camera(c),
            Value::Scene(s) => v::check_scene(s),
            Value::Number(e) => {
                self.expr_nodes += 1;
                if let Some(m) = v::expr_size_problem(e) {
                    return Err(m);
                }
                match e {
                    Expr::Param(p) => self.declare(p),
                    _ => Vec::new(),
                }
            }
            _ => Vec::new(),
        })
    }

    fn count_node(&mut self) -> Result<(), String> {
        self.nodes += 1;
        if self.nodes > v::MAX_NODES {
            return Err(format!("the shape tree has more than {} nodes", v::MAX_NODES));
        }
        Ok(())
    }

    fn declare(&mut self, p: &ParamDecl) -> Vec<Problem> {
        let problems = v::check_param(p);
        if !problems.is_empty() {
            return problems;
        }
        match self.params.iter().find(|q| q.name == p.name) {
            Some(first) => v::check_param_again(first, p)
                .map(|message| vec![Problem { arg: "", index: None, message }])
                .unwrap_or_default(),
            None => {
                self.params.push(p.clone());
                Vec::new()
            }
        }
    }
}

/// Where a broken rule points: the argument it names, the only argument, or the function's name.
fn problem_span(entry: &Entry, name_span: Span, args: &[&syn::Expr], p: &Problem) -> Span {
    if p.arg.is_empty() {
        return name_span;
    }
    if let Some(pi) = entry.params.iter().position(|q| q.name == p.arg) {
        let n = entry.params.len();
        let index = match entry.many_index() {
            Some(m) if pi == m => p.index.map(|i| m + i),
            Some(m) if pi > m => Some(args.len() - (n - pi)),
            _ => Some(pi),
        };
        if let Some(arg) = index.and_then(|i| args.get(i)) {
            return arg.span();
        }
        return name_span;
    }
    match args {
        [only] => only.span(),
        _ => name_span,
    }
}
