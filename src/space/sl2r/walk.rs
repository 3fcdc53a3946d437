//! The walk through the cell of `UT Σ`: the polygon times the whole fibre, in any precision,
//! over the walk contract ([`CellWalk`]).
//!
//! A ray of the walk packs the frame `(e, e⊥, p)`, the body velocity `(a, b, c)` and the
//! fibre cover's sheet `k` into the contract's two 4-vectors: the point `(p_x, p_y, k, e_x)`
//! and the tangent `(e_y, a, b, c)`; `p_w = √(1 + p_x² + p_y²)`,
//! `e_w = (e_x p_x + e_y p_y)/p_w` (`e` is tangent at `p`) and `e⊥ = J(p × e)` are derived
//! ([`super::flow::on_model`]). In a fibre cover the walk counts the sheets climbed along
//! each stretch and through each side ([`super::cover`]); in `UT Σ` the sheet stays 0. Its exit is the first side the
//! base point leaves through ([`super::exit::side_exit`], in closed form); crossing it
//! applies the side's pairing to the frame (a left translation keeps the body velocity).
//! No side is skipped after a crossing: the base point moves on a circle, horocycle or
//! hypercycle, which may cross the side it came in by a second time; at the start it is
//! entering there, so that crossing is no exit.

use super::exit::side_exit;
use super::flow::{Sl2rRay, flow, on_model, perp, tangent_w};
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

/// A side of the cell in the walker's precision: its pairing as the nearest matrix and what
/// that leaves out (zero in double-double), applied by compensated sums.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Side<R> {
    normal: [R; 3],
    pairing: [[R; 3]; 3],
    pairing_lo: [[R; 3]; 3],
    partner: usize,
}

/// What rounding `x` to `R` left out, in `R` (zero where `R` holds all of it).
fn rest<R: Real>(x: DoubleDouble) -> R {
    if R::EPSILON.to_f64() < f64::EPSILON {
        return R::ZERO;
    }
    let held = real::<R>(x).to_f64();
    R::from_f64((x - DoubleDouble::new(held)).to_f64())
}

/// `(hi + lo)·v` by compensated dot products (each row's products and sums with their
/// rounding errors kept, and `lo`'s share added): as if in twice the precision. The
/// pairings' entries reach `cosh 2ρ` while the frame's stay near `cosh R`, so a plain
/// product would lose about a tenth of the digits to cancellation and rounded entries.
fn apply_compensated<R: Real>(hi: &[[R; 3]; 3], lo: &[[R; 3]; 3], v: [R; 3]) -> [R; 3] {
    [0, 1, 2].map(|r| {
        let (mut sum, mut carry) = (R::ZERO, R::ZERO);
        for k in 0..3 {
            let (p, e) = hi[r][k].two_prod(v[k]);
            let (s, e2) = sum.two_sum(p);
            sum = s;
            carry = carry + e + e2 + lo[r][k] * v[k];
        }
        sum + carry
    })
}

/// The cell of a unit tangent bundle in the precision `V`, ready to walk rays.
#[derive(Clone, Debug, PartialEq)]
pub struct Sl2rWalker<V: Vector4> {
    sides: Vec<Side<V::Real>>,
    /// The space, kept for a fibre cover's sheet counts (`None` for `UT Σ`).
    cover: Option<Box<UnitTangentSpace>>,
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
                    pairing_lo: s.pairing.map(|row| row.map(rest)),
                    partner: s.partner,
                })
                .collect(),
            cover: (space.sheets() > 1).then(|| Box::new(space.clone())),
        }
    }

    /// The fibre cover's degree `N` (1 for `UT Σ`).
    #[must_use]
    pub fn sheets(&self) -> u32 {
        self.cover.as_ref().map_or(1, |s| s.sheets())
    }

    /// The sheet a ray of the walk is on.
    #[must_use]
    pub fn sheet_of(ray: &Ray<V>) -> u32 {
        let k = ray.point.component(2).to_f64().round();
        if k >= 0.0 && k < f64::from(u32::MAX) {
            k as u32
        } else {
            0
        }
    }

    /// A flow ray on the sheet `sheet` as a ray of the walk.
    #[must_use]
    pub fn ray_on_sheet(r: &Sl2rRay<V::Real>, sheet: u32) -> Ray<V> {
        let [e, _, p] = r.frame;
        let [a, b, c] = r.velocity;
        Ray {
            point: V::new(p[0], p[1], V::Real::from_f64(f64::from(sheet)), e[0]),
            tangent: V::new(e[1], a, b, c),
        }
    }

    /// The sheet after `ray` moved `t` along its geodesic to the frame `end`.
    fn sheet_after(
        &self,
        ray: &Ray<V>,
        r: &Sl2rRay<V::Real>,
        t: V::Real,
        end: &Sl2rRay<V::Real>,
    ) -> u32 {
        let sheet = Self::sheet_of(ray);
        match &self.cover {
            None => sheet,
            Some(space) => {
                let climbed = super::cover::sheets_climbed(r, t, &end.frame).unwrap_or(0);
                super::cover::sheet_plus(sheet, climbed, space.sheets())
            }
        }
    }

    /// A ray of the walk as the flow's (frame and body velocity).
    #[must_use]
    pub fn sl2r_ray(ray: &Ray<V>) -> Sl2rRay<V::Real> {
        let c = |v: V, i| v.component(i);
        let (x, y) = (c(ray.point, 0), c(ray.point, 1));
        let p = [x, y, (V::Real::ONE + x * x + y * y).sqrt()];
        let (ex, ey) = (c(ray.point, 3), c(ray.tangent, 0));
        let e = [ex, ey, tangent_w(p, ex, ey)];
        let f = perp(p, e);
        Sl2rRay {
            frame: [e, f, p],
            velocity: [c(ray.tangent, 1), c(ray.tangent, 2), c(ray.tangent, 3)],
        }
    }

    /// A flow ray as a ray of the walk, on the first sheet.
    #[must_use]
    pub fn ray_of(r: &Sl2rRay<V::Real>) -> Ray<V> {
        Self::ray_on_sheet(r, 0)
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
        Self::ray_on_sheet(&on_model(&Self::sl2r_ray(&ray)), Self::sheet_of(&ray))
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
        let r = Self::sl2r_ray(ray);
        let at = flow(&r, exit.t);
        let side = &self.sides[exit.face];
        let moved = on_model(&Sl2rRay {
            frame: at
                .frame
                .map(|v| apply_compensated(&side.pairing, &side.pairing_lo, v)),
            velocity: at.velocity,
        });
        let mut sheet = self.sheet_after(ray, &r, exit.t, &at);
        if let Some(space) = &self.cover {
            let climbed = space.sheets_through(exit.face, &at.frame, &moved.frame);
            sheet = super::cover::sheet_plus(sheet, climbed, space.sheets());
        }
        Self::ray_on_sheet(&moved, sheet)
    }

    fn moved_by(&self, ray: &Ray<V>, t: f64) -> Ray<V> {
        let r = Self::sl2r_ray(ray);
        let t = V::Real::from_f64(t);
        let at = on_model(&flow(&r, t));
        Self::ray_on_sheet(&at, self.sheet_after(ray, &r, t, &at))
    }

    fn skip_after(&self, exit: &Self::Exit) -> Option<usize> {
        Some(self.sides[exit.face].partner)
    }
}
