//! Mesh triangles of the product spaces, met exactly. A triangle of H²×R or S²×R is totally
//! geodesic, so a flat piece a ray can meet in closed form, in two cases only:
//!
//! - **horizontal**: its corners at one height, the surface's geodesic triangle in that
//!   slice. A ray meets the slice where its height reaches it; the point is inside when it is
//!   on the inner side of the three edges' lines, `nᵢ·X ≥ 0` with `nᵢ` the cross product of
//!   the edge's two corners (the plane through the model's origin that cuts the surface in
//!   the edge's geodesic).
//! - **vertical**: its corners over one surface geodesic, a triangle of the vertical plane
//!   over it, which is flat (a geodesic times the fibre is isometric to the Euclidean plane,
//!   with coordinates `(s, z)`: arclength along the geodesic and height). The ray's shadow
//!   `X(u) = C(u)·p + S(u)·v̂` meets the plane `n·X = 0` where `A C(u) + B S(u) = 0`
//!   (`A = n·p`, `B = n·v̂`): `u = artanh(−A/B)` in H², `atan(−A/B)` (the first such `u ≥ 0`)
//!   on S², where the segments are at most π/4 of arc and so meet it once. The point is
//!   inside when its barycentric coordinates in `(s, z)` are.
//!
//! Any other triangle (corners at different heights over three surface points off one
//! geodesic) is curved in these geometries and is refused by name: a mesh is exact or not
//! taken.

use crate::geometry::{Geometry, Ray};
use glam::{DVec3, DVec4};

/// A mesh triangle of a product space (see the module's description).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProductTriangle {
    /// In the slice at `height`: the points whose base `X` has `edges[i]·X ≥ 0` for all
    /// three (the edges' cross products, `z` components zero).
    Horizontal {
        /// The three edges' covectors, pointing inwards.
        edges: [DVec4; 3],
        /// The slice's height.
        height: f64,
    },
    /// In the vertical plane over the surface geodesic `covector·X = 0`: a point is
    /// `(s, z)`, `s` its arclength from `origin` in the direction `along`; it is inside when
    /// `to_barycentric · (s − corner[0], z − corner[1])` has both coordinates at least 0 and
    /// their sum at most 1.
    Vertical {
        /// The plane's covector (unit in the dual form, `z` component zero).
        covector: DVec4,
        /// A unit base point of the geodesic (`s = 0`).
        origin: DVec4,
        /// The geodesic's unit tangent at `origin` (`s` grows along it).
        along: DVec4,
        /// The first corner's `(s, z)`.
        corner: [f64; 2],
        /// The inverse of the matrix of the two other corners' offsets, row-major.
        to_barycentric: [f64; 4],
    },
}

fn base3(p: DVec4) -> DVec3 {
    DVec3::new(p.x, p.y, p.w)
}

fn covector(n: DVec3) -> DVec4 {
    DVec4::new(n.x, n.y, 0.0, n.z)
}

fn form(g: Geometry, a: DVec4, b: DVec4) -> f64 {
    a.x * b.x + a.y * b.y + g.kappa() * a.w * b.w
}

/// The arclength coordinate of the base point `x` along the geodesic through `origin` in
/// the direction `along`.
fn arclength(g: Geometry, origin: DVec4, along: DVec4, x: DVec4) -> f64 {
    let (xb, ob) = (
        DVec4::new(x.x, x.y, 0.0, x.w),
        DVec4::new(origin.x, origin.y, 0.0, origin.w),
    );
    let sin = form(g, xb, along);
    match g {
        Geometry::Spherical => sin.atan2(form(g, xb, ob)),
        _ => sin.asinh(),
    }
}

impl ProductTriangle {
    /// The triangle of three points of the product (on the surface's model, with heights),
    /// or why it is not exact: a triangle must lie in a slice or over one surface geodesic,
    /// and have an area.
    pub fn new(g: Geometry, corners: [DVec4; 3]) -> Result<Self, String> {
        let [a, b, c] = corners.map(base3);
        if !corners.iter().all(|p| p.is_finite()) {
            return Err("a corner is not finite".into());
        }
        let scale = a.length().max(b.length()).max(c.length());
        let det = a.cross(b).dot(c) / scale.powi(3);
        let heights = [corners[0].z, corners[1].z, corners[2].z];
        let span = heights.iter().fold(f64::NEG_INFINITY, |m, &z| m.max(z))
            - heights.iter().fold(f64::INFINITY, |m, &z| m.min(z));
        let level = span <= 1e-12 * (1.0 + heights[0].abs());
        if level {
            if det.abs() < 1e-12 {
                return Err(
                    "the triangle has no area: its corners are at one height on one surface \
                     geodesic"
                        .into(),
                );
            }
            let orient = det.signum();
            let edges = [a.cross(b), b.cross(c), c.cross(a)].map(|n| covector(n * orient));
            return Ok(Self::Horizontal {
                edges,
                height: heights[0],
            });
        }
        if det.abs() > 1e-9 {
            return Err(format!(
                "the triangle is curved: its corners are at different heights ({:.4}, {:.4}, \
                 {:.4}) over surface points off one geodesic; only triangles in a slice or \
                 over a surface geodesic are exact",
                heights[0], heights[1], heights[2]
            ));
        }
        // The two base points furthest apart name the geodesic.
        let pairs = [(a, b), (b, c), (c, a)];
        let (p, q) = pairs
            .into_iter()
            .max_by(|x, y| {
                let dx = (x.0 - x.1).length();
                let dy = (y.0 - y.1).length();
                dx.total_cmp(&dy)
            })
            .unwrap_or((a, b));
        let n = p.cross(q);
        let dual = n.x * n.x + n.y * n.y + g.kappa() * n.z * n.z;
        if !(dual > 1e-24) {
            return Err(
                "the triangle stands on one surface point (a vertical segment): it has no area"
                    .into(),
            );
        }
        let covector = covector(n / dual.sqrt());
        let o = DVec4::new(p.x, p.y, 0.0, p.z);
        let origin = o / form(g, o, o).abs().sqrt();
        let q = DVec4::new(q.x, q.y, 0.0, q.z);
        let toward = q - origin * (form(g, q, origin) / form(g, origin, origin));
        let len = form(g, toward, toward).max(0.0).sqrt();
        if !(len > 0.0) {
            return Err("the triangle's corners are over one surface point".into());
        }
        let along = toward / len;
        let st: Vec<[f64; 2]> = corners
            .iter()
            .map(|x| [arclength(g, origin, along, *x), x.z])
            .collect();
        let (u, v) = (
            [st[1][0] - st[0][0], st[1][1] - st[0][1]],
            [st[2][0] - st[0][0], st[2][1] - st[0][1]],
        );
        let area = u[0] * v[1] - v[0] * u[1];
        if area.abs() < 1e-12 {
            return Err("the triangle has no area in its vertical plane".into());
        }
        Ok(Self::Vertical {
            covector,
            origin,
            along,
            corner: st[0],
            to_barycentric: [v[1] / area, -v[0] / area, -u[1] / area, u[0] / area],
        })
    }

    /// Whether every number of it is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        match *self {
            Self::Horizontal { edges, height } => {
                edges.iter().all(|e| e.is_finite()) && height.is_finite()
            }
            Self::Vertical {
                covector,
                origin,
                along,
                corner,
                to_barycentric,
            } => {
                covector.is_finite()
                    && origin.is_finite()
                    && along.is_finite()
                    && corner.iter().chain(&to_barycentric).all(|x| x.is_finite())
            }
        }
    }

    /// Whether the model point `x` (on the triangle's slice or plane) is in the triangle.
    #[must_use]
    pub fn contains(&self, g: Geometry, x: DVec4) -> bool {
        match *self {
            Self::Horizontal { edges, .. } => edges.iter().all(|n| n.dot(x) >= 0.0),
            Self::Vertical {
                origin,
                along,
                corner,
                to_barycentric: m,
                ..
            } => {
                let (ds, dz) = (arclength(g, origin, along, x) - corner[0], x.z - corner[1]);
                let (l1, l2) = (m[0] * ds + m[1] * dz, m[2] * ds + m[3] * dz);
                l1 >= 0.0 && l2 >= 0.0 && l1 + l2 <= 1.0
            }
        }
    }

    /// The first `t` in `[0, t_max]` where the ray meets the triangle's slice or plane, by
    /// the closed forms above, if it does (whether inside the triangle is asked of
    /// [`ProductTriangle::contains`]).
    #[must_use]
    pub fn plane_meeting(&self, g: Geometry, ray: &Ray<DVec4>, t_max: f64) -> Option<f64> {
        match *self {
            Self::Horizontal { height, .. } => {
                let mu = ray.tangent.z;
                if mu == 0.0 {
                    return None;
                }
                let t = (height - ray.point.z) / mu;
                (0.0..=t_max).contains(&t).then_some(t)
            }
            Self::Vertical { covector, .. } => {
                let vb = DVec4::new(ray.tangent.x, ray.tangent.y, 0.0, ray.tangent.w);
                let lambda = form(g, vb, vb).max(0.0).sqrt();
                if lambda <= 0.0 {
                    return None;
                }
                let pb = DVec4::new(ray.point.x, ray.point.y, 0.0, ray.point.w);
                let (a, b) = (covector.dot(pb), covector.dot(vb) / lambda);
                let u = match g {
                    Geometry::Spherical => {
                        let u = if b == 0.0 {
                            std::f64::consts::FRAC_PI_2
                        } else {
                            (-a / b).atan()
                        };
                        if u < 0.0 { u + std::f64::consts::PI } else { u }
                    }
                    _ => {
                        let r = -a / b;
                        if !(0.0..1.0).contains(&r) {
                            return None;
                        }
                        r.atanh()
                    }
                };
                let t = u / lambda;
                (t.is_finite() && (0.0..=t_max).contains(&t)).then_some(t)
            }
        }
    }

    /// The unit normal at `x` (on the slice or the plane), on either side: the fibre, or
    /// the plane's covector made a tangent at `x`.
    #[must_use]
    pub fn normal(&self, g: Geometry, x: DVec4) -> DVec4 {
        match *self {
            Self::Horizontal { .. } => DVec4::Z,
            Self::Vertical { covector, .. } => {
                let xb = DVec4::new(x.x, x.y, 0.0, x.w);
                let m = DVec4::new(covector.x, covector.y, 0.0, g.kappa() * covector.w);
                let t = m - xb * (form(g, m, xb) / form(g, xb, xb));
                let len = form(g, t, t).max(0.0).sqrt();
                if len > 0.0 { t / len } else { DVec4::Z }
            }
        }
    }
}
