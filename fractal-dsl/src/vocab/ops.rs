//! The operators — CSG, transforms, domain operations — each declared once: name, how it takes its shapes, arguments
//! with their rules, identity, bound and meaning; and its builder function or method. The parser, printer, validation,
//! folding, bounds, the plan and the kernels all read these declarations ([`crate::ir::op`]); what each meaning
//! computes is written once in the evaluator ([`crate::eval::walk`]).
//!
//! Adding an operator: its declaration and builder here (and in [`decl::OPS`]), its [`Meaning`] and formula in the
//! walker if no existing meaning fits, a row in the agreement test, a line in the README's vocabulary.
//!
//! [`Meaning`]: crate::ir::op::Meaning

use crate::ir::{Expr, Fractal, Material, Node, Vec3Expr};
use decl::*;

/// Largest cell count per axis of `repeat_limited`.
pub const MAX_REPEAT_COUNT: u32 = 1000;

/// The declarations, and the table the parser looks names up in.
pub mod decl {
    use crate::geom::{Aabb, Bound, Interval};
    use crate::ir::arg::{num, vec, ArgDecl, ArgRange, ArgShape, Rule};
    use crate::ir::op::{Identity, Meaning, OpDecl, Operands};

    use Rule::*;

    /// The operator called `name` in scene source.
    pub fn by_name(name: &str) -> Option<&'static OpDecl> {
        OPS.iter().copied().find(|o| o.name == name)
    }

    /// Every operator, in the order documentation lists them.
    pub static OPS: &[&OpDecl] = &[
        &UNION,
        &INTERSECT,
        &SUBTRACT,
        &SMOOTH_UNION,
        &SMOOTH_INTERSECT,
        &SMOOTH_SUBTRACT,
        &TRANSLATE,
        &ROTATE_X,
        &ROTATE_Y,
        &ROTATE_Z,
        &ROTATE,
        &SCALE,
        &REPEAT,
        &REPEAT_LIMITED,
        &TWIST,
        &BEND,
        &ROUND,
        &ONION,
        &ELONGATE,
        &PLANE_FOLD,
        &ABS_FOLD,
        &BOX_FOLD,
        &SPHERE_FOLD,
        &POLAR_REPEAT,
        &DISPLACE,
    ];

    /// A combination of shapes with no arguments of its own.
    const fn csg(name: &'static str, doc: &'static str, operands: Operands, meaning: Meaning) -> OpDecl {
        OpDecl {
            name,
            doc,
            operands,
            args: &[],
            meaning,
            identity: Identity::Never,
            flattens: matches!(meaning, Meaning::Union | Meaning::Intersect),
            lipschitz: true,
            bound: match meaning {
                Meaning::Union => |s, _| Bound::hull(s),
                Meaning::Intersect => |s, _| Bound::overlap(s),
                // max(a, −b) ≥ a: the left operand bounds the result.
                _ => |s, _| s[0],
            },
        }
    }

    pub static UNION: OpDecl =
        csg("union", "the shapes together: min of the distances", Operands::Many, Meaning::Union);
    pub static INTERSECT: OpDecl =
        csg("intersect", "where all shapes overlap: max of the distances", Operands::Many, Meaning::Intersect);
    pub static SUBTRACT: OpDecl =
        csg("subtract", "`a` with `b` cut away: max(a, −b)", Operands::Two, Meaning::Subtract);

    pub static SMOOTH_UNION: OpDecl = OpDecl {
        name: "smooth_union",
        doc: "the shapes blended together over a radius `k` (polynomial smooth minimum, folded left)",
        operands: Operands::Many,
        args: &[num("k", "smooth_union blend radius k", NonNegative)],
        meaning: Meaning::SmoothUnion,
        identity: Identity::Never,
        flattens: false,
        lipschitz: true,
        // Each step of the left fold subtracts at most k/4 from the plain minimum (`crate::formula::smooth_min`).
        bound: |s, a| Bound::hull(s).grown(s.len().saturating_sub(1) as f64 * a[0].hi() * 0.25),
    };

    pub static SMOOTH_INTERSECT: OpDecl = OpDecl {
        name: "smooth_intersect",
        doc: "the overlap of the shapes with edges blended over a radius `k`",
        operands: Operands::Many,
        args: &[num("k", "smooth_intersect blend radius k", NonNegative)],
        meaning: Meaning::SmoothIntersect,
        identity: Identity::Never,
        flattens: false,
        lipschitz: true,
        // smooth_max(a, b) ≥ max(a, b): a smooth intersection lies inside the plain one.
        bound: |s, _| Bound::overlap(s),
    };

    pub static SMOOTH_SUBTRACT: OpDecl = OpDecl {
        name: "smooth_subtract",
        doc: "`a` with `b` cut away, the cut blended over a radius `k`",
        operands: Operands::Two,
        args: &[num("k", "smooth_subtract blend radius k", NonNegative)],
        meaning: Meaning::SmoothSubtract,
        identity: Identity::Never,
        flattens: false,
        lipschitz: true,
        // smooth_max(a, −b) ≥ max(a, −b) ≥ a.
        bound: |s, _| s[0],
    };

    pub static TRANSLATE: OpDecl = OpDecl {
        name: "translate",
        doc: "the shape moved by `offset`",
        operands: Operands::Receiver,
        args: &[vec("offset", "translate offset", Finite)],
        meaning: Meaning::Translate,
        identity: Identity::When(0, 0.0),
        flattens: false,
        lipschitz: true,
        bound: |s, a| {
            let r = a[0].vec3();
            s[0].map(|b| Some(b.translate(r.map(|i| i.lo), r.map(|i| i.hi))))
        },
    };

    /// A rotation about a coordinate axis: the declaration, given the axis and the bound that rotates about it.
    const fn rotate_about(
        name: &'static str,
        axis: [f64; 3],
        args: &'static [ArgDecl],
        bound: fn(&[Bound], &[ArgRange]) -> Bound,
    ) -> OpDecl {
        OpDecl {
            name,
            doc: "the shape turned by `angle` radians about the axis (right-handed)",
            operands: Operands::Receiver,
            args,
            meaning: Meaning::Rotate(Some(axis)),
            identity: Identity::When(0, 0.0),
            flattens: false,
            lipschitz: true,
            bound,
        }
    }

    const X: [f64; 3] = [1.0, 0.0, 0.0];
    const Y: [f64; 3] = [0.0, 1.0, 0.0];
    const Z: [f64; 3] = [0.0, 0.0, 1.0];
    pub static ROTATE_X: OpDecl = rotate_about("rotate_x", X, &[num("angle", "rotate_x angle", Finite)], |s, a| {
        s[0].map(|b| b.rotated(X, a[0].num()))
    });
    pub static ROTATE_Y: OpDecl = rotate_about("rotate_y", Y, &[num("angle", "rotate_y angle", Finite)], |s, a| {
        s[0].map(|b| b.rotated(Y, a[0].num()))
    });
    pub static ROTATE_Z: OpDecl = rotate_about("rotate_z", Z, &[num("angle", "rotate_z angle", Finite)], |s, a| {
        s[0].map(|b| b.rotated(Z, a[0].num()))
    });

    pub static ROTATE: OpDecl = OpDecl {
        name: "rotate",
        doc: "the shape turned by `angle` radians about a constant `axis` (normalised; right-handed)",
        operands: Operands::Receiver,
        args: &[
            ArgDecl { name: "axis", what: "rotate axis", shape: ArgShape::ConstVec3, rule: Direction },
            num("angle", "rotate angle", Finite),
        ],
        meaning: Meaning::Rotate(None),
        identity: Identity::When(1, 0.0),
        flattens: false,
        lipschitz: true,
        bound: |s, a| match a[0].point3() {
            Some(axis) => s[0].map(|b| b.rotated(axis, a[1].num())),
            None => Bound::UNBOUNDED,
        },
    };

    pub static SCALE: OpDecl = OpDecl {
        name: "scale",
        doc: "the shape scaled by `factor` about the origin (the distance is scaled back, so it stays a distance)",
        operands: Operands::Receiver,
        args: &[num("factor", "scale factor", Positive)],
        meaning: Meaning::Scale,
        identity: Identity::When(0, 1.0),
        flattens: false,
        lipschitz: true,
        bound: |s, a| {
            let f = a[0].num();
            if f.lo.is_nan() || f.lo <= 0.0 || !f.is_finite() {
                return Bound::UNBOUNDED;
            }
            // child(p / f)·f: the shape is f × the child's; every factor in between is a convex combination.
            s[0].map(|b| Some(b.scale(f.lo).union(&b.scale(f.hi))))
        },
    };

    pub static REPEAT: OpDecl = OpDecl {
        name: "repeat",
        doc: "the shape repeated forever with `period` per axis (0 leaves an axis alone; unbounded)",
        operands: Operands::Receiver,
        args: &[vec("period", "repeat period", Period)],
        meaning: Meaning::Repeat { limited: false },
        identity: Identity::Never,
        flattens: false,
        lipschitz: false,
        bound: |s, a| if a[0].vec3().iter().all(|i| *i == Interval::point(0.0)) { s[0] } else { Bound::UNBOUNDED },
    };

    pub static REPEAT_LIMITED: OpDecl = OpDecl {
        name: "repeat_limited",
        doc: "the shape repeated over cells −count..=count per axis with `period`",
        operands: Operands::Receiver,
        args: &[
            vec("period", "repeat_limited period", Period),
            ArgDecl {
                name: "count",
                what: "repeat_limited count",
                shape: ArgShape::Counts,
                rule: AtMost(super::MAX_REPEAT_COUNT),
            },
        ],
        meaning: Meaning::Repeat { limited: true },
        identity: Identity::Never,
        flattens: false,
        lipschitz: false,
        bound: |s, a| {
            let (period, count) = (a[0].vec3(), a[1].vec3());
            let widen: [Option<f64>; 3] = [0, 1, 2].map(|i| {
                if period[i] == Interval::point(0.0) {
                    return Some(0.0);
                }
                period[i].is_finite().then(|| period[i].max_abs() * count[i].hi)
            });
            match widen {
                [Some(x), Some(y), Some(z)] => s[0].map(|b| Some(b.grow3([x, y, z]))),
                _ => Bound::UNBOUNDED,
            }
        },
    };

    /// The bound of a shape whose plane (axes `a`, `b`) turns about the axis `along` by an angle that grows with
    /// `rate`: the radius from that axis and the coordinate along it are kept, so the box is the cylinder of the
    /// child's farthest corner. The distance is divided by the stretch, which far away approaches a constant: nothing
    /// is known about its reach.
    fn swept(inner: Bound, [a, b, along]: [usize; 3], rate: Interval) -> Bound {
        let out = inner.map(|bx| {
            let radius = bx.corners().iter().map(|p| p[a].hypot(p[b])).fold(0.0, f64::max);
            let mut min = [-radius; 3];
            let mut max = [radius; 3];
            min[along] = bx.min[along];
            max[along] = bx.max[along];
            Some(Aabb { min, max })
        });
        if rate == Interval::point(0.0) {
            out
        } else {
            Bound { reach: 0.0, exact_guard: false, ..out }
        }
    }

    pub static TWIST: OpDecl = OpDecl {
        name: "twist",
        doc: "the shape twisted about y: the xz plane turns by `rate`·y radians",
        operands: Operands::Receiver,
        args: &[num("rate", "twist rate", Finite)],
        meaning: Meaning::Twist,
        identity: Identity::When(0, 0.0),
        flattens: false,
        lipschitz: false,
        bound: |s, a| swept(s[0], [0, 2, 1], a[0].num()),
    };

    pub static BEND: OpDecl = OpDecl {
        name: "bend",
        doc: "the shape bent in the xy plane: x turns by `rate`·x radians",
        operands: Operands::Receiver,
        args: &[num("rate", "bend rate", Finite)],
        meaning: Meaning::Bend,
        identity: Identity::When(0, 0.0),
        flattens: false,
        lipschitz: false,
        bound: |s, a| swept(s[0], [0, 1, 2], a[0].num()),
    };

    /// The bound of `{d − by ≤ 0}` over a shape with bound `inner`, for `by` in `range`.
    fn grown_by(inner: Bound, range: &ArgRange) -> Bound {
        // `grown` refuses a non-finite amount itself.
        Bound { exact_guard: inner.exact_guard && inner.reach >= 1.0, ..inner.grown(range.hi()) }
    }

    pub static ROUND: OpDecl = OpDecl {
        name: "round",
        doc: "the shape rounded outward by `radius`: d − radius",
        operands: Operands::Receiver,
        args: &[num("radius", "round radius", NonNegative)],
        meaning: Meaning::Round,
        identity: Identity::When(0, 0.0),
        flattens: false,
        lipschitz: true,
        bound: |s, a| grown_by(s[0], &a[0]),
    };

    pub static ONION: OpDecl = OpDecl {
        name: "onion",
        doc: "the shape hollowed to a shell: |d| − thickness",
        operands: Operands::Receiver,
        args: &[num("thickness", "onion thickness", Positive)],
        meaning: Meaning::Onion,
        identity: Identity::Never,
        flattens: false,
        lipschitz: true,
        // |d| − th ≤ 0 needs d ≤ th.
        bound: |s, a| grown_by(s[0], &a[0]),
    };

    pub static ELONGATE: OpDecl = OpDecl {
        name: "elongate",
        doc: "the shape stretched by `h` along each axis, with straight sections inserted",
        operands: Operands::Receiver,
        args: &[vec("h", "elongate length", NonNegative)],
        meaning: Meaning::Elongate,
        identity: Identity::When(0, 0.0),
        flattens: false,
        lipschitz: true,
        // child(p − clamp(p, −h, h)): every point of the shape is a child point moved by at most |h| per axis.
        bound: |s, a| {
            let h = a[0].vec3();
            if h.iter().any(|i| !i.is_finite()) {
                return Bound::UNBOUNDED;
            }
            s[0].map(|b| Some(b.grow3(h.map(|i| i.max_abs()))))
        },
    };

    /// The bound of a fold that maps points onto the child's box by a reflection: the child's box together with its
    /// `reflected` images. Outside that box a folded point is no nearer the child's box than the point is to it, so
    /// the reach carries over; guards over folds are not claimed exact.
    fn folded(inner: Bound, reflected: impl Fn(&Aabb) -> Vec<Aabb>) -> Bound {
        let out = inner.map(|b| Some(reflected(&b).iter().fold(b, |acc, r| acc.union(r))));
        Bound { exact_guard: false, ..out }
    }

    pub static PLANE_FOLD: OpDecl = OpDecl {
        name: "plane_fold",
        doc: "the half of the shape on the side `normal` points to, mirrored onto the other side of the plane through \
              the origin",
        operands: Operands::Receiver,
        args: &[ArgDecl { name: "normal", what: "plane_fold normal", shape: ArgShape::ConstVec3, rule: Direction }],
        meaning: Meaning::PlaneFold,
        identity: Identity::Never,
        flattens: false,
        lipschitz: true,
        bound: |s, a| match a[0].point3() {
            Some(n) => folded(s[0], |b| {
                let mirror = |p: [f64; 3]| {
                    let d = 2.0 * (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]);
                    [p[0] - d * n[0], p[1] - d * n[1], p[2] - d * n[2]]
                };
                Aabb::of_points(b.corners().map(mirror)).into_iter().collect()
            }),
            None => Bound::UNBOUNDED,
        },
    };

    pub static ABS_FOLD: OpDecl = OpDecl {
        name: "abs_fold",
        doc: "the shape made symmetric in the planes x = 0, y = 0, z = 0 whose `axes` component is 1: p ← |p| there",
        operands: Operands::Receiver,
        args: &[ArgDecl { name: "axes", what: "abs_fold axes", shape: ArgShape::Counts, rule: AtMost(1) }],
        meaning: Meaning::AbsFold,
        identity: Identity::When(0, 0.0),
        flattens: false,
        lipschitz: true,
        bound: |s, a| {
            let axes = a[0].vec3().map(|i| i.hi >= 1.0);
            folded(s[0], |b| {
                let (mut min, mut max) = (b.min, b.max);
                for i in (0..3).filter(|&i| axes[i]) {
                    (min[i], max[i]) = (-b.max[i], -b.min[i]);
                }
                vec![Aabb { min, max }]
            })
        },
    };

    pub static BOX_FOLD: OpDecl = OpDecl {
        name: "box_fold",
        doc: "each coordinate beyond ±`limit` reflected back inside: clamp(p, −limit, limit)·2 − p (the Mandelbox's \
              first fold)",
        operands: Operands::Receiver,
        args: &[num("limit", "box_fold limit", Positive)],
        meaning: Meaning::BoxFold,
        identity: Identity::Never,
        flattens: false,
        lipschitz: true,
        bound: |s, a| {
            let l = a[0].num();
            if !l.is_finite() {
                return Bound::UNBOUNDED;
            }
            // A coordinate q of the child comes from p = q (inside ±l), 2l − q (beyond +l) or −2l − q (beyond −l);
            // each is linear in l, so the ends of l's range bound it.
            folded(s[0], |b| {
                [l.lo, l.hi]
                    .into_iter()
                    .flat_map(|l| {
                        [2.0 * l, -2.0 * l].map(|k| Aabb {
                            min: [0, 1, 2].map(|i| k - b.max[i]),
                            max: [0, 1, 2].map(|i| k - b.min[i]),
                        })
                    })
                    .collect()
            })
        },
    };

    pub static SPHERE_FOLD: OpDecl = OpDecl {
        name: "sphere_fold",
        doc: "inversion in the sphere of `fixed_radius`, a plain scale inside `min_radius` (the Mandelbox's second \
              fold); the distance is divided by the scale",
        operands: Operands::Receiver,
        args: &[
            num("min_radius", "sphere_fold min_radius", Positive),
            num("fixed_radius", "sphere_fold fixed_radius", Positive),
        ],
        meaning: Meaning::SphereFold,
        identity: Identity::Never,
        flattens: false,
        lipschitz: false,
        // Beyond the fixed radius nothing moves; within it, any point may land on the child.
        bound: |s, a| {
            let fixed = a[1].num();
            if !fixed.is_finite() {
                return Bound::UNBOUNDED;
            }
            Bound { exact_guard: false, ..s[0].map(|b| Some(b.union(&Aabb::cube(fixed.hi)))) }
        },
    };

    pub static POLAR_REPEAT: OpDecl = OpDecl {
        name: "polar_repeat",
        doc: "`count` copies of the shape around the y axis, the first centred on +x (each cut at its sector's walls)",
        operands: Operands::Receiver,
        args: &[num("count", "polar_repeat count", CountUpTo(super::MAX_REPEAT_COUNT))],
        meaning: Meaning::PolarRepeat,
        identity: Identity::When(0, 1.0),
        flattens: false,
        lipschitz: false,
        // Points keep their radius from the y axis and their height: the cylinder of the child's farthest corner.
        bound: |s, _| Bound { exact_guard: false, ..swept(s[0], [0, 2, 1], Interval::point(0.0)) },
    };

    pub static DISPLACE: OpDecl = OpDecl {
        name: "displace",
        doc:
            "the surface moved out by `amount`, an expression that may read the point `x`, `y`, `z` (noise, sin, ..); \
              the distance is divided by 1 + the amount's largest slope, so it stays a distance bound",
        operands: Operands::Receiver,
        args: &[num("amount", "displace amount", Displacement)],
        meaning: Meaning::Displace,
        identity: Identity::When(0, 0.0),
        flattens: false,
        lipschitz: true,
        // {d − a ≤ 0} needs d ≤ max a. The reach shrinks by the slope's divisor, which the bound does not see.
        bound: |s, a| Bound { reach: 0.0, exact_guard: false, ..grown_by(s[0], &a[0]) },
    };
}

// ---- builder functions ------------------------------------------------------------------------------------------

pub fn union(a: impl Into<Node>, b: impl Into<Node>) -> Node {
    union_all([a.into(), b.into()])
}
/// n-ary union; nested unions flatten into one.
pub fn union_all(nodes: impl IntoIterator<Item = Node>) -> Node {
    UNION.node(nodes.into_iter().collect(), vec![])
}
pub fn intersect(a: impl Into<Node>, b: impl Into<Node>) -> Node {
    intersect_all([a.into(), b.into()])
}
/// n-ary intersection; nested intersections flatten into one.
pub fn intersect_all(nodes: impl IntoIterator<Item = Node>) -> Node {
    INTERSECT.node(nodes.into_iter().collect(), vec![])
}
/// `a` with `b` cut away.
pub fn subtract(a: impl Into<Node>, b: impl Into<Node>) -> Node {
    SUBTRACT.node(vec![a.into(), b.into()], vec![])
}
pub fn smooth_union(a: impl Into<Node>, b: impl Into<Node>, k: impl Into<Expr>) -> Node {
    smooth_union_all([a.into(), b.into()], k)
}
/// n-ary smooth union, folded left with blend radius `k`.
pub fn smooth_union_all(nodes: impl IntoIterator<Item = Node>, k: impl Into<Expr>) -> Node {
    SMOOTH_UNION.node(nodes.into_iter().collect(), vec![k.into().into()])
}
pub fn smooth_intersect(a: impl Into<Node>, b: impl Into<Node>, k: impl Into<Expr>) -> Node {
    smooth_intersect_all([a.into(), b.into()], k)
}
/// n-ary smooth intersection, folded left with blend radius `k`.
pub fn smooth_intersect_all(nodes: impl IntoIterator<Item = Node>, k: impl Into<Expr>) -> Node {
    SMOOTH_INTERSECT.node(nodes.into_iter().collect(), vec![k.into().into()])
}
pub fn smooth_subtract(a: impl Into<Node>, b: impl Into<Node>, k: impl Into<Expr>) -> Node {
    SMOOTH_SUBTRACT.node(vec![a.into(), b.into()], vec![k.into().into()])
}

/// Chained operations on shapes (nodes and fractals): transforms, domain operations, materials.
pub trait ShapeExt: Into<Node> + Sized {
    fn translate(self, offset: impl Into<Vec3Expr>) -> Node {
        TRANSLATE.node(vec![self.into()], vec![offset.into().into()])
    }
    fn rotate_x(self, angle: impl Into<Expr>) -> Node {
        ROTATE_X.node(vec![self.into()], vec![angle.into().into()])
    }
    fn rotate_y(self, angle: impl Into<Expr>) -> Node {
        ROTATE_Y.node(vec![self.into()], vec![angle.into().into()])
    }
    fn rotate_z(self, angle: impl Into<Expr>) -> Node {
        ROTATE_Z.node(vec![self.into()], vec![angle.into().into()])
    }
    /// Rotation about an arbitrary axis (normalised here; a zero axis is left for validation to report).
    fn rotate(self, axis: impl Into<glam::DVec3>, angle: impl Into<Expr>) -> Node {
        let axis = Vec3Expr::from(axis.into().to_array());
        ROTATE.node(vec![self.into()], vec![axis.into(), angle.into().into()])
    }
    /// Uniform scale; distances are scaled back so they stay distances.
    fn scale(self, factor: impl Into<Expr>) -> Node {
        SCALE.node(vec![self.into()], vec![factor.into().into()])
    }
    /// Infinite repetition with `period` per axis (0 leaves that axis alone).
    fn repeat(self, period: impl Into<Vec3Expr>) -> Node {
        REPEAT.node(vec![self.into()], vec![period.into().into()])
    }
    /// Repetition over cells −count..=count per axis.
    fn repeat_limited(self, period: impl Into<Vec3Expr>, count: [u32; 3]) -> Node {
        let count = Vec3Expr::from(count.map(f64::from));
        REPEAT_LIMITED.node(vec![self.into()], vec![period.into().into(), count.into()])
    }
    fn twist(self, rate: impl Into<Expr>) -> Node {
        TWIST.node(vec![self.into()], vec![rate.into().into()])
    }
    fn bend(self, rate: impl Into<Expr>) -> Node {
        BEND.node(vec![self.into()], vec![rate.into().into()])
    }
    fn round(self, radius: impl Into<Expr>) -> Node {
        ROUND.node(vec![self.into()], vec![radius.into().into()])
    }
    fn onion(self, thickness: impl Into<Expr>) -> Node {
        ONION.node(vec![self.into()], vec![thickness.into().into()])
    }
    fn elongate(self, h: impl Into<Vec3Expr>) -> Node {
        ELONGATE.node(vec![self.into()], vec![h.into().into()])
    }
    /// Mirrors the half on the side `normal` points to onto the other side of the plane through the origin.
    fn plane_fold(self, normal: impl Into<glam::DVec3>) -> Node {
        let normal = Vec3Expr::from(normal.into().to_array());
        PLANE_FOLD.node(vec![self.into()], vec![normal.into()])
    }
    /// Makes the shape symmetric in the coordinate planes whose `axes` entry is 1 (p ← |p| on those axes).
    fn abs_fold(self, axes: [u32; 3]) -> Node {
        ABS_FOLD.node(vec![self.into()], vec![Vec3Expr::from(axes.map(f64::from)).into()])
    }
    fn box_fold(self, limit: impl Into<Expr>) -> Node {
        BOX_FOLD.node(vec![self.into()], vec![limit.into().into()])
    }
    fn sphere_fold(self, min_radius: impl Into<Expr>, fixed_radius: impl Into<Expr>) -> Node {
        SPHERE_FOLD.node(vec![self.into()], vec![min_radius.into().into(), fixed_radius.into().into()])
    }
    /// The surface moved out by `amount`, an expression that may read the point ([`crate::builder::x`], ..).
    fn displace(self, amount: impl Into<Expr>) -> Node {
        DISPLACE.node(vec![self.into()], vec![amount.into().into()])
    }
    /// `count` copies around the y axis.
    fn polar_repeat(self, count: u32) -> Node {
        POLAR_REPEAT.node(vec![self.into()], vec![Expr::Lit(f64::from(count)).into()])
    }
    fn material(self, m: impl Into<Material>) -> Node {
        Node::Material(Box::new(self.into()), Box::new(m.into()))
    }
}
impl ShapeExt for Node {}
impl ShapeExt for Fractal {}
