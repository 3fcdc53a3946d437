//! The distance of `UT H²` (the universal cover's fibre unwound once: `PSL(2,R)`) and the
//! direction of the shortest geodesic to a point — the inverse of the exponential map — and
//! a root-free lower bound on the distance: what metric balls need.
//!
//! **The inverse exponential map.** With `G = F₀⁻¹F₁` (the target seen from the start's
//! frame), a geodesic of length `t` and unit body velocity `(a, b, c)` reaches it where
//! `exp(U)·exp(2γR) = G` with `U = tW = αB₁ + βB₂ − γR` and `(α, β, γ) = t(a, b, c)`
//! ([`mod@super::flow`]). For a given `γ`, `U` is the logarithm of `H(γ) = G·exp(−2γR)`, so the
//! whole problem is one equation in one unknown:
//!
//! ```text
//! φ(γ) = z(log H(γ)) + γ = 0,    z = the R-coefficient,
//! ```
//!
//! found by a scan outwards from `γ = 0` and the Illinois method on each sign change: a
//! geodesic of length `L` has `|γ| ≤ L`, so the roots of the geodesics shorter than a bound
//! lie in `|γ|` below it, and the scan stops there. (`φ` is smooth between jumps of about
//! `2π`, where the logarithm's rotation passes a half turn; its slope is near −1.) The
//! logarithm is in closed form: `H − H⁻¹ = 2S·U` (`H⁻¹ = J Hᵀ J`), whose Lorentz norm is
//! `N = S²ω² = sinh² ω` (or `sin²` of `|ω|` where `ω² < 0`) and whose trace gives
//! `C = cosh ω = (tr H − 1)/2`; `S = sinh ω/ω` follows from `N` and `C` without cancellation
//! (its series in `N` near the identity). **Which geodesic:** the sectional curvature of
//! this metric is at most ¼, so no point is conjugate before `2π`, and every geodesic loop
//! has length at least `2π` (a loop's base point must come back: a circle of the base takes
//! `2π/|ω| ≥ 2π`, and the fibre is `2π` long); so the injectivity radius is `π`, and a
//! geodesic found shorter than [`TRUSTED_LENGTH`] is the shortest.
//!
//! **The floor.** A curve of length `L` from `(q, f)` to `(p, e)` projects to a base curve of
//! length `ℓ ≤ L` (the projection is a Riemannian submersion), so `L ≥ ρ = d(p, q)`; and `e`
//! turns against `f`'s parallel transport along the base geodesic by its vertical length
//! (at most `L`) plus the holonomy of the closed base loop, its enclosed area, at most
//! `(2L)²/4π` (the isoperimetric inequality, Banchoff–Pohl for curves that cross
//! themselves). So with `ψ` that angle, `|ψ| ≤ L + L²/π`, and
//! `L ≥ max(ρ, 2|ψ|/(1 + √(1 + 4|ψ|/π)))`.

use super::flow::lorentz;

/// Below this length the geodesic the solver finds is the shortest (under the injectivity
/// radius `π` of `UT H²`, with room for the solver's rounding).
pub const TRUSTED_LENGTH: f64 = 3.0;

/// A frame as its columns `e`, `e⊥`, `p`.
pub type Frame = [[f64; 3]; 3];

/// `G = F₀⁻¹F₁` (rows): `G[i][j] = sᵢ⟨F₀ᵢ, F₁ⱼ⟩` with `s = (1, 1, −1)`.
#[must_use]
pub fn relative(from: &Frame, to: &Frame) -> [[f64; 3]; 3] {
    let sign = [1.0, 1.0, -1.0];
    [0, 1, 2].map(|i| [0, 1, 2].map(|j| sign[i] * lorentz(from[i], to[j])))
}

/// `sinh ω/ω` (or `sin|ω|/|ω|`) from `N = sinh² ω` (`−sin²|ω|` where `ω² < 0`) and
/// `C = cosh ω` (`cos|ω|`), on the principal branch `|ω| < π`; `None` for an element that is
/// no such exponential (a half turn, or `C < 1` with `N > 0`).
fn sinhc_from(n: f64, c: f64) -> Option<f64> {
    if n.abs() < 1e-3 && c > 0.0 {
        // 1/(asinh(u)/u) with u² = N, a series in N (the same on both sides of 0).
        let series = 1.0
            + n * (-1.0 / 6.0
                + n * (3.0 / 40.0 + n * (-5.0 / 112.0 + n * (35.0 / 1152.0 - n * 63.0 / 2816.0))));
        return Some(1.0 / series);
    }
    if n > 0.0 {
        if c < 1.0 - 1e-12 {
            return None;
        }
        let u = n.sqrt();
        return Some(u / u.asinh());
    }
    let u = (-n).sqrt();
    let w = u.atan2(c);
    (u > 1e-300 && w > 0.0).then(|| u / w)
}

/// `(x, y, z)` with `exp(xB₁ + yB₂ + zR) = h` on the principal branch, or `None` (see
/// `sinhc_from`).
#[must_use]
pub fn log(h: &[[f64; 3]; 3]) -> Option<[f64; 3]> {
    // (H − H⁻¹)/2 with H⁻¹ = J Hᵀ J: the B₁, B₂ and R parts of S·U.
    let x = 0.5 * (h[0][2] + h[2][0]);
    let y = 0.5 * (h[1][2] + h[2][1]);
    let z = 0.5 * (h[1][0] - h[0][1]);
    let n = x * x + y * y - z * z;
    let c = 0.5 * (h[0][0] + h[1][1] + h[2][2] - 1.0);
    let s = sinhc_from(n, c)?;
    Some([x / s, y / s, z / s])
}

/// `h·exp(−2γR)` (rows).
fn turned(h: &[[f64; 3]; 3], gamma: f64) -> [[f64; 3]; 3] {
    let (sin, cos) = (2.0 * gamma).sin_cos();
    h.map(|r| [r[0] * cos - r[1] * sin, r[0] * sin + r[1] * cos, r[2]])
}

/// The step of the scan for roots of `φ` (its slope is near −1 and its jumps, where the
/// logarithm's rotation passes a half turn, are near `2π`: no two roots hide in one step
/// but at a tangency).
const SCAN_STEP: f64 = 0.125;

/// `φ(γ)` and the logarithm of `H(γ)`, or `None` off the logarithm's branch.
fn phi(g: &[[f64; 3]; 3], gamma: f64) -> Option<(f64, [f64; 3])> {
    log(&turned(g, gamma)).map(|u| (u[2] + gamma, u))
}

/// The root of `φ` between `a` and `b`, where it changes sign continuously, by the Illinois
/// method (regula falsi that halves a stuck end's value) to the last bit.
fn refine(
    g: &[[f64; 3]; 3],
    (mut a, mut fa): (f64, f64),
    (mut b, mut fb): (f64, f64),
) -> Option<(f64, [f64; 3])> {
    let mut u = phi(g, b)?.1;
    for _ in 0..MAX_REFINE_STEPS {
        crate::space::roots::count_root_iteration();
        if fb == 0.0 || (b - a).abs() <= 2.0 * f64::EPSILON * (1.0 + b.abs()) {
            break;
        }
        let mut c = (a * fb - b * fa) / (fb - fa);
        if !(c > a.min(b) && c < a.max(b)) {
            c = 0.5 * (a + b);
        }
        let (fc, uc) = phi(g, c)?;
        if (fc < 0.0) != (fb < 0.0) {
            (a, fa) = (b, fb);
        } else {
            fa *= 0.5;
        }
        (b, fb, u) = (c, fc, uc);
    }
    Some((b, u))
}

/// Most steps of [`refine`].
const MAX_REFINE_STEPS: usize = 100;

/// Most steps of [`secant`].
const MAX_SECANT_STEPS: usize = 12;

/// A root of `φ` by the secant method from the principal guess `γ₀ = z(log G)` (`φ′ ≈ −1`
/// near the identity, so the first step is `γ₀ + φ(γ₀)`), or `None` where it leaves the
/// branch or does not settle: the quick way in, as a geodesic shorter than `π` is the only
/// one shorter than `π` ([`shortest_within`]).
fn secant(g: &[[f64; 3]; 3]) -> Option<(f64, [f64; 3])> {
    let mut g0 = log(g)?[2];
    let (mut f0, u0) = phi(g, g0)?;
    if f0 == 0.0 {
        return Some((g0, u0));
    }
    let mut g1 = g0 + f0;
    let (mut f1, mut u1) = phi(g, g1)?;
    for _ in 0..MAX_SECANT_STEPS {
        crate::space::roots::count_root_iteration();
        if f1 == 0.0 {
            return Some((g1, u1));
        }
        if f1 == f0 {
            break;
        }
        let g2 = g1 - f1 * (g1 - g0) / (f1 - f0);
        let (f2, u2) = phi(g, g2)?;
        let settled = (g2 - g1).abs() <= 4.0 * f64::EPSILON * (1.0 + g2.abs());
        (g0, f0) = (g1, f1);
        (g1, f1, u1) = (g2, f2, u2);
        if settled {
            return Some((g1, u1));
        }
    }
    (f1.abs() <= 1e-12 * (1.0 + g1.abs())).then_some((g1, u1))
}

/// The shortest geodesic from the frame `from` to the frame `to` shorter than `bound`
/// (at most [`TRUSTED_LENGTH`]): its length and unit start velocity in `from`'s body frame,
/// or `None` where there is none — the distance is then at least `bound`.
///
/// Below the injectivity radius `π` the exponential map is one to one, so a root of `φ`
/// whose geodesic is shorter than `π` is the shortest geodesic and the only one that short:
/// the secant method from the principal guess is tried first, and where it finds such a
/// root, that is the answer. Otherwise every geodesic of length `L < π` is a root with
/// `|γ| ≤ √(L² − ρ²)` (`ρ` the base distance, which the base point's path of length
/// `√(α² + β²)` must cover), so the roots with `|γ|` below that for `L = bound` are all there
/// is to search: `φ` is scanned
/// outwards from `γ = 0` in steps of `SCAN_STEP` (⅛), each sign change that is no jump of the
/// branch is refined, and the scan stops once `|γ|` passes the shortest length found.
#[must_use]
pub fn shortest_within(from: &Frame, to: &Frame, bound: f64) -> Option<(f64, [f64; 3])> {
    let g = relative(from, to);
    let bound = bound.min(TRUSTED_LENGTH);
    // The base point moves √(α² + β²) along the base, at least the base distance ρ: a
    // geodesic shorter than L has |γ| below √(L² − ρ²), and none is shorter than ρ.
    let rho = base_distance(from[2], to[2]);
    if rho >= bound {
        return None;
    }
    let mut best: Option<(f64, [f64; 3])> = None;
    let length_of = |gamma: f64, u: [f64; 3]| (u[0] * u[0] + u[1] * u[1] + gamma * gamma).sqrt();
    let unit = |(length, [x, y, gamma]): (f64, [f64; 3])| {
        if length == 0.0 {
            (0.0, [0.0, 0.0, 1.0])
        } else {
            (length, [x / length, y / length, gamma / length])
        }
    };
    if let Some((gamma, u)) = secant(&g) {
        let length = length_of(gamma, u);
        if length < TRUSTED_LENGTH {
            return (length < bound).then(|| unit((length, [u[0], u[1], gamma])));
        }
    }
    let zero = phi(&g, 0.0);
    if let Some((f, u)) = zero
        && f == 0.0
        && length_of(0.0, u) < bound
    {
        best = Some((length_of(0.0, u), [u[0], u[1], 0.0]));
    }
    for side in [1.0, -1.0] {
        let mut last = zero.map(|(f, _)| (0.0, f));
        let mut k = 1.0;
        loop {
            let gamma = side * k * SCAN_STEP;
            let reach = best.map_or(bound, |(l, _)| l.min(bound));
            if gamma.abs() - SCAN_STEP >= (reach * reach - rho * rho).max(0.0).sqrt() {
                break;
            }
            k += 1.0;
            let here = phi(&g, gamma).map(|(f, _)| (gamma, f));
            if let (Some((a, fa)), Some((b, fb))) = (last, here)
                && (fa < 0.0) != (fb < 0.0)
                && (fa - fb).abs() < std::f64::consts::PI
                && let Some((root, u)) = refine(&g, (a, fa), (b, fb))
            {
                let length = length_of(root, u);
                if length < reach {
                    best = Some((length, [u[0], u[1], root]));
                }
            }
            last = here;
        }
    }
    best.map(unit)
}

/// [`shortest_within`] the trusted length.
#[must_use]
pub fn shortest(from: &Frame, to: &Frame) -> Option<(f64, [f64; 3])> {
    shortest_within(from, to, TRUSTED_LENGTH)
}

/// The base distance `d(p, q)` of two hyperboloid points, without cancellation:
/// `2 asinh(|p − q|/2)` (the Lorentz norm of the chord).
#[must_use]
pub fn base_distance(p: [f64; 3], q: [f64; 3]) -> f64 {
    let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
    2.0 * (0.5 * lorentz(d, d).max(0.0).sqrt()).asinh()
}

/// A lower bound on the distance between two frames that needs no root (see the module):
/// the base distance, and the turn of `e` against `f`'s parallel transport along the base
/// geodesic.
#[must_use]
pub fn distance_floor(from: &Frame, to: &Frame) -> f64 {
    let [f, _, q] = *from;
    let [e, e_perp, p] = *to;
    let rho = base_distance(p, q);
    // f carried from q to p: v + ⟨p, v⟩/(1 − ⟨q, p⟩)·(q + p).
    let k = lorentz(p, f) / (1.0 - lorentz(q, p));
    let g = [0, 1, 2].map(|i| f[i] + k * (q[i] + p[i]));
    let psi = lorentz(g, e_perp).abs().atan2(lorentz(g, e));
    let turn = 2.0 * psi / (1.0 + (1.0 + 4.0 * psi / std::f64::consts::PI).sqrt());
    rho.max(turn)
}
