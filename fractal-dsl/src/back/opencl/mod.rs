//! opencl backend.
