//! wgsl backend.
