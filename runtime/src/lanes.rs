//! `L` members' values side by side: the number type of a batch model's
//! generated right-hand side (`#[dae_model(batch = L)]`), where one
//! straight-line program computes every member at once.
//!
//! Each operation is a loop over `L` adjacent `f64`s, which the compiler
//! turns into SIMD instructions where the target has them (add, multiply,
//! divide, square root); the transcendental functions run lane by lane.
//! A batch state stores component `i` of lane `l` at `i·L + l`, so each
//! component's lanes are adjacent (heyoka's batch layout).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// `L` values, one per member.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lanes<const L: usize>(pub [f64; L]);

impl<const L: usize> Lanes<L> {
    /// `v` in every lane.
    pub const fn splat(v: f64) -> Self {
        Lanes([v; L])
    }

    /// `f` of every lane.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f64) -> f64) -> Self {
        Lanes(self.0.map(f))
    }

    /// `f` of every lane pair.
    #[inline(always)]
    pub fn zip(self, other: Self, f: impl Fn(f64, f64) -> f64) -> Self {
        let mut out = self.0;
        for (o, b) in out.iter_mut().zip(other.0) {
            *o = f(*o, b);
        }
        Lanes(out)
    }

    /// √x.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }

    /// xⁿ.
    #[inline(always)]
    pub fn powi(self, n: i32) -> Self {
        self.map(|x| x.powi(n))
    }

    /// xᵉ, `e` a number or lanes.
    #[inline(always)]
    pub fn powf(self, e: impl Into<Self>) -> Self {
        self.zip(e.into(), f64::powf)
    }

    /// atan2(self, x), `x` a number or lanes.
    #[inline(always)]
    pub fn atan2(self, x: impl Into<Self>) -> Self {
        self.zip(x.into(), f64::atan2)
    }
}

/// The elementary functions of the model language, lane by lane.
macro_rules! lane_functions {
    ($($f:ident),*) => {
        impl<const L: usize> Lanes<L> {
            $(
                #[doc = concat!("`", stringify!($f), "` of every lane.")]
                #[inline(always)]
                pub fn $f(self) -> Self {
                    self.map(f64::$f)
                }
            )*
        }
    };
}
lane_functions!(sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp, ln, abs);

impl<const L: usize> From<f64> for Lanes<L> {
    fn from(v: f64) -> Self {
        Lanes::splat(v)
    }
}

impl<const L: usize> Neg for Lanes<L> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(|x| -x)
    }
}

/// `+ − × ÷` between lanes, and between lanes and a number on either side.
macro_rules! lane_operators {
    ($($trait:ident $method:ident $op:tt),*) => {$(
        impl<const L: usize> $trait for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, b: Self) -> Self {
                self.zip(b, |x, y| x $op y)
            }
        }
        impl<const L: usize> $trait<f64> for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $method(self, b: f64) -> Self {
                self.map(|x| x $op b)
            }
        }
        impl<const L: usize> $trait<Lanes<L>> for f64 {
            type Output = Lanes<L>;
            #[inline(always)]
            fn $method(self, b: Lanes<L>) -> Lanes<L> {
                b.map(|y| self $op y)
            }
        }
    )*};
}
lane_operators!(Add add +, Sub sub -, Mul mul *, Div div /);

/// The `N` components of a batch state `y` (component `i` of lane `l` at
/// `y[i·L + l]`), each as lanes.
#[inline(always)]
pub fn load<const L: usize, const N: usize>(y: &[f64]) -> [Lanes<L>; N] {
    std::array::from_fn(|i| {
        let mut lanes = [0.0; L];
        if let Some(values) = y.get(i * L..(i + 1) * L) {
            lanes.copy_from_slice(values);
        }
        Lanes(lanes)
    })
}

/// Writes `values` into a batch state `out`, component `i` of lane `l` at
/// `out[i·L + l]`.
#[inline(always)]
pub fn store<const L: usize, const N: usize>(values: &[Lanes<L>; N], out: &mut [f64]) {
    for (chunk, v) in out.chunks_exact_mut(L).zip(values) {
        chunk.copy_from_slice(&v.0);
    }
}

/// Lane `lane` of a batch state `y` of `n` components.
pub fn lane_of(y: &[f64], lanes: usize, lane: usize) -> Vec<f64> {
    y.iter().skip(lane).step_by(lanes).copied().collect()
}

/// A batch state from each member's state, `states[l]` into lane `l`.
pub fn interleave(states: &[Vec<f64>]) -> Vec<f64> {
    let lanes = states.len();
    let n = states.first().map_or(0, Vec::len);
    let mut y = vec![0.0; n * lanes];
    for (l, state) in states.iter().enumerate() {
        for (i, v) in state.iter().enumerate() {
            y[i * lanes + l] = *v;
        }
    }
    y
}
