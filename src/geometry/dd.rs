//! Double-double arithmetic: a value is the unevaluated sum `hi + lo` of two `f64`s with
//! `|lo| ≤ ½ ulp(hi)`, about 106 bits (32 digits) of precision.
//!
//! It is the reference the f64 and f32 walks are measured against: the walker is generic
//! over [`Real`]/[`Vector4`], so [`DdVec4`] runs the very same algorithm at twice the
//! digits, and what differs from it in `f64` is rounding, not a different formula.
//!
//! Why double-double rather than a multiprecision crate: it is pure Rust in one file (no
//! C library to build, nothing added to the dependency tree of a game), it is fast enough
//! to trace thousands of 100-crossing rays in a test (a multiply is a handful of `f64`
//! operations, never an allocation), and 106 bits are ample: what we measure is `f64`
//! rounding (53 bits) amplified by the problem's conditioning, and the same amplification
//! leaves double-double 10¹⁶ times further inside.
//!
//! The algorithms are the classical error-free transformations (Dekker, Knuth) with a
//! fused multiply-add for the exact product; `exp`, `ln`, `sin`/`cos` and `atan2` are
//! Taylor series after argument reduction, or one Newton step from the `f64` value (which
//! doubles its digits).

use super::real::{Real, Vector4};
use glam::{DMat4, DVec4};
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A double-double number `hi + lo` (about 32 significant digits).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DoubleDouble {
    /// The leading part: the `f64` nearest the value.
    pub hi: f64,
    /// The rest, `|lo| ≤ ½ ulp(hi)`.
    pub lo: f64,
}

/// `s + e = a + b` exactly.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `s + e = a + b` exactly, given `|a| ≥ |b|`.
#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// `p + e = a · b` exactly.
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

const LN_2: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::LN_2,
    lo: 2.319_046_813_846_299_6e-17,
};
const FRAC_PI_2: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::FRAC_PI_2,
    lo: 6.123_233_995_736_766e-17,
};

/// π to 32 digits.
pub const DD_PI: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::PI,
    lo: 1.224_646_799_147_353_2e-16,
};

impl DoubleDouble {
    /// The exact value of an `f64`.
    #[must_use]
    pub const fn new(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }

    /// The `f64` nearest the value (ties to even): the leading part of a normalised sum.
    #[must_use]
    pub fn round_f64(self) -> f64 {
        self.hi + self.lo
    }

    /// The `f32` nearest the value (ties to even), rounded once.
    #[must_use]
    pub fn round_f32(self) -> f32 {
        super::real::nearest_f32(self.hi, self.lo)
    }

    /// `cos` and `sin` of `π·p/q`, exact at the multiples of π/2 (0 and ±1) and of π/6
    /// (½ and √3/2 to 32 digits), so a turn by a simple fraction has exact zeros.
    #[must_use]
    pub fn cos_sin_pi(p: i64, q: i64) -> (Self, Self) {
        assert!(q != 0, "cos_sin_pi: zero denominator");
        // The angle is k·π/6 with k = 6p/q when that is whole.
        let twelve = 6 * p;
        if twelve % q == 0 {
            let k = (twelve / q).rem_euclid(12);
            let half = Self::new(0.5);
            let root3 = Self::new(3.0).sqrt() * half;
            let (c, s) = match k % 3 {
                0 => {
                    // Multiples of π/2.
                    let q4 = k / 3;
                    let (c, s) = [(1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0)][q4 as usize];
                    (Self::new(c), Self::new(s))
                }
                _ => {
                    // k = 1, 2 (mod 3): π/6 and π/3 and their images.
                    let base = k % 6;
                    let (c, s) = match base {
                        1 => (root3, half),
                        2 => (half, root3),
                        4 => (-half, root3),
                        5 => (-root3, half),
                        _ => unreachable!(),
                    };
                    if k >= 6 { (-c, -s) } else { (c, s) }
                }
            };
            return (c, s);
        }
        let angle = DD_PI * Self::new(p as f64) / Self::new(q as f64);
        let (s, c) = angle.sin_cos();
        (c, s)
    }

    fn normalized(hi: f64, lo: f64) -> Self {
        let (hi, lo) = quick_two_sum(hi, lo);
        Self { hi, lo }
    }

    /// The value times a power of two (exact).
    #[must_use]
    fn ldexp(self, k: i32) -> Self {
        let f = 2f64.powi(k);
        Self {
            hi: self.hi * f,
            lo: self.lo * f,
        }
    }

    /// `eˣ`.
    #[must_use]
    pub fn exp(self) -> Self {
        if self.hi > 709.8 {
            return Self::new(f64::INFINITY);
        }
        if self.hi < -745.2 {
            return Self::new(0.0);
        }
        if !self.hi.is_finite() {
            return Self::new(self.hi.exp());
        }
        // x = k ln 2 + r, |r| ≤ ½ ln 2; eʳ = (e^(r/2⁹))^(2⁹), from eˢ − 1 by squaring.
        let k = (self.hi / LN_2.hi).round();
        let r = (self - LN_2 * Self::new(k)).ldexp(-9);
        // eˢ − 1 = s + s²/2! + …, |s| < 7e-4: 10 terms reach 10⁻³⁴.
        let mut term = r;
        let mut sum = r;
        for n in 2..=10 {
            term = term * r / Self::new(f64::from(n));
            sum = sum + term;
        }
        // (1 + m)² − 1 = 2m + m², keeping the small part exact.
        for _ in 0..9 {
            sum = sum.ldexp(1) + sum * sum;
        }
        (sum + Self::new(1.0)).ldexp(k as i32)
    }

    /// `(sin x, cos x)`.
    #[must_use]
    pub fn sin_cos(self) -> (Self, Self) {
        if !self.hi.is_finite() {
            return (Self::new(f64::NAN), Self::new(f64::NAN));
        }
        // x = q π/2 + r, |r| ≤ π/4 (accurate while |x| is far below 2⁵³).
        let q = (self.hi / FRAC_PI_2.hi).round();
        let r = self - FRAC_PI_2 * Self::new(q);
        let r2 = r * r;
        // Taylor series to r²⁷/27!: below 10⁻³³ for |r| ≤ π/4.
        let (mut s, mut c) = (r, Self::new(1.0));
        let (mut ts, mut tc) = (r, Self::new(1.0));
        for n in 1..=13 {
            let n = f64::from(n);
            ts = -(ts * r2) / Self::new((2.0 * n) * (2.0 * n + 1.0));
            tc = -(tc * r2) / Self::new((2.0 * n - 1.0) * (2.0 * n));
            s = s + ts;
            c = c + tc;
        }
        match (q as i64).rem_euclid(4) {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }

    /// `(cosh x, sinh x)`.
    #[must_use]
    pub fn cosh_sinh(self) -> (Self, Self) {
        if self.hi.abs() < 0.5 {
            // sinh by its series (no cancellation): x + x³/3! + …, 17 terms below 10⁻³³.
            let x2 = self * self;
            let mut term = self;
            let mut s = self;
            for n in 1..=16 {
                let n = f64::from(n);
                term = term * x2 / Self::new((2.0 * n) * (2.0 * n + 1.0));
                s = s + term;
            }
            let c = (Self::new(1.0) + s * s).sqrt();
            return (c, s);
        }
        let e = self.exp();
        let inv = Self::new(1.0) / e;
        ((e + inv).ldexp(-1), (e - inv).ldexp(-1))
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    #[inline]
    fn add(self, b: Self) -> Self {
        let (s1, s2) = two_sum(self.hi, b.hi);
        let (t1, t2) = two_sum(self.lo, b.lo);
        let (s1, s2) = quick_two_sum(s1, s2 + t1);
        Self::normalized(s1, s2 + t2)
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    #[inline]
    fn sub(self, b: Self) -> Self {
        self + (-b)
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    #[inline]
    fn mul(self, b: Self) -> Self {
        let (p1, p2) = two_prod(self.hi, b.hi);
        Self::normalized(p1, p2 + (self.hi * b.lo + self.lo * b.hi))
    }
}

impl Div for DoubleDouble {
    type Output = Self;
    #[inline]
    fn div(self, b: Self) -> Self {
        let q1 = self.hi / b.hi;
        if !q1.is_finite() {
            return Self::new(q1);
        }
        let r = self - b * Self::new(q1);
        let q2 = r.hi / b.hi;
        let r = r - b * Self::new(q2);
        let q3 = r.hi / b.hi;
        Self::normalized(q1, q2) + Self::new(q3)
    }
}

impl PartialOrd for DoubleDouble {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        match self.hi.partial_cmp(&other.hi)? {
            Ordering::Equal => self.lo.partial_cmp(&other.lo),
            o => Some(o),
        }
    }
}

impl Real for DoubleDouble {
    const ZERO: Self = Self::new(0.0);
    const ONE: Self = Self::new(1.0);
    /// 2⁻¹⁰⁴.
    const EPSILON: Self = Self::new(4.930_380_657_631_324e-32);

    #[inline]
    fn from_f64(x: f64) -> Self {
        Self::new(x)
    }

    #[inline]
    fn to_f64(self) -> f64 {
        self.hi + self.lo
    }

    fn sqrt(self) -> Self {
        if self.hi <= 0.0 || !self.hi.is_finite() {
            return Self::new(self.hi.sqrt());
        }
        // One Newton step from the f64 root: y + (x − y²)/(2y).
        let y = Self::new(self.hi.sqrt());
        y + Self::new((self - y * y).hi / (2.0 * y.hi))
    }

    #[inline]
    fn abs(self) -> Self {
        if self.hi < 0.0 { -self } else { self }
    }

    #[inline]
    fn max(self, other: Self) -> Self {
        if self < other || self.hi.is_nan() {
            other
        } else {
            self
        }
    }

    #[inline]
    fn min(self, other: Self) -> Self {
        if other < self || self.hi.is_nan() {
            other
        } else {
            self
        }
    }

    fn atan2(self, x: Self) -> Self {
        // θ from f64, then one Newton step on tan: θ + (y cos θ − x sin θ)/(x cos θ + y sin θ).
        let theta = Self::new(self.hi.atan2(x.hi));
        if (self.hi == 0.0 && x.hi == 0.0) || !theta.hi.is_finite() {
            return theta;
        }
        let (s, c) = theta.sin_cos();
        theta + (self * c - x * s) / (x * c + self * s)
    }

    fn ln(self) -> Self {
        if self.hi <= 0.0 || !self.hi.is_finite() {
            return Self::new(self.hi.ln());
        }
        // One Newton step on eʸ = x from the f64 logarithm: y + x e⁻ʸ − 1.
        let y = Self::new(self.hi.ln());
        y + self * (-y).exp() - Self::ONE
    }

    #[inline]
    fn is_finite(self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }

    #[inline]
    fn two_sum(self, b: Self) -> (Self, Self) {
        (self + b, Self::ZERO)
    }

    #[inline]
    fn two_prod(self, b: Self) -> (Self, Self) {
        (self * b, Self::ZERO)
    }

    fn cos_sin_of(t: f64) -> (Self, Self) {
        let (s, c) = Self::new(t).sin_cos();
        (c, s)
    }

    fn cosh_sinh_of(t: f64) -> (Self, Self) {
        Self::new(t).cosh_sinh()
    }

    fn cos_sin(self) -> (Self, Self) {
        let (s, c) = self.sin_cos();
        (c, s)
    }

    fn cosh_sinh(self) -> (Self, Self) {
        DoubleDouble::cosh_sinh(self)
    }
}

/// A 4-vector of double-doubles.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DdVec4(pub [DoubleDouble; 4]);

/// A 4×4 matrix of double-doubles, by columns (acts on column vectors like glam's).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DdMat4(pub [DdVec4; 4]);

impl Add for DdVec4 {
    type Output = Self;
    #[inline]
    fn add(self, b: Self) -> Self {
        Self(std::array::from_fn(|i| self.0[i] + b.0[i]))
    }
}

impl Sub for DdVec4 {
    type Output = Self;
    #[inline]
    fn sub(self, b: Self) -> Self {
        Self(std::array::from_fn(|i| self.0[i] - b.0[i]))
    }
}

impl Neg for DdVec4 {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self(self.0.map(|x| -x))
    }
}

impl Mul<DdVec4> for DdMat4 {
    type Output = DdVec4;
    #[inline]
    fn mul(self, v: DdVec4) -> DdVec4 {
        DdVec4(std::array::from_fn(|i| {
            (0..4).fold(DoubleDouble::ZERO, |acc, j| acc + self.0[j].0[i] * v.0[j])
        }))
    }
}

impl Mul for DdMat4 {
    type Output = Self;
    fn mul(self, b: Self) -> Self {
        Self(b.0.map(|col| self * col))
    }
}

impl Sub for DdMat4 {
    type Output = Self;
    fn sub(self, b: Self) -> Self {
        Self(std::array::from_fn(|j| self.0[j] - b.0[j]))
    }
}

impl DdMat4 {
    /// The identity.
    pub const IDENTITY: Self = {
        let (o, z) = (DoubleDouble::new(1.0), DoubleDouble::new(0.0));
        Self([
            DdVec4([o, z, z, z]),
            DdVec4([z, o, z, z]),
            DdVec4([z, z, o, z]),
            DdVec4([z, z, z, o]),
        ])
    };

    /// The exact value of an `f64` matrix.
    #[must_use]
    pub fn from_f64(m: DMat4) -> Self {
        <DdVec4 as Vector4>::matrix_from_f64(m)
    }

    /// The leading and trailing parts, as two `f64` matrices.
    #[must_use]
    pub fn parts(&self) -> (DMat4, DMat4) {
        let cols = self.0.map(|c| c.parts());
        (
            DMat4::from_cols(cols[0].0, cols[1].0, cols[2].0, cols[3].0),
            DMat4::from_cols(cols[0].1, cols[1].1, cols[2].1, cols[3].1),
        )
    }

    /// Each entry rounded once to the nearest `f64`.
    #[must_use]
    pub fn round_f64(&self) -> DMat4 {
        DMat4::from_cols_array_2d(&self.0.map(|c| c.round_f64().to_array()))
    }

    /// Entry `(row i, column j)`.
    #[must_use]
    pub fn at(&self, i: usize, j: usize) -> DoubleDouble {
        self.0[j].0[i]
    }

    /// The transpose.
    #[must_use]
    pub fn transpose(&self) -> Self {
        Self(std::array::from_fn(|j| {
            DdVec4(std::array::from_fn(|i| self.0[i].0[j]))
        }))
    }

    /// The largest absolute entry, in `f64`.
    #[must_use]
    pub fn max_abs(&self) -> f64 {
        self.0
            .iter()
            .flat_map(|c| c.0)
            .fold(0.0_f64, |m, x| m.max(x.abs().to_f64()))
    }
}

impl DdVec4 {
    /// The leading and trailing parts, as two `f64` vectors.
    #[must_use]
    pub fn parts(&self) -> (DVec4, DVec4) {
        (
            DVec4::from_array(self.0.map(|x| x.hi)),
            DVec4::from_array(self.0.map(|x| x.lo)),
        )
    }

    /// Each component rounded once to the nearest `f64`.
    #[must_use]
    pub fn round_f64(&self) -> DVec4 {
        DVec4::from_array(self.0.map(DoubleDouble::round_f64))
    }

    /// Each component rounded once to the nearest `f32`.
    #[must_use]
    pub fn round_f32(&self) -> glam::Vec4 {
        glam::Vec4::from_array(self.0.map(DoubleDouble::round_f32))
    }
}

impl Vector4 for DdVec4 {
    type Real = DoubleDouble;
    type Matrix = DdMat4;

    #[inline]
    fn new(x: DoubleDouble, y: DoubleDouble, z: DoubleDouble, w: DoubleDouble) -> Self {
        Self([x, y, z, w])
    }

    #[inline]
    fn component(self, i: usize) -> DoubleDouble {
        self.0[i]
    }

    #[inline]
    fn dot(self, other: Self) -> DoubleDouble {
        (0..4).fold(DoubleDouble::ZERO, |acc, i| acc + self.0[i] * other.0[i])
    }

    #[inline]
    fn scale(self, s: DoubleDouble) -> Self {
        Self(self.0.map(|x| x * s))
    }

    fn to_f64(self) -> DVec4 {
        DVec4::from_array(self.0.map(Real::to_f64))
    }

    fn from_f64(v: DVec4) -> Self {
        Self(v.to_array().map(DoubleDouble::new))
    }

    fn column(m: &DdMat4, j: usize) -> Self {
        m.0[j]
    }

    fn from_f64_pair(hi: DVec4, lo: DVec4) -> Self {
        Self(std::array::from_fn(|i| {
            DoubleDouble::new(hi[i]) + DoubleDouble::new(lo[i])
        }))
    }

    fn matrix_from_f64(m: DMat4) -> DdMat4 {
        DdMat4(
            m.to_cols_array_2d()
                .map(|c| Self::from_f64(DVec4::from_array(c))),
        )
    }

    fn matrix_from_columns(cols: [Self; 4]) -> DdMat4 {
        DdMat4(cols)
    }

    fn matrix_to_dd(m: &DdMat4) -> DdMat4 {
        *m
    }
}
