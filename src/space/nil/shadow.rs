//! The shadow of a geodesic in the plane, and when it comes within a distance of a point.
//!
//! The projection `(x, y, z) ↦ (x, y)` is a Riemannian submersion onto the Euclidean plane,
//! and a left translation projects to a translation: the shadow of a unit-speed geodesic
//! with body velocity `(u, v, c)` is a curve of constant signed curvature `k = c/a`
//! traversed at speed `a = √(u² + v²)` — a circle of radius `a/|c|`, a straight line where
//! `c = 0`. With `h` the unit horizontal direction, `n` its left normal and `s = a t` the
//! shadow's arc length,
//!
//! ```text
//! P(s) = P₀ + h sin(ks)/k + n (1 − cos ks)/k.
//! ```
//!
//! For a point `b` (`q = b − P₀`, `X = q·h`, `Y = q·n`, `A = |q|² − r²`, and `k ≥ 0` after
//! mirroring across the shadow's start line), `|P(s) − b|² − r²` times `k²/2` is
//! `M − R cos(ks − β)` with `p = 1 − kY`, `R = √(k²X² + p²)`, `M = k²A/2 + p` and
//! `β = atan2(kX, p)`. The shadow is within `r` of `b` on the arcs `|ks − β| ≤ Δ` (mod 2π),
//! `cos Δ = M/R`. Everything is written without dividing by `k`: `R − M = k² E` with
//! `E = X²/(R + p) − A/2` (for `p > 0`), `sin(Δ/2) = k √(E/2R)`, and `β/k`, `Δ/k` through
//! `atan(z)/z` and `asin(z)/z`, so the straight line (`k = 0`, the line–circle formula
//! `s = X ∓ √(X² − A)`) is the limit with no seam.
//!
//! A fibre tube (the points within `r` of a fibre) is met exactly where the shadow first
//! comes within `r` of the fibre's foot; a metric ball lies inside the tube of its radius
//! about its centre's fibre, so no ray meets it outside the times this gives.

use super::flow::NilRay;

/// `atan(z)/z`, 1 at 0.
fn atan_over(z: f64) -> f64 {
    if z.abs() < 1e-4 {
        1.0 - z * z / 3.0
    } else {
        z.atan() / z
    }
}

/// `asin(z)/z` for `0 ≤ z ≤ 1`, 1 at 0.
fn asin_over(z: f64) -> f64 {
    if z < 1e-4 {
        1.0 + z * z / 6.0
    } else {
        z.min(1.0).asin() / z
    }
}

/// The times the shadow of `ray` (a unit body velocity) is within `r` of the plane point
/// `b`: the first interval `[t_in, t_out]` with `t_in ≥ 0` (`t_in = 0` where it starts
/// within; `t_out` infinite where it never leaves: a vertical ray, or a shadow circle
/// within `r` of `b` all round) and the period after which the shadow comes back (infinite
/// for a straight shadow). `None` where it never comes within `r`.
#[must_use]
pub fn shadow_within(ray: &NilRay<f64>, b: [f64; 2], r: f64) -> Option<(f64, f64, f64)> {
    let [x0, y0, _] = ray.point;
    let [u, v, c] = ray.velocity;
    let q = [b[0] - x0, b[1] - y0];
    let big_a = q[0] * q[0] + q[1] * q[1] - r * r;
    let a = u.hypot(v);
    if !(a > 1e-300) {
        // A vertical ray: its shadow stands still.
        return (big_a <= 0.0).then_some((0.0, f64::INFINITY, f64::INFINITY));
    }
    let h = [u / a, v / a];
    let x = q[0] * h[0] + q[1] * h[1];
    let mut y = -q[0] * h[1] + q[1] * h[0];
    let mut k = c / a;
    if k < 0.0 {
        // Mirrored across the start line: the shadow turns left.
        k = -k;
        y = -y;
    }
    let p = 1.0 - k * y;
    let big_r = (k * x).hypot(p);
    // E = (R − M)/k², written without cancellation where k is small (p > 0 there).
    let e = if p > 0.0 {
        x * x / (big_r + p) - 0.5 * big_a
    } else {
        (big_r - p) / (k * k) - 0.5 * big_a
    };
    if !(e >= 0.0) {
        return None;
    }
    let w = (e / (2.0 * big_r)).sqrt();
    let period = if k > 0.0 {
        2.0 * std::f64::consts::PI / k
    } else {
        f64::INFINITY
    };
    if k * w >= 1.0 {
        // The whole shadow circle is within r of b.
        return Some((0.0, f64::INFINITY, period));
    }
    // Half the arc within r, and its middle, in arc length.
    let half = 2.0 * w * asin_over(k * w);
    let middle = if p > 0.0 {
        (x / p) * atan_over(k * x / p)
    } else {
        (k * x).atan2(p) / k
    };
    let (mut s_in, mut s_out) = (middle - half, middle + half);
    if s_in < 0.0 {
        if s_out >= 0.0 || big_a <= 0.0 {
            s_in = 0.0;
            s_out = s_out.max(0.0);
        } else if period.is_finite() {
            s_in += period;
            s_out += period;
        } else {
            return None;
        }
    }
    Some((s_in / a, s_out / a, period / a))
}
