//! The quality settings an accuracy sweep varies, and how each is applied to a scene: the march's step budget and hit
//! epsilon (render settings), the iteration count of escape-time fractals (the scene's fractals), a factor on every
//! distance the march steps by (the step factor, applied by wrapping the CPU evaluator), whether rays are clipped to
//! the scene's bound (on the CPU only), over-relaxation of the march, the normal's taps and membership hits (render
//! settings), and whether OpenCL builds its kernels with fast math (OpenCL only).

use std::fmt;

use fractal_dsl::eval::{Env, Evaluator, Sample};
use fractal_dsl::number::math::{Real, V3};
use fractal_dsl::{Fractal, HitEpsilon, Node, Op, Scene};
use fractal_render::precision::Precision;

/// One point of a sweep; `None` keeps the scene's own value.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quality {
    pub max_steps: Option<u32>,
    pub epsilon: Option<HitEpsilon>,
    /// Iterations of every escape-time fractal (IFS levels are the shape and stay).
    pub iterations: Option<u32>,
    /// Factor on the step factor the scene's fractals declare (1: as declared).
    pub step_scale: Option<f64>,
    /// `Some(false)`: rays are not clipped to the scene's bound (CPU only; the kernels always clip).
    pub bounds: Option<bool>,
    /// Over-relaxation factor ω of the march with its fallback (the scene's `over_relaxation`).
    pub over_relaxation: Option<f64>,
    /// The normal's taps in pixel footprints (the scene's `normal_pixel_epsilon`): the normal method.
    pub normal: Option<f64>,
    /// Whether hits are taken on escape-time sets themselves (the scene's `membership_hits`).
    pub membership: Option<bool>,
    /// `Some(true)`: OpenCL builds the kernels without `-cl-fast-relaxed-math`, `Some(false)`: with it (OpenCL only;
    /// `None` keeps the sweep's own choice, `--precise`).
    pub precise: Option<bool>,
    /// The number type (`None`: the one the view asks for, [`fractal_render::choose_precision`]); f64 renders on
    /// the backend where its device has f64, else on the CPU.
    pub precision: Option<Precision>,
}

impl Quality {
    /// The scene with this quality's render settings and iteration counts.
    pub fn apply(&self, scene: &Scene) -> Scene {
        let mut out = match self.iterations {
            Some(n) => with_fractals(scene, &|f| {
                let mut f = f.clone();
                if f.decl().membership.approaches_limit {
                    let range = f.decl().iterations;
                    f.iterations = Some(n.clamp(range.min, range.max));
                }
                f
            }),
            None => scene.clone(),
        };
        if let Some(n) = self.max_steps {
            out.settings.max_steps = n;
        }
        if let Some(e) = self.epsilon {
            out.settings.epsilon = e;
        }
        if let Some(w) = self.over_relaxation {
            out.settings.over_relaxation = w;
        }
        if let Some(k) = self.normal {
            out.settings.normal_epsilon = Some(k);
        }
        if let Some(m) = self.membership {
            out.settings.membership_hits = m;
        }
        out
    }

    /// The factor on the march's distances.
    pub fn step_scale(&self) -> f64 {
        self.step_scale.unwrap_or(1.0)
    }

    /// Whether this is the scene's own setting.
    /// The scene's own setting, in whichever precision.
    pub fn is_default(&self) -> bool {
        Quality { precision: None, ..*self } == Quality::default()
    }
}

impl fmt::Display for Quality {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        if let Some(n) = self.max_steps {
            parts.push(format!("steps {n}"));
        }
        match self.epsilon {
            Some(HitEpsilon::Fixed(e)) => parts.push(format!("eps {e}")),
            Some(HitEpsilon::Pixel(k)) => parts.push(format!("eps {k} px")),
            None => {}
        }
        if let Some(n) = self.iterations {
            parts.push(format!("iter {n}"));
        }
        if let Some(s) = self.step_scale {
            // Three decimals at most: 4/3 reads 1.333.
            let text = format!("{s:.3}");
            parts.push(format!("step x{}", text.trim_end_matches('0').trim_end_matches('.')));
        }
        if self.bounds == Some(false) {
            parts.push("no bounds".to_string());
        }
        if let Some(w) = self.over_relaxation {
            parts.push(format!("relax {w}"));
        }
        if let Some(k) = self.normal {
            parts.push(format!("normal {k} px"));
        }
        match self.membership {
            Some(true) => parts.push("membership hits".to_string()),
            Some(false) => parts.push("estimate hits".to_string()),
            None => {}
        }
        match self.precise {
            Some(true) => parts.push("precise math".to_string()),
            Some(false) => parts.push("fast math".to_string()),
            None => {}
        }
        let wide = match self.precision {
            Some(Precision::F64) => " in f64",
            _ => "",
        };
        if parts.is_empty() {
            write!(f, "scene default{wide}")
        } else {
            write!(f, "{}{wide}", parts.join(", "))
        }
    }
}

/// The scene with each escape-time fractal's iteration count multiplied by `factor` (IFS levels stay), up to the
/// most its family allows.
pub fn with_iterations_scaled(scene: &Scene, factor: u32) -> Scene {
    if factor == 1 {
        return scene.clone();
    }
    with_fractals(scene, &|f| {
        let mut f = f.clone();
        if f.decl().membership.approaches_limit {
            f.iterations = Some(f.iterations_or_default().saturating_mul(factor).min(f.decl().iterations.max));
        }
        f
    })
}

/// The scene with every fractal replaced by `edit(fractal)`.
pub fn with_fractals(scene: &Scene, edit: &dyn Fn(&Fractal) -> Fractal) -> Scene {
    Scene { root: map_fractals(&scene.root, edit), ..scene.clone() }
}

fn map_fractals(node: &Node, edit: &dyn Fn(&Fractal) -> Fractal) -> Node {
    match node {
        Node::Fractal(f) => Node::Fractal(Box::new(edit(f))),
        Node::Prim(_) => node.clone(),
        Node::Op(op) => Node::Op(Op {
            kind: op.kind,
            shapes: op.shapes.iter().map(|n| map_fractals(n, edit)).collect(),
            args: op.args.clone(),
        }),
        Node::Material(c, m) => Node::Material(Box::new(map_fractals(c, edit)), m.clone()),
    }
}

/// An evaluator whose distances are scaled by a factor: a step factor on the whole scene. The hit test compares the
/// scaled distance with epsilon, as the kernels do with a fractal's declared step factor.
pub struct StepScaled<'a, F> {
    pub inner: &'a dyn Evaluator<F>,
    pub scale: F,
}

impl<F: Real> Evaluator<F> for StepScaled<'_, F> {
    fn distance(&self, p: V3<F>, env: &Env<F>) -> F {
        self.inner.distance(p, env) * self.scale
    }
    fn sample(&self, p: V3<F>, env: &Env<F>) -> Sample<F> {
        let s = self.inner.sample(p, env);
        Sample { distance: s.distance * self.scale, ..s }
    }
    fn normal(&self, p: V3<F>, env: &Env<F>) -> Option<V3<F>> {
        self.inner.normal(p, env)
    }
}
