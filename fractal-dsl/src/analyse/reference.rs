//! Which Mandelbrot patterns a frame's perturbation reference serves
//! ([`crate::formula::mandelbrot`](mod@crate::formula::mandelbrot)): the calls `mandelbrot(a, b, n)` whose first two
//! arguments are coordinates of the point, on a shape whose material reads world coordinates (nothing above it moves
//! the point). The frame computes one reference orbit at the camera's position for those axes, long enough for the
//! largest count; every such call with the same axes is computed by perturbation around it, every other call by the
//! plain iteration.

use crate::ir::{Expr, Func, Material, Node, Scene};
use crate::visit::{material_exprs, visit_node_exprs};

/// What the frame's reference must provide: the pattern axes it is computed on and the largest iteration count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReferenceSpec {
    /// The point coordinates (0 = x, 1 = y, 2 = z) that are the pattern's real and imaginary parts.
    pub axes: [u8; 2],
    pub iterations: u32,
}

impl ReferenceSpec {
    /// Orbit entries the frame holds: Z₀ … Z_iterations.
    pub fn entries(&self) -> usize {
        self.iterations as usize + 1
    }
}

/// The axes and count of `mandelbrot(a, b, n)` whose first two arguments are coordinates of the point.
pub fn perturbable(e: &Expr) -> Option<([u8; 2], u32)> {
    match e {
        Expr::Call(Func::Mandelbrot, args) => match args.as_slice() {
            [Expr::Point(a), Expr::Point(b), n] => Some(([*a, *b], Func::Mandelbrot.count(n.as_lit()))),
            _ => None,
        },
        _ => None,
    }
}

/// The reference a (folded) tree needs: the axes of the first perturbable call in a world-coordinate material, and
/// the largest count of the calls on those axes; `None` when there is no such call.
pub fn reference(root: &Node) -> Option<ReferenceSpec> {
    let mut spec: Option<ReferenceSpec> = None;
    world_materials(root, &mut |m| {
        material_exprs(m, &mut |e| {
            each_subexpr(e, &mut |sub| match (perturbable(sub), spec.as_mut()) {
                (Some((axes, iterations)), None) => spec = Some(ReferenceSpec { axes, iterations }),
                (Some((axes, iterations)), Some(s)) if s.axes == axes => s.iterations = s.iterations.max(iterations),
                _ => {}
            })
        })
    });
    spec
}

/// The reference `scene` needs, as its kernels see it (after folding, which may remove an operator that moved the
/// point). Scenes without a perturbable call anywhere are answered without folding.
pub fn scene_reference(scene: &Scene) -> Option<ReferenceSpec> {
    let mut any = false;
    visit_node_exprs(&scene.root, &mut |e| each_subexpr(e, &mut |sub| any |= perturbable(sub).is_some()));
    if !any {
        return None;
    }
    reference(&crate::analyse::fold::fold_scene(scene).root)
}

/// Calls `f` on every material whose point is the world point: reached from the root through operators that keep
/// the point ([`crate::ir::op::Meaning::keeps_point`]) and other materials only.
pub fn world_materials<'a>(node: &'a Node, f: &mut dyn FnMut(&'a Material)) {
    match node {
        Node::Material(child, m) => {
            f(m);
            world_materials(child, f);
        }
        Node::Op(op) if op.decl().meaning.keeps_point() => op.shapes.iter().for_each(|s| world_materials(s, f)),
        _ => {}
    }
}

/// Calls `f` on `e` and every expression inside it.
fn each_subexpr<'a>(e: &'a Expr, f: &mut dyn FnMut(&'a Expr)) {
    f(e);
    match e {
        Expr::Neg(a) => each_subexpr(a, f),
        Expr::Bin(_, a, b) => {
            each_subexpr(a, f);
            each_subexpr(b, f);
        }
        Expr::Call(_, args) => args.iter().for_each(|a| each_subexpr(a, f)),
        Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => {}
    }
}
