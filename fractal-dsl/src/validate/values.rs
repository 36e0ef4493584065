//! The per-value checks the parser calls while it still knows a value's span, and [`super::validate`] calls on a whole
//! scene: primitives, operators, fractals, nodes, materials, lights, camera, settings and parameters.

use super::problem::*;
use super::rules::*;
use super::size::*;
use crate::analyse::fold::fold_expr;
use crate::ir::arg::{ArgDecl, ArgShape, Rule};
use crate::ir::fractal::{FractalArg, FractalArgShape, FractalArgValue, FractalRule, Setting, STEP_FACTOR_RANGE};
use crate::ir::op::{Meaning, Operands};
use crate::ir::*;
use crate::vocab::fractals::families::FRACTALS;

/// Rules of a primitive's arguments, as its declaration states them.
pub fn check_prim(p: &Prim) -> Vec<Problem> {
    let decl = p.decl();
    let mut out = check_args(decl.args, &p.args);
    if let Some((indices, message)) = decl.not_all_zero {
        if out.is_empty() && indices.iter().all(|&i| p.args[i].exprs().iter().all(|e| constant_value(e) == Some(0.0))) {
            out.push(Problem::new("", message.to_string()));
        }
    }
    out
}

/// Rules of an operator: how many shapes it takes, and its arguments' rules as its declaration states them.
pub fn check_op(op: &Op) -> Vec<Problem> {
    let decl = op.decl();
    let n = op.shapes.len();
    let shapes = match decl.operands {
        Operands::Many if n == 0 => Some(format!("{} needs at least 1 shape", decl.name)),
        Operands::Two if n != 2 => Some(format!("{} takes 2 shapes, found {n}", decl.name)),
        Operands::Receiver if n != 1 => Some(format!("{} applies to 1 shape, found {n}", decl.name)),
        _ => None,
    };
    if op.args.len() != decl.args.len() {
        let message = format!("{} takes {} arguments, found {}", decl.name, decl.args.len(), op.args.len());
        return vec![Problem::new("", message)];
    }
    let mut out: Vec<Problem> = shapes.map(|m| Problem::new("shapes", m)).into_iter().collect();
    out.extend(check_args(decl.args, &op.args));
    out
}

/// Rules of declared arguments (a primitive's or an operator's), each as its declaration states it.
pub(super) fn check_args(decls: &[ArgDecl], values: &[ArgValue]) -> Vec<Problem> {
    let mut out = Vec::new();
    let o = &mut out;
    for (arg, value) in decls.iter().zip(values) {
        let exprs: Vec<&Expr> = value.exprs().iter().collect();
        let (name, what) = (arg.name, arg.what);
        match (arg.rule, value) {
            (_, ArgValue::Num(_)) if arg.shape != ArgShape::Number => o.push(Problem::new(name, mismatch(what))),
            (_, ArgValue::Vec3(_)) if arg.shape == ArgShape::Number => o.push(Problem::new(name, mismatch(what))),
            (_, _) if arg.shape == ArgShape::ConstVec3 && !exprs.iter().all(|e| is_constant(e)) => o.push(
                Problem::new(name, format!("{what} must be a constant: `t` and `param(..)` cannot be used here")),
            ),
            (Rule::Positive | Rule::NonNegative, _) => {
                let lim = if arg.rule == Rule::Positive { gt(0.0) } else { ge(0.0) };
                match value {
                    ArgValue::Num(e) => number(o, name, what, e, lim),
                    ArgValue::Vec3(v) => vector(o, name, what, v, lim),
                }
            }
            (Rule::Finite, _) => finite(o, name, what, &exprs),
            (Rule::Direction, _) => {
                let before = o.len();
                finite(o, name, what, &exprs);
                if o.len() == before && value.exprs().iter().all(|e| e.as_lit() == Some(0.0)) {
                    o.push(Problem::new(name, format!("{what} must be non-zero, found vec3(0, 0, 0)")));
                }
            }
            (Rule::RoundingOf(of), ArgValue::Num(e)) => {
                // Checked once the vector it rounds is valid: the rounding cannot turn the shape inside out.
                if o.is_empty() {
                    let smallest = values[of].exprs().iter().map(|h| value_range(h).0.lo).fold(f64::INFINITY, f64::min);
                    number(o, name, what, e, within(0.0, true, smallest, true));
                    if let Some(problem) = o.last_mut() {
                        let of = decls[of].name;
                        problem.message.push_str(&format!(" (the rounding cannot exceed the smallest {of} extent)"));
                    }
                }
            }
            (Rule::RoundingOf(_), ArgValue::Vec3(_)) => {}
            (Rule::Period, ArgValue::Vec3(v)) => {
                let before = o.len();
                vector(o, name, what, v, ge(0.0));
                if o.len() == before && v.lits() == Some([0.0; 3]) {
                    o.push(Problem::new(
                        name,
                        format!("{what} must be non-zero on at least one axis (0 leaves an axis unrepeated)"),
                    ));
                }
            }
            (Rule::Period, ArgValue::Num(e)) => number(o, name, what, e, ge(0.0)),
            (Rule::Displacement, ArgValue::Num(e)) => {
                let r = crate::analyse::interval::range(e);
                if let Some(m) = literal_problem(e) {
                    o.push(Problem::new(name, format!("{what}: {m}")));
                } else if !r.is_finite() {
                    o.push(Problem::new(
                        name,
                        format!("{what} must stay within a bounded range (wrap the point in noise, sin, clamp, ..)"),
                    ));
                } else if !crate::analyse::slope::slope(e).is_finite() {
                    o.push(Problem::new(
                        name,
                        format!(
                            "{what} must change with the point at a bounded rate (no division by a value that can be 0, \
                             no sqrt reaching 0, no pow with a varying exponent)"
                        ),
                    ));
                }
            }
            (Rule::Displacement, ArgValue::Vec3(_)) => {}
            (Rule::CountUpTo(most), _) => {
                let whole = value.exprs()[0].as_lit().filter(|v| v.fract() == 0.0 && *v >= 1.0 && *v <= most as f64);
                if whole.is_none() {
                    o.push(Problem::new(name, format!("{what} must be a whole number from 1 to {most}")));
                }
            }
            (Rule::AtMost(most), _) => {
                for (e, axis) in value.exprs().iter().zip(AXES) {
                    let whole = e.as_lit().filter(|v| v.fract() == 0.0 && *v >= 0.0);
                    match whole {
                        Some(v) if v <= most as f64 => {}
                        Some(v) => o.push(Problem::new(
                            name,
                            format!("{what} {axis} must be <= {most}, found {}", number_text(v)),
                        )),
                        None => o.push(Problem::new(name, format!("{what} {axis} must be a non-negative integer"))),
                    }
                }
            }
        }
    }
    out
}

pub(super) fn mismatch(what: &str) -> String {
    format!("{what} has the wrong type for its declaration")
}

/// Rules of a fractal, as its family's declaration states them: the constructor argument, the iteration count, and
/// which settings the family has at all.
pub fn check_fractal(f: &Fractal) -> Vec<Problem> {
    let mut out = Vec::new();
    let o = &mut out;
    let decl = f.decl();
    let (name, arg) = (decl.name, decl.arg);
    match (arg.rule, &f.arg) {
        (FractalRule::Between(lo, hi), FractalArgValue::Num(e)) => number(o, arg.name, arg.what, e, ge_le(lo, hi)),
        (FractalRule::AbsBetween(lo, hi), FractalArgValue::Num(e)) => abs_between(o, name, arg, e, lo, hi),
        (FractalRule::Finite, _) => finite(o, arg.name, arg.what, &f.arg_exprs().iter().collect::<Vec<_>>()),
        _ => {}
    }
    if let Some(formula) = f.formula() {
        formula_rules(o, name, formula);
    }
    if let Some(k) = f.step_factor {
        let (lo, hi) = STEP_FACTOR_RANGE;
        constant(o, "factor", &format!("{name} step_factor"), k, within(lo, false, hi, true));
    }
    if let Some(n) = f.iterations {
        let it = decl.iterations;
        match arg.shape {
            FractalArgShape::Levels => integer(o, arg.name, arg.what, n, it.min, it.max),
            _ => integer(o, "iterations", &format!("{name} iterations"), n, it.min, it.max),
        }
    }
    for setting in Setting::ALL {
        let Some(value) = f.setting(setting) else { continue };
        let method = setting.name();
        if f.applies(setting) {
            let what = format!("{name} {method}");
            match setting {
                // A formula's escape-time estimate 0.5·r·ln r/‖J‖ is positive past a bailout of at least 1.
                Setting::Bailout if f.formula().is_some() => {
                    let (lo, hi) = crate::vocab::fractals::families::FORMULA_BAILOUT;
                    number(o, method, &what, value, ge_le(lo, hi))
                }
                Setting::MinRadius => number(o, method, &what, value, within(0.0, false, 1.0, false)),
                Setting::Bailout | Setting::FoldLimit => number(o, method, &what, value, gt(0.0)),
                // The Mandelbulb's range: below 2 the map folds the sphere onto itself, above 64 f32 overflows.
                Setting::Power => number(o, method, &what, value, ge_le(2.0, 64.0)),
                Setting::Angle => finite(o, method, &what, &[value]),
            }
        } else {
            let having: Vec<&str> =
                FRACTALS.iter().filter(|d| d.settings.iter().any(|(s, _)| *s == setting)).map(|d| d.name).collect();
            let having = match having.split_last() {
                Some((last, [])) => last.to_string(),
                Some((last, rest)) => format!("{} and {last}", rest.join(", ")),
                None => "no family".to_string(),
            };
            o.push(Problem::new("", format!("`{method}` applies only to {having}, not {name}")));
        }
    }
    out
}

/// The size rules of a formula written in the scene language (the parser checks its types).
fn formula_rules(o: &mut Vec<Problem>, name: &str, formula: &crate::ir::formula::Formula) {
    use crate::ir::formula::{FormulaKind, MAX_FORMULA_NODES, MAX_HYBRID_MAPS};
    let maps = formula.maps.len();
    if maps == 0 {
        o.push(Problem::new("map", format!("{name} needs a map: |z, c| ..")));
    } else if formula.kind == FormulaKind::Fold && maps > 1 {
        o.push(Problem::new("map", "a fold has one map: write its steps in one closure".to_string()));
    } else if maps > MAX_HYBRID_MAPS {
        o.push(Problem::new("maps", format!("a hybrid takes at most {MAX_HYBRID_MAPS} maps, found {maps}")));
    }
    if formula.size() > MAX_FORMULA_NODES {
        o.push(Problem::new("map", format!("{name}'s formula has more than {MAX_FORMULA_NODES} nodes")));
    }
    // A number beyond f32's range is infinite in every f32 kernel but finite in f64: refused, as elsewhere.
    let mut found = None;
    formula.each_num(&mut |e| {
        if found.is_none() {
            found = literal_problem(&fold_expr(e));
        }
    });
    if let Some(m) = found {
        o.push(Problem::new("map", format!("{name}'s formula: {m}")));
    }
}

/// Checks lo ≤ |value| ≤ hi over the value's whole range ("mandelbox |scale| must be in [1.05, 8]").
pub(super) fn abs_between(o: &mut Vec<Problem>, family: &str, arg: FractalArg, e: &Expr, lo: f64, hi: f64) {
    if let Some(m) = literal_problem(e) {
        o.push(Problem::new(arg.name, format!("{}: {m}", arg.what)));
        return;
    }
    let (r, constant) = value_range(e);
    let rule = format!("|{}| must be in [{}, {}]", arg.name, number_text(lo), number_text(hi));
    let fits = |a: f64, b: f64| (a >= lo && b <= hi) || (a >= -hi && b <= -lo);
    if fits(r.lo, r.hi) {
        return;
    }
    let message = if constant {
        format!("{family} {rule}, found {}", number_text(r.lo))
    } else if !r.lo.is_finite() || !r.hi.is_finite() {
        format!("{family} {rule}, but no bound is known for its value, so it may leave that range")
    } else {
        format!("{family} {rule}, but its range is {}..{}", number_text(r.lo), number_text(r.hi))
    };
    o.push(Problem::new(arg.name, message));
}

/// Rules of one node's own values (not its children's): the primitive, fractal or operator's arguments, or the
/// material.
pub fn check_node(node: &Node) -> Vec<Problem> {
    // A displacement's amount (a displacement's only argument) and a material are the places the point may be read;
    // an expression breaking that (or a count rule) is reported alone, before the ranges it makes meaningless.
    let displaces = node.op().is_some_and(|op| op.decl().meaning == Meaning::Displace);
    let allow_point = displaces || matches!(node, Node::Material(..));
    let broken: Vec<Problem> = own_exprs(node)
        .into_iter()
        .filter_map(|e| expr_rule_problem(e, allow_point))
        .map(|m| Problem::new("", m))
        .collect();
    if !broken.is_empty() {
        return broken;
    }
    match node {
        Node::Prim(p) => check_prim(p),
        Node::Fractal(f) => check_fractal(f),
        Node::Op(op) => check_op(op),
        Node::Material(_, m) => check_material(m),
    }
}

/// The rules every expression keeps wherever it stands: `x`, `y`, `z` only where `allow_point` (a displacement's
/// amount, a material), and a count argument (fbm octaves, Mandelbrot iterations) a whole-number literal in range.
pub fn expr_rule_problem(e: &Expr, allow_point: bool) -> Option<String> {
    let mut stack = vec![e];
    while let Some(e) = stack.pop() {
        match e {
            Expr::Point(axis) if !allow_point => {
                let name = crate::print::POINT_NAMES[*axis as usize % 3];
                return Some(format!(
                    "`{name}` (the point) can be read only in a displacement or a material: shape.displace(..), \
                     shape.material(..)"
                ));
            }
            Expr::Call(f, args) => {
                if let Some((what, most)) = f.count_arg() {
                    let whole = args.last().and_then(Expr::as_lit).filter(|n| n.fract() == 0.0);
                    if !whole.is_some_and(|n| (1.0..=most as f64).contains(&n)) {
                        return Some(format!("{} {what} must be a whole number from 1 to {most}", f.name()));
                    }
                }
                stack.extend(args);
            }
            Expr::Neg(a) => stack.push(a),
            Expr::Bin(_, a, b) => stack.extend([&**a, &**b]),
            Expr::Lit(_) | Expr::Time | Expr::Point(_) | Expr::Param(_) => {}
        }
    }
    None
}

pub fn check_material(m: &Material) -> Vec<Problem> {
    let mut out = Vec::new();
    let o = &mut out;
    match &m.albedo {
        Albedo::Rgb(c) => finite(o, "color", "material color", &c.0.iter().collect::<Vec<_>>()),
        Albedo::OrbitTrap(a, b) => {
            finite(o, "a", "orbit_trap color a", &a.0.iter().collect::<Vec<_>>());
            finite(o, "b", "orbit_trap color b", &b.0.iter().collect::<Vec<_>>());
        }
    }
    number(o, "ambient", "material ambient", &m.ambient, ge(0.0));
    number(o, "diffuse", "material diffuse", &m.diffuse, ge(0.0));
    number(o, "specular", "material specular", &m.specular, ge(0.0));
    number(o, "shininess", "material shininess", &m.shininess, ge(0.0));
    out
}

/// Rules of a light.
pub fn check_light(l: &Light) -> Vec<Problem> {
    if let Some(m) = light_exprs(l).into_iter().find_map(|e| expr_rule_problem(e, false)) {
        return vec![Problem::new("", m)];
    }
    let mut out = Vec::new();
    let o = &mut out;
    match &l.kind {
        LightKind::Directional { direction } => {
            finite(o, "direction", "light direction", &direction.0.iter().collect::<Vec<_>>());
            if o.is_empty() && direction.lits() == Some([0.0; 3]) {
                o.push(Problem::new("direction", "light direction must be non-zero, found vec3(0, 0, 0)".into()));
            }
        }
        LightKind::Point { position } => {
            finite(o, "position", "light position", &position.0.iter().collect::<Vec<_>>())
        }
    }
    finite(o, "color", "light color", &l.color.0.iter().collect::<Vec<_>>());
    number(o, "intensity", "light intensity", &l.intensity, ge(0.0));
    out
}

/// Rules of a camera: field of view, look-at placement, path keys.
pub fn check_camera(c: &Camera) -> Vec<Problem> {
    if let Some(m) = camera_exprs(c).into_iter().find_map(|e| expr_rule_problem(e, false)) {
        return vec![Problem::new("", m)];
    }
    let mut out = Vec::new();
    let o = &mut out;
    constant(o, "degrees", "camera fov", c.fov_degrees, within(0.0, false, 180.0, false));
    constant(o, "radius", "camera aperture", c.aperture, within(0.0, true, MAX_DISTANCE, true));
    if let Some(d) = c.focus {
        constant(o, "distance", "camera focus", d, within(0.0, false, MAX_DISTANCE, true));
    }
    match &c.placement {
        CameraPlacement::LookAt { position, target } => {
            finite(o, "position", "camera position", &position.0.iter().collect::<Vec<_>>());
            finite(o, "target", "camera target", &target.0.iter().collect::<Vec<_>>());
            if o.is_empty() && position.lits().is_some() && position.lits() == target.lits() {
                o.push(Problem::new("target", "camera target must differ from the camera position".into()));
            }
        }
        CameraPlacement::Path { keys, .. } => {
            if keys.len() < 2 {
                o.push(Problem::new("keys", format!("camera_path needs at least 2 keys, found {}", keys.len())));
            }
            for (i, k) in keys.iter().enumerate() {
                let problem = |message: String| Problem { arg: "keys", index: Some(i), message };
                let values = [k.time].into_iter().chain(k.position).chain(k.target);
                if let Some(m) = values.into_iter().find_map(value_problem) {
                    o.push(problem(format!("camera key {}: {m}", i + 1)));
                } else if k.position == k.target {
                    o.push(problem(format!("camera key {}: target must differ from the position", i + 1)));
                } else if i > 0 && k.time <= keys[i - 1].time {
                    o.push(problem(format!(
                        "camera key times must increase strictly: key {} at {} follows {}",
                        i + 1,
                        number_text(k.time),
                        number_text(keys[i - 1].time)
                    )));
                }
            }
        }
    }
    out
}

/// Rules of the scene as a whole: how many lights, and the render settings.
pub fn check_scene(s: &Scene) -> Vec<Problem> {
    let mut out = Vec::new();
    if s.lights.len() > MAX_LIGHTS {
        out.push(Problem::new(
            "light",
            format!("a scene may have at most {MAX_LIGHTS} lights, found {}", s.lights.len()),
        ));
    }
    out.extend(check_settings(&s.settings));
    if s.settings.membership_hits {
        out.extend(check_membership_hits(&s.root));
    }
    out
}

/// `membership_hits` reads the sign of every fractal's estimate as membership of its set: only escape-time families
/// have one ([`crate::ir::fractal::Membership::signed`]), and a scene without them has no set to take hits on.
pub fn check_membership_hits(root: &Node) -> Vec<Problem> {
    fn fractals<'a>(node: &'a Node, out: &mut Vec<&'a Fractal>) {
        if let Node::Fractal(f) = node {
            out.push(f);
        }
        node.children().iter().for_each(|c| fractals(c, out));
    }
    let mut all = Vec::new();
    fractals(root, &mut all);
    let signed: Vec<&str> = FRACTALS.iter().filter(|d| d.membership.has_sign()).map(|d| d.name).collect();
    let takes = format!("it takes {}", signed.join(", "));
    if all.is_empty() {
        return vec![Problem::new("membership_hits", format!("the scene has no fractal to take hits on; {takes}"))];
    }
    all.iter()
        .filter(|f| !f.decl().membership.has_sign())
        .map(|f| {
            let name = f.name();
            Problem::new("membership_hits", format!("{name}'s estimate has no membership sign; {takes}"))
        })
        .collect()
}

/// Rules of the render settings.
pub fn check_settings(s: &RenderSettings) -> Vec<Problem> {
    let mut out = Vec::new();
    let o = &mut out;
    integer(o, "steps", "max_steps", s.max_steps, 1, MAX_MARCH_STEPS);
    constant(o, "distance", "max_distance", s.max_distance, within(0.0, false, MAX_DISTANCE, true));
    match s.epsilon {
        HitEpsilon::Fixed(e) => constant(o, "epsilon", "epsilon", e, gt(0.0)),
        HitEpsilon::Pixel(k) => constant(o, "pixels", "pixel_epsilon", k, gt(0.0)),
    }
    if let Some(k) = s.normal_epsilon {
        constant(o, "pixels", "normal_pixel_epsilon", k, gt(0.0));
    }
    constant(o, "omega", "over_relaxation", s.over_relaxation, within(1.0, true, 2.0, true));
    integer(o, "n", "samples", s.samples, 1, MAX_SAMPLES);
    constant(o, "threshold", "sample_threshold", s.sample_threshold, within(0.0, true, 1.0, true));
    if let Shadows::Soft(k) = s.shadows {
        constant(o, "k", "soft_shadows k", k, gt(0.0));
    }
    if let Some(a) = s.ambient_occlusion {
        constant(o, "strength", "ambient_occlusion strength", a, within(0.0, false, 10.0, true));
    }
    let color = |o: &mut Vec<Problem>, what: &str, c: [f64; 3]| {
        if let Some(m) = c.into_iter().find_map(value_problem) {
            o.push(Problem::new("color", format!("{what} color: {m}")));
        }
    };
    if let Some(g) = s.glow {
        color(o, "glow", g);
    }
    if let Some(f) = &s.fog {
        color(o, "fog", f.color);
        constant(o, "density", "fog density", f.density, gt(0.0));
    }
    color(o, "background", s.background);
    constant(o, "gamma", "gamma", s.gamma, gt(0.0));
    out
}

/// Rules of a parameter declaration: an identifier name, finite numbers, min < max, the default within.
pub fn check_param(p: &ParamDecl) -> Vec<Problem> {
    let mut out = Vec::new();
    let name = &p.name;
    let identifier = p.name.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && p.name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && p.name.len() <= 64;
    if !identifier {
        out.push(Problem::new(
            "name",
            format!("param name must be an identifier of at most 64 letters, digits and `_`, found {name:?}"),
        ));
    }
    if let Some(m) = [p.default, p.min, p.max].into_iter().find_map(value_problem) {
        out.push(Problem::new("", format!("param {name:?}: {m}")));
    } else if p.min >= p.max {
        out.push(Problem::new(
            "range",
            format!("param {name:?} range must have min < max, found {}..{}", number_text(p.min), number_text(p.max)),
        ));
    } else if !(p.min..=p.max).contains(&p.default) {
        out.push(Problem::new(
            "default",
            format!(
                "param {name:?} default must be within {}..{}, found {}",
                number_text(p.min),
                number_text(p.max),
                number_text(p.default)
            ),
        ));
    }
    out
}

/// The message when a parameter is declared again with a different default or range (a uniform has one of each).
/// The two declarations are listed in a fixed order, so the message does not depend on which one is met first.
pub fn check_param_again(first: &ParamDecl, again: &ParamDecl) -> Option<String> {
    if first == again {
        return None;
    }
    let key = |p: &ParamDecl| [p.default, p.min, p.max];
    let (a, b) = if key(first).partial_cmp(&key(again)) == Some(std::cmp::Ordering::Greater) {
        (again, first)
    } else {
        (first, again)
    };
    let describe =
        |p: &ParamDecl| format!("default {} in {}..{}", number_text(p.default), number_text(p.min), number_text(p.max));
    Some(format!("param {:?} is declared twice with different values: {} and {}", first.name, describe(a), describe(b)))
}
