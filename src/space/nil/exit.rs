//! Where a Nil geodesic first meets a vertical plane or a horizontal one, solved, not
//! marched: the time of the first crossing after the start, in any precision.
//!
//! **Vertical planes** `n·(x, y) = r` (`n` a unit vector of the xy-plane). The horizontal
//! displacement is `D(t) = w S(t) + w⊥ C(t)` (`w = (u₁, u₂)`, `w⊥ = (−u₂, u₁)`, `S` and `C`
//! of [`mod@super::flow`]), so the plane is met where `α S + β C = d` with `α = n·w`,
//! `β = n·w⊥`, `d = r − n·p`. With `θ = ct` and `τ = tan(θ/2)` this is the quadratic
//! `(2β − cd) τ² + 2α τ − cd = 0`: the horizontal shadow is a circle of radius `a/|c|`,
//! which meets the line twice or never. Its roots are taken in the stable forms
//! (`q = −(α + sgn(α)√Δ)`, `τ = q/(2β − cd)` and `τ = −cd/q`), and the near root's time
//! `t = 2 atan(τ)/c` is evaluated as `(−2d/q)·(atan τ/τ)`: no division by `c`, so the
//! straight lines (`c = 0`) and the nearly straight ones cross where they should to the last
//! bit. The far root, and a root behind the start, go round the circle (`θ/2` past ±π/2).
//!
//! **Horizontal planes** `z = h`. The height along the geodesic is
//! `z(t) = p_z + ct + ½a² Z(t) + ½(p_x y₀(t) − p_y x₀(t))` and its rate
//! `ż = K₀ + K₁ cos θ + K₂ sin θ` with `K₀ = c + a²/2c`, `K₁ = −a²/2c + ½(p_x u₂ − p_y u₁)`,
//! `K₂ = ½(p_x u₁ + p_y u₂)`: its zeros, the heights' turning points, are in closed form
//! (`θ = φ ± acos(−K₀/ρ)`). Between two of them the height is monotone, so the first
//! interval whose ends straddle `h` holds the first crossing, found there by bisection
//! safeguarding Newton's steps, to the last bit of the precision. A geodesic that only
//! touches the plane (a double root) is the one case whose answer rounding can change:
//! that is the problem's conditioning, not the method's.

use super::flow::{NilRay, flow_terms};
use super::{bracketed_root, half_way, pi};
use crate::geometry::Real;

/// The first time `t > 0` at which `ray` meets the vertical plane `n·(x, y) = r` (`n` a
/// unit vector of the xy-plane; the start on the side `n·p ≤ r`), or `None` if its
/// horizontal shadow never reaches that line.
#[must_use]
pub fn vertical_exit<R: Real>(ray: &NilRay<R>, n: [R; 2], r: R) -> Option<R> {
    let [u1, u2, c] = ray.velocity;
    let zero = R::ZERO;
    let two = R::from_f64(2.0);
    let pi = pi::<R>();
    let alpha = n[0] * u1 + n[1] * u2;
    let beta = -n[0] * u2 + n[1] * u1;
    let d = (r - (n[0] * ray.point[0] + n[1] * ray.point[1])).max(zero);
    let cd = c * d;
    let a2 = two * beta - cd;
    let disc = alpha * alpha + cd * a2;
    if !(disc >= zero) {
        return None;
    }
    let root = disc.sqrt();
    let q = if alpha >= zero {
        -(alpha + root)
    } else {
        root - alpha
    };
    // atan(τ)/τ, 1 at τ = 0.
    let atan_over = |tau: R| {
        if tau == zero {
            R::ONE
        } else {
            tau.atan2(R::ONE) / tau
        }
    };
    // The first time ahead of a crossing whose half-angle tangent is τ: θ = 2 atan τ, or a
    // turn more where that is behind (θ must have the sign of c); `direct` is the near
    // root's time computed without dividing by c, used where no turn is added.
    let time_of = |tau: R, direct: Option<R>| -> Option<R> {
        if c == zero {
            // A straight line: only the near root is a crossing, ahead when α > 0.
            return direct.filter(|t| *t >= zero);
        }
        let psi = tau.atan2(R::ONE);
        let behind = if c > zero { psi < zero } else { psi > zero };
        if behind {
            let turn = if c > zero { pi } else { -pi };
            Some(two * (psi + turn) / c)
        } else {
            Some(direct.unwrap_or(two * psi / c))
        }
    };
    let mut best: Option<R> = None;
    // A start on the plane moving inwards does not cross it there.
    let leaves_at_start = d == zero && alpha <= zero;
    if q != zero && !leaves_at_start {
        // The near root τ = −cd/q, its time −2d/q · atan(τ)/τ.
        let tau = -cd / q;
        best = time_of(tau, Some(-two * d / q * atan_over(tau)));
    } else if q != zero && c != zero {
        best = time_of(-cd / q, None).filter(|t| *t > zero);
    }
    if a2 != zero
        && c != zero
        && let Some(t) = time_of(q / a2, None)
    {
        best = Some(best.map_or(t, |b| b.min(t)));
    }
    best.filter(|t| *t >= zero && t.is_finite())
}

/// The height of `ray`'s geodesic at time `t` and its rate there.
#[must_use]
pub fn height_and_rate<R: Real>(ray: &NilRay<R>, t: R) -> (R, R) {
    let [u1, u2, c] = ray.velocity;
    let [px, py, pz] = ray.point;
    let half = R::from_f64(0.5);
    let (s, one_minus_cos, z_term) = flow_terms(c, t);
    let (cos_u, sin_u) = (c * t).cos_sin();
    let (x0, y0) = (u1 * s - u2 * one_minus_cos, u2 * s + u1 * one_minus_cos);
    let (vx, vy) = (u1 * cos_u - u2 * sin_u, u1 * sin_u + u2 * cos_u);
    let a2 = u1 * u1 + u2 * u2;
    let z = pz + c * t + half * a2 * z_term + half * (px * y0 - py * x0);
    let rate = c + half * a2 * one_minus_cos + half * (px * vy - py * vx);
    (z, rate)
}

/// `(K₀, K₁, K₂)` of the height's rate `ż = K₀ + K₁ cos θ + K₂ sin θ` (`c ≠ 0`).
fn rate_coefficients<R: Real>(ray: &NilRay<R>) -> (R, R, R) {
    let [u1, u2, c] = ray.velocity;
    let [px, py, _] = ray.point;
    let half = R::from_f64(0.5);
    let a2 = u1 * u1 + u2 * u2;
    (
        c + half * a2 / c,
        -half * a2 / c + half * (px * u2 - py * u1),
        half * (px * u1 + py * u2),
    )
}

/// The height's mean rate `K₀` and the amplitude `ρ` of its swing's rate (`c ≠ 0`).
fn rate_terms<R: Real>(ray: &NilRay<R>) -> (R, R) {
    let (k0, k1, k2) = rate_coefficients(ray);
    (k0, (k1 * k1 + k2 * k2).sqrt())
}

/// The turning points of the height along `ray` in `(0, before)`, in order: where
/// `ż = K₀ + K₁ cos θ + K₂ sin θ` vanishes (`θ = ct`; none for `c = 0`, where `ż` is
/// constant).
fn turning_points<R: Real>(ray: &NilRay<R>, before: R) -> Vec<R> {
    let c = ray.velocity[2];
    let zero = R::ZERO;
    let two_pi = R::from_f64(2.0) * pi::<R>();
    if c == zero {
        return Vec::new();
    }
    let (k0, k1, k2) = rate_coefficients(ray);
    let rho = (k1 * k1 + k2 * k2).sqrt();
    if !(rho > zero) || (k0 / rho).abs() > R::ONE {
        return Vec::new();
    }
    let phi = k2.atan2(k1);
    let cos_arg = -k0 / rho;
    let spread = (R::ONE - cos_arg * cos_arg).max(zero).sqrt().atan2(cos_arg);
    // θ = φ ± spread + 2πk, as times t = θ/c in (0, before).
    let period = (two_pi / c).abs();
    let mut out = Vec::new();
    for base in [phi + spread, phi - spread] {
        let mut t = base / c;
        // The first of these times after 0.
        if period.is_finite() && period > zero {
            let turns = (-t / period).to_f64().ceil();
            t = t + period * R::from_f64(turns);
            while t <= zero {
                t = t + period;
            }
        }
        let mut guard = 0;
        while t < before && guard < 64 {
            out.push(t);
            t = t + period;
            guard += 1;
        }
    }
    out.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Equal));
    out
}

/// The first time `t` in `(0, before]` at which `ray` meets the horizontal plane `z = h`,
/// or `None` before `before` (which may be infinite). A ray that starts on the plane is not
/// said to meet it there: its first crossing ahead is after the height's first turn.
#[must_use]
pub fn horizontal_exit<R: Real>(ray: &NilRay<R>, h: R, before: R) -> Option<R> {
    let zero = R::ZERO;
    let f = |t: R| {
        let (z, rate) = height_and_rate(ray, t);
        (z - h, rate)
    };
    let (f0, rate0) = f(zero);
    let [u1, u2, c] = ray.velocity;
    // A straight line (c = 0) climbs at a constant rate: in closed form.
    if c == zero {
        if rate0 == zero || (f0 > zero) == (rate0 > zero) && f0 != zero {
            return None;
        }
        let t = -f0 / rate0;
        return (t > zero && t <= before).then_some(t);
    }
    // A vertical line (a = 0) likewise: z = p_z + ct.
    if u1 == zero && u2 == zero {
        let t = -f0 / c;
        return (t > zero && t <= before).then_some(t);
    }
    // Out of reach before `before`: the height's rate `c + ½(x ẏ − y ẋ)` is at most
    // `|c| + ½ a (r₀ + a t)` (the shadow moves at speed `a` from `r₀` off the axis), so the
    // height moves at most `|c| T + ½ a r₀ T + ¼ a² T²` by the time `T` (widened by a hair
    // for rounding).
    if before.is_finite() {
        let [px, py, _] = ray.point;
        let a = (u1 * u1 + u2 * u2).sqrt();
        let r0 = (px * px + py * py).sqrt();
        let half = R::from_f64(0.5);
        let reach = (c.abs() + half * a * (r0 + half * a * before)) * before;
        if f0.abs() > reach * R::from_f64(1.0 + 1e-9) + R::EPSILON * h.abs() {
            return None;
        }
    }
    // The height is monotone between turning points: the first interval whose ends
    // straddle h holds the first crossing.
    let end = if before.is_finite() {
        before
    } else {
        // No bound: over a turn (θ by 2π) the height gains K₀ times the turn's time and
        // swings by at most 2ρ/|c| about that, so after (|z₀ − h| + 2ρ/|c|)/|K₀| and one
        // turn more it has passed h or never will.
        let (k0, rho) = rate_terms(ray);
        let turn = R::from_f64(2.0) * pi::<R>() / c.abs();
        let swing = R::from_f64(2.0) * rho / c.abs();
        if k0 == zero {
            turn
        } else {
            (f0.abs() + swing) / k0.abs() + turn
        }
    };
    let mut points = turning_points(ray, end);
    points.push(end);
    let (mut lo, mut f_lo, mut rate_lo) = (zero, f0, rate0);
    for hi in points {
        let (f_hi, rate_hi) = f(hi);
        let straddles = (f_lo <= zero && f_hi >= zero) || (f_lo >= zero && f_hi <= zero);
        // A start on the plane (f(0) = 0): the height is monotone up to the first turning
        // point, so the plane is not met again before it (the crossing at the start is no
        // exit ahead).
        let from_the_plane = lo == zero && f_lo == zero;
        if straddles && !from_the_plane {
            let rising = f_lo < zero;
            // Newton's step from the bracket's start (short crossings of thin boxes are
            // nearly straight), else the middle.
            let newton = lo - f_lo / rate_lo;
            let start = if rate_lo != zero && newton > lo && newton < hi {
                newton
            } else {
                half_way(lo, hi)
            };
            let root = bracketed_root(&f, (lo, hi), start, |v| (v < zero) == rising);
            if root > zero {
                return Some(root);
            }
        }
        (lo, f_lo, rate_lo) = (hi, f_hi, rate_hi);
    }
    None
}
