//! The product walk against its double-double reference at the conditioning limit: the
//! measurement of [`crate::space::accuracy`] (error / the error of a walk that rounds its
//! state once per crossing), for [`ProductWalker`].

use super::{ProductSpace, ProductWalker};
use crate::geometry::{DdVec4, DoubleDouble, Geometry, Ray, Real, Vector4};
use crate::space::accuracy::{CrossingAccuracy, SATURATED, conditioning_of};
use crate::space::walk::{Limit, Trace};
use glam::DVec4;

/// The surface form on the base parts, in double-double.
fn base_form(g: Geometry, a: DdVec4, b: DdVec4) -> DoubleDouble {
    a.0[0] * b.0[0] + a.0[1] * b.0[1] + DoubleDouble::new(g.kappa()) * a.0[3] * b.0[3]
}

/// The product metric on tangents.
fn metric(g: Geometry, a: DdVec4, b: DdVec4) -> DoubleDouble {
    base_form(g, a, b) + a.0[2] * b.0[2]
}

/// The distance between two points of the product, from their difference in double-double:
/// `√(d_surface² + Δz²)`, the surface distance from the chord.
#[must_use]
pub fn product_separation(g: Geometry, a: DdVec4, b: DdVec4) -> f64 {
    let mut d = a - b;
    let dz = d.0[2].to_f64();
    d.0[2] = DoubleDouble::ZERO;
    let chord = base_form(g, d, d).to_f64().max(0.0).sqrt();
    let surface = match g {
        Geometry::Spherical => 2.0 * (0.5 * chord).min(1.0).asin(),
        _ => 2.0 * (0.5 * chord).asinh(),
    };
    surface.hypot(dz)
}

/// Two unit tangents at the ray's point, orthogonal to each other and to its tangent.
fn sideways(g: Geometry, ray: &Ray<DdVec4>) -> [DdVec4; 2] {
    let p = ray.point;
    let mut pb = p;
    pb.0[2] = DoubleDouble::ZERO;
    let mut basis = vec![ray.tangent];
    for axis in 0..4 {
        if basis.len() == 3 {
            break;
        }
        let mut e = DdVec4::default();
        e.0[axis] = DoubleDouble::ONE;
        // Tangent: the base part orthogonal to the base point.
        if axis != 2 {
            e = e - pb.scale(base_form(g, e, pb) / base_form(g, pb, pb));
        }
        for b in &basis {
            e = e - b.scale(metric(g, *b, e));
        }
        let norm = metric(g, e, e);
        if norm.to_f64() > 0.1 {
            basis.push(e.scale(DoubleDouble::ONE / norm.sqrt()));
        }
    }
    [basis[1], basis[2]]
}

/// The four rays one `ε` away: moved sideways or turned, in two directions.
fn perturbed(walker: &ProductWalker<DdVec4>, ray: &Ray<DdVec4>, epsilon: f64) -> [Ray<DdVec4>; 4] {
    let e = DoubleDouble::new(epsilon);
    let [a, b] = sideways(walker.base, ray);
    let moved = |d: DdVec4| {
        walker.normalized(Ray {
            point: ray.point + d.scale(e),
            tangent: ray.tangent,
        })
    };
    let turned = |d: DdVec4| {
        walker.normalized(Ray {
            point: ray.point,
            tangent: ray.tangent + d.scale(e),
        })
    };
    [moved(a), moved(b), turned(a), turned(b)]
}

/// The conditioning limit at each crossing of a reference trace (see
/// [`crate::space::accuracy::conditioning`]), and whether a perturbed ray split off.
#[must_use]
pub fn product_conditioning(
    walker: &ProductWalker<DdVec4>,
    start: &Ray<DdVec4>,
    reference: &Trace<DdVec4>,
    epsilon: f64,
) -> Vec<(f64, bool)> {
    let g = walker.base;
    conditioning_of(
        start,
        reference,
        epsilon,
        |ray| perturbed(walker, ray, epsilon),
        |ray, n| walker.trace(ray, Limit::Crossings(n)),
        |a, b| product_separation(g, a, b),
    )
}

/// A product walk's error against the double-double walk of the same cell from the same
/// start at each of `crossings` crossings, with the conditioning limit of its precision.
#[must_use]
pub fn product_walk_accuracy<V: Vector4>(
    space: &ProductSpace,
    start: Ray<DVec4>,
    crossings: usize,
) -> Vec<CrossingAccuracy> {
    let reference = ProductWalker::<DdVec4>::new(space);
    let g = reference.base;
    let start_dd = reference.normalized(Ray {
        point: DdVec4::from_f64(start.point),
        tangent: DdVec4::from_f64(start.tangent),
    });
    let truth = reference.trace(start_dd, Limit::Crossings(crossings));
    let epsilon = V::Real::EPSILON.to_f64();
    let limits = product_conditioning(&reference, &start_dd, &truth, epsilon);
    let walker = ProductWalker::<V>::new(space);
    let ours = walker.trace(
        Ray {
            point: V::from_f64(start_dd.point.to_f64()),
            tangent: V::from_f64(start_dd.tangent.to_f64()),
        },
        Limit::Crossings(truth.crossings.len()),
    );
    let mut diverged = false;
    truth
        .crossings
        .iter()
        .zip(limits)
        .enumerate()
        .map(|(k, (r, (conditioning, split)))| {
            let c = ours.crossings.get(k);
            diverged |= c.is_none_or(|c| c.face != r.face);
            let error = c.map_or(f64::INFINITY, |c| {
                product_separation(g, DdVec4::from_f64(c.ray.point.to_f64()), r.ray.point)
            });
            CrossingAccuracy {
                crossing: k + 1,
                distance: r.distance,
                error,
                conditioning,
                split: split || (diverged && conditioning > SATURATED),
            }
        })
        .collect()
}
