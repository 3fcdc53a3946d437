//! The exact walk through a product cell (see the module above for the model).

use super::ProductSpace;
use crate::geometry::{DoubleDouble, Geometry, Ray, Real, Vector4};
use crate::space::walk::{
    CellWalk, Crossing, Limit, MAX_STEPS_WITHOUT_CROSSING, NO_FACE, NextExit, Trace,
    rounded_with_rest,
};

/// Where a ray leaves the product cell: the face (a side, [`ProductWalker::top`],
/// [`ProductWalker::bottom`] or [`NO_FACE`] for a step without crossing) and
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

impl<V: Vector4> ProductWalker<V> {
    /// The walker of a product space in the precision `V` (every number rounded once from
    /// double-double).
    #[must_use]
    pub fn new(space: &ProductSpace) -> Self {
        let sides = space.side_faces();
        let up = space.top_pairing();
        let down = crate::space::exact::inverse(Geometry::Spherical, &up);
        let (pairings, pairings_lo) = sides
            .iter()
            .map(|f| rounded_with_rest::<V>(&f.pairing))
            .unzip();
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
            up: rounded_with_rest::<V>(&up),
            down: rounded_with_rest::<V>(&down),
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

    /// `⟨v, v⟩` of a surface tangent `v` at the surface point `p`. In H² the form
    /// `vx² + vy² − vw²` of a tangent at a far point cancels (its entries are of size
    /// `cosh d`), and in the product that error would tilt the ray between the surface and
    /// the fibre; with `vw = (px vx + py vy)/pw` and Lagrange's identity it is the sum of
    /// squares `(vx² + vy² + (px vy − py vx)²)/pw²`.
    fn speed_squared(&self, p: V, v: V) -> V::Real {
        match self.base {
            Geometry::Hyperbolic => {
                let (px, py, pw) = (p.component(0), p.component(1), p.w());
                let (vx, vy) = (v.component(0), v.component(1));
                let cross = px * vy - py * vx;
                (vx * vx + vy * vy + cross * cross) / (pw * pw)
            }
            _ => self.base_form(v, v),
        }
    }

    /// The ray put back onto the model: the base point projected onto the surface, the
    /// base tangent made tangent there, the whole tangent of unit length. A ray already on
    /// the model to rounding is kept bit for bit: projecting divides by a form that is
    /// known only to `ε·w²` at a point of size `w`, which would add more error than it
    /// removes (as in the constant-curvature walk).
    #[must_use]
    pub fn normalized(&self, ray: Ray<V>) -> Ray<V> {
        let zero = V::Real::ZERO;
        let one = V::Real::ONE;
        let k = V::Real::from_f64(self.base.kappa());
        let p = ray.point;
        {
            let tolerance = V::Real::from_f64(64.0) * V::Real::EPSILON;
            let w = p.w().abs().max(one);
            let scaled = tolerance * w * w;
            let v = ray.tangent;
            let vb = V::new(v.component(0), v.component(1), zero, v.w());
            let on_model = (k * self.base_form(p, p) - one).abs() <= scaled
                && (self.base != Geometry::Hyperbolic || p.w() > zero);
            let tangent = self.base_form(p, vb).abs() <= scaled;
            let mu = v.component(2);
            let unit = (self.speed_squared(p, vb) + mu * mu - one).abs() <= tolerance;
            if on_model && tangent && unit {
                return ray;
            }
        }
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
        let len = (self.speed_squared(point, vb) + mu * mu).sqrt();
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
        self.exit_stepping(ray, skip, self.step_cap)
    }

    /// [`ProductWalker::exit`], with the steps of π/4 along the surface or without them.
    /// A walk needs them only where sides can be met (the ratio finds a side within π/2
    /// of arc); a tracer also wants them on the sphere, for its searches along the ray.
    fn exit_stepping(
        &self,
        ray: &Ray<V>,
        skip: Option<usize>,
        stepping: bool,
    ) -> Option<ProductExit<V::Real>> {
        let zero = V::Real::ZERO;
        let (p, v) = (ray.point, ray.tangent);
        let (lambda, mu) = self.speeds(ray)?;
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
            if stepping {
                let quarter = V::Real::from_f64(std::f64::consts::FRAC_PI_4);
                consider(ProductExit {
                    face: NO_FACE,
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
        let k = V::Real::from_f64(self.base.kappa());
        let (p, v) = (ray.point, ray.tangent);
        let pb = V::new(p.component(0), p.component(1), zero, p.w());
        let vb = V::new(v.component(0), v.component(1), zero, v.w());
        let lambda = self.speed_squared(p, vb).max(zero).sqrt();
        let mu = v.component(2);
        // C and S of the surface distance λt: from the side's ratio T = S/C exactly, so the
        // point lands on the side's line, else from t.
        let (c, s) = match ratio {
            // C = den/f, S = num/f with f² = den² + κ num², factored in H² as
            // (den − num)(den + num): computing 1 − T² after the division would lose
            // digits like e^(2s) for a far side.
            Some((num, den)) => {
                let f = match self.base {
                    Geometry::Hyperbolic => ((den - num) * (den + num)).max(zero).sqrt(),
                    _ => (den * den + num * num).sqrt(),
                };
                (den / f, num / f)
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
        // The pairings move the surface and keep the height: they are applied to the base
        // point alone and the height set after. (Through the matrix, a height past about
        // 1e300 made the compensated product's splitting overflow, and its NaN reached
        // every component through the zero entries.)
        let base = |m: (&V::Matrix, &V::Matrix), z: V::Real| {
            with_z(self.apply(m, with_z(at.point, V::Real::ZERO)), z)
        };
        let next = if exit.face == self.top() {
            let m = (&self.up.0, &self.up.1);
            Ray {
                point: base(m, -h),
                tangent: self.apply(m, at.tangent),
            }
        } else if exit.face == self.bottom() {
            let m = (&self.down.0, &self.down.1);
            Ray {
                point: base(m, h),
                tangent: self.apply(m, at.tangent),
            }
        } else if exit.face < self.covectors.len() {
            let m = (&self.pairings[exit.face], &self.pairings_lo[exit.face]);
            Ray {
                point: base(m, at.point.component(2)),
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

    /// Walks a ray through the cell until the limit ([`CellWalk::walk`], the one walk loop).
    ///
    /// It never gives up on a ray that will cross a face: on a sphere with no sides it goes
    /// straight to the top or bottom, however long the circle; with sides it steps by π/4
    /// along the surface (a side comes within π of arc), and after
    /// [`MAX_STEPS_WITHOUT_CROSSING`] steps without one (a ray along a side's great circle)
    /// it goes straight to the top or bottom too. It ends early, short of its limit, only
    /// for a ray that meets no face ever again: one with no vertical speed that no side
    /// stops. A caller tells this from the crossings it was handed and the distance.
    pub fn walk(
        &self,
        start: Ray<V>,
        limit: Limit,
        visit: impl FnMut(&Crossing<V>) -> bool,
    ) -> (Ray<V>, f64) {
        CellWalk::walk(self, start, limit, visit)
    }

    /// Traces a ray until the limit, recording each crossing ([`CellWalk::trace`]).
    #[must_use]
    pub fn trace(&self, start: Ray<V>, limit: Limit) -> Trace<V> {
        CellWalk::trace(self, start, limit)
    }

    /// The ray's speeds `(λ, μ)` along the surface and along the circle; `None` for a ray
    /// with no direction to walk (a speed not finite, or both zero).
    fn speeds(&self, ray: &Ray<V>) -> Option<(V::Real, V::Real)> {
        let zero = V::Real::ZERO;
        let v = ray.tangent;
        let vb = V::new(v.component(0), v.component(1), zero, v.w());
        let lambda = self.speed_squared(ray.point, vb).max(zero).sqrt();
        let mu = v.component(2);
        let degenerate = !(lambda.is_finite() && mu.is_finite()) || lambda == zero && mu == zero;
        (!degenerate).then_some((lambda, mu))
    }
}

impl<V: Vector4> CellWalk<V> for ProductWalker<V> {
    type Exit = ProductExit<V::Real>;

    fn on_model(&self, ray: Ray<V>) -> Ray<V> {
        self.normalized(ray)
    }

    /// Steps of π/4 only where sides can be met, and none after
    /// [`MAX_STEPS_WITHOUT_CROSSING`] in a row (the ray runs along a side's great circle).
    fn next_exit(&self, ray: &Ray<V>, skip: Option<usize>, steps: usize) -> NextExit<Self::Exit> {
        let stepping =
            self.step_cap && !self.covectors.is_empty() && steps < MAX_STEPS_WITHOUT_CROSSING;
        match self.exit_stepping(ray, skip, stepping) {
            Some(exit) => NextExit::Exit(exit),
            None if self.speeds(ray).is_none() => NextExit::Degenerate,
            None => NextExit::NoFaceAhead,
        }
    }

    fn exit_face(exit: &Self::Exit) -> usize {
        exit.face
    }

    fn exit_length(&self, exit: &Self::Exit) -> f64 {
        exit.distance.to_f64()
    }

    fn through(&self, ray: &Ray<V>, exit: &Self::Exit) -> Ray<V> {
        self.cross(ray, exit).0
    }

    fn moved_by(&self, ray: &Ray<V>, t: f64) -> Ray<V> {
        self.normalized(self.moved(ray, V::Real::from_f64(t), None))
    }

    fn skip_after(&self, exit: &Self::Exit) -> Option<usize> {
        self.entered(exit)
    }
}
