//! The walk through a Nil cell: the box `|x|, |y| ≤ ½`, `|z| ≤ h` (`h = 1/2K`) of the
//! quotient by `Γ_K = ⟨A, B, C⟩` (`A = (1, 0, 0)`, `B = (0, 1, 0)`, `C = (0, 0, 1/K)`,
//! acting by left multiplication), in any precision, over the walk contract
//! ([`CellWalk`]).
//!
//! A ray is a chart point `(x, y, z, 1)` and a unit body velocity `(u₁, u₂, u₃, 0)`. Its
//! exit is the first of the six faces it meets ([`super::exit`]: the four sides in closed
//! form, the top and bottom bracketed and refined, before the first side). Leaving through
//! a side applies `A⁻¹`, `A`, `B⁻¹` or `B` and then the power of the centre `C` that brings
//! the height back into `[−h, h]` (`A⁻¹` moves `(½, y, z)` to `(−½, y, z − y/2)`: the sides
//! are paired piecewise, the piece chosen by where the ray crosses); leaving through the
//! top applies `C⁻¹`, through the bottom `C`. A left translation keeps the body velocity,
//! so a crossing moves only the point; the face's own coordinate is set to the partner
//! face's exactly, so the walk never drifts out of the box.

use super::exit::{horizontal_exit, vertical_exit};
use super::flow::{NilRay, flow, group_product};
use crate::geometry::{Ray, Real, Vector4};
use crate::space::walk::{CellWalk, NextExit};

/// The faces of the box, in order: `x = ½`, `x = −½`, `y = ½`, `y = −½`, `z = h`, `z = −h`.
pub const NIL_FACES: usize = 6;

/// Where a ray leaves the box: the face and the time to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NilExit<R> {
    /// The face left through (see [`NIL_FACES`]).
    pub face: usize,
    /// The geodesic length to the exit.
    pub t: R,
}

/// The box of `nil-K` in the precision `V`, ready to walk rays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NilWalker<V: Vector4> {
    /// The lattice's `K` (`C = (0, 0, 1/K)`, `[A, B] = C^K`).
    pub k: u32,
    /// Half the box's height, `1/2K`.
    pub h: V::Real,
}

impl<V: Vector4> NilWalker<V> {
    /// The walker of `nil-K` (`k ≥ 1`).
    #[must_use]
    pub fn new(k: u32) -> Self {
        Self {
            k,
            h: V::Real::ONE / V::Real::from_f64(2.0 * f64::from(k.max(1))),
        }
    }

    /// A ray of the walk as the flow's (point and body velocity).
    fn nil_ray(ray: &Ray<V>) -> NilRay<V::Real> {
        NilRay {
            point: [0, 1, 2].map(|i| ray.point.component(i)),
            velocity: [0, 1, 2].map(|i| ray.tangent.component(i)),
        }
    }

    /// A flow ray as a ray of the walk.
    fn ray_of(r: &NilRay<V::Real>) -> Ray<V> {
        let (zero, one) = (V::Real::ZERO, V::Real::ONE);
        Ray {
            point: V::new(r.point[0], r.point[1], r.point[2], one),
            tangent: V::new(r.velocity[0], r.velocity[1], r.velocity[2], zero),
        }
    }

    /// The first exit of `ray`; `None` only for a degenerate ray.
    ///
    /// No face is skipped: a Nil geodesic can meet a plane twice (its shadow is a circle),
    /// so the face just entered may be the next one left. Its crossing at the start is no
    /// exit: a start on a side moving inwards has no near root there, and one on the top
    /// or bottom has none in the first stretch where its height is monotone.
    #[must_use]
    pub fn exit(&self, ray: &Ray<V>) -> Option<NilExit<V::Real>> {
        let r = Self::nil_ray(ray);
        let half = V::Real::from_f64(0.5);
        let (one, zero) = (V::Real::ONE, V::Real::ZERO);
        let sides = [
            ([one, zero], 0),
            ([-one, zero], 1),
            ([zero, one], 2),
            ([zero, -one], 3),
        ];
        let mut best: Option<NilExit<V::Real>> = None;
        for (n, face) in sides {
            if let Some(t) = vertical_exit(&r, n, half)
                && best.is_none_or(|b| t < b.t)
            {
                best = Some(NilExit { face, t });
            }
        }
        let before = best.map_or(V::Real::from_f64(f64::INFINITY), |b| b.t);
        for (height, face) in [(self.h, 4), (-self.h, 5)] {
            if let Some(t) = horizontal_exit(&r, height, before)
                && best.is_none_or(|b| t < b.t)
            {
                best = Some(NilExit { face, t });
            }
        }
        best.filter(|b| b.t.is_finite())
    }

    /// The element of `Γ_K` a ray leaving through `face` at the chart point `p` is carried
    /// by: the side's generator, then the power of `C` that brings the height back into
    /// `[−h, h]`.
    #[must_use]
    pub fn pairing(&self, face: usize, p: [V::Real; 3]) -> [V::Real; 3] {
        let (one, zero) = (V::Real::ONE, V::Real::ZERO);
        let c = V::Real::from_f64(2.0) * self.h;
        let generator = match face {
            0 => [-one, zero, zero],
            1 => [one, zero, zero],
            2 => [zero, -one, zero],
            3 => [zero, one, zero],
            4 => return [zero, zero, -c],
            _ => return [zero, zero, c],
        };
        let moved = group_product(generator, p);
        // C^m with m = −round(z / 2h): the height into [−h, h].
        let m = -(moved[2] / c).to_f64().round();
        group_product([zero, zero, c * V::Real::from_f64(m)], generator)
    }

    /// The partner of a face (the one a crossing enters through).
    #[must_use]
    pub fn partner(face: usize) -> usize {
        face ^ 1
    }
}

impl<V: Vector4> CellWalk<V> for NilWalker<V> {
    type Exit = NilExit<V::Real>;

    fn on_model(&self, ray: Ray<V>) -> Ray<V> {
        let r = Self::nil_ray(&ray);
        let [a, b, c] = r.velocity;
        let n = (a * a + b * b + c * c).sqrt();
        Self::ray_of(&NilRay {
            point: r.point,
            velocity: if n > V::Real::ZERO {
                [a / n, b / n, c / n]
            } else {
                r.velocity
            },
        })
    }

    fn next_exit(&self, ray: &Ray<V>, _skip: Option<usize>, _steps: usize) -> NextExit<Self::Exit> {
        match self.exit(ray) {
            Some(exit) => NextExit::Exit(exit),
            None => NextExit::Degenerate,
        }
    }

    fn exit_face(exit: &Self::Exit) -> usize {
        exit.face
    }

    fn exit_length(&self, exit: &Self::Exit) -> f64 {
        exit.t.to_f64()
    }

    fn through(&self, ray: &Ray<V>, exit: &Self::Exit) -> Ray<V> {
        let mut at = flow(&Self::nil_ray(ray), exit.t);
        // On the face exactly.
        let half = V::Real::from_f64(0.5);
        match exit.face {
            0 => at.point[0] = half,
            1 => at.point[0] = -half,
            2 => at.point[1] = half,
            3 => at.point[1] = -half,
            4 => at.point[2] = self.h,
            _ => at.point[2] = -self.h,
        }
        let g = self.pairing(exit.face, at.point);
        let mut point = group_product(g, at.point);
        // On the partner face exactly, and within the box's height.
        match exit.face {
            0 => point[0] = -half,
            1 => point[0] = half,
            2 => point[1] = -half,
            3 => point[1] = half,
            4 => point[2] = -self.h,
            _ => point[2] = self.h,
        }
        point[2] = point[2].max(-self.h).min(self.h);
        Self::ray_of(&NilRay {
            point,
            velocity: at.velocity,
        })
    }

    fn moved_by(&self, ray: &Ray<V>, t: f64) -> Ray<V> {
        Self::ray_of(&flow(&Self::nil_ray(ray), V::Real::from_f64(t)))
    }

    fn skip_after(&self, exit: &Self::Exit) -> Option<usize> {
        Some(Self::partner(exit.face))
    }
}
