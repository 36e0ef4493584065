//! What a table of leaf functions is made of: argument and result kinds, argument and result values, and the
//! `leaves!` macro that writes the table — the `Leaf` enum with each function's name, typed parameters and result,
//! and one dispatcher that calls it in any [`Num`]. The table itself stands in `formula/mod.rs`.

use crate::number::math::V3;
use crate::number::{Num, Orbit};

/// The type of a leaf function's parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ArgKind {
    /// A number.
    F,
    /// A 3-vector.
    V3,
    /// A loop count (iterations, levels).
    Count,
    /// A perturbation reference orbit ([`Orbit`]): the frame's, in a kernel.
    Orbit,
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
pub enum LeafArg<'a, F: Num> {
    F(F),
    V3(V3<F>),
    Count(F::Count),
    Orbit(Orbit<'a>),
}

impl<F: Num> Clone for LeafArg<'_, F> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<F: Num> Copy for LeafArg<'_, F> {}

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

/// Takes the next argument of a leaf call as the declared kind (used by [`leaves!`]).
macro_rules! take {
    ($it:ident, F) => {
        match $it.next() {
            Some($crate::formula::leaf::LeafArg::F(v)) => *v,
            _ => unreachable!("leaf arguments are built from Leaf::params"),
        }
    };
    ($it:ident, V3) => {
        match $it.next() {
            Some($crate::formula::leaf::LeafArg::V3(v)) => *v,
            _ => unreachable!("leaf arguments are built from Leaf::params"),
        }
    };
    ($it:ident, Count) => {
        match $it.next() {
            Some($crate::formula::leaf::LeafArg::Count(v)) => *v,
            _ => unreachable!("leaf arguments are built from Leaf::params"),
        }
    };
    ($it:ident, Orbit) => {
        match $it.next() {
            Some($crate::formula::leaf::LeafArg::Orbit(v)) => *v,
            _ => unreachable!("leaf arguments are built from Leaf::params"),
        }
    };
}

/// Writes the leaf table: `Variant => function(param: Kind, ..) -> Result;` rows, Kind one of F, V3, Count, Orbit and
/// Result F or Pair, each row naming a function of the module it is written in.
macro_rules! leaves {
    ($($variant:ident => $func:ident($($arg:ident: $kind:ident),*) -> $ret:ident;)*) => {
        /// A leaf function of [`crate::formula`]; the kernels name it [`Leaf::name`].
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum Leaf {
            $($variant,)*
        }

        impl Leaf {
            /// Every leaf, in the order kernels define them.
            pub const ALL: &'static [Leaf] = &[$(Leaf::$variant,)*];

            /// The function's name, the same in `formula/` and in every kernel.
            pub fn name(self) -> &'static str {
                match self {
                    $(Leaf::$variant => stringify!($func),)*
                }
            }

            /// Parameter names and types, in order.
            pub fn params(self) -> &'static [(&'static str, $crate::formula::leaf::ArgKind)] {
                match self {
                    $(Leaf::$variant => &[$((stringify!($arg), $crate::formula::leaf::ArgKind::$kind),)*],)*
                }
            }

            pub fn returns(self) -> $crate::formula::leaf::RetKind {
                match self {
                    $(Leaf::$variant => $crate::formula::leaf::RetKind::$ret,)*
                }
            }

            /// Runs the formula in `F` on arguments of the types [`Leaf::params`] lists.
            #[inline(always)]
            pub fn eval<F: $crate::number::Num>(
                self,
                args: &[$crate::formula::leaf::LeafArg<F>],
            ) -> $crate::formula::leaf::LeafOut<F> {
                #[allow(unused_mut, unused_variables)]
                let mut it = args.iter();
                match self {
                    $(Leaf::$variant => {
                        $(let $arg = $crate::formula::leaf::take!(it, $kind);)*
                        $crate::formula::leaf::leaves!(@ret $ret, $func($($arg),*))
                    })*
                }
            }
        }
    };
    (@ret F, $e:expr) => { $crate::formula::leaf::LeafOut::F($e) };
    (@ret Pair, $e:expr) => { $crate::formula::leaf::LeafOut::Pair($e) };
}

pub(crate) use {leaves, take};
