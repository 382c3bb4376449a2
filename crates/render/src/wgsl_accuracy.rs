//! What the WGSL specification guarantees about f32 arithmetic and built-ins on every
//! conforming GPU, and the running error bound that carries those guarantees through a
//! shader's computation: the source of every GPU parity bound in the workspace.
//!
//! A parity test compares a WGSL function run on the GPU with its f64 reference. The bound
//! it asserts must hold on any GPU that implements WGSL as specified (lavapipe, whose sin,
//! cos, sqrt and division are nearly exact, is far better than the specification; a desktop
//! GPU's special-function unit and a phone's are looser), and still be small enough that a
//! broken shader fails. So a test does not fit its bound to what one device gives: it
//! evaluates the shader's expression a second time on the CPU with [`Inexact`] numbers, each
//! of which carries its f64 value and the most a conforming GPU's f32 result may differ from
//! it, operation by operation, with the accuracy the specification states for that
//! operation. That bound follows the computation's condition case by case (a ray meeting a
//! plane at a grazing angle gets a large one, a well-conditioned case a small one), so every
//! case is checked against its own bound.
//!
//! # The specification's accuracy (WGSL, "Floating Point Accuracy", f32)
//!
//! Stated as the specification words them; ULP is the distance between adjacent f32 values at
//! the result ([`ulp`]):
//!
//! | operation | accuracy |
//! |---|---|
//! | `x + y`, `x - y`, `x * y` | correctly rounded |
//! | `x / y` | 2.5 ULP for \|y\| in the range [2^-126, 2^126] ([`DIVISION_ULP`]) |
//! | `abs`, `min`, `max`, `clamp`, `floor`, `fract`, `select`, comparisons | correctly rounded (exact) |
//! | `fma(x, y, z)` | inherited from x * y + z |
//! | `sin(x)`, `cos(x)` | absolute error ≤ 2^-11 inside the range of [−π, π] ([`SIN_COS_ABSOLUTE`]); nothing outside it |
//! | `exp(x)`, `exp2(x)` | 3 + 2·\|x\| ULP ([`exp_ulp`]) |
//! | `log(x)`, `log2(x)` | absolute error ≤ 2^-21 inside [0.5, 2.0]; 3 ULP outside it ([`LOG_ABSOLUTE_NEAR_ONE`], [`LOG_ULP`]) |
//! | `inverseSqrt(x)` | 2 ULP ([`INVERSE_SQRT_ULP`]) |
//! | `sqrt(x)` | inherited from 1.0 / inverseSqrt(x) |
//! | `pow(x, y)` | inherited from exp2(y * log2(x)) |
//! | `atan(x)`, `atan2(y, x)` | 4096 ULP ([`ATAN_ULP`]) |
//! | `acos(x)` | inherited from atan2(sqrt(1.0 − x * x), x) |
//! | `asin(x)` | inherited from atan2(x, sqrt(1.0 − x * x)) |
//! | `dot(x, y)` | inherited from the sum of x[i] * y[i] |
//! | `length(x)` | inherited from sqrt(dot(x, x)) |
//! | `distance(x, y)` | inherited from length(x − y) |
//! | `normalize(x)` | inherited from x / length(x) |
//! | `mix(x, y, a)` | inherited from x * (1.0 − a) + y * a |
//! | `smoothstep(lo, hi, x)` | inherited from t * t * (3.0 − 2.0 * t), t = clamp((x − lo) / (hi − lo), 0.0, 1.0) |
//!
//! "Inherited" means the result may be anything the expression gives when each of its
//! operations errs as its own row allows: exactly what [`Inexact`] composes. Subnormal
//! results may be flushed to zero; no parity test here works near 2^-126.
//!
//! Two things a shader may rely on are not in that table, and are stated here as assumptions,
//! named where a test uses them:
//! - **sin and cos beyond [−π, π]**: the specification promises nothing there. GPUs reduce
//!   the argument by a multiplication with 1/(2π) in f32 (the hardware takes revolutions),
//!   adding at most [`ARGUMENT_REDUCTION_ULP`] ULP of the argument to the 2^-11.
//! - **texture filtering**: WGSL and WebGPU state no precision for `textureSample*`. Vulkan
//!   requires at least 4 bits of sub-texel precision (`subTexelPrecisionBits` ≥ 4,
//!   [`SUB_TEXEL_PRECISION_BITS_MIN`]), and a filtered half-float texture is not returned more
//!   precisely than its format ([`half_float_ulp`]): an NVIDIA H200 returns a linearly
//!   filtered `Rg16Float` texel to about half an f16 ULP.

use std::f64::consts::PI;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Unit roundoff of f32, 2^-24: a correctly rounded result errs by at most this much
/// relative to its magnitude (half a ULP).
pub const UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

/// `x / y`: 2.5 ULP for |y| in [2^-126, 2^126].
pub const DIVISION_ULP: f64 = 2.5;

/// `inverseSqrt(x)`: 2 ULP.
pub const INVERSE_SQRT_ULP: f64 = 2.0;

/// `sin(x)`, `cos(x)`: absolute error ≤ 2^-11 inside [−π, π].
pub const SIN_COS_ABSOLUTE: f64 = 1.0 / 2048.0;

/// `atan(x)`, `atan2(y, x)`: 4096 ULP.
pub const ATAN_ULP: f64 = 4096.0;

/// `log(x)`, `log2(x)`: absolute error ≤ 2^-21 for x in [0.5, 2.0].
pub const LOG_ABSOLUTE_NEAR_ONE: f64 = 1.0 / 2_097_152.0;

/// `log(x)`, `log2(x)`: 3 ULP for x outside [0.5, 2.0].
pub const LOG_ULP: f64 = 3.0;

/// Assumption (not in the specification): the ULPs of its argument that sin or cos of an
/// argument beyond [−π, π] adds by its reduction into [−π, π] (a product with 1/(2π) in f32:
/// one rounding of the product and one of the constant, each ≤ ½ ULP relative, times 2π).
pub const ARGUMENT_REDUCTION_ULP: f64 = 2.0;

/// Vulkan's lowest allowed `subTexelPrecisionBits`: a filter weight snaps to 1/16 of a texel.
pub const SUB_TEXEL_PRECISION_BITS_MIN: u32 = 4;

/// `exp(x)`, `exp2(x)`: 3 + 2·|x| ULP.
pub fn exp_ulp(x: f64) -> f64 {
    3.0 + 2.0 * x.abs()
}

/// The distance between adjacent f32 values at magnitude |x| (the larger one at a power of
/// two, so a bound stays a bound): 2^(⌊log2 |x|⌋ − 23), 2^-149 below the normal range, 0 for
/// 0. Infinite for a magnitude past f32's range.
pub fn ulp(x: f64) -> f64 {
    let x = x.abs();
    if x == 0.0 {
        return 0.0;
    }
    if x >= f64::from(f32::MAX) {
        return f64::INFINITY;
    }
    let exponent = x.log2().floor().max(-126.0);
    // log2 may round across an integer: keep 2^e ≤ x.
    let exponent = if 2f64.powf(exponent) > x && exponent > -126.0 {
        exponent - 1.0
    } else {
        exponent
    };
    2f64.powf(exponent - 23.0)
}

/// The distance between adjacent f16 values at magnitude |x| (normal range, |x| ≥ 2^-14):
/// what a half-float texture can hold of a value.
pub fn half_float_ulp(x: f64) -> f64 {
    let exponent = x.abs().max(1.0 / 16_384.0).log2().floor();
    2f64.powf(exponent - 10.0)
}

/// A real number a shader computes in f32: its exact value (evaluated in f64) and `error`,
/// the most a conforming GPU's result may differ from it, by the specification's accuracy of
/// each operation so far and the errors of the inputs. Operations follow the table in the
/// module docs; an operation whose inputs' errors reach a singularity (a division by a
/// denominator that may be 0) gives an infinite error: the case cannot be bounded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inexact {
    /// The value in exact (f64) arithmetic.
    pub value: f64,
    /// Bound on |GPU result − value|.
    pub error: f64,
}

impl Inexact {
    /// A value the GPU holds exactly (a small integer, or an input equal to the reference's).
    pub fn exact(value: f64) -> Self {
        Self { value, error: 0.0 }
    }

    /// An input: the reference's `value` and what the GPU is given, `gpu` (its f32 rounding).
    pub fn input(value: f64, gpu: f32) -> Self {
        Self {
            value,
            error: (f64::from(gpu) - value).abs(),
        }
    }

    /// The reference's f32 value given to the GPU as it is (the reference computes with the
    /// same f32 number).
    pub fn of(gpu: f32) -> Self {
        Self::exact(f64::from(gpu))
    }

    /// The largest magnitude the GPU's result can have.
    pub fn magnitude(self) -> f64 {
        self.value.abs() + self.error
    }

    /// The least magnitude the GPU's result can have (0 when it may be 0).
    pub fn least_magnitude(self) -> f64 {
        (self.value.abs() - self.error).max(0.0)
    }

    /// `value` computed from inputs that carry `propagated`, then rounded with an accuracy of
    /// `ulps` ULP of the result.
    fn rounded(value: f64, propagated: f64, ulps: f64) -> Self {
        let error = propagated + ulps * ulp(value.abs() + propagated);
        Self {
            value,
            error: if error.is_nan() { f64::INFINITY } else { error },
        }
    }

    /// Correctly rounded (½ ULP): +, −, ×.
    fn correctly_rounded(value: f64, propagated: f64) -> Self {
        let error = propagated + UNIT_ROUNDOFF * (value.abs() + propagated);
        Self {
            value,
            error: if error.is_nan() { f64::INFINITY } else { error },
        }
    }

    /// Whether the GPU's result is surely above `threshold` (`Some(true)`), surely not
    /// (`Some(false)`), or may fall on either side (`None`: a branch on it is undecided).
    pub fn above(self, threshold: f64) -> Option<bool> {
        if self.value - self.error > threshold {
            Some(true)
        } else if self.value + self.error <= threshold {
            Some(false)
        } else {
            None
        }
    }

    /// `abs(x)`: exact.
    pub fn abs(self) -> Self {
        Self {
            value: self.value.abs(),
            error: self.error,
        }
    }

    /// `min(x, y)`, `max(x, y)`, `clamp`: exact and 1-Lipschitz.
    pub fn min(self, other: Self) -> Self {
        Self {
            value: self.value.min(other.value),
            error: self.error.max(other.error),
        }
    }

    /// See [`Inexact::min`].
    pub fn max(self, other: Self) -> Self {
        Self {
            value: self.value.max(other.value),
            error: self.error.max(other.error),
        }
    }

    /// `clamp(x, lo, hi)` with exact bounds: exact, and it can only shrink an error.
    pub fn clamp(self, lo: f64, hi: f64) -> Self {
        let value = self.value.clamp(lo, hi);
        let least = (self.value - self.error).clamp(lo, hi);
        let most = (self.value + self.error).clamp(lo, hi);
        Self {
            value,
            error: (value - least).max(most - value),
        }
    }

    /// `inverseSqrt(x)`: 2 ULP, and the inputs' error through d(x^-½)/dx = −½ x^-3/2.
    pub fn inverse_sqrt(self) -> Self {
        let least = self.value - self.error;
        if least <= 0.0 {
            return Self {
                value: 1.0 / self.value.sqrt(),
                error: f64::INFINITY,
            };
        }
        let value = 1.0 / self.value.sqrt();
        Self::rounded(value, 1.0 / least.sqrt() - value, INVERSE_SQRT_ULP)
    }

    /// `sqrt(x)`: inherited from 1.0 / inverseSqrt(x). At an argument that may be 0 the
    /// result is only known to lie in [0, √(x + error)] (and the GPU's 1.0 / inverseSqrt(0) is
    /// 1/∞ = 0).
    pub fn sqrt(self) -> Self {
        if self.value - self.error <= 0.0 {
            let value = self.value.max(0.0).sqrt();
            let top = (self.value.max(0.0) + self.error).sqrt();
            return Self {
                value,
                error: top * (1.0 + 8.0 * UNIT_ROUNDOFF),
            };
        }
        Self::exact(1.0) / self.inverse_sqrt()
    }

    /// `sin(x)`: 2^-11 absolute inside [−π, π] (beyond it with the reduction assumption,
    /// [`ARGUMENT_REDUCTION_ULP`]), and the argument's error (sin is 1-Lipschitz).
    pub fn sin(self) -> Self {
        self.trig(self.value.sin())
    }

    /// `cos(x)`: as [`Inexact::sin`].
    pub fn cos(self) -> Self {
        self.trig(self.value.cos())
    }

    fn trig(self, value: f64) -> Self {
        let reduction = if self.magnitude() <= PI {
            0.0
        } else {
            ARGUMENT_REDUCTION_ULP * ulp(self.magnitude())
        };
        Self {
            value,
            error: (self.error + reduction + SIN_COS_ABSOLUTE).min(2.0),
        }
    }

    /// `exp(x)`: 3 + 2·|x| ULP, and the argument's error through e^x.
    pub fn exp(self) -> Self {
        let value = self.value.exp();
        let propagated = value * self.error.exp_m1();
        Self::rounded(value, propagated, exp_ulp(self.magnitude()))
    }

    /// `exp2(x)`: as [`Inexact::exp`].
    pub fn exp2(self) -> Self {
        let value = self.value.exp2();
        let propagated = value * (self.error * std::f64::consts::LN_2).exp_m1();
        Self::rounded(value, propagated, exp_ulp(self.magnitude()))
    }

    /// `log2(x)`: 2^-21 absolute in [0.5, 2], 3 ULP outside, and the argument's error through
    /// 1/(x ln 2).
    pub fn log2(self) -> Self {
        let least = self.value - self.error;
        let value = self.value.log2();
        if least <= 0.0 {
            return Self {
                value,
                error: f64::INFINITY,
            };
        }
        let propagated = value - least.log2();
        let near_one = least >= 0.5 && self.value + self.error <= 2.0;
        let own = if near_one {
            LOG_ABSOLUTE_NEAR_ONE
        } else {
            LOG_ULP * ulp(value.abs() + propagated)
        };
        Self {
            value,
            error: propagated + own,
        }
    }

    /// `pow(x, y)`: inherited from exp2(y * log2(x)).
    pub fn pow(self, exponent: Self) -> Self {
        (exponent * self.log2()).exp2()
    }

    /// `atan2(y, x)` with `self` as y: 4096 ULP, and the inputs' error through the gradient
    /// the angle a displacement of the inputs subtends at the origin.
    pub fn atan2(self, x: Self) -> Self {
        let value = self.value.atan2(x.value);
        let r = self.value.hypot(x.value);
        let e = self.error.hypot(x.error);
        if e >= r {
            return Self {
                value,
                error: 2.0 * PI,
            };
        }
        // Moving a point at distance r from the origin by e turns it by at most e/(r − e).
        let propagated = e / (r - e);
        Self::rounded(value, propagated, ATAN_ULP)
    }

    /// `acos(x)`: inherited from atan2(sqrt(1.0 − x * x), x).
    pub fn acos(self) -> Self {
        (Self::exact(1.0) - self * self).sqrt().atan2(self)
    }
}

impl Add for Inexact {
    type Output = Self;
    fn add(self, other: Self) -> Self {
        Self::correctly_rounded(self.value + other.value, self.error + other.error)
    }
}

impl Sub for Inexact {
    type Output = Self;
    fn sub(self, other: Self) -> Self {
        Self::correctly_rounded(self.value - other.value, self.error + other.error)
    }
}

impl Neg for Inexact {
    type Output = Self;
    fn neg(self) -> Self {
        Self {
            value: -self.value,
            error: self.error,
        }
    }
}

impl Mul for Inexact {
    type Output = Self;
    fn mul(self, other: Self) -> Self {
        let propagated = self.value.abs() * other.error
            + other.value.abs() * self.error
            + self.error * other.error;
        Self::correctly_rounded(self.value * other.value, propagated)
    }
}

impl Div for Inexact {
    type Output = Self;
    /// `x / y`: 2.5 ULP, and the inputs' error through x/y at the smallest |y| they allow.
    fn div(self, other: Self) -> Self {
        let value = self.value / other.value;
        let least = other.least_magnitude();
        if least < 1.0 / 8.507_059_173_023_462e37 {
            // |y| may be 0 or under 2^-126: the specification bounds nothing.
            return Self {
                value,
                error: f64::INFINITY,
            };
        }
        let propagated = (self.error + value.abs() * other.error) / least;
        Self::rounded(value, propagated, DIVISION_ULP)
    }
}

/// A sum of `terms` in whatever order (and association) the GPU's compiler picks: each of
/// the n − 1 additions rounds a partial sum no larger than Σ |term|.
pub fn sum(terms: &[Inexact]) -> Inexact {
    let value: f64 = terms.iter().map(|t| t.value).sum();
    let propagated: f64 = terms.iter().map(|t| t.error).sum();
    let largest: f64 = terms.iter().map(|t| t.magnitude()).sum();
    let additions = terms.len().saturating_sub(1) as f64;
    Inexact {
        value,
        error: propagated + additions * UNIT_ROUNDOFF * largest,
    }
}

/// `dot(a, b)`: inherited from the sum of a[i] * b[i] (in any order: [`sum`]).
pub fn dot(a: &[Inexact], b: &[Inexact]) -> Inexact {
    let terms: Vec<Inexact> = a.iter().zip(b).map(|(x, y)| *x * *y).collect();
    sum(&terms)
}

/// `length(v)`: inherited from sqrt(dot(v, v)).
pub fn length(v: &[Inexact]) -> Inexact {
    dot(v, v).sqrt()
}

/// `normalize(v)`: inherited from v / length(v).
pub fn normalize<const N: usize>(v: [Inexact; N]) -> [Inexact; N] {
    let l = length(&v);
    v.map(|c| c / l)
}

/// `mix(x, y, a)`: inherited from x * (1.0 − a) + y * a.
pub fn mix(x: Inexact, y: Inexact, a: Inexact) -> Inexact {
    x * (Inexact::exact(1.0) - a) + y * a
}

/// `smoothstep(lo, hi, x)`: inherited from t * t * (3.0 − 2.0 * t),
/// t = clamp((x − lo) / (hi − lo), 0.0, 1.0).
pub fn smoothstep(lo: Inexact, hi: Inexact, x: Inexact) -> Inexact {
    let t = ((x - lo) / (hi - lo)).clamp(0.0, 1.0);
    t * t * (Inexact::exact(3.0) - Inexact::exact(2.0) * t)
}

/// Componentwise `a + b`, `a − b`, `s * a` of 3-vectors.
pub fn add3(a: [Inexact; 3], b: [Inexact; 3]) -> [Inexact; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// See [`add3`].
pub fn sub3(a: [Inexact; 3], b: [Inexact; 3]) -> [Inexact; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// See [`add3`].
pub fn scale3(s: Inexact, a: [Inexact; 3]) -> [Inexact; 3] {
    a.map(|c| s * c)
}

/// The half float nearest `x` (round to nearest even, normal range): what an `Rg16Float`
/// texel or a half-precision filter result holds of it.
pub fn to_half_float(x: f64) -> f64 {
    let step = half_float_ulp(x);
    (x / step).round_ties_even() * step
}

/// The most a linear filter may move a sampled position, in texels, per axis, by Vulkan's
/// least sub-texel precision: a weight snapped to 2^-bits of a texel (truncated: a whole
/// step).
pub fn sub_texel_snap_texels() -> f64 {
    1.0 / f64::from(1u32 << SUB_TEXEL_PRECISION_BITS_MIN)
}

#[cfg(test)]
mod tests;
