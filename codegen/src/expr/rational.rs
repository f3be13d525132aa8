//! Exact small rationals: the constants `1/2`, `1/6`, `-3/2` that symbolic
//! differentiation and Taylor coefficients produce must stay exact.

use std::cmp::Ordering;
use std::fmt;

/// A reduced fraction `num / den` with `den > 0` and `gcd(num, den) = 1`.
///
/// Arithmetic is checked: an operation whose exact result does not fit in
/// `i64` returns `None`, and the caller falls back to `f64` (see
/// [`crate::Number`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rational {
    num: i64,
    den: i64,
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    a = a.abs();
    b = b.abs();
    while b != 0 {
        let r = a % b;
        a = b;
        b = r;
    }
    a
}

impl Rational {
    /// Zero.
    pub const ZERO: Rational = Rational { num: 0, den: 1 };
    /// One.
    pub const ONE: Rational = Rational { num: 1, den: 1 };
    /// Minus one.
    pub const MINUS_ONE: Rational = Rational { num: -1, den: 1 };

    /// The integer `n`.
    pub const fn integer(n: i64) -> Rational {
        Rational { num: n, den: 1 }
    }

    /// `num / den` reduced; `None` when `den == 0` or the result overflows.
    pub fn new(num: i64, den: i64) -> Option<Rational> {
        Self::from_i128(num as i128, den as i128)
    }

    fn from_i128(num: i128, den: i128) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        let g = gcd(num, den).max(1);
        let (mut num, mut den) = (num / g, den / g);
        if den < 0 {
            num = -num;
            den = -den;
        }
        Some(Rational { num: i64::try_from(num).ok()?, den: i64::try_from(den).ok()? })
    }

    /// The exact rational value of `v` when it is a fraction with a small
    /// power-of-two denominator (0.5, -1.5, 3.0, 0.125), else `None`.
    /// 0.1 is not: its binary value is not 1/10.
    pub fn from_f64_exact(v: f64) -> Option<Rational> {
        if !v.is_finite() {
            return None;
        }
        // Scale by 2^k until integral; bounded so that the denominator stays small.
        let mut scaled = v;
        let mut den: i64 = 1;
        for _ in 0..=20 {
            if scaled.fract() == 0.0 && scaled.abs() < 9.007_199_254_740_992e15 {
                return Rational::new(scaled as i64, den);
            }
            scaled *= 2.0;
            den *= 2;
        }
        None
    }

    /// Numerator.
    pub fn numer(self) -> i64 {
        self.num
    }

    /// Denominator (always positive).
    pub fn denom(self) -> i64 {
        self.den
    }

    /// `true` for whole numbers.
    pub fn is_integer(self) -> bool {
        self.den == 1
    }

    /// `true` for zero.
    pub fn is_zero(self) -> bool {
        self.num == 0
    }

    /// `true` for strictly negative values.
    pub fn is_negative(self) -> bool {
        self.num < 0
    }

    /// The nearest `f64` (correctly rounded when both parts are below 2^53).
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    /// `true` when `to_f64` is exact: the denominator is a power of two and the
    /// numerator fits in 53 bits.
    pub fn is_exact_in_f64(self) -> bool {
        (self.den as u64).is_power_of_two() && self.num.unsigned_abs() < (1u64 << 53)
    }

    /// Exact sum.
    pub fn checked_add(self, o: Rational) -> Option<Rational> {
        let (a, b, c, d) = (self.num as i128, self.den as i128, o.num as i128, o.den as i128);
        Self::from_i128(a * d + c * b, b * d)
    }

    /// Exact product.
    pub fn checked_mul(self, o: Rational) -> Option<Rational> {
        let (a, b, c, d) = (self.num as i128, self.den as i128, o.num as i128, o.den as i128);
        Self::from_i128(a * c, b * d)
    }

    /// Exact quotient; `None` for division by zero.
    pub fn checked_div(self, o: Rational) -> Option<Rational> {
        let (a, b, c, d) = (self.num as i128, self.den as i128, o.num as i128, o.den as i128);
        Self::from_i128(a * d, b * c)
    }

    /// Negation.
    pub fn checked_neg(self) -> Option<Rational> {
        Self::from_i128(-(self.num as i128), self.den as i128)
    }

    /// Exact integer power; `None` on overflow or `0` to a negative power.
    pub fn checked_powi(self, n: i64) -> Option<Rational> {
        let base = if n < 0 { Rational::ONE.checked_div(self)? } else { self };
        let mut e = n.unsigned_abs();
        let mut acc = Rational::ONE;
        let mut sq = base;
        while e > 0 {
            if e & 1 == 1 {
                acc = acc.checked_mul(sq)?;
            }
            e >>= 1;
            if e > 0 {
                sq = sq.checked_mul(sq)?;
            }
        }
        Some(acc)
    }

    /// The exact `q`-th root when it is rational (`4/9` to the `1/2` is `2/3`).
    pub fn exact_root(self, q: i64) -> Option<Rational> {
        if q <= 0 || (self.num < 0 && q % 2 == 0) {
            return None;
        }
        let root = |v: i64| -> Option<i64> {
            let guess = (v.unsigned_abs() as f64).powf(1.0 / q as f64).round() as i64;
            (guess.saturating_sub(1)..=guess + 1)
                .find(|r| Rational::integer(*r).checked_powi(q) == Some(Rational::integer(v.abs())))
                .map(|r| if v < 0 { -r } else { r })
        };
        Rational::new(root(self.num)?, root(self.den)?)
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        (self.num as i128 * other.den as i128).cmp(&(other.num as i128 * self.den as i128))
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(n: i64, d: i64) -> Rational {
        Rational::new(n, d).unwrap()
    }

    #[test]
    fn reduces_and_normalises_sign() {
        assert_eq!(r(2, -4), r(-1, 2));
        assert_eq!(r(-6, -9), r(2, 3));
        assert_eq!(Rational::new(1, 0), None);
    }

    #[test]
    fn arithmetic_is_exact() {
        assert_eq!(r(1, 2).checked_add(r(1, 3)), Some(r(5, 6)));
        assert_eq!(r(1, 6).checked_mul(r(-3, 2)), Some(r(-1, 4)));
        assert_eq!(r(2, 3).checked_powi(-3), Some(r(27, 8)));
        assert_eq!(Rational::ZERO.checked_powi(-1), None);
        assert_eq!(Rational::integer(i64::MAX).checked_add(Rational::ONE), None);
    }

    #[test]
    fn exact_roots_only_when_rational() {
        assert_eq!(r(4, 9).exact_root(2), Some(r(2, 3)));
        assert_eq!(r(-8, 27).exact_root(3), Some(r(-2, 3)));
        assert_eq!(r(2, 1).exact_root(2), None);
        assert_eq!(r(-4, 1).exact_root(2), None);
    }

    #[test]
    fn f64_conversion_is_exact_or_refused() {
        assert_eq!(Rational::from_f64_exact(-1.5), Some(r(-3, 2)));
        assert_eq!(Rational::from_f64_exact(0.125), Some(r(1, 8)));
        assert_eq!(Rational::from_f64_exact(3.0), Some(r(3, 1)));
        assert_eq!(Rational::from_f64_exact(0.1), None);
        assert_eq!(Rational::from_f64_exact(f64::NAN), None);
        assert!(r(3, 8).is_exact_in_f64());
        assert!(!r(1, 3).is_exact_in_f64());
    }
}
