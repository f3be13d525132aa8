//! What several test files share: error measures, and small models whose
//! solutions are known in closed form.

// Each test file uses some of these.
#![allow(dead_code)]

use daegen::prelude::*;

pub mod harness;

/// max |got − want| over the components.
pub fn max_error(got: &[f64], want: &[f64]) -> f64 {
    got.iter().zip(want).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
}

/// max |got − want| / max(|want|, floor): relative where the reference is
/// large, absolute (scaled by the floor) where it is small.
pub fn mixed_error(got: &[f64], want: &[f64], floor: f64) -> f64 {
    got.iter().zip(want).map(|(g, r)| (g - r).abs() / r.abs().max(floor)).fold(0.0, f64::max)
}

/// The state a run ended with.
pub fn final_state(sol: &Solution) -> Vec<f64> {
    sol.final_state().to_vec()
}

/// x'' = −x from (1, 0), as x' = v, v' = −x: x = cos t, v = −sin t (with
/// the economic derivatives to order 6, for `Method::TaylorFixed`).
#[dae_model(taylor = 6)]
pub fn oscillator() {
    let x = state(1.0);
    let v = state(0.0);
    der(x) == v;
    der(v) == -x;
}

/// y' = y², y(0) = 1: y = 1/(1 − t), which blows up at t = 1.
#[dae_model]
pub fn blow_up() {
    let y = state(1.0);
    der(y) == y * y;
}

/// A body dropped from 1 m, stopped at the ground: h = 1 − 9.81 t²/2,
/// the impact at t = √(2/9.81).
#[dae_model]
pub fn falling() {
    let h = state(1.0);
    der(der(h)) == -9.81;
    let impact = event(h).falling().terminal();
}

/// `M::default()` from 0 to `t1` by DOP853 at `tol`: the tight run that
/// tests compare a formulation or a method against.
pub fn tight<M: Simulate + Default>(t1: f64, tol: f64) -> Solution {
    let opts = Options::new().method(Method::Dop853).tolerance(tol);
    M::default().simulate(0.0, t1, &opts).unwrap()
}

/// Asserts that `a` and `b` agree on every one of `names` at every one of
/// `times` within `bound`, naming the time and the variable where not.
pub fn assert_agree(a: &Solution, b: &Solution, names: &[&str], times: &[f64], bound: f64) {
    for &t in times {
        for &name in names {
            let (x, y) = (a.at(t, name).unwrap(), b.at(t, name).unwrap());
            assert!((x - y).abs() <= bound, "t = {t}: {name} is {x} against {y}");
        }
    }
}

/// Prothero–Robinson: y' = λ(y − sin t) + cos t, y(0) = 0, exact y = sin t,
/// with λ = −1e6, far stiffer than any step is short.
#[dae_model]
pub fn prothero_robinson() {
    let t = time();
    let lambda = param(-1e6);
    let y = state(0.0);
    der(y) == lambda * (y - sin(t)) + cos(t);
}

include!("impact_times.rs");
