//! fractal facade
