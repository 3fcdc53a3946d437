//! SL̃(2,R), the seventh of Thurston's geometries, as the unit tangent bundle `UT H²` with
//! its Sasaki metric: a point is a base point `p` of the hyperboloid with a unit tangent
//! vector `e` there, kept as the frame `(e, e⊥, p)` of `SO⁺(2,1)`. This folder holds what is
//! SL̃(2,R)'s own: its geodesic flow in closed form ([`mod@flow`]), one formula for the
//! three kinds of geodesic, generic over precision, checked against an independent 40-digit
//! integration of the geodesic equations (`tests/data/sl2r_geodesics.json`, written by
//! `scripts/sl2r-reference.py`); the exits through the polygon's sides in closed form
//! ([`mod@exit`]); the spaces `UT Σ` of orientable hyperbolic surfaces given by their words
//! ([`UnitTangentSpace`]); and the walk ([`Sl2rWalker`]).
//!
//! Conventions:
//! - the base point `p` on `x² + y² − w² = −1`, `w > 0`, and `e` a unit tangent vector there;
//!   `e⊥` is `e` turned by +90°, counter-clockwise seen from `+w`;
//! - velocities in the orthonormal frame `X` (the horizontal lift of `e`: `p` moves along
//!   `e`, `e` parallel transported), `Y` (that of `e⊥`) and `V` (vertical: `e` turns
//!   counter-clockwise at one radian per unit length, so a fibre is a closed geodesic of
//!   length `2π`), invariant under `PSL(2,R)`: the *body* velocity `(a, b, c)`;
//! - an isometry `M` of `H²` acts on `(p, e)` by its differential, on the frame by `F ↦ M F`.

pub mod accuracy;
pub mod ball;
pub mod cover;
pub mod distance;
pub mod exit;
pub mod flow;
mod frames;
pub use frames::frame_sheet;
mod space;
pub mod walk;

pub use exit::{first_crossing, side_exit};
pub use flow::{Sl2rRay, flow, on_model};
pub use space::{Sl2rError, Sl2rSide, UNIT_TANGENT_PREFIX, UnitTangentSpace, sl2r_space};
pub use walk::{Sl2rExit, Sl2rWalker};

/// The frame at the chart point `(x, y, θ)`: the base point `(x, y, √(1 + x² + y²))` and `e`
/// at the angle `θ` from the boost of the origin's `(1, 0, 0)` (the frame the commands'
/// `--from x,y,θ` and the scene files' points name).
#[must_use]
pub fn chart_frame(x: f64, y: f64, theta: f64) -> [[f64; 3]; 3] {
    let w = (1.0 + x * x + y * y).sqrt();
    let e1 = [1.0 + x * x / (1.0 + w), x * y / (1.0 + w), x];
    let e2 = [x * y / (1.0 + w), 1.0 + y * y / (1.0 + w), y];
    let (c, s) = (theta.cos(), theta.sin());
    let e = [0, 1, 2].map(|i| c * e1[i] + s * e2[i]);
    let p = [x, y, w];
    [e, flow::perp(p, e), p]
}

/// The chart point `[x, y, θ]` of a frame of `UT H²` (the inverse of [`chart_frame`]): the
/// base point's `x, y`, and the angle of `e` in the frame boosted from the origin's.
#[must_use]
pub fn chart_point(frame: &[[f64; 3]; 3]) -> glam::DVec3 {
    let [e, _, p] = *frame;
    let at = chart_frame(p[0], p[1], 0.0);
    let l = flow::lorentz;
    glam::DVec3::new(p[0], p[1], l(e, at[1]).atan2(l(e, at[0])))
}
