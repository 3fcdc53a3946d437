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
use crate::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Ray, Real, Vector4};
use glam::{DMat4, DVec4};

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
    conditioning_of(
        start,
        reference,
        epsilon,
        |ray| perturbed(g, ray, epsilon),
        |ray, n| walker.trace(ray, Limit::Crossings(n)),
        |a, b| separation(g, a, b),
    )
}

/// [`conditioning`] for any walk: `perturb` gives the four rays `ε` away from a ray,
/// `walk` walks a ray for a number of crossings in double-double, `separation` is the
/// geometry's distance between two points.
pub(crate) fn conditioning_of(
    start: &Ray<DdVec4>,
    reference: &Trace<DdVec4>,
    epsilon: f64,
    perturb: impl Fn(&Ray<DdVec4>) -> [Ray<DdVec4>; 4],
    walk: impl Fn(Ray<DdVec4>, usize) -> Trace<DdVec4>,
    separation: impl Fn(DdVec4, DdVec4) -> f64,
) -> Vec<(f64, bool)> {
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
        for p in perturb(&ray) {
            let trace = walk(p, n - i);
            for (j, c) in trace.crossings.iter().enumerate() {
                let k = i + j;
                let r = &reference.crossings[k];
                if c.face != r.face || split[k] {
                    split[k..].iter_mut().for_each(|s| *s = true);
                    break;
                }
                squares[k] += separation(c.ray.point, r.ray.point).powi(2);
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
    if n > 0 {
        squares[n - 1] += 2.0 * epsilon * epsilon;
    }
    squares.into_iter().map(f64::sqrt).zip(split).collect()
}

/// A ray walked in double-double: the truth other walks of the same start are measured
/// against.
#[derive(Clone, Debug)]
pub struct ReferenceWalk {
    walker: CellWalker<DdVec4>,
    start: Ray<DdVec4>,
    trace: Trace<DdVec4>,
}

impl ReferenceWalk {
    /// Walks `start` for `crossings` crossings in double-double.
    #[must_use]
    pub fn new(space: &Space, start: Ray<DVec4>, crossings: usize) -> Self {
        let walker = reference_walker(space);
        let start = walker.normalized(to_dd(&start));
        let trace = walker.trace(start, Limit::Crossings(crossings));
        Self {
            walker,
            start,
            trace,
        }
    }

    /// The reference trace.
    #[must_use]
    pub fn trace(&self) -> &Trace<DdVec4> {
        &self.trace
    }

    /// The conditioning limit at each crossing for rounding unit `epsilon` (see
    /// [`conditioning`]).
    #[must_use]
    pub fn conditioning(&self, epsilon: f64) -> Vec<(f64, bool)> {
        conditioning(&self.walker, &self.start, &self.trace, epsilon)
    }

    /// The accuracy of `walker`'s walk from the same start (rounded to its precision) at
    /// each crossing, given the conditioning limits of its precision.
    #[must_use]
    pub fn accuracy_of<V: Vector4>(
        &self,
        walker: &CellWalker<V>,
        limits: &[(f64, bool)],
    ) -> Vec<CrossingAccuracy> {
        let g = walker.geometry;
        let start = Ray {
            point: V::from_f64(self.start.point.to_f64()),
            tangent: V::from_f64(self.start.tangent.to_f64()),
        };
        let walk = walker.trace(start, Limit::Crossings(self.trace.crossings.len()));
        let mut diverged = false;
        self.trace
            .crossings
            .iter()
            .zip(limits)
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
                    // A walk that took other faces where the reference's perturbations did
                    // not is wrong, not ill-conditioned: its ratio stays in (and is large).
                    split: split || (diverged && conditioning > SATURATED),
                }
            })
            .collect()
    }
}

/// A walk's error against the double-double reference at each of `crossings` crossings,
/// with the conditioning limit of its precision.
#[must_use]
pub fn walk_accuracy<V: Vector4>(
    space: &Space,
    start: Ray<DVec4>,
    crossings: usize,
) -> Vec<CrossingAccuracy> {
    let reference = ReferenceWalk::new(space, start, crossings);
    let limits = reference.conditioning(V::Real::EPSILON.to_f64());
    reference.accuracy_of(&CellWalker::<V>::new(space), &limits)
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

/// A frame (columns right, up, back, position) moved in double-double along the path a
/// player's `f64` frame took: the same local motions (computed exactly from the same
/// inputs) and the same face crossings, with the pairings made exact isometries. What the
/// player's frame differs from it by is the player's rounding ([`ReferenceFrame::drift`]).
#[derive(Clone, Debug)]
pub struct ReferenceFrame {
    geometry: Geometry,
    frame: [DdVec4; 4],
    pairings: Vec<DdMat4>,
}

/// Gram–Schmidt of a frame in the form: the position projected onto the model, then the
/// three axes made tangent there and orthonormal, in order.
fn orthonormal(g: Geometry, cols: [DdVec4; 4]) -> [DdVec4; 4] {
    let p = g.project_point(cols[3]);
    let mut out = [p; 4];
    for i in 0..3 {
        let mut v = g.project_tangent(p, cols[i]);
        for done in &out[..i] {
            v = v - done.scale(g.form(v, *done));
        }
        out[i] = v.scale(DoubleDouble::ONE / g.form(v, v).sqrt());
    }
    out
}

impl ReferenceFrame {
    /// Starts at an `f64` frame of `space`.
    #[must_use]
    pub fn new(space: &Space, frame: DMat4) -> Self {
        let g = space.geometry;
        let pairings = space
            .faces
            .iter()
            .map(|f| {
                // The pairing carries the origin's frame to its columns: orthonormalising
                // them in double-double gives the isometry the f64 matrix rounds.
                let m = DdMat4::from_f64(f.pairing);
                DdMat4(orthonormal(g, m.0))
            })
            .collect();
        Self {
            geometry: g,
            frame: DdMat4::from_f64(frame).0,
            pairings,
        }
    }

    /// The frame in `f64` (rounded).
    #[must_use]
    pub fn frame(&self) -> DMat4 {
        let c = self.frame.map(|v| v.to_f64());
        DMat4::from_cols(c[0], c[1], c[2], c[3])
    }

    /// One player step: translate by `translation` in the frame's own axes, turn about its
    /// right, up and back axes by `rotation` (radians, in that order), then cross `faces`
    /// in order — what `player::step_frame` and `space::wrap_into_cell` did.
    pub fn step(&mut self, translation: glam::DVec3, rotation: glam::DVec3, faces: &[usize]) {
        let g = self.geometry;
        let one = DoubleDouble::ONE;
        let zero = DoubleDouble::ZERO;
        let mut m = DdMat4(self.frame);
        let t = translation.to_array().map(DoubleDouble::new);
        let length = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
        if length.hi > 0.0 && length.is_finite() {
            let u = t.map(|x| x / length);
            let (c, s) = match g {
                Geometry::Spherical => {
                    let (s, c) = length.sin_cos();
                    (c, s)
                }
                Geometry::Euclidean => (one, length),
                Geometry::Hyperbolic => length.cosh_sinh(),
            };
            let k = DoubleDouble::new(g.kappa());
            let u4 = DdVec4([u[0], u[1], u[2], zero]);
            let o = DdVec4([zero, zero, zero, one]);
            let col = |j: usize| {
                let mut e = DdVec4::default();
                e.0[j] = one;
                e + u4.scale((c - one) * u[j]) - o.scale(k * s * u[j])
            };
            m = m * DdMat4([col(0), col(1), col(2), o.scale(c) + u4.scale(s)]);
        }
        for (axis, angle) in rotation.to_array().into_iter().enumerate() {
            if angle == 0.0 || !angle.is_finite() {
                continue;
            }
            let (s, c) = DoubleDouble::new(angle).sin_cos();
            // Right-handed rotation about `axis` (as glam's `from_axis_angle`).
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            let mut r = DdMat4(std::array::from_fn(|j| {
                let mut e = DdVec4::default();
                e.0[j] = one;
                e
            }));
            r.0[a].0[a] = c;
            r.0[a].0[b] = s;
            r.0[b].0[a] = -s;
            r.0[b].0[b] = c;
            m = m * r;
        }
        for &f in faces {
            m = self.pairings[f] * m;
        }
        self.frame = m.0;
    }

    /// How far an `f64` frame is from this one: the geodesic distance between the
    /// positions, and the largest angle between corresponding axes (radians, to first
    /// order).
    #[must_use]
    pub fn drift(&self, frame: DMat4) -> (f64, f64) {
        let g = self.geometry;
        let theirs = DdMat4::from_f64(frame).0;
        let position = separation(g, self.frame[3], theirs[3]);
        let orientation = (0..3)
            .map(|i| {
                let d = self.frame[i] - theirs[i];
                g.form(d, d).to_f64().abs().sqrt()
            })
            .fold(0.0, f64::max);
        (position, orientation)
    }
}
