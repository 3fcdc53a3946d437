//! How many digits a walk loses beyond what the problem itself loses (`docs/performance.md`,
//! "Accuracy at the conditioning limit").
//!
//! * The **reference** is the same walk ([`CellWalker`]) in double-double
//!   ([`DdVec4`], 106 bits), over the same cell data (the `f64` faces and pairings, exact in
//!   double-double), from the same start. What the `f64` or `f32` walk differs from it by is
//!   its **error** at each crossing: the geodesic distance between the two crossing points.
//! * The **conditioning limit** at crossing `k` is the error a walk would make that computed
//!   each segment exactly and only rounded its state once per crossing, by one unit in the
//!   last place: the root sum of squares, over the start and every crossing `i ≤ k`, of how
//!   far crossing `k` moves (in the reference) when the ray at `i` is moved by `ε` (machine
//!   epsilon of the precision) sideways, or turned by `ε` radians, in each of the two
//!   directions across the ray. No walk in that precision can do better than rounding its
//!   state, so `error / conditioning` is what the walk loses beyond the problem: 1 is the
//!   limit, and 10 is a digit lost.
//! * Past a point the perturbed rays leave through other faces than the reference (they
//!   pass on the other side of an edge, or their error has grown to the cell's size); from
//!   there on the crossing is **split** and the ratio means nothing, so statistics leave it
//!   out.

use super::Space;
use super::walk::{CellWalker, Exit, Limit, Trace};
use crate::geometry::{DdVec4, DoubleDouble, Geometry, Ray, Real, Vector4};
use glam::DVec4;

/// The errors of a walk at one crossing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CrossingAccuracy {
    /// Crossing number, from 1.
    pub crossing: usize,
    /// Geodesic distance of the crossing from the start (reference).
    pub distance: f64,
    /// Distance between the walk's crossing point and the reference's.
    pub error: f64,
    /// The conditioning limit: the error of a walk that rounds its state once per crossing.
    pub conditioning: f64,
    /// A perturbed reference ray, or the walk itself, left through another face on the way.
    pub split: bool,
}

impl CrossingAccuracy {
    /// `error / conditioning`, or `None` where the crossing is split.
    #[must_use]
    pub fn ratio(&self) -> Option<f64> {
        (!self.split).then(|| self.error / self.conditioning.max(f64::MIN_POSITIVE))
    }
}

/// The walker of a space in double-double: the reference.
#[must_use]
pub fn reference_walker(space: &Space) -> CellWalker<DdVec4> {
    CellWalker::new(space)
}

/// A ray in double-double.
fn to_dd<V: Vector4>(ray: &Ray<V>) -> Ray<DdVec4> {
    Ray {
        point: DdVec4::from_f64(ray.point.to_f64()),
        tangent: DdVec4::from_f64(ray.tangent.to_f64()),
    }
}

/// The geodesic distance between two points of the model, computed from their difference
/// in double-double (so it resolves distances far below `f64`'s rounding of the points).
#[must_use]
pub fn separation(g: Geometry, a: DdVec4, b: DdVec4) -> f64 {
    match g {
        Geometry::Euclidean => {
            let (ia, ib) = (DoubleDouble::ONE / a.w(), DoubleDouble::ONE / b.w());
            let d = a.scale(ia) - b.scale(ib);
            (0..3)
                .map(|i| (d.component(i) * d.component(i)).to_f64())
                .sum::<f64>()
                .sqrt()
        }
        Geometry::Spherical => {
            let d = a - b;
            let s = a + b;
            2.0 * d.dot(d).to_f64().sqrt().atan2(s.dot(s).to_f64().sqrt())
        }
        Geometry::Hyperbolic => {
            let d = a - b;
            2.0 * (g.form(d, d).to_f64().max(0.0).sqrt() / 2.0).asinh()
        }
    }
}

/// Two unit tangents at `ray.point`, orthogonal to each other and to `ray.tangent`.
fn sideways(g: Geometry, ray: &Ray<DdVec4>) -> [DdVec4; 2] {
    let p = ray.point;
    let mut basis = vec![ray.tangent];
    for axis in 0..4 {
        if basis.len() == 3 {
            break;
        }
        let mut e = DdVec4::default();
        e.0[axis] = DoubleDouble::ONE;
        let mut t = g.project_tangent(p, e);
        for b in &basis {
            t = t - b.scale(g.form(*b, t));
        }
        let norm = g.form(t, t).to_f64().sqrt();
        if norm > 0.3 {
            t = t.scale(DoubleDouble::ONE / g.form(t, t).sqrt());
            basis.push(t);
        }
    }
    [basis[1], basis[2]]
}

/// The four rays one `ε` away from `ray`: moved sideways, or turned, in two directions.
fn perturbed(g: Geometry, ray: &Ray<DdVec4>, epsilon: f64) -> [Ray<DdVec4>; 4] {
    let e = DoubleDouble::new(epsilon);
    let [a, b] = sideways(g, ray);
    let moved = |d: DdVec4| {
        let point = g.project_point(ray.point + d.scale(e));
        Ray {
            point,
            tangent: g.unit_tangent(point, ray.tangent),
        }
    };
    let turned = |d: DdVec4| Ray {
        point: ray.point,
        tangent: g.unit_tangent(ray.point, ray.tangent + d.scale(e)),
    };
    [moved(a), moved(b), turned(a), turned(b)]
}

/// The conditioning limit at each crossing of a reference trace, for rounding unit
/// `epsilon`, and whether a perturbed ray split from the reference by then.
#[must_use]
pub fn conditioning(
    walker: &CellWalker<DdVec4>,
    start: &Ray<DdVec4>,
    reference: &Trace<DdVec4>,
    epsilon: f64,
) -> Vec<(f64, bool)> {
    let g = walker.geometry;
    let n = reference.crossings.len();
    let mut squares = vec![0.0_f64; n];
    let mut split = vec![false; n];
    for i in 0..n {
        // The state after crossing i (i = 0: the start), and the crossings still to come.
        let ray = if i == 0 {
            *start
        } else {
            reference.crossings[i - 1].ray
        };
        for p in perturbed(g, &ray, epsilon) {
            let trace = walker.trace(p, Limit::Crossings(n - i));
            for (j, c) in trace.crossings.iter().enumerate() {
                let k = i + j;
                let r = &reference.crossings[k];
                if c.face != r.face || split[k] {
                    split[k..].iter_mut().for_each(|s| *s = true);
                    break;
                }
                squares[k] += separation(g, c.ray.point, r.ray.point).powi(2);
            }
            if trace.crossings.len() < n - i {
                split[i + trace.crossings.len()..]
                    .iter_mut()
                    .for_each(|s| *s = true);
            }
        }
        // Rounding the crossing point itself: ε sideways, in two directions.
        if i > 0 {
            squares[i - 1] += 2.0 * epsilon * epsilon;
        }
    }
    squares[n - 1] += 2.0 * epsilon * epsilon;
    squares.into_iter().map(f64::sqrt).zip(split).collect()
}

/// A walk's error against the double-double reference at each of `crossings` crossings,
/// with the conditioning limit of its precision.
#[must_use]
pub fn walk_accuracy<V: Vector4>(
    space: &Space,
    start: Ray<DVec4>,
    crossings: usize,
) -> Vec<CrossingAccuracy> {
    let reference_walker = reference_walker(space);
    let start_dd = reference_walker.normalized(to_dd(&start));
    let reference = reference_walker.trace(start_dd, Limit::Crossings(crossings));
    let walker = CellWalker::<V>::new(space);
    let walk = walker.trace(
        Ray {
            point: V::from_f64(start.point),
            tangent: V::from_f64(start.tangent),
        },
        Limit::Crossings(crossings),
    );
    let epsilon = V::Real::EPSILON.to_f64();
    let limits = conditioning(&reference_walker, &start_dd, &reference, epsilon);
    let g = space.geometry;
    let mut diverged = false;
    reference
        .crossings
        .iter()
        .zip(&limits)
        .enumerate()
        .map(|(k, (r, &(conditioning, split)))| {
            let ours = walk.crossings.get(k);
            diverged |= ours.is_none_or(|c| c.face != r.face);
            let error = ours.map_or(f64::INFINITY, |c| {
                separation(g, to_dd(&c.ray).point, r.ray.point)
            });
            CrossingAccuracy {
                crossing: k + 1,
                distance: r.distance,
                error,
                conditioning,
                split: split || (diverged && conditioning > 1e-3),
            }
        })
        .collect()
}

/// Crossings whose conditioning limit is past this (geodesic units) are left out of the
/// statistics: the perturbed rays have grown to a sizeable part of the cell, where the
/// walk is no longer linear in its rounding and every precision has lost every digit.
pub const SATURATED: f64 = 1e-4;

/// Median and worst `error / conditioning` over the crossings that count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccuracySummary {
    /// Median ratio.
    pub median: f64,
    /// Largest ratio.
    pub worst: f64,
    /// Crossings counted.
    pub counted: usize,
    /// Crossings left out: split, or saturated (conditioning past [`SATURATED`]).
    pub left_out: usize,
}

/// The summary of some crossings' accuracies; `None` when none counts.
#[must_use]
pub fn summarize<'a>(
    rows: impl IntoIterator<Item = &'a CrossingAccuracy>,
) -> Option<AccuracySummary> {
    let mut left_out = 0;
    let mut ratios: Vec<f64> = Vec::new();
    for row in rows {
        match row.ratio() {
            Some(r) if row.conditioning <= SATURATED => ratios.push(r),
            _ => left_out += 1,
        }
    }
    if ratios.is_empty() {
        return None;
    }
    ratios.sort_by(f64::total_cmp);
    Some(AccuracySummary {
        median: ratios[ratios.len() / 2],
        worst: ratios[ratios.len() - 1],
        counted: ratios.len(),
        left_out,
    })
}

/// How far the end of a walk is from the double-double walk of the same path: the
/// reference crosses the faces the walk crossed, in the walk's order, and goes on to the
/// walk's end distance. Where a ray meets an edge or a vertex, any order of the faces there
/// is right (they differ by rounding), so this checks walks along edges and through
/// vertices, where comparing with the reference's own face choices cannot.
///
/// `trace` must come from `start` (in any precision) and end at `trace.distance` (a
/// [`Limit::Distance`] walk, or the last crossing of a crossings-limited one).
#[must_use]
pub fn same_path_error<V: Vector4>(space: &Space, start: Ray<DVec4>, trace: &Trace<V>) -> f64 {
    let walker = reference_walker(space);
    let g = space.geometry;
    let zero = DoubleDouble::ZERO;
    let mut ray = walker.normalized(to_dd(&start));
    let mut travelled = zero;
    // On a face to the walk's rounding: 64 units of it.
    let on_face = DoubleDouble::new(64.0 * V::Real::EPSILON.to_f64());
    for c in &trace.crossings {
        let n = walker.covectors[c.face];
        let den = n.dot(ray.tangent);
        let num = (-n.dot(ray.point)).max(zero);
        // A ray on the face to the walk's rounding (at an edge or a vertex, where the walk
        // hops from face to face), or running along it, crosses where it is.
        let exit = if den > zero && num > on_face {
            Exit {
                face: c.face,
                num,
                den,
            }
        } else {
            Exit {
                face: c.face,
                num: zero,
                den: DoubleDouble::ONE,
            }
        };
        let (next, length) = walker.cross(&ray, &exit);
        travelled = travelled + length;
        ray = next;
    }
    let rest = (DoubleDouble::new(trace.distance) - travelled).to_f64();
    let end = if rest > 0.0 {
        walker.advance(&ray, rest)
    } else {
        ray
    };
    separation(g, end.point, to_dd(&trace.end).point)
}
