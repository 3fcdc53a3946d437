//! Nil, the Heisenberg group with its left-invariant metric, the first of the geometries
//! whose metric varies with the point (Thurston's eight: E³, S³, H³, H²×R, S²×R, Nil,
//! SL̃(2,R), Sol). This folder holds what is Nil's own: its geodesic flow in closed form
//! ([`mod@flow`]), generic over precision, checked against an independent 40-digit integration
//! of the geodesic equations (`tests/data/nil_geodesics.json`, written by
//! `scripts/nil-reference.py`); the exits from the box solved to the last bit ([`mod@exit`]);
//! the walk ([`NilWalker`]); and the spaces `nil-K` with their invariants and the motion of
//! frames by parallel transport ([`NilSpace`]); distances and metric balls
//! ([`mod@distance`], [`mod@ball`]) and the shadow of a geodesic on the plane
//! ([`mod@shadow`]). The tracers ([`crate::trace::nil`], `shaders/nil.wgsl`), the plugin and
//! every command build on them.
//!
//! Conventions:
//! - the chart `(x, y, z) ∈ R³` with the metric `ds² = dx² + dy² + (dz − ½(x dy − y dx))²`;
//! - the group law `(x, y, z)·(x′, y′, z′) = (x + x′, y + y′, z + z′ + ½(x y′ − y x′))`,
//!   whose left translations are the isometries the lattices act by, affine in the chart;
//! - velocities in the orthonormal left-invariant frame `E₁ = ∂x − (y/2)∂z`,
//!   `E₂ = ∂y + (x/2)∂z`, `E₃ = ∂z` (the *body* velocity), which a left translation keeps.

pub mod accuracy;
pub mod ball;
pub mod distance;
pub mod exit;
pub mod flow;
pub mod shadow;
mod space;
pub mod walk;

pub use ball::{ball_hit, ball_hit_between, ball_meets_between, distance_floor, normal};
pub use distance::{distance, shortest};
pub use exit::{horizontal_exit, vertical_exit};
pub use flow::{NilRay, flow, group_product};
pub use shadow::shadow_within;
pub use space::{MAX_NIL_K, NilError, NilSpace, nil_space, translation_matrix, transport};
pub use walk::{NIL_FACES, NilExit, NilWalker};

use crate::geometry::Real;

/// π to the type's precision: the `f64` nearest π and what it leaves out (which
/// double-double keeps and the others round away).
fn pi<R: Real>() -> R {
    R::from_f64(std::f64::consts::PI) + R::from_f64(1.224_646_799_147_353_2e-16)
}

/// The work Nil's root finding has done on this thread so far (the shared counters of
/// [`crate::space::roots`]: the horizontal exits, the distance's winding, the balls' and
/// the tracer's refinements, and the safe steps towards objects).
pub use crate::space::roots::work;
pub(crate) use crate::space::roots::{
    bracketed_root, count_root_iteration, count_safe_step, half_way,
};
