//! fractal-runtime: the tools around the renderer — the `fractal` command line, the interactive viewer, the bench,
//! the accuracy study against a ground truth, image and video output, meshes, and export to other engines.
//!
//! The renderers themselves (frame uniforms, camera poses, the wgpu, OpenCL and CPU backends and the choice between
//! them) are `fractal_render`'s, which a program that only renders embeds alone; everything here is built on it.
//!
//! The modules form layers, each using only modules listed before it: [`text`], [`export`], [`output`], [`mesh`],
//! [`package`], [`quality`], [`truth`], [`accuracy`], [`bench`](mod@bench), [`viewer`], [`cli`].
//!
//! Accuracy: [`truth`] renders a ground truth that never reads a distance estimate (each fractal's own membership
//! test, exact distances for primitives), [`accuracy`] measures renders against it and sweeps the [`quality`]
//! settings for `fractal accuracy`.

pub mod accuracy;
pub mod bench;
pub mod cli;
pub mod export;
pub mod frame_precision;
pub mod mesh;
pub mod output;
pub mod package;
pub mod quality;
pub mod step_factors;
pub mod text;
pub mod truth;
pub mod viewer;
