//! Jacobi's elliptic functions by the arithmetic-geometric mean, in any precision
//! ([`Real`]: `f32`, `f64`, double-double): what Sol's geodesics are written with.
//!
//! For the parameter `m = k²` (`0 ≤ m ≤ 1`, with its complement `m₁ = 1 − m = k′²` given
//! apart, so that `m` near 1 loses nothing) the descending sequence
//!
//! ```text
//! a₀ = 1,  b₀ = k′,  c₀ = k;   aₙ₊₁ = (aₙ + bₙ)/2,  bₙ₊₁ = √(aₙbₙ),  cₙ₊₁ = cₙ²/(4aₙ₊₁)
//! ```
//!
//! (`cₙ₊₁ = (aₙ − bₙ)/2` without its cancellation) converges quadratically; it stops where
//! `c_N` is below the precision. Then (Abramowitz & Stegun 16.4, 17.5, 17.6; DLMF §22.20):
//!
//! - `K(m) = π/(2a_N)`, `E(m) = K·(1 − Σₙ 2ⁿ⁻¹cₙ²)`;
//! - the amplitude `φ₀ = am(u|m)` from `φ_N = 2ᴺa_N·u` down by
//!   `φₙ₋₁ = (φₙ + asin((cₙ/aₙ) sin φₙ))/2`; `sn = sin φ₀`, `cn = cos φ₀`,
//!   `dn = √(m₁ + m·cn²)` (no cancellation);
//! - Jacobi's zeta function `Z(u|m) = E(am u|m) − (E/K)·u = Σₙ₌₁ᴺ cₙ sin φₙ` from the same
//!   amplitudes;
//! - the incomplete integral of the first kind `F(φ|m) = φ_N/(2ᴺa_N)` from `φ₀ = φ` up by
//!   `φₙ₊₁ = φₙ + atan((bₙ/aₙ) tan φₙ)` (the branch that follows `2φₙ`).
//!
//! At `m = 1` the sequence does not converge (`b₀ = 0`): there `sn = tanh u`,
//! `cn = dn = sech u`, `Z = tanh u` and `F(φ|1) = atanh(sin φ)` in closed form. Tested
//! against mpmath at 50 digits (`scripts/elliptic-reference.py`,
//! `tests/data/elliptic.json`) across the parameter and over several periods.

use super::Real;

/// The most steps of the sequence: double-double converges within 9 for `m₁ ≥ 1e-24`.
const MAX_STEPS: usize = 24;

/// A parameter `m = k²` with its complement `m₁ = 1 − m`, and the descending sequence's
/// `aₙ`, `bₙ`, `cₙ` for it.
#[derive(Clone, Copy, Debug)]
pub struct Parameter<R: Real> {
    /// `m = k²`.
    pub m: R,
    /// `m₁ = 1 − m = k′²`.
    pub m1: R,
    a: [R; MAX_STEPS + 1],
    b: [R; MAX_STEPS + 1],
    c: [R; MAX_STEPS + 1],
    /// The last index `N` (0 at `m = 0`; unused at `m = 1`).
    steps: usize,
}

impl<R: Real> Parameter<R> {
    /// The parameter from its moduli `k` and `k′` (`k² + k′² = 1`, both ≥ 0): each given
    /// apart, so that neither loses digits to the other's rounding. `None` outside
    /// `0 ≤ k, k′ ≤ 1`.
    #[must_use]
    pub fn from_moduli(k: R, k_prime: R) -> Option<Self> {
        let in_range = |x: R| x >= R::ZERO && x <= R::ONE;
        if !(in_range(k) && in_range(k_prime)) {
            return None;
        }
        let mut p = Self {
            m: k * k,
            m1: k_prime * k_prime,
            a: [R::ZERO; MAX_STEPS + 1],
            b: [R::ZERO; MAX_STEPS + 1],
            c: [R::ZERO; MAX_STEPS + 1],
            steps: 0,
        };
        p.a[0] = R::ONE;
        p.b[0] = k_prime;
        p.c[0] = k;
        if k_prime == R::ZERO {
            return Some(p);
        }
        let mut n = 0;
        while n < MAX_STEPS && p.c[n] > R::EPSILON * p.a[n] {
            let next = R::from_f64(0.5) * (p.a[n] + p.b[n]);
            p.b[n + 1] = (p.a[n] * p.b[n]).sqrt();
            p.c[n + 1] = p.c[n] * p.c[n] / (R::from_f64(4.0) * next);
            p.a[n + 1] = next;
            n += 1;
        }
        p.steps = n;
        Some(p)
    }

    /// The parameter `m` (`0 ≤ m ≤ 1`; `None` outside), its complement `1 − m` computed
    /// here.
    #[must_use]
    pub fn new(m: R) -> Option<Self> {
        if !(m >= R::ZERO && m <= R::ONE) {
            return None;
        }
        Self::from_moduli(m.sqrt(), (R::ONE - m).sqrt())
    }

    /// Whether `m = 1`, where the functions are hyperbolic and the periods infinite.
    #[must_use]
    pub fn is_one(&self) -> bool {
        self.b[0] == R::ZERO
    }

    /// `K(m)`, the quarter period (infinite at `m = 1`).
    #[must_use]
    pub fn k(&self) -> R {
        if self.is_one() {
            return R::from_f64(f64::INFINITY);
        }
        half_pi::<R>() / self.a[self.steps]
    }

    /// `E(m)`, the complete integral of the second kind (1 at `m = 1`).
    #[must_use]
    pub fn e(&self) -> R {
        if self.is_one() {
            return R::ONE;
        }
        let mut sum = R::ZERO;
        let mut weight = R::from_f64(0.5);
        for n in 0..=self.steps {
            sum = sum + weight * self.c[n] * self.c[n];
            weight = weight * R::from_f64(2.0);
        }
        self.k() * (R::ONE - sum)
    }

    /// The amplitudes `φ₀ = am(u|m), φ₁, …, φ_N` of `u` (`φ_N = 2ᴺa_N·u`).
    fn amplitudes(&self, u: R) -> [R; MAX_STEPS + 1] {
        let mut phi = [R::ZERO; MAX_STEPS + 1];
        let n = self.steps;
        phi[n] = R::from_f64(2f64.powi(n as i32)) * self.a[n] * u;
        for i in (1..=n).rev() {
            let (_, s) = phi[i].cos_sin();
            let x = self.c[i] / self.a[i] * s;
            let asin = x.atan2((R::ONE - x * x).max(R::ZERO).sqrt());
            phi[i - 1] = R::from_f64(0.5) * (phi[i] + asin);
        }
        phi
    }

    /// `am(u|m)`, the amplitude: the continuous angle whose sine is `sn u` and cosine `cn u`.
    #[must_use]
    pub fn am(&self, u: R) -> R {
        if self.is_one() {
            // am(u|1) = gd u = atan(sinh u).
            let (_, sh) = u.cosh_sinh();
            return sh.atan2(R::ONE);
        }
        self.amplitudes(u)[0]
    }

    /// `(sn, cn, dn)(u|m)`.
    #[must_use]
    pub fn sn_cn_dn(&self, u: R) -> (R, R, R) {
        if self.is_one() {
            let (ch, sh) = u.cosh_sinh();
            return (sh / ch, R::ONE / ch, R::ONE / ch);
        }
        let (c, s) = self.am(u).cos_sin();
        (s, c, (self.m1 + self.m * c * c).sqrt())
    }

    /// Jacobi's zeta function `Z(u|m) = E(am u|m) − (E/K)·u` (`tanh u` at `m = 1`).
    #[must_use]
    pub fn zeta(&self, u: R) -> R {
        if self.is_one() {
            let (ch, sh) = u.cosh_sinh();
            return sh / ch;
        }
        let phi = self.amplitudes(u);
        let mut z = R::ZERO;
        for (c, p) in self.c.iter().zip(&phi).take(self.steps + 1).skip(1) {
            let (_, s) = p.cos_sin();
            z = z + *c * s;
        }
        z
    }

    /// `F(φ|m) = ∫₀^φ dθ/√(1 − m sin²θ)`, the incomplete integral of the first kind (the
    /// `u` with `am(u|m) = φ`; `atanh(sin φ)` at `m = 1`, for `|φ| < π/2`).
    #[must_use]
    pub fn f(&self, phi: R) -> R {
        if self.is_one() {
            let (_, s) = phi.cos_sin();
            return R::from_f64(0.5) * ((R::ONE + s) / (R::ONE - s)).ln();
        }
        let two_pi = R::from_f64(4.0) * half_pi::<R>();
        let mut p = phi;
        for n in 0..self.steps {
            let (c, s) = p.cos_sin();
            // atan((b/a) tan φ) on the branch nearest φ itself (it follows φ round the
            // circle: b/a > 0 keeps the quadrant).
            let mut d = (self.b[n] * s).atan2(self.a[n] * c);
            let turns = ((p - d) / two_pi).to_f64().round();
            d = d + R::from_f64(turns) * two_pi;
            p = p + d;
        }
        p / (R::from_f64(2f64.powi(self.steps as i32)) * self.a[self.steps])
    }
}

/// `π/2` to the precision of `R`.
fn half_pi<R: Real>() -> R {
    R::ONE.atan2(R::ZERO)
}
