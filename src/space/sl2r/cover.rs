//! The fibre's angle and the sheets of the fibre covers `unit-tangent-WORD-cover-N`.
//!
//! The fibre of `UT Σ` is the circle of directions `e` at a base point `p`; its `N`-fold cover
//! unwinds it `N` times, so a point is `(p, e)` with a *sheet* `k ∈ Z/N`, and the lifted
//! fibre angle `Λ = θ + 2πk` (modulo `2πN`) is continuous. `θ ∈ (−π, π]` is the chart's
//! angle ([`super::chart_point`]): the angle of `e` from the *radially parallel* field `u(p)`
//! (the boost of the origin's `(1, 0, 0)` to `p`, a smooth field on all of `H²`). The cell is
//! the polygon times `Λ ∈ (−πN, πN]`: its top and bottom are where `e = −u(p)` on the last
//! and the first sheet, glued by the central turn by `2πN`, which moves no frame. So a walk
//! keeps its frame `(e, e⊥, p)` as in `UT Σ` and counts the sheet: it turns a sheet up each
//! time `θ` passes `π` upwards (down each time downwards), and a side's pairing `g` adds the
//! continuous lift `δ_f(p)` of `angle(u(gp), g·u(p))` to `Λ`.
//!
//! Both are counted exactly, without a root: along a geodesic of unit speed
//! `|dθ/dt| ≤ |c| + |(a, b)| ≤ √2` (with `ℓ` a null vector, `θ` is the polar angle of
//! `(⟨e, ℓ⟩, ⟨e⊥, ℓ⟩)` up to a constant, and `(L_e, L_f)′ = (aL_p − cL_f… )`: the rotation
//! part turns it at `|c|`, the boost part at most `|(a, b)|`), so over a piece of length
//! [`ANGLE_PIECE`] it changes by less than `π` and its change is the wrapped difference of
//! the ends; `δ_f` changes by at most 2 per unit of length in `H²` (the field's connection
//! form is below 1 at `p` and at `gp`), so it is followed along the geodesic from the side's
//! midpoint in steps of 1. The sides' lifts are fixed at their midpoints, a side and
//! its partner's by one choice (`δ_{f′}(q) = −δ_f(g_{f′} q)`), so going through a side and
//! back returns the sheet. Going once round the polygon's vertex cycle composes the lifted
//! pairings to the central turn by `2πm`; `m = ±χ` (the bundle's Euler number), and the
//! `N`-fold cover exists exactly where `N` divides it ([`UnitTangentSpace::euler_turns`]).

use super::flow::{Sl2rRay, flow};
use super::space::UnitTangentSpace;
use crate::geometry::Real;
use std::f64::consts::{PI, TAU};

/// The longest piece of a geodesic over which the fibre angle is followed by its ends alone
/// (it turns by at most `√2 · 2 < π` over it).
pub const ANGLE_PIECE: f64 = 2.0;

/// The longest step in `H²` over which a side's turn is followed by its ends alone (it
/// changes by at most 2 over it).
const TURN_PIECE: f64 = 1.0;

/// The most pieces a count follows (a length past `ANGLE_PIECE` times this is refused).
const MAX_PIECES: f64 = 1.0e6;

/// `x` wrapped into `(−π, π]`.
#[must_use]
pub fn wrap_angle(x: f64) -> f64 {
    let w = x - TAU * (x / TAU).round();
    if w <= -PI { w + TAU } else { w }
}

/// The whole turns `x` wraps away (`x = wrap_angle(x) + 2π·turns`).
fn turns_of(x: f64) -> i64 {
    ((x - wrap_angle(x)) / TAU).round() as i64
}

/// The fibre angle `θ ∈ (−π, π]` of a frame `(e, e⊥, p)` (the chart's, [`super::chart_point`]).
#[must_use]
pub fn fibre_angle<R: Real>(frame: &[[R; 3]; 3]) -> f64 {
    super::chart_point(&frame.map(|v| v.map(Real::to_f64))).z
}

/// The sheets the ray climbs from its start to `t` along it (up positive), `end` the frame
/// reached at `t` as the walk computed it (so that the count agrees with the end's angle):
/// the times `θ` passes the cut `±π`, each counted by the wrapped change over pieces no
/// longer than [`ANGLE_PIECE`]. `None` for a non-finite or absurdly long stretch.
#[must_use]
pub fn sheets_climbed<R: Real>(ray: &Sl2rRay<R>, t: R, end: &[[R; 3]; 3]) -> Option<i64> {
    let length = t.to_f64();
    if !length.is_finite() {
        return None;
    }
    let pieces = (length.abs() / ANGLE_PIECE).ceil().max(1.0);
    if pieces > MAX_PIECES {
        return None;
    }
    let pieces = pieces as usize;
    let mut previous = fibre_angle(&ray.frame);
    let mut climbed = 0;
    for i in 1..=pieces {
        let angle = if i == pieces {
            fibre_angle(end)
        } else {
            let at = R::from_f64(length * i as f64 / pieces as f64);
            fibre_angle(&flow(ray, at).frame)
        };
        // A change past ±π is the cut passed: θ jumped by ∓2π while Λ moved on.
        climbed -= turns_of(angle - previous);
        previous = angle;
    }
    Some(climbed)
}

/// The sheet after climbing `by` from `sheet`, in `Z/sheets`.
#[must_use]
pub fn sheet_plus(sheet: u32, by: i64, sheets: u32) -> u32 {
    let n = i64::from(sheets.max(1));
    (i64::from(sheet) + by).rem_euclid(n) as u32
}

/// `m·v` for a 3×3 `m` (rows).
fn apply(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

impl UnitTangentSpace {
    /// `angle(u(gp), g·u(p))` wrapped, for the pairing `g` of side `face`.
    fn raw_side_turn(&self, face: usize, p: [f64; 3]) -> f64 {
        let g = self.sides()[face].pairing.map(|r| r.map(|x| x.hi));
        let frame = super::chart_frame(p[0], p[1], 0.0).map(|v| apply(&g, v));
        fibre_angle(&frame)
    }

    /// The midpoint of side `face` (the foot of the perpendicular from the centre).
    fn side_midpoint(&self, face: usize) -> [f64; 3] {
        let n = self.sides().len() as f64;
        let angle = TAU * face as f64 / n;
        let rho = self.inradius();
        [
            rho.sinh() * angle.cos(),
            rho.sinh() * angle.sin(),
            rho.cosh(),
        ]
    }

    /// The lift for the first side of its pair, followed from the midpoint's principal value
    /// along the geodesic of `H²` to `p`.
    fn first_side_turn(&self, face: usize, p: [f64; 3]) -> f64 {
        let m = self.side_midpoint(face);
        let start = self.raw_side_turn(face, m);
        let cosh_d = (m[2] * p[2] - m[0] * p[0] - m[1] * p[1]).max(1.0);
        let d = cosh_d.acosh();
        if !d.is_finite() {
            return start;
        }
        let steps = (d / TURN_PIECE).ceil().clamp(1.0, MAX_PIECES) as usize;
        let mut previous = start;
        let mut total = start;
        for i in 1..=steps {
            let s = i as f64 / steps as f64;
            // The point a share s of the way along the geodesic from m to p.
            let q = if d > 1e-12 {
                let (a, b) = (((1.0 - s) * d).sinh() / d.sinh(), (s * d).sinh() / d.sinh());
                [0, 1, 2].map(|k| a * m[k] + b * p[k])
            } else {
                p
            };
            let raw = self.raw_side_turn(face, q);
            total += wrap_angle(raw - previous);
            previous = raw;
        }
        total
    }

    /// `δ_f(p)`: what the pairing of side `face` adds to the lifted fibre angle of a point over
    /// `p` (continuous in `p` over all of `H²`; a side and its partner's lifts are inverse).
    #[must_use]
    pub fn side_turn(&self, face: usize, p: [f64; 3]) -> f64 {
        let partner = self.sides()[face].partner;
        if face <= partner {
            self.first_side_turn(face, p)
        } else {
            let g = self.sides()[face].pairing.map(|r| r.map(|x| x.hi));
            -self.first_side_turn(partner, apply(&g, p))
        }
    }

    /// Side `face`'s turn at its midpoint, wrapped and lifted: `δ_f(p)` near the side is the
    /// lift plus the wrapped difference of the raw turn at `p` from the wrapped one (the GPU
    /// tracer's form: the turn changes by less than `π` along a side).
    #[must_use]
    pub fn side_turn_reference(&self, face: usize) -> (f64, f64) {
        let m = self.side_midpoint(face);
        (self.raw_side_turn(face, m), self.side_turn(face, m))
    }

    /// The sheets a crossing of side `face` climbs: `before` the frame at the exit (on the
    /// side), `after` the same point moved by the pairing.
    #[must_use]
    pub fn sheets_through<R: Real>(
        &self,
        face: usize,
        before: &[[R; 3]; 3],
        after: &[[R; 3]; 3],
    ) -> i64 {
        let p = before[2].map(Real::to_f64);
        let lifted = fibre_angle(before) + self.side_turn(face, p);
        turns_of(lifted - fibre_angle(after))
    }

    /// For each cycle of the polygon's vertices, the central turn (in whole turns of the
    /// fibre) that the lifted pairings met going once round it compose to: `±χ` for the one
    /// cycle of a surface word. The fibre's `N`-fold cover exists where `N` divides each.
    #[must_use]
    pub fn euler_turns(&self) -> Vec<i64> {
        let vertices = self.vertices();
        let n = vertices.len();
        let nearest = |q: [f64; 3]| {
            (0..n)
                .min_by(|&i, &j| {
                    let d = |k: usize| (0..3).map(|c| (vertices[k][c] - q[c]).abs()).sum::<f64>();
                    d(i).total_cmp(&d(j))
                })
                .unwrap_or(0)
        };
        let mut seen = vec![false; n];
        let mut cycles = Vec::new();
        for start in 0..n {
            if seen[start] {
                continue;
            }
            // At vertex v, leave through side s (vertex k lies on sides k − 1 and k).
            let (mut v, mut s) = (start, start);
            let mut total = 0.0;
            for _ in 0..=2 * n {
                seen[v] = true;
                total += self.side_turn(s, vertices[v]);
                let g = self.sides()[s].pairing.map(|r| r.map(|x| x.hi));
                let w = nearest(apply(&g, vertices[v]));
                let entered = self.sides()[s].partner;
                let other = if entered == w { (w + n - 1) % n } else { w };
                (v, s) = (w, other);
                if (v, s) == (start, start) {
                    break;
                }
            }
            cycles.push((total / TAU).round() as i64);
        }
        cycles
    }
}
