//! Operators in the IR: CSG, transforms and domain operations. An [`Op`] is an [`OpDecl`] (what the operator is:
//! name, how it takes its shapes, typed arguments with their rules, identity, bound, meaning) with its shapes and
//! argument values. Parser, printer, validation, folding, bounds, the plan and the kernels all read the declaration
//! (`crate::vocab::ops`), so an operator is declared once.

use super::arg::{normalise_directions, ArgDecl, ArgRange, ArgValue};
use super::Node;
use super::MAX_NODES;
use crate::geom::Bound;

/// How an operator takes its shapes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Operands {
    /// One or more shapes, then the arguments: `union(a, b, c)`, `smooth_union(a, b, k)`.
    Many,
    /// Exactly two shapes, then the arguments: `subtract(a, b)`.
    Two,
    /// A method of one shape: `shape.translate(offset)`.
    Receiver,
}

/// What an operator does to distances: the evaluator's formula for it (`crate::eval::walk`), which every backend
/// traces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Meaning {
    /// Minimum of the shapes, with union guards and cheap shapes first.
    Union,
    /// Maximum of the shapes.
    Intersect,
    /// max(a, −b).
    Subtract,
    /// Polynomial smooth minimum with blend radius `k`, folded left over the shapes.
    SmoothUnion,
    SmoothIntersect,
    SmoothSubtract,
    /// The shape moved by the offset.
    Translate,
    /// The shape turned by the angle (radians, right-handed) about this unit axis, or about the axis argument.
    Rotate(Option<[f64; 3]>),
    /// Uniform scale; the distance is multiplied back so it stays a distance.
    Scale,
    /// Repetition with a period per axis (0 = not repeated on that axis), over cells −count..=count when limited.
    Repeat {
        limited: bool,
    },
    /// The xz plane rotates by `rate`·y radians.
    Twist,
    /// x rotates into y by `rate`·x radians.
    Bend,
    /// d − r.
    Round,
    /// |d| − thickness.
    Onion,
    /// Straight sections of length 2h inserted along each axis.
    Elongate,
    /// The half-space on the normal's side mirrored onto the other: p − 2·min(p·n, 0)·n.
    PlaneFold,
    /// |p| on the axes whose mask component is 1.
    AbsFold,
    /// Each coordinate beyond ±limit reflected back: clamp(p, −limit, limit)·2 − p.
    BoxFold,
    /// Inversion in the sphere of `fixed_radius`, linear inside `min_radius`; the distance is divided by the scale.
    SphereFold,
    /// `count` copies around the y axis: the angle about y taken modulo 2π/count.
    PolarRepeat,
    /// (d − amount(p)) / (1 + the amount's slope bound): moved out by an expression of the point, and still a lower
    /// bound of the distance.
    Displace,
}

impl Meaning {
    /// Whether the operator hands its shapes the point it was given (combinations, and the operators that only
    /// change the distance): a material below it reads the same coordinates as one above it.
    pub fn keeps_point(self) -> bool {
        matches!(
            self,
            Meaning::Union
                | Meaning::Intersect
                | Meaning::Subtract
                | Meaning::SmoothUnion
                | Meaning::SmoothIntersect
                | Meaning::SmoothSubtract
                | Meaning::Round
                | Meaning::Onion
                | Meaning::Displace
        )
    }
}

/// When an operator changes nothing (folding removes it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Identity {
    Never,
    /// Every component of the argument at this index is the literal value.
    When(usize, f64),
}

/// What an operator is, declared once.
pub struct OpDecl {
    /// The function or method that makes it in scene source and in the builder API.
    pub name: &'static str,
    /// One line for the documentation.
    pub doc: &'static str,
    pub operands: Operands,
    /// The arguments after the shapes.
    pub args: &'static [ArgDecl],
    pub meaning: Meaning,
    pub identity: Identity,
    /// Whether nested uses flatten into one: `union(union(a, b), c)` is `union(a, b, c)`.
    pub flattens: bool,
    /// Whether the result is 1-Lipschitz wherever its shapes' distances are (so it stays a lower bound of the true
    /// distance and a step of its value never passes the surface). Repetition is not (a shape wider than its cell is
    /// cut at the cell wall), nor are twist and bend (their stretch is bounded per point, not globally).
    pub lipschitz: bool,
    /// The bound of the result from the shapes' bounds and the arguments' ranges.
    pub bound: fn(&[Bound], &[ArgRange]) -> Bound,
}

impl OpDecl {
    /// The operator over these shapes and arguments, in canonical form: constant directions normalised, nested
    /// uses of a flattening operator spliced in.
    pub fn node(&'static self, shapes: Vec<Node>, mut args: Vec<ArgValue>) -> Node {
        normalise_directions(self.args, &mut args);
        let shapes = if self.flattens {
            // The first shape's list is taken whole, so `node = union(node, x)` in a loop is linear. A later one is
            // copied, so `node = union(x, node)` costs the list's length per call: past [`MAX_NODES`] children (a
            // scene validation refuses anyway) it is kept nested instead, and a list that already ends in one is
            // never copied again, so the loop stays bounded.
            let same = |op: &Op| op.kind.0.name == self.name;
            let capped = |op: &Op| op.shapes.last().and_then(Node::op).is_some_and(same);
            let mut flat = Vec::new();
            for mut s in shapes {
                match &mut s {
                    Node::Op(op) if same(op) && flat.is_empty() => flat = std::mem::take(&mut op.shapes),
                    Node::Op(op) if same(op) && !capped(op) && flat.len() + op.shapes.len() <= MAX_NODES => {
                        flat.append(&mut op.shapes)
                    }
                    _ => flat.push(s),
                }
            }
            flat
        } else {
            shapes
        };
        Node::Op(Op { kind: OpKind(self), shapes, args })
    }
    /// Whether the operator takes several shapes (their path labels are numbered).
    pub fn combines(&self) -> bool {
        self.operands != Operands::Receiver
    }
    /// Whether the operator changes nothing over `shapes` shapes with these arguments: a combination of one shape,
    /// or the identity value of its argument.
    pub fn is_identity(&self, shapes: usize, args: &[ArgValue]) -> bool {
        match self.identity {
            _ if self.combines() => shapes == 1,
            Identity::When(i, v) => shapes == 1 && args.get(i).is_some_and(|a| a.is_all(v)),
            Identity::Never => false,
        }
    }
}

/// A reference to an operator's declaration; equal when the names are.
#[derive(Clone, Copy)]
pub struct OpKind(pub &'static OpDecl);

super::named_by_declaration!(OpKind);

/// An operator applied to shapes.
#[derive(Clone, Debug, PartialEq)]
pub struct Op {
    pub kind: OpKind,
    /// The shapes it combines or transforms: one for a method, two or more for CSG.
    pub shapes: Vec<Node>,
    /// One value per declared argument, in order.
    pub args: Vec<ArgValue>,
}

super::declared_item!(Op, OpDecl);

/// Trees from the builder may nest far deeper than the native stack allows (validation refuses them, but they must
/// still drop): the children are moved onto a heap stack, so every node drops with no children left to recurse into.
impl Drop for Node {
    fn drop(&mut self) {
        let mut pending = Vec::new();
        self.detach_children(&mut pending);
        while let Some(mut node) = pending.pop() {
            node.detach_children(&mut pending);
        }
    }
}

impl Node {
    fn detach_children(&mut self, into: &mut Vec<Node>) {
        match self {
            Node::Op(op) => into.append(&mut op.shapes),
            Node::Material(inner, _) if !inner.children().is_empty() => {
                let leaf = Node::Op(Op { kind: OpKind(&DETACHED), shapes: Vec::new(), args: Vec::new() });
                into.push(std::mem::replace(inner, leaf));
            }
            _ => {}
        }
    }
}

/// The childless node left where a material's subtree was moved out while a tree drops; never part of a scene.
static DETACHED: OpDecl = OpDecl {
    name: "union",
    doc: "",
    operands: Operands::Many,
    args: &[],
    meaning: Meaning::Union,
    identity: Identity::Never,
    flattens: false,
    lipschitz: true,
    bound: |s, _| Bound::hull(s),
};
