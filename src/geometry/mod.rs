//! The exact model shared by the three geometries (see `docs/design.md` §1).
//!
//! Points and tangent vectors are 4-vectors `X = (x, y, z, w)` with the bilinear form
//! `⟨u, v⟩ = u.x v.x + u.y v.y + u.z v.z + κ u.w v.w`:
//! S³ is `⟨X,X⟩ = 1`, H³ the upper sheet of `⟨X,X⟩ = −1`, E³ the plane `w = 1`.
//! The chart `x = X.xyz / X.w` (gnomonic, Klein, affine) maps geodesics to straight lines.

mod dd;
pub mod elliptic;
mod isometry;
mod ray;
mod real;

pub(crate) use isometry::max_abs_entry;
pub use isometry::translate_local;
pub use ray::{Ray, chart_ray};

pub use dd::{DD_PI, DdMat4, DdVec4, DoubleDouble};
pub use real::{Real, Vector4};

use glam::{DVec3, DVec4};
use serde::{Deserialize, Serialize};

/// Curvature sign of a space: spherical (κ = +1), Euclidean (κ = 0) or hyperbolic (κ = −1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Geometry {
    /// The 3-sphere S³, κ = +1.
    Spherical,
    /// Euclidean space E³, κ = 0.
    Euclidean,
    /// Hyperbolic space H³, κ = −1.
    Hyperbolic,
}

/// The chart origin `(0, 0, 0, 1)`, a point in all three geometries.
pub const ORIGIN: DVec4 = DVec4::new(0.0, 0.0, 0.0, 1.0);

/// Errors of the geometry core: inputs that name no point or direction of the model.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// A chart point (attached) is not in hyperbolic space: the Klein model needs |x| < 1.
    #[error(
        "chart point ({0:?}, {1:?}, {2:?}) is not in hyperbolic space: the Klein model needs |x| < 1"
    )]
    OutsideKleinBall(f64, f64, f64),
    /// A chart point (attached) is not finite.
    #[error("chart point ({0:?}, {1:?}, {2:?}) is not finite")]
    NotFinite(f64, f64, f64),
    /// A chart point (attached) of S³ lies farther out than [`MAX_SPHERE_CHART`]: within
    /// 1e-300 of the equator, where the chart can no longer place it.
    #[error(
        "chart point ({0:?}, {1:?}, {2:?}) is farther out than 1e300: the gnomonic chart of the \
         sphere puts it within 1e-300 of the equator, closer than f64 can place a point"
    )]
    PastSphereChart(f64, f64, f64),
    /// A direction (attached) has zero length or is not finite.
    #[error("direction ({0:?}, {1:?}, {2:?}) has zero length or is not finite")]
    ZeroDirection(f64, f64, f64),
}

/// The largest chart coordinate of a point of S³: farther out, the point's `w` would be
/// below 1e-300, near where f64 stops holding numbers in full.
pub const MAX_SPHERE_CHART: f64 = 1e300;

impl Geometry {
    /// All three geometries.
    pub const ALL: [Geometry; 3] = [Self::Spherical, Self::Euclidean, Self::Hyperbolic];

    /// The curvature κ ∈ {+1, 0, −1}.
    #[must_use]
    pub const fn kappa(self) -> f64 {
        match self {
            Self::Spherical => 1.0,
            Self::Euclidean => 0.0,
            Self::Hyperbolic => -1.0,
        }
    }

    /// Lower-case name used by the CLI and JSON.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Spherical => "spherical",
            Self::Euclidean => "euclidean",
            Self::Hyperbolic => "hyperbolic",
        }
    }

    /// The bilinear form `⟨a, b⟩`.
    #[inline]
    #[must_use]
    pub fn form<V: Vector4>(self, a: V, b: V) -> V::Real {
        let k = V::Real::from_f64(self.kappa());
        a.component(0) * b.component(0)
            + a.component(1) * b.component(1)
            + a.component(2) * b.component(2)
            + k * a.w() * b.w()
    }

    /// Projects a 4-vector back onto the model (undoes rounding drift of a point).
    ///
    /// The projection is along the ray through the origin of R⁴, so the chart point is
    /// unchanged: `⟨X,X⟩ = κ` with `w > 0` (S³, H³), `w = 1` (E³). A vector that is not
    /// timelike in H³ is first pulled just inside the Klein ball.
    #[inline]
    #[must_use]
    pub fn project_point<V: Vector4>(self, p: V) -> V {
        let one = V::Real::ONE;
        match self {
            Self::Euclidean => p.scale(one / p.w()),
            Self::Spherical => {
                let n = p.dot(p).sqrt();
                let s = if p.w() < V::Real::ZERO { -one } else { one };
                p.scale(s / n)
            }
            Self::Hyperbolic => {
                let s = if p.w() < V::Real::ZERO { -one } else { one };
                let q = -self.form(p, p);
                let floor = V::Real::from_f64(16.0) * V::Real::EPSILON * p.w() * p.w();
                if q > floor {
                    p.scale(s / q.sqrt())
                } else {
                    // Rounding pushed the point onto or past the sphere at infinity: pull
                    // its chart point inside, keeping its direction from the origin.
                    let w = p.w().abs();
                    let r2 = p.component(0) * p.component(0)
                        + p.component(1) * p.component(1)
                        + p.component(2) * p.component(2);
                    let target = (one - V::Real::from_f64(8.0) * V::Real::EPSILON).sqrt();
                    let f = target * w / r2.sqrt();
                    let x = V::new(
                        p.component(0) * f,
                        p.component(1) * f,
                        p.component(2) * f,
                        w,
                    );
                    x.scale(one / (-self.form(x, x)).sqrt())
                }
            }
        }
    }

    /// The part of `v` tangent at the point `p` (projected along `p`, not normalized).
    ///
    /// Projecting along `p` keeps the chart direction of `v` at `p`.
    #[inline]
    #[must_use]
    pub fn project_tangent<V: Vector4>(self, p: V, v: V) -> V {
        match self {
            Self::Euclidean => v - p.scale(v.w() / p.w()),
            _ => v - p.scale(self.form(p, v) / self.form(p, p)),
        }
    }

    /// The unit tangent at `p` in the direction of `v` (after projection onto `T_p`).
    #[inline]
    #[must_use]
    pub fn unit_tangent<V: Vector4>(self, p: V, v: V) -> V {
        let t = self.project_tangent(p, v);
        t.scale(V::Real::ONE / self.form(t, t).sqrt())
    }

    /// `(C(t), S(t))`: `(cos t, sin t)`, `(1, t)` or `(cosh t, sinh t)`.
    #[must_use]
    pub fn cs(self, t: f64) -> (f64, f64) {
        match self {
            Self::Spherical => (t.cos(), t.sin()),
            Self::Euclidean => (1.0, t),
            Self::Hyperbolic => (t.cosh(), t.sinh()),
        }
    }

    /// `S(t)`: `sin t`, `t` or `sinh t` (light falls off as `1/S(d)²`).
    #[must_use]
    pub fn s(self, t: f64) -> f64 {
        self.cs(t).1
    }

    /// Point and tangent at distance `t` along the geodesic from `p` with unit tangent `v`:
    /// `γ(t) = C p + S v`, `γ'(t) = −κ S p + C v`.
    #[must_use]
    pub fn geodesic<V: Vector4>(self, p: V, v: V, t: f64) -> (V, V) {
        let (c, s) = match self {
            Self::Spherical => V::Real::cos_sin_of(t),
            Self::Euclidean => (V::Real::ONE, V::Real::from_f64(t)),
            Self::Hyperbolic => V::Real::cosh_sinh_of(t),
        };
        let k = V::Real::from_f64(self.kappa());
        (p.scale(c) + v.scale(s), p.scale(-k * s) + v.scale(c))
    }

    /// Geodesic length of the segment from `p` to `λ(p + T v)`, `T = S/C` the chart ratio:
    /// `atan T`, `T`, `atanh T`. Given as `T = num/den` with `num, den ≥ 0` so that no
    /// precision is lost forming the quotient.
    #[inline]
    #[must_use]
    pub fn distance_from_ratio<R: Real>(self, num: R, den: R) -> R {
        match self {
            Self::Spherical => num.atan2(den),
            Self::Euclidean => num / den,
            // atanh(n/d) = ½ ln((d + n)/(d − n)); d > n because the target is inside H³.
            Self::Hyperbolic => {
                R::from_f64(0.5) * ((den + num) / (den - num).max(R::EPSILON * den)).ln()
            }
        }
    }

    /// Geodesic distance between two points of the model, in forms that stay accurate for
    /// near and far points alike (no `acos` of a rounded dot product).
    #[must_use]
    pub fn distance(self, p: DVec4, q: DVec4) -> f64 {
        match self {
            // |p − q| = 2 sin(d/2), |p + q| = 2 cos(d/2)
            Self::Spherical => 2.0 * (p - q).length().atan2((p + q).length()),
            Self::Euclidean => (p.truncate() / p.w - q.truncate() / q.w).length(),
            // ⟨p − q, p − q⟩ = 4 sinh²(d/2)
            Self::Hyperbolic => {
                let d = p - q;
                2.0 * (self.form(d, d).max(0.0).sqrt() / 2.0).asinh()
            }
        }
    }

    /// The model point of a chart point.
    pub fn from_chart(self, x: DVec3) -> Result<DVec4, GeometryError> {
        if !x.is_finite() {
            return Err(GeometryError::NotFinite(x.x, x.y, x.z));
        }
        if self == Self::Hyperbolic && x.length_squared() >= 1.0 {
            return Err(GeometryError::OutsideKleinBall(x.x, x.y, x.z));
        }
        if self == Self::Spherical {
            // (x, 1) scaled down by a power of two (exact) before its length is taken where
            // it is large: past about 1.3e154 the squares overflow, and the point would come
            // out as the zero vector.
            let largest = x.abs().max_element();
            if largest > MAX_SPHERE_CHART {
                return Err(GeometryError::PastSphereChart(x.x, x.y, x.z));
            }
            if largest > 1e150 {
                let scale = 2f64.powi(-(largest.log2().ceil() as i32));
                return Ok(self.project_point((x * scale).extend(scale)));
            }
        }
        Ok(self.project_point(x.extend(1.0)))
    }

    /// The chart point of a model point.
    #[must_use]
    pub fn to_chart(self, p: DVec4) -> DVec3 {
        p.truncate() / p.w
    }

    /// The unit tangent at `p` whose chart direction is `dir`.
    /// Any finite non-zero `dir` names a direction, however large or small its entries:
    /// it is scaled by its largest entry before its length is taken (so `1e308` does not
    /// overflow and `1e-320` does not underflow).
    pub fn tangent_from_chart(self, p: DVec4, dir: DVec3) -> Result<DVec4, GeometryError> {
        let largest = dir.abs().max_element();
        // Every component finite: `max_element` passes over a NaN.
        if !(dir.is_finite() && largest > 0.0) {
            return Err(GeometryError::ZeroDirection(dir.x, dir.y, dir.z));
        }
        let scaled = dir / largest;
        let v = (scaled / scaled.length()).extend(0.0);
        let t = self.unit_tangent(p, v);
        if t.is_finite() {
            return Ok(t);
        }
        // Far out in the chart a direction along the point's own is nearly the model's w:
        // what is left of it after the point's part is taken out is so small that its square
        // underflows. Scaled up by a power of two (exact) first, it has a length.
        let rest = self.project_tangent(p, v);
        let size = rest.abs().max_element();
        if !(size > 0.0 && size.is_finite()) {
            return Err(GeometryError::ZeroDirection(dir.x, dir.y, dir.z));
        }
        // In two factors: 2^1024 itself would overflow for a rest of about 1e-308.
        let e = -(size.log2().floor() as i32);
        let t = rest * 2f64.powi(e / 2) * 2f64.powi(e - e / 2);
        Ok(t / self.form(t, t).sqrt())
    }

    /// The unit chart direction of the tangent `v` at `p`
    /// (the derivative of `(p + s v).xyz / (p + s v).w` at `s = 0`, normalized).
    #[must_use]
    pub fn chart_direction(self, p: DVec4, v: DVec4) -> DVec3 {
        (v.truncate() * p.w - p.truncate() * v.w).normalize()
    }

    /// The unit tangent at `p` of the geodesic towards `q` (`q ≠ p`, not antipodal).
    #[must_use]
    pub fn tangent_towards(self, p: DVec4, q: DVec4) -> DVec4 {
        let d = self.project_tangent(p, q - p);
        // Scaled by its largest entry first: a far `q` (1e155 in E³) would overflow the form.
        let d = d / d.abs().max_element();
        d / self.form(d, d).sqrt()
    }
}
