//! The number type of the tape's Taylor coefficients: `f64` for one
//! solution, [`Lanes`] for a batch's members side by side, so that the
//! recurrences are written once and run on either (heyoka's batch mode
//! runs its Taylor jets on SIMD lanes the same way).

use crate::lanes::Lanes;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A Taylor coefficient: arithmetic and the elementary functions the tape
/// needs, lane by lane. The operations on `f64` are the plain ones, so a
/// recurrence written on `Coefficient` rounds as it would written on `f64`.
pub trait Coefficient:
    Copy
    + std::fmt::Debug
    + PartialEq
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `v` in every lane.
    fn splat(v: f64) -> Self;
    /// Whether `self` and `other` hold the same bits in every lane (the
    /// tape shares a row between equal constants).
    fn same(&self, other: &Self) -> bool;
    /// `f` of every lane.
    fn map(self, f: impl Fn(f64) -> f64) -> Self;
    /// `f` of every pair of lanes.
    fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self;
    /// `(sin, cos)` of every lane.
    fn sin_cos(self) -> (Self, Self);
    /// The number of lanes.
    const WIDTH: usize;
    /// Lane `i`'s value.
    fn lane(&self, i: usize) -> f64;
    /// `self` with lane `i` replaced by `v`.
    fn with_lane(self, i: usize, v: f64) -> Self;
}

impl Coefficient for f64 {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        v
    }
    fn same(&self, other: &Self) -> bool {
        self.to_bits() == other.to_bits()
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        f(self)
    }
    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        f(self, other)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        f64::sin_cos(self)
    }
    const WIDTH: usize = 1;
    #[inline(always)]
    fn lane(&self, _: usize) -> f64 {
        *self
    }
    #[inline(always)]
    fn with_lane(self, _: usize, v: f64) -> Self {
        v
    }
}

impl<const L: usize> Coefficient for Lanes<L> {
    #[inline(always)]
    fn splat(v: f64) -> Self {
        Lanes::splat(v)
    }
    fn same(&self, other: &Self) -> bool {
        self.0.iter().zip(&other.0).all(|(a, b)| a.to_bits() == b.to_bits())
    }
    #[inline(always)]
    fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Lanes::map(self, f)
    }
    #[inline(always)]
    fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        Lanes::zip(self, other, f)
    }
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        let (mut s, mut c) = ([0.0; L], [0.0; L]);
        for ((s, c), x) in s.iter_mut().zip(&mut c).zip(self.0) {
            (*s, *c) = x.sin_cos();
        }
        (Lanes(s), Lanes(c))
    }
    const WIDTH: usize = L;
    #[inline(always)]
    fn lane(&self, i: usize) -> f64 {
        self.0.get(i).copied().unwrap_or(f64::NAN)
    }
    #[inline(always)]
    fn with_lane(mut self, i: usize, v: f64) -> Self {
        if let Some(x) = self.0.get_mut(i) {
            *x = v;
        }
        self
    }
}
