//! Precision-generic scalars and 4-vectors, so the tracer runs the same code in
//! double-double (the reference, [`super::DoubleDouble`]), `f64` and `f32` (what the GPU
//! computes), and the differences can be measured.

use glam::{DMat4, DVec4, Mat4, Vec4};
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A floating-point scalar: `f32`, `f64` or [`super::DoubleDouble`].
pub trait Real:
    Copy
    + PartialOrd
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// Machine epsilon of the type.
    const EPSILON: Self;
    /// The nearest value to an `f64`.
    #[must_use]
    fn from_f64(x: f64) -> Self;
    /// The value as an `f64` (exact for `f32` and `f64`, rounded for double-double).
    #[must_use]
    fn to_f64(self) -> f64;
    /// Square root.
    #[must_use]
    fn sqrt(self) -> Self;
    /// Absolute value.
    #[must_use]
    fn abs(self) -> Self;
    /// The larger of the two.
    #[must_use]
    fn max(self, other: Self) -> Self;
    /// The smaller of the two.
    #[must_use]
    fn min(self, other: Self) -> Self;
    /// The angle of the point `(x, self)`.
    #[must_use]
    fn atan2(self, x: Self) -> Self;
    /// Natural logarithm.
    #[must_use]
    fn ln(self) -> Self;
    /// Neither infinite nor NaN.
    #[must_use]
    fn is_finite(self) -> bool;
    /// `(s, e)` with `s + e = self + b` exactly (Knuth's two-sum; for double-double, `e`
    /// is zero).
    #[must_use]
    fn two_sum(self, b: Self) -> (Self, Self) {
        let s = self + b;
        let bb = s - self;
        (s, (self - (s - bb)) + (b - bb))
    }
    /// `(p, e)` with `p + e = self · b` exactly (a fused multiply-add gives `e`; for
    /// double-double, `e` is zero).
    #[must_use]
    fn two_prod(self, b: Self) -> (Self, Self);
    /// `(cos t, sin t)` of an exact `f64` angle, to this type's precision.
    #[must_use]
    fn cos_sin_of(t: f64) -> (Self, Self) {
        (Self::from_f64(t.cos()), Self::from_f64(t.sin()))
    }
    /// `(cosh t, sinh t)` of an exact `f64` distance, to this type's precision.
    #[must_use]
    fn cosh_sinh_of(t: f64) -> (Self, Self) {
        (Self::from_f64(t.cosh()), Self::from_f64(t.sinh()))
    }
    /// `(cos t, sin t)` of this value, to this type's precision.
    #[must_use]
    fn cos_sin(self) -> (Self, Self) {
        Self::cos_sin_of(self.to_f64())
    }
    /// `(cosh t, sinh t)` of this value, to this type's precision.
    #[must_use]
    fn cosh_sinh(self) -> (Self, Self) {
        Self::cosh_sinh_of(self.to_f64())
    }
}

macro_rules! impl_real {
    ($t:ty) => {
        impl Real for $t {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const EPSILON: Self = <$t>::EPSILON;
            #[inline]
            fn from_f64(x: f64) -> Self {
                x as $t
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn sqrt(self) -> Self {
                <$t>::sqrt(self)
            }
            #[inline]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline]
            fn max(self, other: Self) -> Self {
                <$t>::max(self, other)
            }
            #[inline]
            fn min(self, other: Self) -> Self {
                <$t>::min(self, other)
            }
            #[inline]
            fn atan2(self, x: Self) -> Self {
                <$t>::atan2(self, x)
            }
            #[inline]
            fn ln(self) -> Self {
                <$t>::ln(self)
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$t>::is_finite(self)
            }
            #[inline]
            fn two_prod(self, b: Self) -> (Self, Self) {
                let p = self * b;
                (p, self.mul_add(b, -p))
            }
        }
    };
}
impl_real!(f32);
impl_real!(f64);

/// A 4-vector of the model (glam's `Vec4` or `DVec4`, or [`super::DdVec4`]) with its
/// matching 4×4 matrix type.
pub trait Vector4:
    Copy + Debug + Send + Sync + 'static + Add<Output = Self> + Sub<Output = Self> + Neg<Output = Self>
{
    /// Its scalar.
    type Real: Real;
    /// Its 4×4 matrix.
    type Matrix: Copy + Debug + Send + Sync + 'static + Mul<Self, Output = Self>;
    /// A vector from its components.
    #[must_use]
    fn new(x: Self::Real, y: Self::Real, z: Self::Real, w: Self::Real) -> Self;
    /// Component `i` (x, y, z, w).
    #[must_use]
    fn component(self, i: usize) -> Self::Real;
    /// The w component.
    #[must_use]
    fn w(self) -> Self::Real {
        self.component(3)
    }
    /// The plain Euclidean dot product of R⁴ (a covector applied to a vector).
    #[must_use]
    fn dot(self, other: Self) -> Self::Real;
    /// The vector times a scalar.
    #[must_use]
    fn scale(self, s: Self::Real) -> Self;
    /// The vector in `f64`.
    #[must_use]
    fn to_f64(self) -> DVec4;
    /// The nearest vector to an `f64` one.
    #[must_use]
    fn from_f64(v: DVec4) -> Self;
    /// The nearest matrix to an `f64` one.
    #[must_use]
    fn matrix_from_f64(m: DMat4) -> Self::Matrix;
    /// The nearest vector to `hi + lo` (a double-double's parts), rounded once: for `f64`
    /// the sum, for `f32` its nearest `f32`, for double-double the pair itself.
    #[must_use]
    fn from_f64_pair(hi: DVec4, lo: DVec4) -> Self;
    /// The nearest matrix to `hi + lo`, each entry rounded once.
    #[must_use]
    fn matrix_from_f64_pair(hi: DMat4, lo: DMat4) -> Self::Matrix {
        Self::matrix_from_columns(std::array::from_fn(|j| {
            Self::from_f64_pair(hi.col(j), lo.col(j))
        }))
    }
    /// A matrix from its columns.
    #[must_use]
    fn matrix_from_columns(cols: [Self; 4]) -> Self::Matrix;
    /// Column `j` of a matrix.
    #[must_use]
    fn column(m: &Self::Matrix, j: usize) -> Self;
    /// A matrix in `f64` (exact for `f32` and `f64`).
    #[must_use]
    fn matrix_to_f64(m: &Self::Matrix) -> DMat4 {
        DMat4::from_cols_array_2d(&std::array::from_fn(|j| {
            Self::column(m, j).to_f64().to_array()
        }))
    }
    /// A matrix in double-double, exactly (the walkers split their pairings into the
    /// matrix they use and the rest left out from this).
    #[must_use]
    fn matrix_to_dd(m: &Self::Matrix) -> crate::geometry::DdMat4 {
        crate::geometry::DdMat4::from_f64(Self::matrix_to_f64(m))
    }
    /// `(hi + lo) · x` with the products and sums of `hi · x` compensated (Ogita, Rump and
    /// Oishi's `Dot2`): as accurate as computing in twice the precision and rounding once.
    ///
    /// A pairing of a curved space has entries up to `e^(2r)` for faces at distance `r`
    /// while the points it moves have size `e^r`, so the plain product cancels and loses
    /// about a digit in the Seifert–Weber space; `lo` is what rounding `hi` to this
    /// precision left out (zero in `f64`). See `docs/design.md` §3.
    #[must_use]
    fn transform_compensated(hi: &Self::Matrix, lo: &Self::Matrix, x: Self) -> Self {
        let row = |i: usize| {
            let (mut p, mut s) = Self::column(hi, 0).component(i).two_prod(x.component(0));
            s = s + Self::column(lo, 0).component(i) * x.component(0);
            for j in 1..4 {
                let (h, r) = Self::column(hi, j).component(i).two_prod(x.component(j));
                let (sum, q) = p.two_sum(h);
                p = sum;
                s = s + (q + r) + Self::column(lo, j).component(i) * x.component(j);
            }
            p + s
        };
        Self::new(row(0), row(1), row(2), row(3))
    }
}

macro_rules! impl_vector4 {
    ($v:ident, $m:ty, $t:ty) => {
        impl Vector4 for $v {
            type Real = $t;
            type Matrix = $m;
            #[inline]
            fn new(x: $t, y: $t, z: $t, w: $t) -> Self {
                <$v>::new(x, y, z, w)
            }
            #[inline]
            fn component(self, i: usize) -> $t {
                self[i]
            }
            #[inline]
            fn dot(self, other: Self) -> $t {
                <$v>::dot(self, other)
            }
            #[inline]
            fn scale(self, s: $t) -> Self {
                self * s
            }
            #[inline]
            fn to_f64(self) -> DVec4 {
                DVec4::new(self.x as f64, self.y as f64, self.z as f64, self.w as f64)
            }
            #[inline]
            fn from_f64(v: DVec4) -> Self {
                <$v>::new(v.x as $t, v.y as $t, v.z as $t, v.w as $t)
            }
            #[inline]
            fn column(m: &$m, j: usize) -> Self {
                m.col(j)
            }
            #[inline]
            fn from_f64_pair(hi: DVec4, lo: DVec4) -> Self {
                <$v>::from_array(std::array::from_fn(|i| <$t>::nearest_of_pair(hi[i], lo[i])))
            }
            #[inline]
            fn matrix_from_columns(cols: [Self; 4]) -> $m {
                <$m>::from_cols(cols[0], cols[1], cols[2], cols[3])
            }
            /// The same `Dot2` as the default, four rows at once in glam's SIMD vectors, with
            /// Veltkamp–Dekker splitting for the exact products (plain arithmetic, no
            /// library `fma` call where the target has no fused multiply-add).
            #[inline]
            fn transform_compensated(hi: &$m, lo: &$m, x: Self) -> Self {
                const FACTOR: $t = ((1u64 << <$t>::MANTISSA_DIGITS.div_ceil(2)) + 1) as $t;
                let split = |a: $v| {
                    let c = a * FACTOR;
                    let h = c - (c - a);
                    (h, a - h)
                };
                let mut p = <$v>::ZERO;
                let mut s = <$v>::ZERO;
                for j in 0..4 {
                    let col = hi.col(j);
                    let xj = <$v>::splat(x[j]);
                    let h = col * xj;
                    let (ch, cl) = split(col);
                    let (xh, xl) = split(xj);
                    let r = ((ch * xh - h) + ch * xl + cl * xh) + cl * xl;
                    let extra = lo.col(j) * xj;
                    if j == 0 {
                        p = h;
                        s = r + extra;
                    } else {
                        let sum = p + h;
                        let bb = sum - p;
                        let q = (p - (sum - bb)) + (h - bb);
                        p = sum;
                        s += (q + r) + extra;
                    }
                }
                p + s
            }
            #[inline]
            fn matrix_from_f64(m: DMat4) -> $m {
                <$m>::from_cols(
                    Self::from_f64(m.x_axis),
                    Self::from_f64(m.y_axis),
                    Self::from_f64(m.z_axis),
                    Self::from_f64(m.w_axis),
                )
            }
        }
    };
}
/// The nearest value of a precision to the sum of two `f64`s (a double-double's parts).
trait NearestOfPair {
    fn nearest_of_pair(hi: f64, lo: f64) -> Self;
}

impl NearestOfPair for f64 {
    fn nearest_of_pair(hi: f64, lo: f64) -> f64 {
        hi + lo
    }
}

impl NearestOfPair for f32 {
    fn nearest_of_pair(hi: f64, lo: f64) -> f32 {
        nearest_f32(hi, lo)
    }
}

/// The `f32` nearest `hi + lo` (ties to even), rounded once: `hi`'s nearest `f32`, or its
/// neighbour where the rest of the sum says so (rounding `hi + lo` to `f64` first, then to
/// `f32`, can land on the wrong side of a half-way point).
pub(crate) fn nearest_f32(hi: f64, lo: f64) -> f32 {
    let h = hi as f32;
    if !h.is_finite() {
        return h;
    }
    // `hi − h` is exact (the two are within an f32 unit); lo, far below hi's last place,
    // only decides where hi itself is half-way between two f32s (or on one).
    let d = hi - f64::from(h);
    let toward = if d != 0.0 { d } else { lo };
    if toward == 0.0 {
        return h;
    }
    let next = if toward > 0.0 {
        h.next_up()
    } else {
        h.next_down()
    };
    let half_gap = (f64::from(next) - f64::from(h)).abs() / 2.0;
    let lo_beyond = lo * toward.signum();
    let go = match d.abs().total_cmp(&half_gap) {
        std::cmp::Ordering::Greater => true,
        std::cmp::Ordering::Less => false,
        std::cmp::Ordering::Equal => lo_beyond > 0.0 || lo_beyond == 0.0 && h.to_bits() & 1 == 1,
    };
    if go { next } else { h }
}

impl_vector4!(DVec4, DMat4, f64);
impl_vector4!(Vec4, Mat4, f32);
