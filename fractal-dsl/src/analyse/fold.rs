//! Constant folding: literal arithmetic becomes one literal, and identity nodes (translate by zero, rotate by zero,
//! scale by one, one-child unions) disappear, so kernels carry only the work that changes the result.

use crate::ir::fractal::Setting;
use crate::ir::*;

/// Folds an expression bottom-up.
pub fn fold_expr(e: &Expr) -> Expr {
    match e {
        Expr::Lit(_) | Expr::Time | Expr::Param(_) => e.clone(),
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
                Some(v) => Expr::Lit(f.apply(&v)),
                None => Expr::Call(*f, args),
            }
        }
    }
}

fn fold_v3(v: &Vec3Expr) -> Vec3Expr {
    Vec3Expr(v.0.clone().map(|e| fold_expr(&e)))
}

fn is_lit(e: &Expr, v: f64) -> bool {
    e.as_lit() == Some(v)
}

/// Folds every expression of the tree and removes identity nodes.
pub fn fold_node(n: &Node) -> Node {
    let b = |c: &Node| Box::new(fold_node(c));
    let all = |c: &[Node]| c.iter().map(fold_node).collect::<Vec<_>>();
    match n {
        Node::Prim(p) => Node::Prim(fold_prim(p)),
        Node::Fractal(f) => Node::Fractal(fold_fractal(f)),
        Node::Union(c) | Node::Intersect(c) if c.len() == 1 => fold_node(&c[0]),
        Node::SmoothUnion(c, _) | Node::SmoothIntersect(c, _) if c.len() == 1 => fold_node(&c[0]),
        Node::Union(c) => Node::Union(all(c)),
        Node::Intersect(c) => Node::Intersect(all(c)),
        Node::Subtract(a, c) => Node::Subtract(b(a), b(c)),
        Node::SmoothUnion(c, k) => Node::SmoothUnion(all(c), fold_expr(k)),
        Node::SmoothIntersect(c, k) => Node::SmoothIntersect(all(c), fold_expr(k)),
        Node::SmoothSubtract(a, c, k) => Node::SmoothSubtract(b(a), b(c), fold_expr(k)),
        Node::Translate(c, v) => {
            let v = fold_v3(v);
            if v.lits() == Some([0.0; 3]) {
                fold_node(c)
            } else {
                Node::Translate(b(c), v)
            }
        }
        Node::Rotate(c, axis, a) => {
            let a = fold_expr(a);
            if is_lit(&a, 0.0) {
                fold_node(c)
            } else {
                Node::Rotate(b(c), *axis, a)
            }
        }
        Node::Scale(c, s) => {
            let s = fold_expr(s);
            if is_lit(&s, 1.0) {
                fold_node(c)
            } else {
                Node::Scale(b(c), s)
            }
        }
        Node::Repeat(c, v) => Node::Repeat(b(c), fold_v3(v)),
        Node::RepeatLimited(c, v, n) => Node::RepeatLimited(b(c), fold_v3(v), *n),
        Node::Twist(c, r) => {
            let r = fold_expr(r);
            if is_lit(&r, 0.0) {
                fold_node(c)
            } else {
                Node::Twist(b(c), r)
            }
        }
        Node::Bend(c, r) => {
            let r = fold_expr(r);
            if is_lit(&r, 0.0) {
                fold_node(c)
            } else {
                Node::Bend(b(c), r)
            }
        }
        Node::Round(c, r) => {
            let r = fold_expr(r);
            if is_lit(&r, 0.0) {
                fold_node(c)
            } else {
                Node::Round(b(c), r)
            }
        }
        Node::Onion(c, t) => Node::Onion(b(c), fold_expr(t)),
        Node::Elongate(c, h) => {
            let h = fold_v3(h);
            if h.lits() == Some([0.0; 3]) {
                fold_node(c)
            } else {
                Node::Elongate(b(c), h)
            }
        }
        Node::Material(c, m) => Node::Material(b(c), fold_material(m)),
    }
}

fn fold_prim(p: &Prim) -> Prim {
    let mut folded = p.clone();
    for a in &mut folded.args {
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
