//! Precision-generic scalars and 4-vectors, so the tracer runs the same code in `f64`
//! (the reference) and `f32` (what the GPU computes), and the difference can be measured.

use glam::{DMat4, DVec4, Mat4, Vec4};
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A floating-point scalar: `f32` or `f64`.
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
    /// The value as an `f64` (exact).
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
        }
    };
}
impl_real!(f32);
impl_real!(f64);

/// A 4-vector of the model (glam's `Vec4` or `DVec4`) with its matching 4×4 matrix type.
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
}

macro_rules! impl_vector4 {
    ($v:ty, $m:ty, $t:ty) => {
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
impl_vector4!(DVec4, DMat4, f64);
impl_vector4!(Vec4, Mat4, f32);
