//! rust backend.
