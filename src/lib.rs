//! # bevy_curved_spaces
//!
//! Walk inside closed 3-manifolds and orbifolds of constant curvature — the 3-torus and the
//! other flat spaces, the Seifert–Weber space, the Poincaré dodecahedral space, mirrored
//! cubes and dodecahedra — and see what light does there.
//!
//! This crate holds the exact geometry core ([`geometry`]), the validated spaces
//! ([`space`]) and the f64 CPU reference ray tracer ([`trace`]). They use glam types only,
//! so they work without a Bevy app.

// `!(x < tol)` is how this crate rejects NaN along with large values: keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod geometry;
pub mod space;
pub mod trace;

/// The types most programs need.
pub mod prelude {
    pub use crate::geometry::{Geometry, GeometryError, ORIGIN};
    pub use crate::space::{SEED_SPACES, Space, SpaceError, seed_space};
}
