//! Lowering: the scene IR becomes a [`Program`] — the distance function and the sample (distance + material)
//! function as lowered [`code`], the leaf functions they call, and what the kernel needs around them (params, time,
//! the scene bound, lights, settings). All three writers spell the same `Program`, so they cannot disagree about
//! meaning.
//!
//! Nothing here restates a formula: the scene functions are the scene walker ([`crate::eval::walk`], the code the
//! interpreter runs) traced on symbolic values, and each leaf function is its [`crate::formula`] body traced once
//! ([`mod@trace`]).

pub mod code;
pub mod portable;
pub mod ray;
pub mod tape;
pub mod trace;

use std::collections::BTreeSet;

use crate::analyse::{self, fold, Aabb};
use crate::eval::plan::Plan;
use crate::eval::walk::Walk;
use crate::eval::{Env, Reference};
use crate::ir::*;
use code::{visit_ops, Body, Op, Ty, Val};
use trace::{trace, trace_leaf, Function, Sym};

/// The sample function's results.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SampleVals {
    pub distance: Val,
    pub albedo: Val,
    pub ambient: Val,
    pub diffuse: Val,
    pub specular: Val,
    pub shininess: Val,
}

impl SampleVals {
    /// Distance, albedo, ambient, diffuse, specular, shininess.
    pub fn all(&self) -> [Val; 6] {
        [self.distance, self.albedo, self.ambient, self.diffuse, self.specular, self.shininess]
    }
}

/// How a light reaches the scene (its values come from the frame uniform at run time).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LightShape {
    Directional,
    Point,
}

/// A scene lowered for the writers.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    pub distance: Body,
    pub distance_result: Val,
    pub sample: Body,
    pub sample_result: SampleVals,
    /// The normal of a scene shaded by its gradient ([`Plan::shaded_by_gradient`]): the walk differentiated
    /// ([`Walk::gradient`]) at the point `p`, its direction (V3). `None`: the ray program's tetrahedral normal.
    pub normal: Option<(Body, Val)>,
    /// The leaf functions the bodies call, traced, in [`crate::formula::Leaf`] order.
    pub functions: Vec<Function>,
    /// Uniform parameters, in slot order.
    pub params: Vec<ParamDecl>,
    pub lights: Vec<LightShape>,
    /// Whether the distance body reads the frame (time or params).
    pub distance_reads_frame: bool,
    /// Whether the sample body reads the frame.
    pub sample_reads_frame: bool,
    /// The scene's bound; rays are clipped to it.
    pub bound: Option<Aabb>,
    /// Whether any material can have a specular term (otherwise the kernels omit it).
    pub specular: bool,
    /// How the march refines its hits by the distance's sign, if it does ([`analyse::sign_refinement`]).
    pub refine: Option<analyse::SignRefinement>,
    /// The perturbation reference the frame holds for the scene's Mandelbrot patterns; when there is one, the
    /// sample function takes the point relative to it as a second argument, [`REFERENCE_OFFSET`].
    pub reference: Option<crate::analyse::ReferenceSpec>,
    /// Whether the scene functions read the frame's anchor ([`reads_anchor`]); where they do not, the ray program
    /// computes relative to the origin.
    pub anchored: bool,
    pub settings: RenderSettings,
    /// The camera's thin lens, if it has one (its samples spread over it).
    pub lens: Option<crate::ray::Lens>,
}

/// The name of the sample function's second argument where the scene has a perturbation reference: the point minus
/// the reference point (the camera's position), exact to the precision of the ray's t.
pub const REFERENCE_OFFSET: &str = "dp";

/// Lowers a scene (folding it first).
pub fn lower(scene: &Scene) -> Program {
    lower_with(scene, true)
}

/// Lowers a scene for a function library ([`crate::back::kernel::write_library`]): like [`lower`], but its
/// Mandelbrot patterns iterate plainly, with no perturbation reference.
pub fn lower_library(scene: &Scene) -> Program {
    lower_with(scene, false)
}

/// `kernel`: for a kernel with a frame, whose scene functions take points relative to the frame's anchor and whose
/// Mandelbrot patterns perturb around the frame's reference; a library's take the scene's own points.
fn lower_with(scene: &Scene, kernel: bool) -> Program {
    let folded = fold::fold_scene(scene);
    let plan = Plan::folded_with(&folded, scene.params(), kernel);
    let walk = Walk { plan: &plan, guards: true };
    let params = plan.params.clone();
    let anchored = kernel && meets_translation(&folded.root);

    let (distance, distance_result) = trace(|| {
        let (p, slots) = scene_inputs(params.len());
        walk.distance(p, &Env { anchor: anchored.then(anchor), ..Env::new(Sym::time(), &slots) }).0
    });
    let distance = distance.pruned(&[distance_result]);
    let (sample, sample_result) = trace(|| {
        let (p, slots) = scene_inputs(params.len());
        let mut env = Env { anchor: anchored.then(anchor), ..Env::new(Sym::time(), &slots) };
        if plan.reference.is_some() {
            // The point relative to the reference, which the kernels pass beside the point (`dp`).
            let offset = Sym::components(Sym::arg_of(REFERENCE_OFFSET, Ty::V3));
            env.reference = Some(Reference { offset, orbit: &[] });
        }
        let s = walk.sample(p, &env);
        SampleVals {
            distance: s.distance.0,
            albedo: Sym::vector(s.albedo),
            ambient: s.ambient.0,
            diffuse: s.diffuse.0,
            specular: s.specular.0,
            shininess: s.shininess.0,
        }
    });
    let sample = sample.pruned(&sample_result.all());
    let normal = plan.shaded_by_gradient().then(|| {
        let (body, result) = trace(|| {
            let (p, slots) = scene_inputs(params.len());
            let env = Env { anchor: anchored.then(anchor), ..Env::new(Sym::time(), &slots) };
            Sym::vector(crate::number::math::direction(walk.gradient(p, &env)))
        });
        (body.pruned(&[result]), result)
    });

    let mut used = BTreeSet::new();
    let mut reads = [false, false];
    for (i, body) in [&distance, &sample].into_iter().enumerate() {
        visit_ops(body, &mut |op| match op {
            Op::Call(leaf, _) => {
                used.insert(*leaf);
            }
            Op::Time | Op::Param(_) | Op::Orbit | Op::OrbitEntry(_) | Op::OrbitLast | Op::Frame(_) => reads[i] = true,
            _ => {}
        });
    }

    Program {
        functions: used.into_iter().map(trace_leaf).collect(),
        params,
        lights: folded
            .effective_lights()
            .iter()
            .map(|l| match l.kind {
                LightKind::Directional { .. } => LightShape::Directional,
                LightKind::Point { .. } => LightShape::Point,
            })
            .collect(),
        distance_reads_frame: reads[0],
        sample_reads_frame: reads[1],
        bound: analyse::bound(&folded.root),
        specular: analyse::has_specular(&folded.root),
        refine: analyse::sign_refinement(&folded.root, &folded.settings),
        reference: plan.reference,
        anchored,
        settings: folded.settings.clone(),
        lens: crate::ray::Lens::of(&folded.camera),
        distance,
        distance_result,
        sample,
        sample_result,
        normal,
    }
}

/// Whether a kernel of `scene` reads its frame's anchor: where the scene, folded as the lowering folds it, meets a
/// translation before any operation that takes the whole point. Elsewhere an anchor gains nothing — the scene adds
/// it back to the point at once — so the frame keeps the origin and the kernel skips the reads.
pub fn reads_anchor(scene: &Scene) -> bool {
    meets_translation(&fold::fold_scene(scene).root)
}

/// Whether the scene walker meets a translation at `node` before any operation that takes the whole point (a
/// combination or a material hands its shapes the point as it is): only then does a frame's anchor keep precision
/// ([`crate::eval::Env::anchor`]).
fn meets_translation(node: &Node) -> bool {
    use crate::ir::op::Meaning::*;
    match node {
        Node::Prim(_) | Node::Fractal(_) => false,
        Node::Material(child, _) => meets_translation(child),
        Node::Op(op) => match op.decl().meaning {
            Translate => true,
            Union | Intersect | Subtract | SmoothUnion | SmoothIntersect | SmoothSubtract => {
                op.shapes.iter().any(meets_translation)
            }
            _ => false,
        },
    }
}

/// The frame's anchor, as the scene functions of a kernel read it.
fn anchor() -> crate::number::math::V3<Sym> {
    Sym::components(Sym::frame(code::FrameField::Anchor))
}

/// The scene functions' inputs while tracing: the point `p` and a value per parameter slot.
fn scene_inputs(params: usize) -> (crate::number::math::V3<Sym>, Vec<Sym>) {
    let p = Sym::components(Sym::arg_of("p", Ty::V3));
    (p, (0..params).map(Sym::param).collect())
}
