//! Face culling: which objects a ray segment can meet, from how near it comes to the faces.
//!
//! The default scene draws the cell's edges as thin tubes and its vertices as small balls:
//! tens of objects, each tested in every cell a ray passes, though few rays come near them.
//! An object that hugs faces (a tube along the edge where faces `f` and `g` meet, a ball on
//! a vertex) lies within a small distance `T` of each of those face planes, so a segment
//! can meet it only where the segment is within `T` of all of them. Along a segment
//! `X(s) ∝ p + s v` the face residual `−N·X(s)` is linear in `s`, so its smallest value is
//! at an end, and from it a bound on the distance follows: per segment one mask of the
//! faces the segment comes near (two dot products a face), per object one AND.
//!
//! The test is conservative: an object it skips cannot be hit, so pictures are unchanged.
//! The CPU tracer ([`crate::trace`]) and the WGSL tracer use the same masks and thresholds.

use super::{CurvedScene, Object};
use crate::geometry::Geometry;
use crate::space::Space;
use glam::DVec4;

/// Faces beyond this index are never in a mask (objects stay tested against the others).
pub const MAX_CULLED_FACES: usize = 32;

/// Relative and absolute slack on each face threshold: covers rounding in `f32` (the GPU)
/// and `f64`, so that no object a ray meets is skipped.
const SLACK_RELATIVE: f64 = 1e-3;
const SLACK_ABSOLUTE: f64 = 1e-4;

/// The face masks of a scene's objects and the per-face thresholds a segment is tested with.
#[derive(Clone, Debug, PartialEq)]
pub struct FaceCulling {
    /// The distance `T` the masks are built with: an object's mask holds the faces all of
    /// whose points within the cell are within `T` of.
    pub reach: f64,
    /// Per face: the bound on `−N·X` (for a point `X` on the model) of the points within
    /// `reach` of the face plane, slack included.
    pub thresholds: Vec<f64>,
    /// Per object (in the scene's order): the faces a segment must come near to meet it.
    pub masks: Vec<u32>,
    covectors: Vec<DVec4>,
    geometry: Geometry,
}

impl FaceCulling {
    /// The culling of `scene`'s objects in `space`, or `None` where no object hugs two or
    /// more faces (then nothing would be skipped) and in a space of several cells (an
    /// object's reach would be measured within each cell; every object is tested there).
    #[must_use]
    pub fn new(space: &Space, scene: &CurvedScene) -> Option<Self> {
        if space.cells().len() > 1 {
            return None;
        }
        let g = space.geometry;
        let faces = space.faces.len().min(MAX_CULLED_FACES);
        let reaches: Vec<(Vec<f64>, f64)> = scene
            .objects
            .iter()
            .map(|o| {
                let reach = (0..faces).map(|f| inner_reach(space, o, f)).collect();
                (reach, size_of_object(g, o))
            })
            .collect();
        // The smallest distance that covers every object hugging two faces or more.
        let reach = reaches
            .iter()
            .filter_map(|(r, size)| {
                let mut r = r.clone();
                r.sort_by(f64::total_cmp);
                r.get(1).copied().filter(|&second| second <= 2.0 * size)
            })
            .fold(f64::NAN, f64::max);
        if !(reach.is_finite() && reach >= 0.0) {
            return None;
        }
        let s_reach = match g {
            Geometry::Euclidean => reach,
            _ => g.s(reach.min(std::f64::consts::FRAC_PI_2)),
        };
        let thresholds = space.faces[..faces]
            .iter()
            .map(|face| {
                let b = face_scale(g, face.normal.length(), face.offset);
                s_reach * b * (1.0 + SLACK_RELATIVE)
                    + SLACK_ABSOLUTE * (1.0 + face.covector.length())
            })
            .collect();
        let masks = reaches
            .iter()
            .map(|(r, _)| {
                r.iter()
                    .enumerate()
                    .filter(|(_, d)| **d <= reach)
                    .fold(0u32, |m, (f, _)| m | (1 << f))
            })
            .collect();
        Some(Self {
            reach,
            thresholds,
            masks,
            covectors: space.faces[..faces].iter().map(|f| f.covector).collect(),
            geometry: g,
        })
    }

    /// The faces the segment `X(s) ∝ p + s v`, `0 ≤ s ≤ s_max`, comes within `reach` of (or
    /// may: the test is conservative). `p` is a model point and `v` a unit tangent at it.
    #[must_use]
    pub fn near_faces(&self, p: DVec4, v: DVec4, s_max: f64) -> u32 {
        let scale = self.segment_scale(s_max);
        let mut near = 0u32;
        for (f, (n, t)) in self.covectors.iter().zip(&self.thresholds).enumerate() {
            let r0 = -n.dot(p);
            let r1 = r0 - s_max * n.dot(v);
            if r0.min(r1) <= t * scale {
                near |= 1 << f;
            }
        }
        near
    }

    /// Whether a segment that comes near the faces `near` may meet object `object`.
    #[must_use]
    pub fn may_meet(&self, object: usize, near: u32) -> bool {
        self.masks
            .get(object)
            .is_none_or(|&mask| mask & near == mask)
    }

    /// Whether the segment `X(s) ∝ p + s v`, `0 ≤ s ≤ s_max`, comes near all of object
    /// `object`'s faces at one point: the parts of it near each face (intervals of `s`,
    /// `−N·X` being linear) overlap. Sharper than [`FaceCulling::may_meet`], at two dot
    /// products a face of the mask; the GPU checks it for the pair of faces it visits.
    #[must_use]
    pub fn may_meet_at_once(&self, object: usize, p: DVec4, v: DVec4, s_max: f64) -> bool {
        // An object without a mask is tested everywhere: nothing to check.
        let Some(&mask) = self.masks.get(object).filter(|&&m| m != 0) else {
            return true;
        };
        let scale = self.segment_scale(s_max);
        let (mut lo, mut hi) = (0.0, s_max);
        for (f, (n, t)) in self.covectors.iter().zip(&self.thresholds).enumerate() {
            if mask & (1 << f) == 0 {
                continue;
            }
            // a − s b ≤ t: s ≥ (a − t)/b where b > 0, s ≤ (a − t)/b where b < 0.
            let (a, b, t) = (-n.dot(p), n.dot(v), t * scale);
            if b > 0.0 {
                lo = f64::max(lo, (a - t) / b);
            } else if b < 0.0 {
                hi = f64::min(hi, (a - t) / b);
            } else if a > t {
                return false;
            }
        }
        lo <= hi
    }

    /// Whether the segment `X(s) ∝ p + s v`, `0 ≤ s ≤ s_max`, comes near two faces at one
    /// point: only then can it meet an object hugging two faces or more, and only then does
    /// the GPU visit the buckets of face pairs (the shader's `Near::pairs`). The part of the
    /// segment near a face is an interval of `s` (`−N·X` is linear); two overlap exactly
    /// when both faces are near at the start, or both at the end, or one near only up to `a`
    /// and the other only from `b ≤ a`.
    #[must_use]
    pub fn near_at_once(&self, p: DVec4, v: DVec4, s_max: f64) -> bool {
        let scale = self.segment_scale(s_max);
        let (mut at_start, mut at_end) = (0u32, 0u32);
        let (mut leaves, mut reaches) = (f64::NEG_INFINITY, f64::INFINITY);
        for (n, t) in self.covectors.iter().zip(&self.thresholds) {
            let (r0, rate, t) = (-n.dot(p), n.dot(v), t * scale);
            let (start, end) = (r0 <= t, r0 - s_max * rate <= t);
            at_start += u32::from(start);
            at_end += u32::from(end);
            if start && !end {
                leaves = leaves.max((r0 - t) / rate);
            }
            if end && !start {
                reaches = reaches.min((r0 - t) / rate);
            }
        }
        at_start >= 2 || at_end >= 2 || reaches <= leaves
    }

    /// `max |X(s)|` over a segment on the model's scale: 1 in E³ (w = 1), `√(1 − s²) ≤ 1` in
    /// H³, `√(1 + s_max²)` in S³.
    fn segment_scale(&self, s_max: f64) -> f64 {
        match self.geometry {
            Geometry::Spherical => (1.0 + s_max * s_max).sqrt(),
            _ => 1.0,
        }
    }

    /// How many objects have a mask (are tested only where a segment comes near their faces).
    #[must_use]
    pub fn masked_objects(&self) -> usize {
        self.masks.iter().filter(|&&m| m != 0).count()
    }
}

/// `√B(N, N)` of the covector `(n, −r)`: `N·X` over it is `S(d)` of the distance to the plane.
fn face_scale(g: Geometry, n: f64, r: f64) -> f64 {
    (n * n + g.kappa() * r * r).max(0.0).sqrt()
}

/// A size of the object for deciding whether it hugs faces: the radius of balls and tubes,
/// the bounding radius of the rest.
fn size_of_object(g: Geometry, o: &Object) -> f64 {
    match o {
        Object::Ball(b) => b.radius,
        Object::Tube(t) => t.radius,
        _ => o.bounding_ball(g).1,
    }
}

/// An upper bound on how far inside face `f`'s plane any point of the object is (negative
/// where the object is wholly outside it).
fn inner_reach(space: &Space, o: &Object, f: usize) -> f64 {
    let g = space.geometry;
    match o {
        Object::Tube(t) => t.radius + deepest_on_segment(space, f, t.a, t.towards_b(), t.b),
        _ => {
            let (centre, radius) = o.bounding_ball(g);
            radius - space.face_distance(f, centre)
        }
    }
}

/// The largest `−d` (d the signed distance to face `f`'s plane, positive outside) along the
/// geodesic segment from `a` (unit tangent `u`) to `b`.
fn deepest_on_segment(space: &Space, f: usize, a: DVec4, u: DVec4, b: DVec4) -> f64 {
    let g = space.geometry;
    let at_ends = (-space.face_distance(f, a)).max(-space.face_distance(f, b));
    match g {
        // Linear along the segment.
        Geometry::Euclidean => at_ends,
        // sinh d(t) = A cosh t + B sinh t has g'' = g: no interior minimum below zero.
        Geometry::Hyperbolic => at_ends.max(0.0),
        // sin d(t) = A cos t + B sin t = R cos(t − φ): its minimum −R at t = φ + π, if on
        // the segment.
        Geometry::Spherical => {
            let face = &space.faces[f];
            let scale = face_scale(g, face.normal.length(), face.offset);
            let (ca, cb) = (face.covector.dot(a) / scale, face.covector.dot(u) / scale);
            let length = g.distance(a, b);
            let turn = (cb.atan2(ca) + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU);
            if turn <= length {
                ca.hypot(cb).min(1.0).asin().max(at_ends)
            } else {
                at_ends
            }
        }
    }
}
