//! Constant folding: literal arithmetic becomes one literal, and identity nodes (translate by zero, rotate by zero,
//! scale by one, one-child unions) disappear, so kernels carry only the work that changes the result.

use crate::ir::fractal::Setting;
use crate::ir::*;

/// Folds an expression bottom-up.
pub fn fold_expr(e: &Expr) -> Expr {
    match e {
        Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => e.clone(),
        Expr::Neg(a) => match fold_expr(a) {
            Expr::Lit(v) => Expr::Lit(-v),
            a => Expr::Neg(Box::new(a)),
        },
        Expr::Bin(op, a, b) => match (fold_expr(a), fold_expr(b)) {
            (Expr::Lit(x), Expr::Lit(y)) => Expr::Lit(op.apply(x, y)),
            (a, b) => Expr::Bin(*op, Box::new(a), Box::new(b)),
        },
        Expr::Call(f, args) => {
            let args: Vec<Expr> = args.iter().map(fold_expr).collect();
            match args.iter().map(Expr::as_lit).collect::<Option<Vec<f64>>>() {
                Some(v) => Expr::Lit(f.apply(&v, f.count(v.last().copied()))),
                None => Expr::Call(*f, args),
            }
        }
    }
}

fn fold_v3(v: &Vec3Expr) -> Vec3Expr {
    Vec3Expr(v.0.clone().map(|e| fold_expr(&e)))
}

/// Folds every expression of the tree and removes identity nodes (a one-shape union, a translation by zero, ... as
/// each operator's declaration states).
pub fn fold_node(n: &Node) -> Node {
    match n {
        Node::Prim(p) => Node::Prim(Prim { args: fold_args(&p.args), ..p.clone() }),
        Node::Fractal(f) => Node::Fractal(Box::new(fold_fractal(f))),
        Node::Op(op) => {
            let args = fold_args(&op.args);
            match op.shapes.as_slice() {
                [only] if op.decl().is_identity(1, &args) => fold_node(only),
                shapes => Node::Op(Op { kind: op.kind, shapes: shapes.iter().map(fold_node).collect(), args }),
            }
        }
        Node::Material(c, m) => Node::Material(Box::new(fold_node(c)), Box::new(fold_material(m))),
    }
}

fn fold_args(args: &[ArgValue]) -> Vec<ArgValue> {
    let mut folded = args.to_vec();
    for a in &mut folded {
        for e in a.exprs_mut() {
            *e = fold_expr(e);
        }
    }
    folded
}

fn fold_fractal(fr: &Fractal) -> Fractal {
    let mut folded = fr.clone();
    for e in folded.arg_exprs_mut() {
        *e = fold_expr(e);
    }
    for s in Setting::ALL {
        if let Some(e) = folded.setting_mut(s) {
            *e = fold_expr(e);
        }
    }
    folded
}

fn fold_material(m: &Material) -> Material {
    Material {
        albedo: match &m.albedo {
            Albedo::Rgb(c) => Albedo::Rgb(fold_v3(c)),
            Albedo::OrbitTrap(a, b) => Albedo::OrbitTrap(fold_v3(a), fold_v3(b)),
        },
        ambient: fold_expr(&m.ambient),
        diffuse: fold_expr(&m.diffuse),
        specular: fold_expr(&m.specular),
        shininess: fold_expr(&m.shininess),
    }
}

/// The scene with its tree and light expressions folded.
pub fn fold_scene(s: &Scene) -> Scene {
    Scene {
        root: fold_node(&s.root),
        lights: s
            .lights
            .iter()
            .map(|l| Light {
                kind: match &l.kind {
                    LightKind::Directional { direction } => LightKind::Directional { direction: fold_v3(direction) },
                    LightKind::Point { position } => LightKind::Point { position: fold_v3(position) },
                },
                color: fold_v3(&l.color),
                intensity: fold_expr(&l.intensity),
            })
            .collect(),
        camera: s.camera.clone(),
        settings: s.settings.clone(),
    }
}
