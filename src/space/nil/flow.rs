//! Nil's geodesics in closed form, in any precision ([`Real`]: `f32`, `f64`,
//! double-double).
//!
//! From the origin with unit body velocity `(a cos α, a sin α, c)` the geodesic is
//!
//! ```text
//! x(t) = (a/c)(sin(ct + α) − sin α)
//! y(t) = (a/c)(cos α − cos(ct + α))
//! z(t) = ct + (a²/2)(ct − sin ct)/c²
//! ```
//!
//! and its body velocity at `t` is `(a cos(α + ct), a sin(α + ct), c)`: the horizontal part
//! turns at the constant rate `c`. From a point `p` it is `p·γ(t)` (a left translation keeps
//! the body velocity). Written with `u = ct`, `x = u₁ S − u₂ C`, `y = u₂ S + u₁ C`,
//! `z = ct + ½(u₁² + u₂²) Z` with
//!
//! ```text
//! S = sin(u)/c = t Σ (−u²)ᵏ/(2k+1)!,   C = (1 − cos u)/c = t u Σ (−u²)ᵏ/(2k+2)!,
//! Z = (u − sin u)/c² = t² u Σ (−u²)ᵏ/(2k+3)!
//! ```
//!
//! evaluated by these series (no division by `c`: exact at `c = 0`, the horizontal lines,
//! and without the cancellation of `u − sin u` at small `u`) while `|u| < 2`, and from `sin`
//! and `cos` of `u` and `u/2` beyond, where nothing cancels (`C = 2 sin²(u/2)/c`). The
//! series' coefficients come from a recurrence of exact divisions, so double-double keeps
//! its 32 digits.

use crate::geometry::Real;

/// A point of Nil in the chart and a velocity in the left-invariant frame `E₁, E₂, E₃`
/// (unit for a ray).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NilRay<R> {
    /// The chart point `(x, y, z)`.
    pub point: [R; 3],
    /// The body velocity `(u₁, u₂, u₃)`.
    pub velocity: [R; 3],
}

/// The group product `p·q`: `q` moved by the left translation by `p` (an isometry, affine
/// in `q`).
#[must_use]
pub fn group_product<R: Real>(p: [R; 3], q: [R; 3]) -> [R; 3] {
    let half = R::from_f64(0.5);
    [
        p[0] + q[0],
        p[1] + q[1],
        p[2] + q[2] + half * (p[0] * q[1] - p[1] * q[0]),
    ]
}

/// Below this `|ct|` the flow's `S`, `C` and `Z` are summed as series.
const SERIES_BELOW: f64 = 2.0;

/// Terms of each series: `4ᵏ/(2k+1)!` is below 10⁻⁴² at `k = 22`, past double-double's
/// precision at `|ct| < 2`.
const SERIES_TERMS: usize = 22;

/// `(S, C, Z)` of the flow for the rate `c` at time `t` (see the module's formulas).
#[must_use]
pub fn flow_terms<R: Real>(c: R, t: R) -> (R, R, R) {
    let u = c * t;
    if R::EPSILON.to_f64() >= f64::EPSILON {
        return flow_terms_short(c, t, u);
    }
    if u.abs() < R::from_f64(SERIES_BELOW) {
        // Σ (−u²)ᵏ/(n+2k)! for n = 1, 2, 3, by the exact recurrence of the terms.
        let minus_u2 = -(u * u);
        let sum = |n: u32| {
            let mut term = R::ONE;
            for k in 1..=n {
                term = term / R::from_f64(f64::from(k));
            }
            let mut total = term;
            for k in 0..SERIES_TERMS as u32 {
                let (a, b) = (n + 2 * k + 1, n + 2 * k + 2);
                term = term * minus_u2 / R::from_f64(f64::from(a * b));
                total = total + term;
                // The terms fall faster than geometrically from here: the rest is below
                // the precision's last bit.
                if term.abs() <= R::EPSILON * R::from_f64(1e-3) * total.abs() {
                    break;
                }
            }
            total
        };
        (t * sum(1), t * u * sum(2), t * t * u * sum(3))
    } else {
        let (_, sin_u) = u.cos_sin();
        let (_, sin_half) = (u * R::from_f64(0.5)).cos_sin();
        let two = R::from_f64(2.0);
        (
            sin_u / c,
            two * sin_half * sin_half / c,
            (u - sin_u) / (c * c),
        )
    }
}

/// `1/(2k+3)!` with the sign of `(−1)ᵏ`, `k = 0 … 10`: the series of `(u − sin u)/u³`, whose
/// eleventh term is below `f64`'s last bit at `|u| < 2`.
const Z_SERIES: [f64; 11] = [
    1.0 / 6.0,
    -1.0 / 120.0,
    1.0 / 5040.0,
    -1.0 / 362_880.0,
    1.0 / 39_916_800.0,
    -1.0 / 6_227_020_800.0,
    1.0 / 1_307_674_368_000.0,
    -1.0 / 355_687_428_096_000.0,
    1.0 / 121_645_100_408_832_000.0,
    -1.0 / 51_090_942_171_709_440_000.0,
    1.0 / 25_852_016_738_884_976_640_000.0,
];

/// [`flow_terms`] where `f64`'s coefficients are precise enough (`f64`, `f32`): `S` and `C`
/// in closed form, which cancel nowhere (`sin u/c`, `2 sin²(u/2)/c`), and `Z` — whose
/// `u − sin u` cancels at small `u` — by its series in Horner's form below `|u| = 2`: no
/// loop that stops early and no division.
fn flow_terms_short<R: Real>(c: R, t: R, u: R) -> (R, R, R) {
    if u == R::ZERO {
        return (t, R::ZERO, R::ZERO);
    }
    let (_, sin_u) = u.cos_sin();
    let (_, sin_half) = (u * R::from_f64(0.5)).cos_sin();
    let s = sin_u / c;
    let one_minus_cos = R::from_f64(2.0) * sin_half * sin_half / c;
    let z = if u.abs() < R::from_f64(SERIES_BELOW) {
        let u2 = u * u;
        let mut sum = R::from_f64(Z_SERIES[10]);
        for coefficient in Z_SERIES[..10].iter().rev() {
            sum = sum * u2 + R::from_f64(*coefficient);
        }
        t * t * u * sum
    } else {
        (u - sin_u) / (c * c)
    };
    (s, one_minus_cos, z)
}

/// The ray moved by `t` along its geodesic: the chart point and the body velocity there.
#[must_use]
pub fn flow<R: Real>(ray: &NilRay<R>, t: R) -> NilRay<R> {
    let [u1, u2, c] = ray.velocity;
    let (s, one_minus_cos, z_term) = flow_terms(c, t);
    let (cos_u, sin_u) = (c * t).cos_sin();
    let half = R::from_f64(0.5);
    let from_origin = [
        u1 * s - u2 * one_minus_cos,
        u2 * s + u1 * one_minus_cos,
        c * t + half * (u1 * u1 + u2 * u2) * z_term,
    ];
    NilRay {
        point: group_product(ray.point, from_origin),
        velocity: [u1 * cos_u - u2 * sin_u, u1 * sin_u + u2 * cos_u, c],
    }
}
