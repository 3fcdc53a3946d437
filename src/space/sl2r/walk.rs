//! The walk through the cell of `UT Σ`: the polygon times the whole fibre, in any precision,
//! over the walk contract ([`CellWalk`]).
//!
//! A ray of the walk packs the frame `(e, e⊥, p)` and the body velocity `(a, b, c)` into
//! the contract's two 4-vectors: the point `(p_x, p_y, p_w, e_x)` and the tangent
//! `(e_y, a, b, c)`; `e_w = (e_x p_x + e_y p_y)/p_w` (`e` is tangent at `p`) and
//! `e⊥ = J(p × e)` are derived ([`super::flow::on_model`]). Its exit is the first side the
//! base point leaves through ([`super::exit::side_exit`], in closed form); crossing it
//! applies the side's pairing to the frame (a left translation keeps the body velocity).
//! No side is skipped after a crossing: the base point moves on a circle, horocycle or
//! hypercycle, which may cross the side it came in by a second time; at the start it is
//! entering there, so that crossing is no exit.

use super::exit::side_exit;
use super::flow::{Sl2rRay, flow, moved_by, on_model};
use super::space::UnitTangentSpace;
use crate::geometry::{DoubleDouble, Ray, Real, Vector4};
use crate::space::walk::{CellWalk, NextExit};

/// Where a ray leaves the cell: the side and the time to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sl2rExit<R> {
    /// The side left through.
    pub face: usize,
    /// The geodesic length to the exit.
    pub t: R,
}

/// A side of the cell in the walker's precision.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Side<R> {
    normal: [R; 3],
    pairing: [[R; 3]; 3],
    partner: usize,
}

/// The cell of a unit tangent bundle in the precision `V`, ready to walk rays.
#[derive(Clone, Debug, PartialEq)]
pub struct Sl2rWalker<V: Vector4> {
    sides: Vec<Side<V::Real>>,
}

/// A double-double in the precision `R` (the nearest `f64` or `f32` of its sum).
fn real<R: Real>(x: DoubleDouble) -> R {
    R::from_f64(x.hi) + R::from_f64(x.lo)
}

impl<V: Vector4> Sl2rWalker<V> {
    /// The walker of `space`.
    #[must_use]
    pub fn new(space: &UnitTangentSpace) -> Self {
        Self {
            sides: space
                .sides()
                .iter()
                .map(|s| Side {
                    normal: s.normal.map(real),
                    pairing: s.pairing.map(|row| row.map(real)),
                    partner: s.partner,
                })
                .collect(),
        }
    }

    /// A ray of the walk as the flow's (frame and body velocity).
    #[must_use]
    pub fn sl2r_ray(ray: &Ray<V>) -> Sl2rRay<V::Real> {
        let c = |v: V, i| v.component(i);
        let p = [c(ray.point, 0), c(ray.point, 1), c(ray.point, 2)];
        let (ex, ey) = (c(ray.point, 3), c(ray.tangent, 0));
        let e = [ex, ey, (ex * p[0] + ey * p[1]) / p[2]];
        let f = [
            p[1] * e[2] - p[2] * e[1],
            p[2] * e[0] - p[0] * e[2],
            -(p[0] * e[1] - p[1] * e[0]),
        ];
        Sl2rRay {
            frame: [e, f, p],
            velocity: [c(ray.tangent, 1), c(ray.tangent, 2), c(ray.tangent, 3)],
        }
    }

    /// A flow ray as a ray of the walk.
    #[must_use]
    pub fn ray_of(r: &Sl2rRay<V::Real>) -> Ray<V> {
        let [e, _, p] = r.frame;
        let [a, b, c] = r.velocity;
        Ray {
            point: V::new(p[0], p[1], p[2], e[0]),
            tangent: V::new(e[1], a, b, c),
        }
    }

    /// The first exit of `ray` (the side `entered` just crossed into: no exit at its
    /// start); `None` where the base point stays in the polygon for ever (a small circle).
    #[must_use]
    pub fn exit(&self, ray: &Ray<V>, entered: Option<usize>) -> Option<Sl2rExit<V::Real>> {
        let r = Self::sl2r_ray(ray);
        let mut best: Option<Sl2rExit<V::Real>> = None;
        for (face, side) in self.sides.iter().enumerate() {
            let Some(t) = side_exit(&r, side.normal) else {
                continue;
            };
            if entered == Some(face) && t == V::Real::ZERO {
                continue;
            }
            if best.is_none_or(|b| t < b.t) {
                best = Some(Sl2rExit { face, t });
            }
        }
        best
    }
}

impl<V: Vector4> CellWalk<V> for Sl2rWalker<V> {
    type Exit = Sl2rExit<V::Real>;

    fn on_model(&self, ray: Ray<V>) -> Ray<V> {
        Self::ray_of(&on_model(&Self::sl2r_ray(&ray)))
    }

    fn next_exit(&self, ray: &Ray<V>, skip: Option<usize>, _steps: usize) -> NextExit<Self::Exit> {
        let r = Self::sl2r_ray(ray);
        if !r
            .velocity
            .iter()
            .chain(r.frame.iter().flatten())
            .all(|x| x.is_finite())
        {
            return NextExit::Degenerate;
        }
        match self.exit(ray, skip) {
            Some(exit) => NextExit::Exit(exit),
            None => NextExit::NoFaceAhead,
        }
    }

    fn exit_face(exit: &Self::Exit) -> usize {
        exit.face
    }

    fn exit_length(&self, exit: &Self::Exit) -> f64 {
        exit.t.to_f64()
    }

    fn through(&self, ray: &Ray<V>, exit: &Self::Exit) -> Ray<V> {
        let at = flow(&Self::sl2r_ray(ray), exit.t);
        let moved = moved_by(&self.sides[exit.face].pairing, &at);
        Self::ray_of(&on_model(&moved))
    }

    fn moved_by(&self, ray: &Ray<V>, t: f64) -> Ray<V> {
        let at = flow(&Self::sl2r_ray(ray), V::Real::from_f64(t));
        Self::ray_of(&on_model(&at))
    }

    fn skip_after(&self, exit: &Self::Exit) -> Option<usize> {
        Some(self.sides[exit.face].partner)
    }
}
