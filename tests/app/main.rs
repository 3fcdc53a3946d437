//! Tests of what the `app` feature adds: the command line end to end, the GPU tracer against
//! the CPU reference through the real plugin, scene files and glTF, and every shader variant
//! validated with naga. One test binary, so Bevy is linked once.

#[allow(dead_code)]
#[path = "../common/mod.rs"]
mod common;

mod cli;
mod fuzz;
mod gpu;
mod hostile_models;
mod products;
mod scenes;
mod shaders;
