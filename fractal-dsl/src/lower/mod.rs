//! Lowering: the scene IR becomes a [`Program`] — the distance function and the sample (distance + material)
//! function as straight-line [`code`], plus what the kernel needs around them (helpers, params, time, the scene bound,
//! lights, settings). All three writers spell the same `Program`, so they cannot disagree about meaning.
//!
//! The rules are those of [`crate::eval`] (the interpreter implements them independently; the agreement tests hold
//! the two together).

pub mod code;

use crate::analyse::{self, fold, Aabb};
use crate::back::{with_dependencies, Helper};
use crate::ir::*;
use code::{Arg, Body, Builder, MathFn, Op, Stmt, Val};

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
    /// Albedo, ambient, diffuse, specular, shininess.
    pub fn fields(&self) -> [Val; 5] {
        [self.albedo, self.ambient, self.diffuse, self.specular, self.shininess]
    }
    fn with_fields(distance: Val, f: [Val; 5]) -> SampleVals {
        SampleVals { distance, albedo: f[0], ambient: f[1], diffuse: f[2], specular: f[3], shininess: f[4] }
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
    /// Helpers the bodies call, with their dependencies, in emission order.
    pub helpers: Vec<Helper>,
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
    pub settings: RenderSettings,
}

impl Program {
    pub fn layout(&self) -> crate::back::FrameLayout {
        crate::back::FrameLayout { lights: self.lights.len(), params: self.params.len() }
    }
}

/// Lowers a scene (folding it first).
pub fn lower(scene: &Scene) -> Program {
    // Param slots come from the scene as written (folding may drop a param's only use; the host packs them all).
    let params = scene.params();
    let scene = fold::fold_scene(scene);
    let default_material = Material::default_surface();

    let mut l = Lower { b: Builder::new(), params: &params, material: false };
    let p = l.b.point();
    let distance_result = l.node(&scene.root, p, &default_material).distance;
    let distance = l.b.finish();

    let mut l = Lower { b: Builder::new(), params: &params, material: true };
    let p = l.b.point();
    let sample_result = l.node(&scene.root, p, &default_material).into();
    let sample = l.b.finish();

    let mut used = Vec::new();
    let mut reads = [false, false];
    for (i, body) in [&distance, &sample].into_iter().enumerate() {
        visit_ops(body, &body.stmts, &mut |op| match op {
            Op::Call(h, _) => used.push(*h),
            Op::Time | Op::Param(_) => reads[i] = true,
            _ => {}
        });
    }
    let mut specular = false;
    visit_materials(&scene.root, &mut |m| specular |= m.specular.as_lit() != Some(0.0));

    Program {
        helpers: with_dependencies(used),
        params,
        lights: scene
            .effective_lights()
            .iter()
            .map(|l| match l.kind {
                LightKind::Directional { .. } => LightShape::Directional,
                LightKind::Point { .. } => LightShape::Point,
            })
            .collect(),
        distance_reads_frame: reads[0],
        sample_reads_frame: reads[1],
        bound: analyse::bound(&scene.root),
        specular,
        settings: scene.settings.clone(),
        distance,
        distance_result,
        sample,
        sample_result,
    }
}

fn visit_materials(n: &Node, f: &mut dyn FnMut(&Material)) {
    if let Node::Material(_, m) = n {
        f(m)
    }
    for c in n.children() {
        visit_materials(c, f)
    }
}

/// Calls `f` on the op of every statement and every inline value they use, recursively through `if` bodies.
fn visit_ops(body: &Body, stmts: &[Stmt], f: &mut dyn FnMut(&Op)) {
    let seen_inline = |v: Val, f: &mut dyn FnMut(&Op)| {
        if let Some(op) = body.op(v) {
            if code::is_inline(op) {
                f(op)
            }
        }
    };
    for s in stmts {
        match s {
            Stmt::Let { op, .. } => {
                f(op);
                for v in operands(op) {
                    seen_inline(v, f);
                }
            }
            Stmt::Var { init, .. } => seen_inline(*init, f),
            Stmt::Assign { value, .. } => seen_inline(*value, f),
            Stmt::If { cond, body: inner } => {
                if let Some(Op::Less(a, b)) = body.op(*cond) {
                    seen_inline(*a, f);
                    seen_inline(*b, f);
                }
                visit_ops(body, inner, f)
            }
        }
    }
}

/// The values an op reads.
pub fn operands(op: &Op) -> Vec<Val> {
    match op {
        Op::Lit(_) | Op::Time | Op::Param(_) | Op::Point => vec![],
        Op::MakeV3(a, b, c) | Op::Select(a, b, c) => vec![*a, *b, *c],
        Op::Comp(a, _) | Op::Neg(a) | Op::Length(a) | Op::Load(a) => vec![*a],
        Op::Bin(_, a, b) | Op::Less(a, b) => vec![*a, *b],
        Op::Math(_, args) => args.clone(),
        Op::Call(_, args) => args
            .iter()
            .filter_map(|a| match a {
                Arg::Val(v) => Some(*v),
                Arg::Int(_) => None,
            })
            .collect(),
    }
}

struct Lower<'a> {
    b: Builder,
    params: &'a [ParamDecl],
    /// Whether materials are tracked (the sample function) or only distances (the distance function).
    material: bool,
}

/// A lowered subtree: its distance, and its material fields when materials are tracked.
struct Surf {
    distance: Val,
    fields: Option<[Val; 5]>,
}

impl From<Surf> for SampleVals {
    fn from(s: Surf) -> SampleVals {
        let f = s.fields.expect("the sample function tracks materials");
        SampleVals::with_fields(s.distance, f)
    }
}

impl Lower<'_> {
    fn expr(&mut self, e: &Expr) -> Val {
        match e {
            Expr::Lit(v) => self.b.lit(*v),
            Expr::Time => self.b.time(),
            Expr::Param(p) => {
                let i = self.params.iter().position(|q| q.name == p.name).expect("params() lists every param");
                self.b.param(i)
            }
            Expr::Neg(a) => {
                let a = self.expr(a);
                self.b.neg(a)
            }
            Expr::Bin(op, a, c) => {
                let (a, c) = (self.expr(a), self.expr(c));
                self.b.bin(*op, a, c)
            }
            Expr::Call(f, args) => {
                let args: Vec<Val> = args.iter().map(|a| self.expr(a)).collect();
                let f = match f {
                    Func::Sin => MathFn::Sin,
                    Func::Cos => MathFn::Cos,
                    Func::Abs => MathFn::Abs,
                    Func::Sqrt => MathFn::Sqrt,
                    Func::Min => MathFn::Min,
                    Func::Max => MathFn::Max,
                    Func::Pow => MathFn::Pow,
                    Func::Clamp => MathFn::Clamp,
                    Func::Mix => MathFn::Mix,
                };
                self.b.math(f, args)
            }
        }
    }

    fn v3e(&mut self, v: &Vec3Expr) -> Val {
        let [x, y, z] = [&v.0[0], &v.0[1], &v.0[2]].map(|e| self.expr(e));
        self.b.v3(x, y, z)
    }

    fn comps(&mut self, p: Val) -> [Val; 3] {
        [0, 1, 2].map(|i| self.b.comp(p, i))
    }

    /// Material fields of a leaf under `m`; `trap` is the fractal's orbit trap, if the leaf is a fractal.
    fn leaf_fields(&mut self, m: &Material, trap: Option<Val>) -> Option<[Val; 5]> {
        if !self.material {
            return None;
        }
        let albedo = match (&m.albedo, trap) {
            (Albedo::Rgb(c), _) => self.v3e(c),
            (Albedo::OrbitTrap(a, _), None) => self.v3e(a),
            (Albedo::OrbitTrap(a, c), Some(t)) => {
                let (a, c) = (self.v3e(a), self.v3e(c));
                self.mix3(a, c, t)
            }
        };
        let [ambient, diffuse, specular, shininess] =
            [&m.ambient, &m.diffuse, &m.specular, &m.shininess].map(|e| self.expr(e));
        Some([albedo, ambient, diffuse, specular, shininess])
    }

    fn mix3(&mut self, a: Val, c: Val, t: Val) -> Val {
        let d = self.b.sub(c, a);
        let s = self.b.mul(d, t);
        self.b.add(a, s)
    }

    fn mix_fields(&mut self, a: [Val; 5], c: [Val; 5], w: Val) -> [Val; 5] {
        let albedo = self.mix3(a[0], c[0], w);
        let mut out = [albedo, a[1], a[2], a[3], a[4]];
        for i in 1..5 {
            out[i] = if a[i] == c[i] { a[i] } else { self.b.math(MathFn::Mix, vec![a[i], c[i], w]) };
        }
        out
    }

    fn select_fields(&mut self, cond: Val, a: [Val; 5], c: [Val; 5]) -> [Val; 5] {
        [0, 1, 2, 3, 4].map(|i| self.b.select(cond, a[i], c[i]))
    }

    fn call(&mut self, h: Helper, args: Vec<Arg>) -> Val {
        self.b.call(h, args)
    }

    fn node(&mut self, n: &Node, p: Val, m: &Material) -> Surf {
        match n {
            Node::Prim(prim) => {
                let distance = self.prim(prim, p);
                Surf { distance, fields: self.leaf_fields(m, None) }
            }
            Node::Fractal(fr) => {
                let pair = self.fractal(fr, p);
                let raw = self.b.comp(pair, 0);
                let factor = self.b.lit(fr.kind.step_factor());
                let distance = self.b.mul(raw, factor);
                let trap = if self.material { Some(self.b.comp(pair, 1)) } else { None };
                Surf { distance, fields: self.leaf_fields(m, trap) }
            }
            Node::Union(children) => self.union(children, p, m),
            Node::Intersect(children) => {
                let mut acc = self.node(&children[0], p, m);
                for c in &children[1..] {
                    let s = self.node(c, p, m);
                    let farther = self.b.less(acc.distance, s.distance);
                    let fields = match (acc.fields, s.fields) {
                        (Some(a), Some(f)) => Some(self.select_fields(farther, f, a)),
                        _ => None,
                    };
                    acc = Surf { distance: self.b.max(acc.distance, s.distance), fields };
                }
                acc
            }
            Node::Subtract(a, c) => {
                let sa = self.node(a, p, m);
                let sc = self.distance_only(c, p, m);
                let neg = self.b.neg(sc);
                Surf { distance: self.b.max(sa.distance, neg), fields: sa.fields }
            }
            Node::SmoothUnion(children, k) | Node::SmoothIntersect(children, k) => {
                let is_union = matches!(n, Node::SmoothUnion(..));
                let kv = self.expr(k);
                let mut acc = self.node(&children[0], p, m);
                for c in &children[1..] {
                    let s = self.node(c, p, m);
                    let (blend, w_args) = if is_union {
                        (Helper::SmoothMin, [acc.distance, s.distance])
                    } else {
                        (Helper::SmoothMax, [s.distance, acc.distance])
                    };
                    let distance = self.call(blend, vec![Arg::Val(acc.distance), Arg::Val(s.distance), Arg::Val(kv)]);
                    let fields = match (acc.fields, s.fields) {
                        (Some(a), Some(f)) => {
                            let w = self.call(
                                Helper::BlendWeight,
                                vec![Arg::Val(w_args[0]), Arg::Val(w_args[1]), Arg::Val(kv)],
                            );
                            Some(self.mix_fields(a, f, w))
                        }
                        _ => None,
                    };
                    acc = Surf { distance, fields };
                }
                acc
            }
            Node::SmoothSubtract(a, c, k) => {
                let kv = self.expr(k);
                let sa = self.node(a, p, m);
                let sc = self.distance_only(c, p, m);
                let neg = self.b.neg(sc);
                let distance = self.call(Helper::SmoothMax, vec![Arg::Val(sa.distance), Arg::Val(neg), Arg::Val(kv)]);
                Surf { distance, fields: sa.fields }
            }
            Node::Translate(c, off) => {
                let off = self.v3e(off);
                let q = self.b.sub(p, off);
                self.node(c, q, m)
            }
            Node::Rotate(c, axis, angle) => {
                let q = self.rotate_point(p, axis.unit(), angle);
                self.node(c, q, m)
            }
            Node::Scale(c, s) => {
                let s = self.expr(s);
                let q = self.b.div(p, s);
                let r = self.node(c, q, m);
                Surf { distance: self.b.mul(r.distance, s), fields: r.fields }
            }
            Node::Repeat(c, period) => {
                let q = self.repeat(p, period, None);
                self.node(c, q, m)
            }
            Node::RepeatLimited(c, period, count) => {
                let q = self.repeat(p, period, Some(*count));
                self.node(c, q, m)
            }
            Node::Twist(c, k) | Node::Bend(c, k) => {
                // Twist turns the xz plane by k·y; bend turns the xy plane by k·x. At radius ρ from the axis the map
                // stretches space by up to (v + sqrt(v² + 4))/2 with v = |k|·ρ (the Jacobian's largest singular
                // value), so the child's distance is divided by that to stay a lower bound.
                let twist = matches!(n, Node::Twist(..));
                let kv = self.expr(k);
                let [x, y, z] = self.comps(p);
                let (a_in, b_in, driver) = if twist { (x, z, y) } else { (x, y, x) };
                let angle = self.b.mul(kv, driver);
                let co = self.b.math(MathFn::Cos, vec![angle]);
                let si = self.b.math(MathFn::Sin, vec![angle]);
                let ca = self.b.mul(co, a_in);
                let sb = self.b.mul(si, b_in);
                let sa = self.b.mul(si, a_in);
                let cb = self.b.mul(co, b_in);
                let ra = self.b.sub(ca, sb);
                let rb = self.b.add(sa, cb);
                let q = if twist { self.b.v3(ra, y, rb) } else { self.b.v3(ra, rb, z) };
                let r = self.node(c, q, m);
                let aa = self.b.mul(a_in, a_in);
                let bb = self.b.mul(b_in, b_in);
                let rho2 = self.b.add(aa, bb);
                let rho = self.b.math(MathFn::Sqrt, vec![rho2]);
                let k_abs = self.b.math(MathFn::Abs, vec![kv]);
                let v = self.b.mul(k_abs, rho);
                let vv = self.b.mul(v, v);
                let four = self.b.lit(4.0);
                let vv4 = self.b.add(vv, four);
                let root = self.b.math(MathFn::Sqrt, vec![vv4]);
                let sum = self.b.add(v, root);
                let half = self.b.lit(0.5);
                let stretch = self.b.mul(sum, half);
                Surf { distance: self.b.div(r.distance, stretch), fields: r.fields }
            }
            Node::Round(c, r) => {
                let rv = self.expr(r);
                let s = self.node(c, p, m);
                Surf { distance: self.b.sub(s.distance, rv), fields: s.fields }
            }
            Node::Onion(c, t) => {
                let tv = self.expr(t);
                let s = self.node(c, p, m);
                let a = self.b.math(MathFn::Abs, vec![s.distance]);
                Surf { distance: self.b.sub(a, tv), fields: s.fields }
            }
            Node::Elongate(c, h) => {
                let pc = self.comps(p);
                let q = [0, 1, 2].map(|i| {
                    let hi = self.expr(&h.0[i]);
                    if self.b.lit_value(hi) == Some(0.0) {
                        return pc[i];
                    }
                    let lo = self.b.neg(hi);
                    let cl = self.b.math(MathFn::Clamp, vec![pc[i], lo, hi]);
                    self.b.sub(pc[i], cl)
                });
                let q = self.b.v3(q[0], q[1], q[2]);
                self.node(c, q, m)
            }
            Node::Material(c, inner) => self.node(c, p, inner),
        }
    }

    fn distance_only(&mut self, n: &Node, p: Val, m: &Material) -> Val {
        let tracked = std::mem::replace(&mut self.material, false);
        let d = self.node(n, p, m).distance;
        self.material = tracked;
        d
    }

    fn union(&mut self, children: &[Node], p: Val, m: &Material) -> Surf {
        let order = analyse::union_order(children);
        let mut acc = self.node(&children[order[0]], p, m);
        for (pos, &i) in order.iter().enumerate().skip(1) {
            let child = &children[i];
            let Some(bound) = analyse::guarded_bound(children, pos) else {
                let s = self.node(child, p, m);
                let fields = match (acc.fields, s.fields) {
                    (Some(a), Some(f)) => {
                        let nearer = self.b.less(s.distance, acc.distance);
                        Some(self.select_fields(nearer, f, a))
                    }
                    _ => None,
                };
                acc = Surf { distance: self.b.min(acc.distance, s.distance), fields };
                continue;
            };
            // The child cannot come nearer than its bound: skip it while the bound is no nearer than what we have.
            let center = self.b.v3_lits(bound.center());
            let half = self.b.v3_lits(bound.half_extents());
            let local = self.b.sub(p, center);
            let to_bound = self.call(Helper::SdBox, vec![Arg::Val(local), Arg::Val(half)]);
            let worth_it = self.b.less(to_bound, acc.distance);
            let d_var = self.b.var(acc.distance);
            let field_vars = acc.fields.map(|f| f.map(|v| self.b.var(v)));
            self.b.begin_if();
            let s = self.node(child, p, m);
            let current = self.b.load(d_var);
            if let (Some(vars), Some(f)) = (field_vars, s.fields) {
                let nearer = self.b.less(s.distance, current);
                for (var, value) in vars.into_iter().zip(f) {
                    let old = self.b.load(var);
                    let new = self.b.select(nearer, value, old);
                    self.b.assign(var, new);
                }
            }
            let nearest = self.b.min(current, s.distance);
            self.b.assign(d_var, nearest);
            self.b.end_if(worth_it);
            let distance = self.b.load(d_var);
            let fields = field_vars.map(|vars| vars.map(|v| self.b.load(v)));
            acc = Surf { distance, fields };
        }
        acc
    }

    /// The point rotated by −angle about `axis` (so the shape turns by +angle), by Rodrigues' formula as a matrix.
    fn rotate_point(&mut self, p: Val, k: [f64; 3], angle: &Expr) -> Val {
        let a = self.expr(angle);
        let c = self.b.math(MathFn::Cos, vec![a]);
        let sin = self.b.math(MathFn::Sin, vec![a]);
        let s = self.b.neg(sin);
        let one = self.b.lit(1.0);
        let one_minus_c = self.b.sub(one, c);
        // [k]× (cross-product matrix) entries.
        let cross = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
        let pc = self.comps(p);
        let mut q = [p; 3];
        for (i, qi) in q.iter_mut().enumerate() {
            let mut sum = self.b.lit(0.0);
            for j in 0..3 {
                let diag = if i == j { c } else { self.b.lit(0.0) };
                let kk = self.b.lit(k[i] * k[j]);
                let outer = self.b.mul(one_minus_c, kk);
                let kx = self.b.lit(cross[i][j]);
                let skew = self.b.mul(s, kx);
                let e0 = self.b.add(diag, outer);
                let e = self.b.add(e0, skew);
                let term = self.b.mul(e, pc[j]);
                sum = self.b.add(sum, term);
            }
            *qi = sum;
        }
        self.b.v3(q[0], q[1], q[2])
    }

    fn repeat(&mut self, p: Val, period: &Vec3Expr, count: Option<[u32; 3]>) -> Val {
        let pc = self.comps(p);
        let q = [0, 1, 2].map(|i| {
            let per = self.expr(&period.0[i]);
            if self.b.lit_value(per) == Some(0.0) {
                return pc[i];
            }
            let scaled = self.b.div(pc[i], per);
            let half = self.b.lit(0.5);
            let shifted = self.b.add(scaled, half);
            let mut cell = self.b.math(MathFn::Floor, vec![shifted]);
            if let Some(n) = count {
                let hi = self.b.lit(n[i] as f64);
                let lo = self.b.lit(-(n[i] as f64));
                cell = self.b.math(MathFn::Clamp, vec![cell, lo, hi]);
            }
            let offset = self.b.mul(per, cell);
            self.b.sub(pc[i], offset)
        });
        self.b.v3(q[0], q[1], q[2])
    }

    fn prim(&mut self, prim: &Prim, p: Val) -> Val {
        let (h, args): (Helper, Vec<Val>) = match prim {
            Prim::Sphere { radius } => (Helper::SdSphere, vec![self.expr(radius)]),
            Prim::Box { half } => (Helper::SdBox, vec![self.v3e(half)]),
            Prim::RoundBox { half, radius } => (Helper::SdRoundBox, vec![self.v3e(half), self.expr(radius)]),
            Prim::Torus { major, minor } => (Helper::SdTorus, vec![self.expr(major), self.expr(minor)]),
            Prim::Capsule { a, b, radius } => (Helper::SdCapsule, vec![self.v3e(a), self.v3e(b), self.expr(radius)]),
            Prim::Cylinder { radius, half_height } => {
                (Helper::SdCylinder, vec![self.expr(radius), self.expr(half_height)])
            }
            Prim::Cone { half_height, bottom, top } => {
                (Helper::SdCone, vec![self.expr(half_height), self.expr(bottom), self.expr(top)])
            }
            Prim::Plane { normal, offset } => (Helper::SdPlane, vec![self.v3e(normal), self.expr(offset)]),
            Prim::Octahedron { size } => (Helper::SdOctahedron, vec![self.expr(size)]),
            Prim::Ellipsoid { radii } => (Helper::SdEllipsoid, vec![self.v3e(radii)]),
        };
        let mut all = vec![Arg::Val(p)];
        all.extend(args.into_iter().map(Arg::Val));
        self.call(h, all)
    }

    fn fractal(&mut self, fr: &Fractal, p: Val) -> Val {
        let iterations = Arg::Int(fr.iterations_or_default());
        let bailout = fr.bailout_or_default();
        let (h, args) = match &fr.kind {
            FractalKind::Mandelbulb { power } if power.as_lit() == Some(8.0) => {
                (Helper::DeMandelbulb8, vec![Arg::Val(p), iterations, Arg::Val(self.expr(&bailout))])
            }
            FractalKind::Mandelbulb { power } => (
                Helper::DeMandelbulb,
                vec![Arg::Val(p), Arg::Val(self.expr(power)), iterations, Arg::Val(self.expr(&bailout))],
            ),
            FractalKind::Menger => (Helper::DeMenger, vec![Arg::Val(p), iterations]),
            FractalKind::Sierpinski => (Helper::DeSierpinski, vec![Arg::Val(p), iterations]),
            FractalKind::Julia { c } => {
                let mut args = vec![Arg::Val(p)];
                args.extend(c.0.iter().map(|e| Arg::Val(self.expr(e))));
                args.push(iterations);
                args.push(Arg::Val(self.expr(&bailout)));
                (Helper::DeJulia, args)
            }
            FractalKind::Mandelbox { scale } => {
                let s = self.expr(scale);
                let mr = self.expr(&fr.min_radius_or_default());
                let fl = self.expr(&fr.fold_limit_or_default());
                (Helper::DeMandelbox, vec![Arg::Val(p), Arg::Val(s), iterations, Arg::Val(mr), Arg::Val(fl)])
            }
        };
        self.call(h, args)
    }
}
