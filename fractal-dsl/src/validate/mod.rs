//! Validation: every value a scene names is checked against its allowed range, with a message naming the parameter.
//!
//! The rules live here once. [`validate`] applies them to a whole scene (scenes made with the builder), and the parser
//! calls the per-value checks ([`check_prim`], [`check_fractal`], [`check_node`], ...) on each value it builds while
//! it still knows the argument's span, so a rule reports the same message at the token in `scene!`, at `line:column`
//! in a `.fractal` file and with a node path here.
//!
//! A value that is not a constant (it reads `t` or a `param`) is checked over the range it can take
//! ([`crate::analyse::interval::range`]): an animated radius must stay positive for all time, and one whose range is
//! unknown is refused where the rule has a limit.

mod problem;
mod rules;
mod size;
mod values;

pub use problem::*;
pub use rules::*;
pub use size::*;
pub use values::*;

use crate::ir::*;

/// [`validate`] with its errors as one [`InvalidScene`].
pub fn checked(scene: &Scene) -> Result<(), InvalidScene> {
    validate(scene).map_err(InvalidScene)
}

/// Checks a whole scene; every broken rule is reported.
pub fn validate(scene: &Scene) -> Result<(), Vec<ValidationError>> {
    let mut errors = Vec::new();
    let at = |path: &str, problems: Vec<Problem>, errors: &mut Vec<ValidationError>| {
        errors.extend(problems.into_iter().map(|p| ValidationError { path: path.to_string(), message: p.message }))
    };

    // Sizes first and without recursion: a tree too deep is refused before anything recurses into it.
    if let Some(message) = size_problem(scene) {
        errors.push(ValidationError { path: "scene".into(), message });
        return Err(errors);
    }

    let mut path = Vec::new();
    walk(&scene.root, &mut path, &mut errors);
    for (i, light) in scene.lights.iter().enumerate() {
        at(&format!("light {}", i + 1), check_light(light), &mut errors);
    }
    at("camera", check_camera(&scene.camera), &mut errors);
    at("scene", check_scene(scene), &mut errors);

    let mut declared: Vec<&ParamDecl> = Vec::new();
    let mut params: Vec<&ParamDecl> = Vec::new();
    crate::visit::visit_exprs(scene, &mut |e| e.visit_params(&mut |p| params.push(p)));
    for p in params {
        let path = format!("param {:?}", p.name);
        match declared.iter().find(|q| q.name == p.name) {
            Some(first) => {
                if let Some(message) = check_param_again(first, p) {
                    if !errors.iter().any(|e| e.path == path && e.message == message) {
                        errors.push(ValidationError { path, message });
                    }
                }
            }
            None => {
                at(&path, check_param(p), &mut errors);
                declared.push(p);
            }
        }
    }

    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

fn walk(node: &Node, path: &mut Vec<String>, errors: &mut Vec<ValidationError>) {
    path.push(node_label(node).to_string());
    let problems = check_node(node);
    if !problems.is_empty() {
        let here = path.join(" > ");
        errors.extend(problems.into_iter().map(|p| ValidationError { path: here.clone(), message: p.message }));
    }
    let n_ary = node.op().is_some_and(|op| op.decl().combines());
    for (i, child) in node.children().iter().enumerate() {
        if n_ary {
            path.push(format!("child {}", i + 1));
        }
        walk(child, path, errors);
        if n_ary {
            path.pop();
        }
    }
    path.pop();
}

/// The name a node has in scene source (the function or method that makes it).
pub fn node_label(node: &Node) -> &'static str {
    match node {
        Node::Prim(p) => p.name(),
        Node::Fractal(f) => f.name(),
        Node::Op(op) => op.name(),
        Node::Material(..) => "material",
    }
}
