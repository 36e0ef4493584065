//! Walks over every expression of a scene, for analyses that only care about the numbers, and the facts they give:
//! the scene's parameters ([`Scene::params`]) and whether it reads the time ([`Scene::uses_time`]).

use crate::ir::{Albedo, CameraPlacement, Expr, LightKind, Material, Node, ParamDecl, Scene};

/// Calls `f` on every expression in the distance tree (geometry and materials), in tree order.
pub fn visit_node_exprs<'a>(node: &'a Node, f: &mut dyn FnMut(&'a Expr)) {
    match node {
        Node::Prim(p) => p.exprs().for_each(&mut *f),
        Node::Fractal(fr) => {
            fr.arg_exprs().iter().for_each(&mut *f);
            fr.settings.iter().flatten().for_each(&mut *f);
        }
        Node::Op(op) => op.exprs().for_each(&mut *f),
        Node::Material(_, m) => material_exprs(m, f),
    }
    for c in node.children() {
        visit_node_exprs(c, f);
    }
}

/// Calls `f` on every expression of a material.
pub fn material_exprs<'a>(m: &'a Material, f: &mut dyn FnMut(&'a Expr)) {
    match &m.albedo {
        Albedo::Rgb(c) => c.0.iter().for_each(&mut *f),
        Albedo::OrbitTrap(a, b) => a.0.iter().chain(b.0.iter()).for_each(&mut *f),
    }
    for e in [&m.ambient, &m.diffuse, &m.specular, &m.shininess] {
        f(e)
    }
}

/// Calls `f` on every expression of the scene: the tree, then lights, then the camera.
pub fn visit_exprs<'a>(scene: &'a Scene, f: &mut dyn FnMut(&'a Expr)) {
    visit_node_exprs(&scene.root, f);
    for l in &scene.lights {
        match &l.kind {
            LightKind::Directional { direction: v } | LightKind::Point { position: v } => v.0.iter().for_each(&mut *f),
        }
        l.color.0.iter().for_each(&mut *f);
        f(&l.intensity);
    }
    if let CameraPlacement::LookAt { position, target } = &scene.camera.placement {
        position.0.iter().chain(target.0.iter()).for_each(&mut *f);
    }
}

impl Scene {
    /// The scene's parameters in order of first appearance (geometry, then materials, then lights);
    /// index i is uniform slot i.
    pub fn params(&self) -> Vec<ParamDecl> {
        let mut out: Vec<ParamDecl> = Vec::new();
        let mut add = |p: &ParamDecl| {
            if !out.iter().any(|q| q.name == p.name) {
                out.push(p.clone());
            }
        };
        visit_exprs(self, &mut |e| e.visit_params(&mut add));
        out
    }
    /// Whether anything in the kernel reads `t`.
    pub fn uses_time(&self) -> bool {
        let mut used = false;
        visit_node_exprs(&self.root, &mut |e| used |= e.uses_time());
        used
    }
}
