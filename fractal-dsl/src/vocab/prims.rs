//! The primitives, each declared once: name, arguments with their rules, distance function, bound — and its builder
//! function. The parser, printer, validation, folding, bounds, evaluators and kernels all read these declarations
//! ([`crate::ir::prim`]).
//!
//! Adding a primitive: its declaration and builder function here (and in [`decl::PRIMS`]), its leaf function in
//! `formula/shapes.rs` (with its row in the leaf table there), a row in the agreement test, a line in the README's
//! vocabulary.

use crate::ir::{Expr, Node, Vec3Expr};
use decl::*;

/// The declarations, and the table the parser looks names up in.
pub mod decl {
    use crate::formula::Leaf;
    use crate::geom::Aabb;
    use crate::ir::arg::{num, vec, Rule};
    use crate::ir::prim::{PrimBound, PrimDecl};

    use Rule::*;

    /// The primitive called `name` in scene source.
    pub fn by_name(name: &str) -> Option<&'static PrimDecl> {
        PRIMS.iter().copied().find(|p| p.name == name)
    }

    /// Every primitive, in the order documentation lists them.
    pub static PRIMS: &[&PrimDecl] =
        &[&SPHERE, &BOX3, &ROUND_BOX, &TORUS, &CAPSULE, &CYLINDER, &CONE, &PLANE, &OCTAHEDRON, &HEX_PRISM, &ELLIPSOID];

    pub static SPHERE: PrimDecl = PrimDecl {
        name: "sphere",
        doc: "a sphere of `radius` around the origin",
        args: &[num("radius", "sphere radius", Positive)],
        leaf: Leaf::SdSphere,
        bound: |a| PrimBound::exact(Aabb::cube(a[0].hi())),
        not_all_zero: None,
    };

    pub static BOX3: PrimDecl = PrimDecl {
        name: "box3",
        doc: "a box of half extents `half` (`box` is a Rust keyword)",
        args: &[vec("half", "box3 half extent", Positive)],
        leaf: Leaf::SdBox,
        // |p_i| ≤ half_i inside the box.
        bound: |a| PrimBound::exact(Aabb::centered(a[0].vec3().map(|i| i.hi.max(0.0)))),
        not_all_zero: None,
    };

    pub static ROUND_BOX: PrimDecl = PrimDecl {
        name: "round_box",
        doc: "a box of half extents `half` with edges rounded by `radius` (the outer size stays `half`)",
        args: &[vec("half", "round_box half extent", Positive), num("radius", "round_box radius", RoundingOf(0))],
        leaf: Leaf::SdRoundBox,
        bound: |a| PrimBound::exact(Aabb::centered(a[0].vec3().map(|i| i.hi.max(0.0)))),
        not_all_zero: None,
    };

    pub static TORUS: PrimDecl = PrimDecl {
        name: "torus",
        doc: "a torus in the xz plane: ring radius `major`, tube radius `minor`",
        args: &[num("major", "torus major radius", NonNegative), num("minor", "torus minor radius", Positive)],
        leaf: Leaf::SdTorus,
        bound: |a| {
            let r = a[0].max_abs() + a[1].hi();
            PrimBound::exact(Aabb::centered([r, a[1].hi(), r]))
        },
        not_all_zero: None,
    };

    pub static CAPSULE: PrimDecl = PrimDecl {
        name: "capsule",
        doc: "the segment from `a` to `b` swept by a sphere of `radius`",
        args: &[
            vec("a", "capsule end a", Finite),
            vec("b", "capsule end b", Finite),
            num("radius", "capsule radius", Positive),
        ],
        leaf: Leaf::SdCapsule,
        bound: |a| {
            let (ea, eb, r) = (a[0].vec3(), a[1].vec3(), a[2].hi());
            PrimBound::exact(Aabb::new(
                [0, 1, 2].map(|i| ea[i].lo.min(eb[i].lo) - r),
                [0, 1, 2].map(|i| ea[i].hi.max(eb[i].hi) + r),
            ))
        },
        not_all_zero: None,
    };

    pub static CYLINDER: PrimDecl = PrimDecl {
        name: "cylinder",
        doc: "a capped cylinder along y",
        args: &[num("radius", "cylinder radius", Positive), num("half_height", "cylinder half_height", Positive)],
        leaf: Leaf::SdCylinder,
        bound: |a| PrimBound::exact(Aabb::centered([a[0].hi(), a[1].hi(), a[0].hi()])),
        not_all_zero: None,
    };

    pub static CONE: PrimDecl = PrimDecl {
        name: "cone",
        doc: "a capped cone along y: radius `bottom` at −half_height, `top` at +half_height",
        args: &[
            num("half_height", "cone half_height", Positive),
            num("bottom", "cone bottom radius", NonNegative),
            num("top", "cone top radius", NonNegative),
        ],
        leaf: Leaf::SdCone,
        bound: |a| {
            let r = a[1].max_abs().max(a[2].max_abs());
            PrimBound::exact(Aabb::centered([r, a[0].max_abs(), r]))
        },
        not_all_zero: Some((&[1, 2], "cone radii bottom and top cannot both be 0")),
    };

    pub static PLANE: PrimDecl = PrimDecl {
        name: "plane",
        doc: "the half-space dot(p, normal) + offset ≤ 0 (unbounded; a constant normal is normalised)",
        args: &[vec("normal", "plane normal", Direction), num("offset", "plane offset", Finite)],
        leaf: Leaf::SdPlane,
        bound: |_| None,
        not_all_zero: None,
    };

    pub static OCTAHEDRON: PrimDecl = PrimDecl {
        name: "octahedron",
        doc: "the regular octahedron |x| + |y| + |z| = size",
        args: &[num("size", "octahedron size", Positive)],
        leaf: Leaf::SdOctahedron,
        bound: |a| PrimBound::exact(Aabb::cube(a[0].hi())),
        not_all_zero: None,
    };

    pub static HEX_PRISM: PrimDecl = PrimDecl {
        name: "hex_prism",
        doc: "a hexagonal prism along y: inradius `radius` in the xz plane, `half_height` above and below",
        args: &[num("radius", "hex_prism radius", Positive), num("half_height", "hex_prism half_height", Positive)],
        leaf: Leaf::SdHexPrism,
        // The corners lie at 2/√3 of the inradius (a hair more, so rounding never puts one outside).
        bound: |a| {
            let corner = a[0].hi() * 1.154_700_6;
            PrimBound::exact(Aabb::centered([corner, a[1].hi(), corner]))
        },
        not_all_zero: None,
    };

    pub static ELLIPSOID: PrimDecl = PrimDecl {
        name: "ellipsoid",
        doc: "an ellipsoid of semi-axes `radii` (a lower bound of the distance, not exact)",
        args: &[vec("radii", "ellipsoid radius", Positive)],
        leaf: Leaf::SdEllipsoid,
        bound: |a| {
            let r = a[0].vec3();
            // IQ's ellipsoid estimate falls short of the distance by up to the ratio of its radii.
            let smallest = r.iter().map(|i| i.min_abs()).fold(f64::INFINITY, f64::min);
            let largest = r.iter().map(|i| i.max_abs()).fold(0.0, f64::max);
            let reach = if largest > 0.0 { smallest / largest } else { 0.0 };
            Some(PrimBound { aabb: Aabb::centered(r.map(|i| i.max_abs())), reach })
        },
        not_all_zero: None,
    };
}

pub fn sphere(radius: impl Into<Expr>) -> Node {
    SPHERE.node(vec![radius.into().into()])
}

/// A box with half extents `half` (`box3` because `box` is a Rust keyword).
pub fn box3(half: impl Into<Vec3Expr>) -> Node {
    BOX3.node(vec![half.into().into()])
}

pub fn round_box(half: impl Into<Vec3Expr>, radius: impl Into<Expr>) -> Node {
    ROUND_BOX.node(vec![half.into().into(), radius.into().into()])
}

pub fn torus(major: impl Into<Expr>, minor: impl Into<Expr>) -> Node {
    TORUS.node(vec![major.into().into(), minor.into().into()])
}

pub fn capsule(a: impl Into<Vec3Expr>, b: impl Into<Vec3Expr>, radius: impl Into<Expr>) -> Node {
    CAPSULE.node(vec![a.into().into(), b.into().into(), radius.into().into()])
}

/// Capped cylinder along y.
pub fn cylinder(radius: impl Into<Expr>, half_height: impl Into<Expr>) -> Node {
    CYLINDER.node(vec![radius.into().into(), half_height.into().into()])
}

/// Capped cone along y, radius `bottom` at −half_height and `top` at +half_height.
pub fn cone(half_height: impl Into<Expr>, bottom: impl Into<Expr>, top: impl Into<Expr>) -> Node {
    CONE.node(vec![half_height.into().into(), bottom.into().into(), top.into().into()])
}

/// The half-space below the plane dot(p, normal) + offset = 0. The normal is normalised here when constant.
pub fn plane(normal: impl Into<Vec3Expr>, offset: impl Into<Expr>) -> Node {
    PLANE.node(vec![normal.into().into(), offset.into().into()])
}

pub fn octahedron(size: impl Into<Expr>) -> Node {
    OCTAHEDRON.node(vec![size.into().into()])
}

/// Hexagonal prism along y with inradius `radius`.
pub fn hex_prism(radius: impl Into<Expr>, half_height: impl Into<Expr>) -> Node {
    HEX_PRISM.node(vec![radius.into().into(), half_height.into().into()])
}

pub fn ellipsoid(radii: impl Into<Vec3Expr>) -> Node {
    ELLIPSOID.node(vec![radii.into().into()])
}
