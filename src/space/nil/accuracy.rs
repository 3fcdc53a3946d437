//! How far a walk in the box of `nil-K`, in some precision, ends from the exact geodesic:
//! the walked end against the double-double flow in the universal cover, the difference
//! taken modulo the lattice (each crossing applies one of its elements). Nil's geodesics
//! spread polynomially (a start rounded by ε ends `O(ε t²)` away), so the error is
//! reported over `ε (1 + t²)`, the shape of the conditioning limit.

use super::flow::{NilRay, flow, group_product};
use super::walk::NilWalker;
use crate::geometry::{DoubleDouble, Ray, Real, Vector4};
use crate::space::walk::{CellWalk, Limit};
use glam::DVec4;

/// The chart distance from `g` to the nearest element of `Γ_K` (an element is
/// `(p, q, pq/2 + m/K)`).
fn off_lattice(g: [f64; 3], k: u32) -> f64 {
    let (p, q) = (g[0].round(), g[1].round());
    let m = (g[2] - p * q / 2.0) * f64::from(k);
    (g[0] - p)
        .abs()
        .max((g[1] - q).abs())
        .max((m - m.round()).abs() / f64::from(k))
}

/// The distance, modulo the lattice, between the end of `start` walked `distance` through
/// the box in the precision `V` and the exact geodesic (double-double, from the start as
/// `V` rounds it, so the start's own rounding is not counted).
#[must_use]
pub fn walk_error<V: Vector4>(k: u32, start: Ray<DVec4>, distance: f64) -> f64 {
    let walker = NilWalker::<V>::new(k);
    let rounded = Ray {
        point: V::new(
            V::Real::from_f64(start.point.x),
            V::Real::from_f64(start.point.y),
            V::Real::from_f64(start.point.z),
            V::Real::ONE,
        ),
        tangent: V::new(
            V::Real::from_f64(start.tangent.x),
            V::Real::from_f64(start.tangent.y),
            V::Real::from_f64(start.tangent.z),
            V::Real::ZERO,
        ),
    };
    let rounded = walker.on_model(rounded);
    let (end, _) = CellWalk::walk(&walker, rounded, Limit::Distance(distance), |_| true);
    let exact = |r: &Ray<V>, i: usize, tangent: bool| {
        let v = if tangent { r.tangent } else { r.point };
        DoubleDouble::new(v.component(i).to_f64())
    };
    let cover = flow(
        &NilRay {
            point: [0, 1, 2].map(|i| exact(&rounded, i, false)),
            velocity: [0, 1, 2].map(|i| exact(&rounded, i, true)),
        },
        DoubleDouble::new(distance),
    );
    let end = [0, 1, 2].map(|i| exact(&end, i, false));
    let g = group_product(end, cover.point.map(|x| -x)).map(|x| x.to_f64());
    off_lattice(g, k)
}
