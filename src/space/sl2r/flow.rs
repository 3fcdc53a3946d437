//! The geodesics of SL̃(2,R) in closed form, in any precision ([`Real`]: `f32`, `f64`,
//! double-double).
//!
//! A point of the unit tangent bundle `UT H²` is a base point `p` on the hyperboloid
//! `x² + y² − w² = −1` (`w > 0`) with a unit tangent vector `e` there; we keep it as the
//! Lorentz-orthonormal frame `F = (e, e⊥, p)` (columns; `e⊥` is `e` turned by +90°,
//! counter-clockwise seen from `+w`), an element of `SO⁺(2,1) ≅ PSL(2,R)`. The orthonormal
//! frame of the Sasaki metric at `F` is `F·B₁` (`X`: `p` moves along `e`, `e` parallel),
//! `F·B₂` (`Y`: along `e⊥`) and `F·R` (`V`: `e` turns towards `e⊥`, one radian per unit
//! length), with, in the basis `(e, e⊥, p)`,
//!
//! ```text
//! B₁ = E₂₀ + E₀₂,   B₂ = E₂₁ + E₁₂,   R = E₁₀ − E₀₁,
//! [B₁, B₂] = −R,   [R, B₁] = B₂,   [R, B₂] = −B₁.
//! ```
//!
//! The metric is left-invariant and invariant under `Ad(exp sR)`, so (Euler–Arnold) a
//! geodesic's body velocity `ξ = a B₁ + b B₂ + c R` keeps `c`, while `(a, b)` turns at the
//! rate `−2c`; the geodesic from `F₀` is
//!
//! ```text
//! F(t) = F₀ · exp(t W) · exp(2ct R),   W = a B₁ + b B₂ − c R.
//! ```
//!
//! `W³ = ω² W` with `ω² = a² + b² − c²`, so `exp(tW) = I + S W + K W²` with
//!
//! ```text
//! S = t Σ (ω²t²)ᵏ/(2k+1)!  = sinh(ωt)/ω,          K = t² Σ (ω²t²)ᵏ/(2k+2)!  = (cosh ωt − 1)/ω²
//! ```
//!
//! (`sin`/`cos` of `|ω|t` where `ω² < 0`, and `t`, `t²/2` at `ω = 0`): entire functions of
//! `ω²t²`, summed as series while `|ω²t²| < 4` and in closed form beyond, where nothing
//! cancels. So the three kinds of geodesic — the base point on a hypercycle (`ω² > 0`), a
//! horocycle (`ω² = 0`) or a circle (`ω² < 0`) — are one formula, with no test choosing
//! between them and no seam as `ω²` changes sign.
//!
//! The base point moves as `p(t) = F₀ (S a + K bc, S b − K ac, 1 + K(a² + b²))`.

use crate::geometry::Real;

/// A point of `UT H²` as its frame and a velocity in the frame `(X, Y, V)` (unit for a ray).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sl2rRay<R> {
    /// The frame's columns `e`, `e⊥`, `p`, each `(x, y, w)`.
    pub frame: [[R; 3]; 3],
    /// The body velocity `(a, b, c)`.
    pub velocity: [R; 3],
}

/// Below this `|ω²t²|` the flow's `S` and `K` are summed as series.
const SERIES_BELOW: f64 = 4.0;

/// Terms of each series: `4ᵏ/(2k+1)!` is below 10⁻⁴² at `k = 22`, past double-double's
/// precision.
const SERIES_TERMS: u32 = 22;

/// `Σ xᵏ/(n + 2k)!` for `n = 1, 2`, by the exact recurrence of the terms.
fn series<R: Real>(x: R, n: u32) -> R {
    let mut term = R::ONE;
    for k in 1..=n {
        term = term / R::from_f64(f64::from(k));
    }
    let mut total = term;
    for k in 0..SERIES_TERMS {
        let (a, b) = (n + 2 * k + 1, n + 2 * k + 2);
        term = term * x / R::from_f64(f64::from(a * b));
        total = total + term;
        if term.abs() <= R::EPSILON * R::from_f64(1e-3) * total.abs() {
            break;
        }
    }
    total
}

/// `(S, K)` of the flow for `ω² = w2` at time `t` (see the module's formulas).
#[must_use]
pub fn flow_terms<R: Real>(w2: R, t: R) -> (R, R) {
    let x = w2 * t * t;
    if x.abs() < R::from_f64(SERIES_BELOW) {
        return (t * series(x, 1), t * t * series(x, 2));
    }
    let two = R::from_f64(2.0);
    let half = R::from_f64(0.5);
    if w2 > R::ZERO {
        let omega = w2.sqrt();
        let (_, sinh) = (omega * t).cosh_sinh();
        let (_, sinh_half) = (omega * t * half).cosh_sinh();
        (sinh / omega, two * sinh_half * sinh_half / w2)
    } else {
        let omega = (-w2).sqrt();
        let (_, sin) = (omega * t).cos_sin();
        let (_, sin_half) = (omega * t * half).cos_sin();
        (sin / omega, two * sin_half * sin_half / (-w2))
    }
}

/// `ω² = a² + b² − c²` of a body velocity.
#[must_use]
pub fn omega_squared<R: Real>(v: [R; 3]) -> R {
    v[0] * v[0] + v[1] * v[1] - v[2] * v[2]
}

/// The matrix `exp(tW) = I + S W + K W²` (rows) for the body velocity `v`.
fn exp_w<R: Real>(v: [R; 3], s: R, k: R) -> [[R; 3]; 3] {
    let [a, b, c] = v;
    let w = [[R::ZERO, c, a], [-c, R::ZERO, b], [a, b, R::ZERO]];
    let w2 = [
        [a * a - c * c, a * b, b * c],
        [a * b, b * b - c * c, -(a * c)],
        [-(b * c), a * c, a * a + b * b],
    ];
    let mut m = [[R::ZERO; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let id = if i == j { R::ONE } else { R::ZERO };
            m[i][j] = id + s * w[i][j] + k * w2[i][j];
        }
    }
    m
}

/// The frame `F` (columns) times the matrix `m` (rows).
fn times<R: Real>(f: &[[R; 3]; 3], m: &[[R; 3]; 3]) -> [[R; 3]; 3] {
    let mut out = [[R::ZERO; 3]; 3];
    for (j, column) in out.iter_mut().enumerate() {
        for (r, x) in column.iter_mut().enumerate() {
            *x = f[0][r] * m[0][j] + f[1][r] * m[1][j] + f[2][r] * m[2][j];
        }
    }
    out
}

/// The ray moved by `t` along its geodesic: the frame and the body velocity there.
#[must_use]
pub fn flow<R: Real>(ray: &Sl2rRay<R>, t: R) -> Sl2rRay<R> {
    let v = ray.velocity;
    let (s, k) = flow_terms(omega_squared(v), t);
    let moved = times(&ray.frame, &exp_w(v, s, k));
    // exp(φR) turns e towards e⊥ by φ = 2ct.
    let phi = R::from_f64(2.0) * v[2] * t;
    let (cos, sin) = phi.cos_sin();
    let [e, f, p] = moved;
    let frame = [
        [0, 1, 2].map(|r| e[r] * cos + f[r] * sin),
        [0, 1, 2].map(|r| f[r] * cos - e[r] * sin),
        p,
    ];
    let [a, b, c] = v;
    Sl2rRay {
        frame,
        velocity: [a * cos + b * sin, b * cos - a * sin, c],
    }
}

/// The base point `p(t)` alone (cheaper than [`flow`]: no turn of the frame).
#[must_use]
pub fn base_point<R: Real>(ray: &Sl2rRay<R>, t: R) -> [R; 3] {
    let [a, b, c] = ray.velocity;
    let (s, k) = flow_terms(omega_squared(ray.velocity), t);
    let body = [
        s * a + k * b * c,
        s * b - k * a * c,
        R::ONE + k * (a * a + b * b),
    ];
    let f = &ray.frame;
    [0, 1, 2].map(|r| f[0][r] * body[0] + f[1][r] * body[1] + f[2][r] * body[2])
}

/// The Lorentz form `x x′ + y y′ − w w′`.
#[must_use]
pub fn lorentz<R: Real>(u: [R; 3], v: [R; 3]) -> R {
    u[0] * v[0] + u[1] * v[1] - u[2] * v[2]
}

/// `a d − b c` with the products' rounding errors kept (by `two_prod`): no cancellation loss.
fn det2<R: Real>(a: R, d: R, b: R, c: R) -> R {
    let (p, e) = a.two_prod(d);
    let (q, f) = b.two_prod(c);
    (p - q) + (e - f)
}

/// `e⊥ = J(p × e)` (`J = diag(1, 1, −1)`): `e` turned by +90° at `p`, Lorentz-orthogonal to
/// both, positively oriented; each entry a 2×2 determinant summed without cancellation loss.
#[must_use]
pub fn perp<R: Real>(p: [R; 3], e: [R; 3]) -> [R; 3] {
    [
        det2(p[1], e[2], p[2], e[1]),
        det2(p[2], e[0], p[0], e[2]),
        -det2(p[0], e[1], p[1], e[0]),
    ]
}

/// The `w` entry of the tangent vector at `p` with entries `e_x`, `e_y` (`⟨e, p⟩ = 0`):
/// `(e_x p_x + e_y p_y)/p_w`, its sum without cancellation loss.
#[must_use]
pub fn tangent_w<R: Real>(p: [R; 3], ex: R, ey: R) -> R {
    det2(ex, p[0], -ey, p[1]) / p[2]
}

/// The ray put back on the model: `p` on the hyperboloid, `e` a unit tangent vector at it,
/// `e⊥` completing the positively oriented frame, the velocity unit.
#[must_use]
pub fn on_model<R: Real>(ray: &Sl2rRay<R>) -> Sl2rRay<R> {
    let [e, _, p] = ray.frame;
    let scale = |v: [R; 3], s: R| v.map(|x| x * s);
    let p = scale(p, R::ONE / (-lorentz(p, p)).sqrt());
    let along = lorentz(e, p);
    let e = [0, 1, 2].map(|i| e[i] + along * p[i]);
    let e = scale(e, R::ONE / lorentz(e, e).sqrt());
    let f = perp(p, e);
    let v = ray.velocity;
    let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    Sl2rRay {
        frame: [e, f, p],
        velocity: v.map(|x| x / norm),
    }
}

/// The ray moved by the isometry `m` of `H²` (rows; an element of `SO⁺(2,1)`, acting on
/// the frame by its differential): the body velocity is kept.
#[must_use]
pub fn moved_by<R: Real>(m: &[[R; 3]; 3], ray: &Sl2rRay<R>) -> Sl2rRay<R> {
    let apply = |v: [R; 3]| [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2]);
    Sl2rRay {
        frame: ray.frame.map(apply),
        velocity: ray.velocity,
    }
}
