//! "Which orbit point is this?": the one lookup of points of the model by geodesic distance,
//! shared by the group enumeration ([`super::dirichlet`]), the closed geodesics and the
//! deck-group walks ([`super::invariants`]) and the sight lines ([`super::motion`]).
//!
//! Points are bucketed on a grid of coordinates in which geodesically close points are close:
//! the point itself in S³ (a chord is shorter than its arc), the affine point in E³, and the
//! tangent vector at the origin in H³ (the logarithm at a point does not stretch distances in
//! negative curvature). A bucket is at least as wide as the tolerance, so two points within it
//! lie in the same or neighbouring buckets, and the geodesic distance decides.

use crate::geometry::Geometry;
use glam::DVec4;
use std::collections::HashMap;

/// Points of the model, found again by geodesic distance.
#[derive(Clone, Debug)]
pub struct OrbitPoints {
    geometry: Geometry,
    within: f64,
    points: Vec<DVec4>,
    buckets: HashMap<[i64; 3], Vec<usize>>,
}

impl OrbitPoints {
    /// An empty set whose points count as one when closer than `within` (a geodesic distance,
    /// far below the points' spacing and far above their rounding error).
    #[must_use]
    pub fn new(geometry: Geometry, within: f64) -> Self {
        Self {
            geometry,
            within,
            points: Vec::new(),
            buckets: HashMap::new(),
        }
    }

    /// How many points it holds.
    #[must_use]
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether it holds none.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// The coordinates bucketed (see the module docs).
    fn coordinates(&self, p: DVec4) -> [f64; 3] {
        let c = match self.geometry {
            Geometry::Spherical => p,
            Geometry::Euclidean => p / p.w,
            Geometry::Hyperbolic => {
                // |x| = sinh d, so x·d/|x| is the tangent vector of length d.
                let x = p.truncate();
                let len = x.length();
                let d = self.geometry.distance(crate::geometry::ORIGIN, p);
                if len > 0.0 {
                    (x * (d / len)).extend(0.0)
                } else {
                    DVec4::ZERO
                }
            }
        };
        [c.x, c.y, c.z]
    }

    fn key(&self, c: [f64; 3]) -> [i64; 3] {
        c.map(|x| (x / self.within).floor() as i64)
    }

    /// The index and distance of the point nearest `p`, if one is closer than the tolerance.
    #[must_use]
    pub fn nearest(&self, p: DVec4) -> Option<(usize, f64)> {
        let [a, b, c] = self.key(self.coordinates(p));
        let mut best: Option<(usize, f64)> = None;
        for da in -1..=1 {
            for db in -1..=1 {
                for dc in -1..=1 {
                    let Some(list) = self.buckets.get(&[
                        a.saturating_add(da),
                        b.saturating_add(db),
                        c.saturating_add(dc),
                    ]) else {
                        continue;
                    };
                    for &i in list {
                        let d = self.geometry.distance(self.points[i], p);
                        if d < self.within && best.is_none_or(|(_, bd)| d < bd) {
                            best = Some((i, d));
                        }
                    }
                }
            }
        }
        best
    }

    /// Adds `p` (whether or not a point near it is held) and returns its index.
    pub fn push(&mut self, p: DVec4) -> usize {
        let i = self.points.len();
        let key = self.key(self.coordinates(p));
        self.buckets.entry(key).or_default().push(i);
        self.points.push(p);
        i
    }

    /// Adds `p` unless a point within the tolerance is held: `true` when it was new.
    pub fn insert(&mut self, p: DVec4) -> bool {
        if self.nearest(p).is_some() {
            return false;
        }
        self.push(p);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// Points just inside the tolerance are found across bucket boundaries, points just
    /// outside are not, in every geometry and far from the origin in H³.
    #[test]
    fn points_within_the_tolerance_are_found_across_buckets() {
        for g in Geometry::ALL {
            for far in [0.0, 0.4, 6.0] {
                if g == Geometry::Spherical && far > 3.0 {
                    continue;
                }
                let within = 1e-4;
                let mut set = OrbitPoints::new(g, within);
                let base = g.translation(DVec3::new(1.0, 0.3, -0.2).normalize(), far)
                    * crate::geometry::ORIGIN;
                let i = set.push(base);
                for k in 0..50 {
                    let dir = DVec3::new((k as f64).sin(), (k as f64 * 1.7).cos(), 0.3).normalize();
                    let frame = g.translation(DVec3::new(1.0, 0.3, -0.2).normalize(), far);
                    let near = frame * g.translation(dir, 0.9 * within) * crate::geometry::ORIGIN;
                    let away = frame * g.translation(dir, 1.2 * within) * crate::geometry::ORIGIN;
                    assert_eq!(set.nearest(near).map(|(j, _)| j), Some(i), "{g:?} {far}");
                    assert!(set.nearest(away).is_none(), "{g:?} {far}");
                }
                assert!(!set.insert(base));
                assert_eq!(set.len(), 1);
            }
        }
    }
}
