//! Sizes of a scene: tree depth, expression depth and counts, checked without recursion before anything recurses.

use super::problem::*;
use crate::ir::*;

/// Depth of an expression, counted without recursion.
pub fn expr_depth(e: &Expr) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(e, 1usize)];
    while let Some((e, d)) = stack.pop() {
        deepest = deepest.max(d);
        match e {
            Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => {}
            Expr::Neg(a) => stack.push((a, d + 1)),
            Expr::Bin(_, a, b) => {
                stack.push((a, d + 1));
                stack.push((b, d + 1));
            }
            Expr::Call(_, args) => stack.extend(args.iter().map(|a| (a, d + 1))),
        }
    }
    deepest
}

/// Depth of a distance tree, counted without recursion.
pub fn node_depth(n: &Node) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(n, 1usize)];
    while let Some((n, d)) = stack.pop() {
        deepest = deepest.max(d);
        stack.extend(n.children().iter().map(|c| (c, d + 1)));
    }
    deepest
}

/// The expressions a node holds itself (not those of its children).
pub fn own_exprs(node: &Node) -> Vec<&Expr> {
    let mut out: Vec<&Expr> = Vec::new();
    match node {
        Node::Prim(p) => out.extend(p.exprs()),
        Node::Fractal(f) => {
            out.extend(f.arg_exprs());
            out.extend(f.settings.iter().flatten());
        }
        Node::Op(op) => out.extend(op.exprs()),
        Node::Material(_, m) => crate::visit::material_exprs(m, &mut |e| out.push(e)),
    }
    out
}

pub(super) fn light_exprs(l: &Light) -> Vec<&Expr> {
    let v = match &l.kind {
        LightKind::Directional { direction: v } | LightKind::Point { position: v } => v,
    };
    v.0.iter().chain(&l.color.0).chain([&l.intensity]).collect()
}

pub(super) fn camera_exprs(c: &Camera) -> Vec<&Expr> {
    match &c.placement {
        CameraPlacement::LookAt { position, target } => position.0.iter().chain(&target.0).collect(),
        CameraPlacement::Path { .. } => Vec::new(),
    }
}

/// The message for a scene over a size or depth cap, found without recursion.
pub(super) fn size_problem(scene: &Scene) -> Option<String> {
    let mut nodes = 0usize;
    let mut expr_nodes = 0usize;
    let mut stack = vec![(&scene.root, 1usize)];
    let mut exprs: Vec<&Expr> = Vec::new();
    let mut deepest = 0;
    // Every node is counted before depth is judged: a tree that is too big says so even where it is also deep.
    while let Some((n, d)) = stack.pop() {
        nodes += 1;
        deepest = deepest.max(d);
        if nodes > MAX_NODES {
            return Some(format!("the shape tree has more than {MAX_NODES} nodes"));
        }
        exprs.extend(own_exprs(n));
        stack.extend(n.children().iter().map(|c| (c, d + 1)));
    }
    if deepest > MAX_DEPTH {
        return Some(format!("the shape tree nests more than {MAX_DEPTH} levels deep"));
    }
    for l in &scene.lights {
        exprs.extend(light_exprs(l));
    }
    exprs.extend(camera_exprs(&scene.camera));
    for e in exprs {
        if let Some(m) = expr_size_problem(e) {
            return Some(m);
        }
        expr_nodes += e.size();
        if expr_nodes > MAX_EXPR_NODES {
            return Some(format!("the scene's expressions have more than {MAX_EXPR_NODES} nodes"));
        }
    }
    None
}

/// The message for an expression nested deeper than [`MAX_EXPR_DEPTH`].
pub fn expr_size_problem(e: &Expr) -> Option<String> {
    (expr_depth(e) > MAX_EXPR_DEPTH).then(|| format!("an expression nests more than {MAX_EXPR_DEPTH} levels deep"))
}
