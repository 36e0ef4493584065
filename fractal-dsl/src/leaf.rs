//! The table of leaf functions: each formula of [`crate::sdf`] with its name, typed parameters and result, and one
//! dispatcher ([`Leaf::eval`]) that calls it in any [`Num`]. The scene walker calls leaves through [`CallLeaf`], so
//! scalars run the formula directly while the tracer records a call of a named kernel function and traces that
//! function's body once ([`crate::lower::trace`]).
//!
//! Adding a leaf function: write it in `sdf.rs`, add its row here.

use crate::math::V3;
use crate::num::Num;
use crate::sdf;

/// The type of a leaf function's parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArgKind {
    /// A number.
    F,
    /// A 3-vector.
    V3,
    /// A loop count (iterations, levels).
    Count,
}

/// What a leaf function returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RetKind {
    /// A distance (or a blend weight).
    F,
    /// A fractal's (distance estimate, orbit trap).
    Pair,
}

/// An argument of a leaf call.
#[derive(Debug)]
pub enum LeafArg<F: Num> {
    F(F),
    V3(V3<F>),
    Count(F::Count),
}

impl<F: Num> Clone for LeafArg<F> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<F: Num> Copy for LeafArg<F> {}

/// The result of a leaf call.
#[derive(Clone, Copy, Debug)]
pub enum LeafOut<F> {
    F(F),
    Pair([F; 2]),
}

impl<F: Copy> LeafOut<F> {
    /// The distance (the first of a pair).
    #[inline(always)]
    pub fn distance(self) -> F {
        match self {
            LeafOut::F(d) | LeafOut::Pair([d, _]) => d,
        }
    }
    /// The orbit trap of a fractal; a plain leaf has none.
    #[inline(always)]
    pub fn trap(self) -> Option<F> {
        match self {
            LeafOut::F(_) => None,
            LeafOut::Pair([_, t]) => Some(t),
        }
    }
}

/// How a number type calls a leaf function: directly (the default), or — when tracing — as a call of the named
/// function the kernel defines once.
pub trait CallLeaf: Num {
    #[inline(always)]
    fn leaf(leaf: Leaf, args: &[LeafArg<Self>]) -> LeafOut<Self> {
        leaf.eval(args)
    }
}

impl CallLeaf for f32 {}
impl CallLeaf for f64 {}

macro_rules! take {
    ($it:ident, F) => {
        match $it.next() {
            Some(LeafArg::F(v)) => *v,
            _ => unreachable!("leaf arguments are built from Leaf::params"),
        }
    };
    ($it:ident, V3) => {
        match $it.next() {
            Some(LeafArg::V3(v)) => *v,
            _ => unreachable!("leaf arguments are built from Leaf::params"),
        }
    };
    ($it:ident, Count) => {
        match $it.next() {
            Some(LeafArg::Count(v)) => *v,
            _ => unreachable!("leaf arguments are built from Leaf::params"),
        }
    };
}

macro_rules! leaves {
    ($($variant:ident => $func:ident($($arg:ident: $kind:ident),*) -> $ret:ident;)*) => {
        /// A leaf function of [`crate::sdf`]; the kernels name it [`Leaf::name`].
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum Leaf {
            $($variant,)*
        }

        impl Leaf {
            /// Every leaf, in the order kernels define them.
            pub const ALL: &'static [Leaf] = &[$(Leaf::$variant,)*];

            /// The function's name, the same in `sdf.rs` and in every kernel.
            pub fn name(self) -> &'static str {
                match self {
                    $(Leaf::$variant => stringify!($func),)*
                }
            }

            /// Parameter names and types, in order.
            pub fn params(self) -> &'static [(&'static str, ArgKind)] {
                match self {
                    $(Leaf::$variant => &[$((stringify!($arg), ArgKind::$kind),)*],)*
                }
            }

            pub fn returns(self) -> RetKind {
                match self {
                    $(Leaf::$variant => RetKind::$ret,)*
                }
            }

            /// Runs the formula in `F` on arguments of the types [`Leaf::params`] lists.
            #[inline(always)]
            pub fn eval<F: Num>(self, args: &[LeafArg<F>]) -> LeafOut<F> {
                #[allow(unused_mut, unused_variables)]
                let mut it = args.iter();
                match self {
                    $(Leaf::$variant => {
                        $(let $arg = take!(it, $kind);)*
                        leaves!(@ret $ret, sdf::$func($($arg),*))
                    })*
                }
            }
        }
    };
    (@ret F, $e:expr) => { LeafOut::F($e) };
    (@ret Pair, $e:expr) => { LeafOut::Pair($e) };
}

leaves! {
    SdSphere => sd_sphere(p: V3, r: F) -> F;
    SdBox => sd_box(p: V3, b: V3) -> F;
    SdRoundBox => sd_round_box(p: V3, b: V3, r: F) -> F;
    SdTorus => sd_torus(p: V3, major: F, minor: F) -> F;
    SdCapsule => sd_capsule(p: V3, a: V3, b: V3, r: F) -> F;
    SdCylinder => sd_cylinder(p: V3, r: F, h: F) -> F;
    SdCone => sd_cone(p: V3, h: F, r1: F, r2: F) -> F;
    SdPlane => sd_plane(p: V3, n: V3, offset: F) -> F;
    SdOctahedron => sd_octahedron(p: V3, s: F) -> F;
    SdEllipsoid => sd_ellipsoid(p: V3, r: V3) -> F;
    SmoothMin => smooth_min(a: F, b: F, k: F) -> F;
    SmoothMax => smooth_max(a: F, b: F, k: F) -> F;
    BlendWeight => blend_weight(a: F, b: F, k: F) -> F;
    DeMandelbulb => de_mandelbulb(p: V3, power: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbulb8 => de_mandelbulb8(p: V3, iterations: Count, bailout: F) -> Pair;
    DeMenger => de_menger(p: V3, levels: Count) -> Pair;
    DeSierpinski => de_sierpinski(p: V3, levels: Count) -> Pair;
    DeJulia => de_julia(p: V3, cx: F, cy: F, cz: F, cw: F, iterations: Count, bailout: F) -> Pair;
    DeMandelbox => de_mandelbox(p: V3, scale: F, iterations: Count, min_radius: F, fold_limit: F) -> Pair;
}
