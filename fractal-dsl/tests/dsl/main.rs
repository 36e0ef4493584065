//! fractal-dsl's integration tests, one binary: the parser and its errors, validation, the printer's round trip, the
//! interpreter, the leaf formulas (Lipschitz bounds, membership, noise) and the bounds. `common` holds the helpers
//! they share.

mod bounds;
mod common;
mod formula;
mod interp;
mod leaves;
mod lipschitz;
mod membership;
mod noise;
mod parse;
mod roundtrip;
mod validate;
