//! The product geometries H²×R and S²×R: a closed surface (from its word,
//! [`super::surface`]) times a circle of length `L`, optionally turned by `2π/P` once round
//! the circle (`docs/surfaces.md`).
//!
//! A point is a 4-vector `(x, y, z, w)`: `(x, y, w)` on the surface's model
//! (`x² + y² + κw² = κ`, the centre `(0, 0, 1)`) and `z` the height along the fibre; the
//! chart is `(x/w, y/w, z)`. A unit tangent `(vx, vy, vz, vw)` splits into the base part of
//! speed `λ` and the fibre speed `μ = vz`, `λ² + μ² = 1`. The geodesic is exact: its shadow
//! on the surface is the surface geodesic at speed `λ`, `p(t) = C(λt) p + S(λt)/λ · v`, and
//! its height `z + μt`. The cell is the polygon times `[−L/2, L/2]`: its side faces are the
//! polygon's sides times the fibre (totally geodesic, met where the shadow crosses the
//! side's line, a ratio as in the constant-curvature walk), and its top and bottom are the
//! slices `z = ±L/2`, met at `t = (±L/2 − z)/μ`. Leaving through a side applies the
//! polygon's pairing (a 4×4 matrix that fixes `z`); leaving through the top applies
//! `(p, z) ↦ (R⁻¹p, z − L)`, `R` the turn, and the bottom its inverse.

use super::exact::ExactFace;
use super::surface::{Polygon, SurfaceWord, WordError, turn};
use super::walk::{Crossing, Limit, MAX_STEPS_WITHOUT_CROSSING, Trace};
use crate::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Ray, Real, Vector4};
use glam::DVec4;
use std::sync::Arc;

/// The largest turn order `P`.
pub const MAX_TURN: u32 = 64;

/// Why a product space cannot be built.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProductError {
    /// The word is not a closed surface.
    #[error(transparent)]
    Word(#[from] WordError),
    /// The circle's length is not a positive finite number.
    #[error("the circle's length L = {0} must be a positive finite number")]
    BadLength(f64),
    /// The turn order is out of range.
    #[error("the turn -turn-{0} must be a whole number from 1 to {MAX_TURN}")]
    BadTurn(u32),
    /// The turn does not carry the polygon's gluing to itself.
    #[error(
        "a turn by 2π/{turn} does not carry the gluing of {word} to itself: it must move each \
         side to a side glued the same way to the turned partner (the word has {sides} sides)"
    )]
    TurnNotSymmetry { turn: u32, word: String, sides: usize },
    /// A flat word: its product is a flat space.
    #[error(
        "{word} is a flat surface (Euler characteristic 0): its product with a circle is a flat \
         space, built as one (`Space`)"
    )]
    Flat { word: String },
}

/// A closed 3-manifold (or, with a non-orientable surface, still a manifold) of the product
/// geometry H²×R or S²×R, as its cell: the surface's polygon times an interval.
#[derive(Clone, Debug)]
pub struct ProductSpace {
    pub(crate) name: String,
    pub(crate) description: String,
    pub(crate) word: SurfaceWord,
    pub(crate) polygon: Arc<Polygon>,
    pub(crate) length: f64,
    pub(crate) turn: u32,
}

impl ProductSpace {
    /// The surface of `word` times a circle of length `length`, turned by `2π/turn` once
    /// round it (`turn` 1: no turn).
    pub fn new(
        name: impl Into<String>,
        word: &str,
        length: f64,
        turn: u32,
    ) -> Result<Self, ProductError> {
        let word = SurfaceWord::parse(word)?;
        if !(length.is_finite() && length > 0.0) {
            return Err(ProductError::BadLength(length));
        }
        if !(1..=MAX_TURN).contains(&turn) {
            return Err(ProductError::BadTurn(turn));
        }
        if word.geometry() == Geometry::Euclidean {
            return Err(ProductError::Flat {
                word: word.word.clone(),
            });
        }
        let n = word.side_count();
        // The sphere and the hemisphere are glued the same way all round (identity, the
        // antipodal map): every turn commutes with that. A polygon's turn moves side k to
        // k + n/P and must keep the partners and the kind of gluing.
        if word.corners_per_vertex() > 2 || word.geometry() == Geometry::Hyperbolic {
            let step = n / turn as usize;
            let symmetric = n % turn as usize == 0
                && (0..n).all(|k| {
                    let (s, t) = (word.sides[k], word.sides[(k + step) % n]);
                    t.partner == (s.partner + step) % n && t.preserving == s.preserving
                });
            if !symmetric {
                return Err(ProductError::TurnNotSymmetry {
                    turn,
                    word: word.word.clone(),
                    sides: n,
                });
            }
        }
        let polygon = Arc::new(Polygon::of(&word));
        let description = format!(
            "{} ({}) times a circle of length {length}{}",
            word.common_name(),
            word.word,
            if turn > 1 {
                format!(", turned by 2π/{turn} once round it")
            } else {
                String::new()
            }
        );
        Ok(Self {
            name: name.into(),
            description,
            word,
            polygon,
            length,
            turn,
        })
    }

    /// The space's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// A one-line description.
    #[must_use]
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The surface's geometry: [`Geometry::Hyperbolic`] for H²×R, [`Geometry::Spherical`]
    /// for S²×R.
    #[must_use]
    pub fn base(&self) -> Geometry {
        self.polygon.geometry
    }

    /// `H2xR` or `S2xR`.
    #[must_use]
    pub fn geometry_name(&self) -> &'static str {
        match self.base() {
            Geometry::Hyperbolic => "H2xR",
            _ => "S2xR",
        }
    }

    /// The surface's word.
    #[must_use]
    pub fn word(&self) -> &SurfaceWord {
        &self.word
    }

    /// The surface's polygon in double-double.
    #[must_use]
    pub fn polygon(&self) -> &Polygon {
        &self.polygon
    }

    /// The circle's length `L`.
    #[must_use]
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The turn's order `P` (1: none).
    #[must_use]
    pub fn turn(&self) -> u32 {
        self.turn
    }

    /// The surface's area by Gauss–Bonnet, `2π|χ|`.
    #[must_use]
    pub fn base_area(&self) -> f64 {
        std::f64::consts::TAU * self.word.euler_characteristic().unsigned_abs() as f64
    }

    /// The volume: the surface's area times `L`.
    #[must_use]
    pub fn volume(&self) -> f64 {
        self.base_area() * self.length
    }

    /// Whether the space is orientable (the surface is; the turn preserves orientation).
    #[must_use]
    pub fn orientable(&self) -> bool {
        self.word.orientable()
    }

    /// The number of the cell's faces: the side faces, then the top and the bottom.
    #[must_use]
    pub fn face_count(&self) -> usize {
        self.side_faces().len() + 2
    }

    /// The side faces as the walk uses them: the polygon's sides, or for the hemisphere one
    /// face (the equator, every side of which is glued by the antipodal map), or none for
    /// the sphere.
    #[must_use]
    pub fn side_faces(&self) -> Vec<ExactFace> {
        let sides = &self.polygon.sides;
        if self.hemisphere() {
            let z = DoubleDouble::ZERO;
            vec![ExactFace {
                normal: [z, z, z],
                offset: DoubleDouble::new(f64::INFINITY),
                partner: 0,
                pairing: sides[0].pairing,
            }]
        } else {
            sides.clone()
        }
    }

    /// Whether the base is the hemisphere (a projective plane of S²).
    #[must_use]
    pub fn hemisphere(&self) -> bool {
        self.base() == Geometry::Spherical && self.word.corners_per_vertex() == 2
    }

    /// The unit covector of a side face in the model (`N·X ≤ 0` inside), in double-double:
    /// `(C(ρ)·n, 0, −S(ρ))` for a side at chart offset `S/C` (the equator `(0, 0, 0, −1)`).
    #[must_use]
    pub fn side_covector(&self, face: &ExactFace) -> DdVec4 {
        let one = DoubleDouble::ONE;
        if !face.offset.is_finite() {
            return DdVec4([DoubleDouble::ZERO, DoubleDouble::ZERO, DoubleDouble::ZERO, -one]);
        }
        let k = DoubleDouble::new(self.base().kappa());
        // n·x ≤ r·w with |n| = 1: scale (n, −r) to unit length in the dual form.
        let r = face.offset;
        let len = (one + k * r * r).sqrt();
        DdVec4([
            face.normal[0] / len,
            face.normal[1] / len,
            DoubleDouble::ZERO,
            -r / len,
        ])
    }

    /// The top's pairing `R⁻¹` (the bottom's is `R`), fixing `z`; the height shift is
    /// applied by the walk.
    #[must_use]
    pub fn top_pairing(&self) -> DdMat4 {
        turn(-2, i64::from(self.turn))
    }

    /// How far the model point `p` is outside the cell: the largest of the side faces'
    /// `N·X` of the unit base point and `|z| − L/2` (negative inside).
    #[must_use]
    pub fn outside_by(&self, p: DVec4) -> f64 {
        let g = self.base();
        let base = DVec4::new(p.x, p.y, 0.0, p.w);
        let norm = (g.kappa() * g.form(base, base)).abs().sqrt().max(f64::MIN_POSITIVE);
        let base = base / norm;
        self.side_faces()
            .iter()
            .map(|f| self.side_covector(f).round_f64().dot(base))
            .fold(p.z.abs() - 0.5 * self.length, f64::max)
    }

    /// The cell's centre `(0, 0, 0, 1)`.
    #[must_use]
    pub fn centre(&self) -> DVec4 {
        DVec4::W
    }
}

/// Where a ray leaves the product cell: the face (a side, [`ProductWalker::top`],
/// [`ProductWalker::bottom`] or [`super::walk::NO_FACE`] for a step without crossing) and
/// the geodesic distance to it; for a side, the ratio `num/den` of its base chart point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProductExit<R> {
    /// The face.
    pub face: usize,
    /// The distance to the exit point.
    pub distance: R,
    /// For a side: `λ·(−N·p)` and `N·v`, the base chart ratio of the exit point.
    pub ratio: Option<(R, R)>,
}

/// The product cell's faces in one precision, ready to walk rays.
#[derive(Clone, Debug)]
pub struct ProductWalker<V: Vector4> {
    /// The surface's geometry.
    pub base: Geometry,
    /// The side faces' unit covectors.
    pub covectors: Vec<V>,
    /// Their pairings (fixing `z`), rounded to this precision.
    pub pairings: Vec<V::Matrix>,
    /// What that rounding left out.
    pub pairings_lo: Vec<V::Matrix>,
    /// Each side face's partner.
    pub partners: Vec<usize>,
    /// The top's pairing `R⁻¹` and its low part.
    pub up: (V::Matrix, V::Matrix),
    /// The bottom's pairing `R` and its low part.
    pub down: (V::Matrix, V::Matrix),
    /// Half the circle's length.
    pub half_length: V::Real,
    /// Steps of at most π/4 along the surface where no face is nearer (S², whose geodesics
    /// can stay in the cell for ever).
    pub step_cap: bool,
}

/// A matrix of double-doubles rounded to `V`, and its low part.
fn rounded<V: Vector4>(m: &DdMat4) -> (V::Matrix, V::Matrix) {
    let (hi, lo) = m.parts();
    let r = V::matrix_from_f64_pair(hi, lo);
    let (h2, l2) = (*m - DdMat4::from_f64(V::matrix_to_f64(&r))).parts();
    (r, V::matrix_from_f64_pair(h2, l2))
}

impl<V: Vector4> ProductWalker<V> {
    /// The walker of a product space in the precision `V` (every number rounded once from
    /// double-double).
    #[must_use]
    pub fn new(space: &ProductSpace) -> Self {
        let sides = space.side_faces();
        let up = space.top_pairing();
        let down = super::exact::inverse(Geometry::Spherical, &up);
        let (pairings, pairings_lo) = sides.iter().map(|f| rounded::<V>(&f.pairing)).unzip();
        Self {
            base: space.base(),
            covectors: sides
                .iter()
                .map(|f| {
                    let (hi, lo) = space.side_covector(f).parts();
                    V::from_f64_pair(hi, lo)
                })
                .collect(),
            pairings,
            pairings_lo,
            partners: sides.iter().map(|f| f.partner).collect(),
            up: rounded::<V>(&up),
            down: rounded::<V>(&down),
            half_length: {
                let h = DoubleDouble::new(space.length) * DoubleDouble::new(0.5);
                V::Real::from_f64(h.hi) + V::Real::from_f64(h.lo)
            },
            step_cap: space.base() == Geometry::Spherical,
        }
    }

    /// The top face's index.
    #[must_use]
    pub fn top(&self) -> usize {
        self.covectors.len()
    }

    /// The bottom face's index.
    #[must_use]
    pub fn bottom(&self) -> usize {
        self.covectors.len() + 1
    }

    /// The surface's form on the base parts of two vectors.
    fn base_form(&self, a: V, b: V) -> V::Real {
        let k = V::Real::from_f64(self.base.kappa());
        a.component(0) * b.component(0) + a.component(1) * b.component(1) + k * a.w() * b.w()
    }

    /// The ray put back onto the model: the base point projected onto the surface, the
    /// base tangent made tangent there, the whole tangent of unit length.
    #[must_use]
    pub fn normalized(&self, ray: Ray<V>) -> Ray<V> {
        let zero = V::Real::ZERO;
        let k = V::Real::from_f64(self.base.kappa());
        let p = ray.point;
        let norm = (k * self.base_form(p, p)).abs().sqrt();
        let mut w = p.w() / norm;
        if self.base == Geometry::Hyperbolic && w < zero {
            w = -w;
        }
        let sign = if p.w() < zero && self.base == Geometry::Hyperbolic {
            -V::Real::ONE
        } else {
            V::Real::ONE
        };
        let point = V::new(
            sign * p.component(0) / norm,
            sign * p.component(1) / norm,
            p.component(2),
            w,
        );
        let v = ray.tangent;
        let vb = V::new(v.component(0), v.component(1), zero, v.w());
        let pb = V::new(point.component(0), point.component(1), zero, point.w());
        // Remove the part along p: v − (⟨p, v⟩/⟨p, p⟩) p.
        let along = self.base_form(pb, vb) / self.base_form(pb, pb);
        let vb = vb - pb.scale(along);
        let mu = v.component(2);
        let len = (self.base_form(vb, vb) + mu * mu).sqrt();
        let tangent = V::new(
            vb.component(0) / len,
            vb.component(1) / len,
            mu / len,
            vb.w() / len,
        );
        Ray { point, tangent }
    }

    /// The exit: the nearest of the side the ray's shadow meets first (the smallest
    /// positive ratio `−(N·p)/(N·v)`, as in the constant-curvature walk), the top or bottom
    /// the height reaches, and on S² a step of π/4 along the surface. `skip` is the side
    /// just entered. `None` only for a degenerate ray.
    #[must_use]
    pub fn exit(&self, ray: &Ray<V>, skip: Option<usize>) -> Option<ProductExit<V::Real>> {
        let zero = V::Real::ZERO;
        let (p, v) = (ray.point, ray.tangent);
        let vb = V::new(v.component(0), v.component(1), zero, v.w());
        let lambda = self.base_form(vb, vb).max(zero).sqrt();
        let mu = v.component(2);
        if !(lambda.is_finite() && mu.is_finite()) || lambda == zero && mu == zero {
            return None;
        }
        let mut best: Option<ProductExit<V::Real>> = None;
        let mut consider = |e: ProductExit<V::Real>| {
            if best.is_none_or(|b| e.distance < b.distance) {
                best = Some(e);
            }
        };
        if lambda > zero {
            let mut side: Option<(usize, V::Real, V::Real)> = None;
            for (f, n) in self.covectors.iter().enumerate() {
                if Some(f) == skip {
                    continue;
                }
                let den = n.dot(v);
                if !(den > zero) {
                    continue;
                }
                let num = (-n.dot(p)).max(zero);
                if side.is_none_or(|(_, bn, bd)| num * bd < bn * den) {
                    side = Some((f, num, den));
                }
            }
            if let Some((f, num, den)) = side {
                let num = lambda * num;
                // In H² a shadow whose ratio reaches 1 never meets the side's line.
                let reaches = self.base != Geometry::Hyperbolic || num < den;
                if reaches {
                    let s = self.base.distance_from_ratio(num, den);
                    consider(ProductExit {
                        face: f,
                        distance: s / lambda,
                        ratio: Some((num, den)),
                    });
                }
            }
            if self.step_cap {
                let quarter = V::Real::from_f64(std::f64::consts::FRAC_PI_4);
                consider(ProductExit {
                    face: super::walk::NO_FACE,
                    distance: quarter / lambda,
                    ratio: None,
                });
            }
        }
        if mu > zero {
            consider(ProductExit {
                face: self.top(),
                distance: ((self.half_length - p.component(2)) / mu).max(zero),
                ratio: None,
            });
        } else if mu < zero {
            consider(ProductExit {
                face: self.bottom(),
                distance: ((-self.half_length - p.component(2)) / mu).max(zero),
                ratio: None,
            });
        }
        best
    }

    /// The ray moved by `t` along its geodesic, not normalized.
    fn moved(&self, ray: &Ray<V>, t: V::Real, ratio: Option<(V::Real, V::Real)>) -> Ray<V> {
        let zero = V::Real::ZERO;
        let one = V::Real::ONE;
        let k = V::Real::from_f64(self.base.kappa());
        let (p, v) = (ray.point, ray.tangent);
        let pb = V::new(p.component(0), p.component(1), zero, p.w());
        let vb = V::new(v.component(0), v.component(1), zero, v.w());
        let lambda = self.base_form(vb, vb).max(zero).sqrt();
        let mu = v.component(2);
        // C and S of the surface distance λt: from the side's ratio T = S/C exactly, so the
        // point lands on the side's line, else from t.
        let (c, s) = match ratio {
            Some((num, den)) => {
                let tt = num / den;
                let c = one / (one + k * tt * tt).sqrt();
                (c, tt * c)
            }
            None => match self.base {
                Geometry::Spherical => (lambda * t).cos_sin(),
                _ => (lambda * t).cosh_sinh(),
            },
        };
        let (pb2, vb2) = if lambda > zero {
            (
                pb.scale(c) + vb.scale(s / lambda),
                pb.scale(-k * lambda * s) + vb.scale(c),
            )
        } else {
            (pb, vb)
        };
        Ray {
            point: V::new(
                pb2.component(0),
                pb2.component(1),
                p.component(2) + mu * t,
                pb2.w(),
            ),
            tangent: V::new(vb2.component(0), vb2.component(1), mu, vb2.w()),
        }
    }

    /// Applies a pairing (compensated) to a point or tangent.
    fn apply(&self, (hi, lo): (&V::Matrix, &V::Matrix), x: V) -> V {
        V::transform_compensated(hi, lo, x)
    }

    /// Crosses the exit face: moves to it, applies its pairing, and for the top and bottom
    /// shifts the height by ∓L (set exactly to the opposite slice). Returns the new ray and
    /// the distance walked.
    #[must_use]
    pub fn cross(&self, ray: &Ray<V>, exit: &ProductExit<V::Real>) -> (Ray<V>, V::Real) {
        let at = self.moved(ray, exit.distance, exit.ratio);
        let h = self.half_length;
        let with_z = |x: V, z: V::Real| V::new(x.component(0), x.component(1), z, x.w());
        let next = if exit.face == self.top() {
            let m = (&self.up.0, &self.up.1);
            Ray {
                point: with_z(self.apply(m, at.point), -h),
                tangent: self.apply(m, at.tangent),
            }
        } else if exit.face == self.bottom() {
            let m = (&self.down.0, &self.down.1);
            Ray {
                point: with_z(self.apply(m, at.point), h),
                tangent: self.apply(m, at.tangent),
            }
        } else if exit.face < self.covectors.len() {
            let m = (&self.pairings[exit.face], &self.pairings_lo[exit.face]);
            Ray {
                point: self.apply(m, at.point),
                tangent: self.apply(m, at.tangent),
            }
        } else {
            at
        };
        (self.normalized(next), exit.distance)
    }

    /// The side face to skip after crossing `exit` (the partner entered through).
    #[must_use]
    pub fn entered(&self, exit: &ProductExit<V::Real>) -> Option<usize> {
        (exit.face < self.covectors.len()).then(|| self.partners[exit.face])
    }

    /// Walks a ray through the cell until the limit, handing each crossing to `visit`
    /// (`false` stops). Returns where it stopped and the distance walked.
    pub fn walk(
        &self,
        start: Ray<V>,
        limit: Limit,
        mut visit: impl FnMut(&Crossing<V>) -> bool,
    ) -> (Ray<V>, f64) {
        let mut ray = self.normalized(start);
        let mut count = 0usize;
        let mut distance = 0.0;
        let mut skip = None;
        let mut steps = 0usize;
        let max_crossings = match limit {
            Limit::Crossings(n) => n,
            Limit::Distance(_) => usize::MAX,
        };
        while count < max_crossings {
            let Some(exit) = self.exit(&ray, skip) else {
                break;
            };
            let length = exit.distance.to_f64();
            if let Limit::Distance(d) = limit
                && distance + length >= d
            {
                let rest = V::Real::from_f64(d - distance);
                return (self.normalized(self.moved(&ray, rest, None)), d);
            }
            let (next, _) = self.cross(&ray, &exit);
            distance += length;
            ray = next;
            skip = self.entered(&exit);
            if exit.face == super::walk::NO_FACE {
                steps += 1;
                if matches!(limit, Limit::Crossings(_)) && steps >= MAX_STEPS_WITHOUT_CROSSING {
                    break;
                }
                continue;
            }
            steps = 0;
            count += 1;
            if !visit(&Crossing {
                face: exit.face,
                distance,
                ray,
            }) {
                break;
            }
        }
        (ray, distance)
    }

    /// Traces a ray until the limit, recording each crossing.
    #[must_use]
    pub fn trace(&self, start: Ray<V>, limit: Limit) -> Trace<V> {
        let mut crossings = Vec::new();
        let (end, distance) = self.walk(start, limit, |c| {
            crossings.push(*c);
            true
        });
        Trace {
            crossings,
            end,
            distance,
        }
    }
}

/// A ray from the centre with unit chart direction `d`: base speed `|d.xy|`, fibre speed
/// `d.z` (the convention of the product spaces' CLI and tests).
#[must_use]
pub fn ray_from_centre(d: glam::DVec3) -> Ray<DVec4> {
    let d = d.normalize();
    Ray {
        point: DVec4::W,
        tangent: DVec4::new(d.x, d.y, d.z, 0.0),
    }
}

/// A ray at the chart point `x = (x/w, y/w, z)` with chart direction `d`: the base part of
/// the direction is taken along the surface's chart (straight lines are geodesics there)
/// and the height part along the fibre, each at the speed the chart says, then the tangent
/// is scaled to unit length.
pub fn chart_ray(base: Geometry, x: glam::DVec3, d: glam::DVec3) -> Result<Ray<DVec4>, String> {
    let g = base;
    let p = g
        .from_chart(glam::DVec3::new(x.x, x.y, 0.0))
        .map_err(|e| e.to_string())?;
    if !(d.is_finite() && d.length() > 0.0 && x.z.is_finite()) {
        return Err(format!("direction {d:?} or height {} is not usable", x.z));
    }
    let vb = g
        .tangent_from_chart(p, glam::DVec3::new(d.x, d.y, 0.0))
        .ok();
    let horizontal = glam::DVec2::new(d.x, d.y).length() / d.length();
    let vertical = d.z / d.length();
    let tangent = match vb {
        Some(v) => v * horizontal + DVec4::Z * vertical,
        None => DVec4::Z * vertical.signum(),
    };
    Ok(Ray {
        point: DVec4::new(p.x, p.y, x.z, p.w),
        tangent,
    })
}
