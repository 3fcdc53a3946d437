//! Where a geodesic of SL̃(2,R) leaves a side of the cell, in closed form.
//!
//! A side of the polygon lies on a geodesic of `H²`, `n·p = 0` (`n` a covector of the
//! hyperboloid's space, `n·p ≤ 0` inside); the cell is the polygon times the whole fibre,
//! so a side is crossed where the base point crosses it. Along a ray the base point is
//! `p(t) = F₀ (S a + K bc, S b − K ac, 1 + K(a² + b²))` ([`mod@super::flow`]), so with
//! `u = F₀ᵀ n`,
//!
//! ```text
//! f(t) = n·p(t) = α + β S(t) + γ K(t),   α = u₂,  β = a u₀ + b u₁,  γ = c(b u₀ − a u₁) + (a² + b²) u₂.
//! ```
//!
//! With `σ = sinh(ωt/2)/(ω/2)` and `κ = cosh(ωt/2)` (so `S = σκ`, `K = σ²/2`,
//! `κ² − ω²σ²/4 = 1`), `f = α κ² + β σκ + (γ/2 − αω²/4) σ²`: a quadratic form in `(σ, κ)`,
//! so `f = 0` where `τ = σ/κ` is a root of
//!
//! ```text
//! Q(τ) = A τ² + β τ + α,   A = γ/2 − α ω²/4,
//! ```
//!
//! the same for the three kinds of geodesic. `τ(t)` increases with `t`: `(2/ω) tanh(ωt/2)`
//! (below `2/ω`) for a hypercycle, `t` for a horocycle, `(2/ω′) tan(ω′t/2)` for a circle
//! (through `±∞` at half its period, where the base point's path repeats). The side is
//! left where `f` goes from inside to outside, `Q′(τ) = 2Aτ + β > 0` (`df/dt` has its
//! sign there). The roots come from the quadratic formula written without cancellation,
//! `t` from `τ` by `τ · atanh(√y)/√y` (`y = ω²τ²/4`; `atan` where `y < 0`, a series near
//! 0), and a few Newton steps on `f` itself take it to the precision's last bit.

use super::flow::{Sl2rRay, flow_terms, omega_squared};
use crate::geometry::Real;

/// The coefficients `(α, β, γ)` of `f(t) = α + β S + γ K` for the side covector `n`.
#[must_use]
pub fn side_coefficients<R: Real>(ray: &Sl2rRay<R>, n: [R; 3]) -> (R, R, R) {
    let u = ray
        .frame
        .map(|col| n[0] * col[0] + n[1] * col[1] + n[2] * col[2]);
    let [a, b, c] = ray.velocity;
    (
        u[2],
        a * u[0] + b * u[1],
        c * (b * u[0] - a * u[1]) + (a * a + b * b) * u[2],
    )
}

/// `atanh(√y)/√y` (`atan(√−y)/√−y` for `y < 0`), `|y| < 1` where `y > 0`.
fn atanhc(y: f64) -> f64 {
    if y.abs() < 0.01 {
        // Σ yᵏ/(2k+1): eight terms reach 10⁻¹⁶.
        let mut sum = 0.0;
        for k in (0..9).rev() {
            sum = sum * y + 1.0 / f64::from(2 * k + 1);
        }
        sum
    } else if y > 0.0 {
        let s = y.sqrt();
        s.atanh() / s
    } else {
        let s = (-y).sqrt();
        s.atan() / s
    }
}

/// The first time `t > 0` (or `t = 0` where the ray starts on the side, leaving it) at
/// which the ray leaves the side `n·p ≤ 0`; `None` where it never does.
#[must_use]
pub fn side_exit<R: Real>(ray: &Sl2rRay<R>, n: [R; 3]) -> Option<R> {
    first_crossing(ray, n, R::ZERO)
}

/// The first time at which `n·p(t) + offset` goes from `≤ 0` to `> 0` (a side's exit with
/// `offset = 0`; the entry into the tube of radius `r` about the fibre over `q` with
/// `n = (q_x, q_y, −q_w)`, `offset = cosh r`: inside it `⟨p, q⟩ ≥ −cosh r`); `t = 0` where
/// it starts there and leaving; `None` where it never does. The constant only moves `α`,
/// so the same quadratic in `τ` holds (see the module).
#[must_use]
pub fn first_crossing<R: Real>(ray: &Sl2rRay<R>, n: [R; 3], offset: R) -> Option<R> {
    let (alpha, beta, gamma) = side_coefficients(ray, n);
    let alpha = alpha + offset;
    let w2 = omega_squared(ray.velocity);
    let (al, be, ga, w) = (alpha.to_f64(), beta.to_f64(), gamma.to_f64(), w2.to_f64());
    // Already outside (by rounding) and leaving: at once.
    if al >= 0.0 && be > 0.0 {
        return Some(R::ZERO);
    }
    let a = 0.5 * ga - 0.25 * al * w;
    let disc = be * be - 4.0 * a * al;
    if disc < 0.0 {
        return None;
    }
    // The roots q/A and α/q without cancellation.
    let q = -0.5 * (be + be.signum() * disc.sqrt());
    let roots = [q / a, if q == 0.0 { f64::NAN } else { al / q }];
    let mut best: Option<f64> = None;
    for tau in roots {
        // Where f goes from inside to outside. An infinite root is a circle's half period
        // (κ = 0, A = 0), where f ≈ βσκ changes sign as κ does: left where β < 0.
        let leaving = if tau.is_infinite() {
            be < 0.0
        } else {
            2.0 * a * tau + be > 0.0
        };
        if !leaving || tau.is_nan() {
            continue;
        }
        if let Some(t) = time_of(tau, w) {
            best = Some(best.map_or(t, |b: f64| b.min(t)));
        }
    }
    best.map(|t| polish(alpha, beta, gamma, w2, R::from_f64(t)))
}

/// The time at which `τ(t)` first equals `tau` (see the module), `None` where it never does.
fn time_of(tau: f64, w2: f64) -> Option<f64> {
    use std::f64::consts::PI;
    let y = 0.25 * w2 * tau * tau;
    if w2 >= 0.0 {
        // τ runs over [0, 2/ω).
        return (tau >= 0.0 && tau.is_finite() && y < 1.0).then(|| tau * atanhc(y));
    }
    let omega = (-w2).sqrt();
    if tau.is_infinite() {
        return Some(PI / omega);
    }
    if tau >= 0.0 {
        // The first half of the period: ω′t/2 = atan(ω′τ/2) ∈ [0, π/2).
        return Some(if y > -0.01 {
            tau * atanhc(y)
        } else {
            2.0 * (0.5 * omega * tau).atan() / omega
        });
    }
    // The second half: ω′t/2 = π + atan(ω′τ/2) ∈ (π/2, π).
    Some(2.0 * (PI + (0.5 * omega * tau).atan()) / omega)
}

/// Newton's steps on `f(t) = α + βS + γK` from `t` (`f′ = βC + γS`, `C = 1 + ω²K`), each
/// kept only where it makes `|f|` smaller.
fn polish<R: Real>(alpha: R, beta: R, gamma: R, w2: R, mut t: R) -> R {
    let f_at = |t: R| {
        crate::space::roots::count_root_iteration();
        let (s, k) = flow_terms(w2, t);
        (
            alpha + beta * s + gamma * k,
            beta * (R::ONE + w2 * k) + gamma * s,
        )
    };
    let (mut f, mut df) = f_at(t);
    for _ in 0..6 {
        if f == R::ZERO || !(df.abs() > R::ZERO) {
            break;
        }
        let next = (t - f / df).max(R::ZERO);
        let (f_next, df_next) = f_at(next);
        if !(f_next.abs() < f.abs()) {
            break;
        }
        t = next;
        f = f_next;
        df = df_next;
    }
    t
}
