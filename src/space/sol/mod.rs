//! Sol, the eighth of Thurston's geometries: `ds² = e^{−2z}dx² + e^{2z}dy² + dz²` in the chart
//! `(x, y, z)`, with the group law `(x₁, y₁, z₁)(x₂, y₂, z₂) = (x₁ + e^{z₁}x₂, y₁ + e^{−z₁}y₂,
//! z₁ + z₂)`. Its closed manifolds here are the torus bundles with an Anosov gluing
//! ([`bundle`]: their ids, lattices and invariants). Its geodesics are written with Jacobi's
//! elliptic functions ([`crate::geometry::elliptic`]).

pub mod bundle;

pub use bundle::{SolError, TORUS_BUNDLE_PREFIX, TorusBundle};
