//! Numeric constants of the DAG: exact rationals where possible, finite `f64`
//! otherwise. Every operation either stays finite or reports that it would not.

use crate::expr::rational::Rational;
use std::fmt;

/// A constant value: exact when it can be, a finite `f64` when it cannot.
///
/// Invariant: a `Float` is finite and is not a small dyadic rational (those
/// are stored as `Rational`, so `2.0` and `2` are the same constant).
#[derive(Clone, Copy, Debug)]
pub enum Number {
    /// An exact fraction.
    Rational(Rational),
    /// A finite floating-point value.
    Float(f64),
}

impl PartialEq for Number {
    fn eq(&self, other: &Self) -> bool {
        match (self, other) {
            (Number::Rational(a), Number::Rational(b)) => a == b,
            (Number::Float(a), Number::Float(b)) => a.to_bits() == b.to_bits(),
            _ => false,
        }
    }
}
impl Eq for Number {}

impl std::hash::Hash for Number {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        match self {
            Number::Rational(r) => {
                0u8.hash(state);
                r.hash(state)
            }
            Number::Float(v) => {
                1u8.hash(state);
                v.to_bits().hash(state)
            }
        }
    }
}

impl Number {
    /// Zero.
    pub const ZERO: Number = Number::Rational(Rational::ZERO);
    /// One.
    pub const ONE: Number = Number::Rational(Rational::ONE);
    /// Minus one.
    pub const MINUS_ONE: Number = Number::Rational(Rational::MINUS_ONE);

    /// The canonical constant for `v`; `None` when `v` is not finite.
    pub fn from_f64(v: f64) -> Option<Number> {
        if !v.is_finite() {
            return None;
        }
        Some(match Rational::from_f64_exact(v) {
            Some(r) => Number::Rational(r),
            None => Number::Float(v),
        })
    }

    /// The integer `n`.
    pub fn integer(n: i64) -> Number {
        Number::Rational(Rational::integer(n))
    }

    /// The value as `f64`.
    pub fn to_f64(self) -> f64 {
        match self {
            Number::Rational(r) => r.to_f64(),
            Number::Float(v) => v,
        }
    }

    /// `true` for exact zero.
    pub fn is_zero(self) -> bool {
        matches!(self, Number::Rational(r) if r.is_zero())
    }

    /// `true` for exact one.
    pub fn is_one(self) -> bool {
        self == Number::ONE
    }

    /// `true` for values below zero.
    pub fn is_negative(self) -> bool {
        match self {
            Number::Rational(r) => r.is_negative(),
            Number::Float(v) => v < 0.0,
        }
    }

    /// The exact integer value, if this is one.
    pub fn as_integer(self) -> Option<i64> {
        match self {
            Number::Rational(r) if r.is_integer() => Some(r.numer()),
            _ => None,
        }
    }

    /// The exact rational value, if this is one.
    pub fn as_rational(self) -> Option<Rational> {
        match self {
            Number::Rational(r) => Some(r),
            Number::Float(_) => None,
        }
    }

    fn float(v: f64) -> Option<Number> {
        Number::from_f64(v)
    }

    /// Sum; exact for rationals, `None` if the float result is not finite.
    pub fn checked_add(self, o: Number) -> Option<Number> {
        match (self, o) {
            (Number::Rational(a), Number::Rational(b)) => match a.checked_add(b) {
                Some(r) => Some(Number::Rational(r)),
                None => Number::float(a.to_f64() + b.to_f64()),
            },
            _ => Number::float(self.to_f64() + o.to_f64()),
        }
    }

    /// Product; exact for rationals, `None` if the float result is not finite.
    pub fn checked_mul(self, o: Number) -> Option<Number> {
        match (self, o) {
            (Number::Rational(a), Number::Rational(b)) => match a.checked_mul(b) {
                Some(r) => Some(Number::Rational(r)),
                None => Number::float(a.to_f64() * b.to_f64()),
            },
            _ => Number::float(self.to_f64() * o.to_f64()),
        }
    }

    /// Negation (always finite).
    pub fn negated(self) -> Number {
        match self {
            Number::Rational(r) => match r.checked_neg() {
                Some(n) => Number::Rational(n),
                None => Number::Float(-r.to_f64()),
            },
            Number::Float(v) => Number::Float(-v),
        }
    }

    /// The absolute value.
    pub fn abs(self) -> Number {
        if self.is_negative() {
            self.negated()
        } else {
            self
        }
    }

    /// `self ^ e`: exact when the base is rational and the exponent an
    /// integer, or when a rational root is exact (`4^(1/2) = 2`); `None` when
    /// the result is not a finite real (`0^-1`, `(-2)^(1/2)`).
    pub fn pow(self, e: Number) -> Option<Number> {
        if let (Number::Rational(b), Number::Rational(x)) = (self, e) {
            if b.is_zero() && x.is_negative() {
                return None;
            }
            if x.is_integer() {
                if let Some(r) = b.checked_powi(x.numer()) {
                    return Some(Number::Rational(r));
                }
            } else if let Some(root) = b.exact_root(x.denom()) {
                if let Some(r) = root.checked_powi(x.numer()) {
                    return Some(Number::Rational(r));
                }
            }
        }
        Number::float(pow_f64(self.to_f64(), e))
    }
}

/// `b ^ e` with the semantics of emitted code: `powi` for integer exponents,
/// square roots for half-integers, `powf` otherwise (NaN for a negative base).
pub fn pow_f64(b: f64, e: Number) -> f64 {
    if let Some(n) = e.as_integer() {
        if let Ok(n) = i32::try_from(n) {
            return b.powi(n);
        }
    }
    if let Some(r) = e.as_rational() {
        if r.denom() == 2 {
            // b^(n/2) = b^k * sqrt(b) with k = (n-1)/2, exact since n is odd.
            let k = (r.numer() - 1) / 2;
            if let Ok(k) = i32::try_from(k) {
                return b.powi(k) * b.sqrt();
            }
        }
    }
    b.powf(e.to_f64())
}

impl From<Rational> for Number {
    fn from(r: Rational) -> Number {
        Number::Rational(r)
    }
}

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Number::Rational(r) => write!(f, "{r}"),
            Number::Float(v) => write!(f, "{v:?}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_that_are_small_dyadics_become_exact() {
        assert_eq!(Number::from_f64(2.0), Some(Number::integer(2)));
        assert_eq!(Number::from_f64(-0.0), Some(Number::ZERO));
        assert!(matches!(Number::from_f64(0.1), Some(Number::Float(_))));
        assert_eq!(Number::from_f64(f64::INFINITY), None);
    }

    #[test]
    fn powers_stay_exact_or_refuse() {
        let half = Number::Rational(Rational::new(1, 2).unwrap());
        assert_eq!(Number::integer(9).pow(half), Some(Number::integer(3)));
        assert_eq!(Number::integer(0).pow(Number::MINUS_ONE), None);
        assert_eq!(Number::integer(-2).pow(half), None);
        let sqrt2 = Number::integer(2).pow(half).unwrap().to_f64();
        assert_eq!(sqrt2, 2f64.sqrt());
    }

    #[test]
    fn half_integer_powers_use_square_roots() {
        let e = |n, d| Number::Rational(Rational::new(n, d).unwrap());
        assert_eq!(pow_f64(4.0, e(3, 2)), 8.0);
        assert_eq!(pow_f64(4.0, e(-3, 2)), 0.125);
        assert_eq!(pow_f64(4.0, e(-1, 2)), 0.5);
        assert_eq!(pow_f64(4.0, e(5, 2)), 32.0);
        assert!(pow_f64(-4.0, e(1, 2)).is_nan());
    }

    #[test]
    fn float_overflow_is_reported() {
        let big = Number::from_f64(1e308).unwrap();
        assert_eq!(big.checked_add(big), None);
        assert_eq!(big.checked_mul(big), None);
    }
}
