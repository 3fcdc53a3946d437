//! Nil's distance and the direction of the shortest geodesic to a point (the inverse of the
//! exponential map), in any precision: what metric balls and the light of a lamp need.
//!
//! A left translation is an isometry, so it is enough to reach `q = (X, Y, Z)` from the
//! origin. The shortest geodesic winds by an angle `θ = cL` with `|θ| < 2π` (`L` its
//! length, `c` its vertical velocity), and its horizontal shadow is a chord of length
//! `ρ = √(X² + Y²) = (a/|c|)·2|sin(θ/2)|` of a circle, while its height is
//! `Z = θ + (a²/2c²)(θ − sin θ)`. Eliminating `a/c`, `θ` (of the sign of `Z`) solves
//!
//! ```text
//! h(θ) = |θ| + ρ² (|θ| − sin|θ|) / (8 sin²(θ/2)) − |Z| = 0,
//! ```
//!
//! which increases from `−|Z|` at 0 to `+∞` at 2π: its one root is bracketed and found by
//! bisection safeguarding Newton's steps, in `θ` itself where `h(π) ≥ 0` (with `θ − sin θ`
//! from the series of [`super::flow::flow_terms`], exact at small `θ`) and in the complement
//! `δ = 2π − θ` beyond (near the vertical axis above `2π`, where `sin(θ/2) = sin(δ/2)` would
//! lose its digits if computed from `θ`). Then `|c| = 2 sin(θ/2)/√(ρ² + 4 sin²(θ/2))`,
//! `L = θ/c` (as `θ/(2 sin(θ/2)) · √(ρ² + 4 sin²(θ/2))`, without cancellation at small θ), and
//! the start direction's angle is `atan2(Y, X) − θ/2`. On the vertical axis (`ρ = 0`) the
//! vertical line is shortest up to `|Z| = 2π` and a helix beyond, of length
//! `2π √(|Z|/π − 1)` (a circle of them: the one starting along `E₁` is taken).

use super::flow::{NilRay, flow_terms, group_product};
use super::{bracketed_root, pi};
use crate::geometry::Real;

/// The shortest geodesic from `p` to `q`: its length and its unit start velocity in the
/// left-invariant frame (`E₁` along the first coordinate). The length is `0` and the
/// direction `E₃` where `p = q`.
#[must_use]
pub fn shortest<R: Real>(p: [R; 3], q: [R; 3]) -> (R, [R; 3]) {
    let inverse = p.map(|x| -x);
    let [x, y, z] = group_product(inverse, q);
    let zero = R::ZERO;
    let one = R::ONE;
    let two = R::from_f64(2.0);
    let half = R::from_f64(0.5);
    let pi = pi::<R>();
    let rho2 = x * x + y * y;
    let height = z.abs();
    let up = if z < zero { -one } else { one };
    if rho2 == zero {
        if height == zero {
            return (zero, [zero, zero, one]);
        }
        if height <= two * pi {
            return (height, [zero, zero, up]);
        }
        // A helix winding once: θ = 2π, |c| = 2π/L.
        let length = two * pi * (height / pi - one).sqrt();
        let c = two * pi / length;
        return (length, [(one - c * c).max(zero).sqrt(), zero, up * c]);
    }
    let rho = rho2.sqrt();
    if height == zero {
        // The horizontal straight line.
        return (rho, [x / rho, y / rho, zero]);
    }
    // h and its rate in the winding's variable: θ itself on (0, π], its complement
    // δ = 2π − θ on (π, 2π) (where sin(θ/2) = sin(δ/2) is then known to full relative
    // precision: near θ = 2π, sin(θ/2) from θ would lose it).
    let two_pi = two * pi;
    let eight = R::from_f64(8.0);
    let h = |v: R, complement: bool| {
        let (_, sin_half) = (v * half).cos_sin();
        let s2 = sin_half * sin_half;
        let (_, sin_v) = v.cos_sin();
        let (theta, theta_minus_sin, sin_theta) = if complement {
            (two_pi - v, two_pi - v + sin_v, -sin_v)
        } else {
            (v, flow_terms(one, v).2, sin_v)
        };
        let value = theta + rho2 * theta_minus_sin / (eight * s2) - height;
        // dh/dθ = 1 + ρ²/8 · (2 − (θ − sin θ) sin θ / (2 sin⁴(θ/2))); dθ/dδ = −1.
        let rate = one + (two - theta_minus_sin * sin_theta / (two * s2 * s2)) * rho2 / eight;
        (value, if complement { -rate } else { rate })
    };
    let complement = h(pi, false).0 < zero;
    // The variable's bracket: h rises with θ, falls with δ.
    let start = if complement {
        half * pi
    } else {
        // The small-θ root θ ≈ |Z|/(1 + ρ²/12).
        (height / (one + rho2 / R::from_f64(12.0))).min(pi)
    };
    let v = bracketed_root(&|v| h(v, complement), (zero, pi), start, |value| {
        if complement {
            value > zero
        } else {
            value < zero
        }
    });
    let t = if complement { two_pi - v } else { v };
    let (_, sin_half) = (v * half).cos_sin();
    let chord = (rho2 + R::from_f64(4.0) * sin_half * sin_half).sqrt();
    let length = t / (two * sin_half) * chord;
    let c = two * sin_half / chord;
    let a = rho / chord;
    // The start angle: the chord's direction less half the winding (θ signed as Z).
    let angle = y.atan2(x) - up * t * half;
    let (cos_a, sin_a) = angle.cos_sin();
    (length, [a * cos_a, a * sin_a, up * c])
}

/// The distance between two points of Nil (the universal cover: the quotient's is the least
/// over the lattice's images).
#[must_use]
pub fn distance<R: Real>(p: [R; 3], q: [R; 3]) -> R {
    shortest(p, q).0
}

/// Where the shortest geodesic from `p` to `q` ends when walked: `q` (up to rounding), a
/// check of [`shortest`].
#[must_use]
pub fn reached<R: Real>(p: [R; 3], q: [R; 3]) -> [R; 3] {
    let (length, velocity) = shortest(p, q);
    super::flow::flow(&NilRay { point: p, velocity }, length).point
}
