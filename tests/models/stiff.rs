// The stiff reference problems of the IVP Test Set (Bari) with their
// published solutions, shared by tests/stiff.rs and the benchmark
// (`include!`d; reference-problems.md §5–§7). The ODEs are macros so each
// includer chooses the `#[dae_model]` arguments: `van_der_pol_model!();`.

#[allow(unused_macros)]
macro_rules! van_der_pol_model {
    ($($arguments:tt)*) => {
/// Van der Pol, ε = 1e-6 (test set `vdpol`).
#[dae_model($($arguments)*)]
fn van_der_pol() {
    let eps = param(1e-6);
    let y1 = state(2.0);
    let y2 = state(0.0);
    der(y1) == y2;
    der(y2) == ((1.0 - y1 * y1) * y2 - y1) / eps;
}
    };
}

/// Published at t = 2 (test set vdpol.f, RADAU in extended precision).
#[allow(dead_code)]
const VDP_AT_2: [f64; 2] = [0.1706167732170483e1, -0.8928097010247975];

#[allow(unused_macros)]
macro_rules! robertson_model {
    ($($arguments:tt)*) => {
/// Robertson's chemical kinetics (test set `rober`).
#[dae_model($($arguments)*)]
fn robertson() {
    let y1 = state(1.0);
    let y2 = state(0.0);
    let y3 = state(0.0);
    der(y1) == -0.04 * y1 + 1e4 * y2 * y3;
    der(y2) == 0.04 * y1 - 1e4 * y2 * y3 - 3e7 * y2 * y2;
    der(y3) == 3e7 * y2 * y2;
}
    };
}

#[allow(unused_macros)]
macro_rules! robertson_rates_model {
    ($($arguments:tt)*) => {
/// Robertson's kinetics with its three rate constants as parameters (for
/// their sensitivities).
#[dae_model($($arguments)*)]
fn robertson_rates() {
    let k1 = param(0.04);
    let k2 = param(3.0e7);
    let k3 = param(1.0e4);
    let y1 = state(1.0);
    let y2 = state(0.0);
    let y3 = state(0.0);
    der(y1) == -k1 * y1 + k3 * y2 * y3;
    der(y2) == k1 * y1 - k3 * y2 * y3 - k2 * y2 * y2;
    der(y3) == k2 * y2 * y2;
}
    };
}

/// Robertson's kinetics as a semi-explicit index-1 DAE: the third equation
/// replaced by the conservation law it implies (Hairer–Wanner II §IV.10),
/// which the macro solves for y3.
#[dae_model]
fn robertson_dae() {
    let y1 = state(1.0);
    let y2 = state(0.0);
    let y3 = algebraic(0.0);
    der(y1) == -0.04 * y1 + 1e4 * y2 * y3;
    der(y2) == 0.04 * y1 - 1e4 * y2 * y3 - 3e7 * y2 * y2;
    0.0 == y1 + y2 + y3 - 1.0;
}

/// Published at t = 1e11 (test set rober.f).
#[allow(dead_code)]
const ROBER_AT_1E11: [f64; 3] = [
    0.2083340149701255e-7,
    0.8333360770334713e-13,
    0.9999999791665050,
];

#[allow(unused_macros)]
macro_rules! hires_model {
    ($($arguments:tt)*) => {
/// HIRES (test set `hires`).
#[dae_model($($arguments)*)]
fn hires() {
    let y = state_array([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0057]);
    der(y[0]) == -1.71 * y[0] + 0.43 * y[1] + 8.32 * y[2] + 0.0007;
    der(y[1]) == 1.71 * y[0] - 8.75 * y[1];
    der(y[2]) == -10.03 * y[2] + 0.43 * y[3] + 0.035 * y[4];
    der(y[3]) == 8.32 * y[1] + 1.71 * y[2] - 1.12 * y[3];
    der(y[4]) == -1.745 * y[4] + 0.43 * y[5] + 0.43 * y[6];
    der(y[5]) == -280.0 * y[5] * y[7] + 0.69 * y[3] + 1.71 * y[4] - 0.43 * y[5] + 0.69 * y[6];
    der(y[6]) == 280.0 * y[5] * y[7] - 1.81 * y[6];
    der(y[7]) == -280.0 * y[5] * y[7] + 1.81 * y[6];
}
    };
}

/// Published at t = 321.8122 (test set hires.f; Hairer's hir_exact.txt agrees).
#[allow(dead_code)]
const HIRES_AT_END: [f64; 8] = [
    0.7371312573325668e-3,
    0.1442485726316185e-3,
    0.5888729740967575e-4,
    0.1175651343283149e-2,
    0.2386356198831331e-2,
    0.6238968252742796e-2,
    0.2849998395185769e-2,
    0.2850001604814231e-2,
];

#[allow(unused_macros)]
macro_rules! low_pass_model {
    ($($arguments:tt)*) => {
/// A low-pass filter (an RC circuit) driven by a sine, x' = (sin ωt − x)/τ:
/// stiff (ρ = 1/τ) while the solution is a smooth sine; the default
/// τ = 2e-4 at 5 Hz holds DOPRI5 well inside its stability region.
#[dae_model($($arguments)*)]
fn low_pass() {
    let t = time();
    let tau = param(2e-4);
    let omega = param(31.415926535897932);
    let x = state(0.0);
    der(x) == (sin(omega * t) - x) / tau;
}
    };
}

/// The low-pass filter's exact solution from x(0) = 0:
/// x = [sin ωt − ωτ cos ωt + ωτ e^(−t/τ)]/(1 + ω²τ²).
#[allow(dead_code)]
fn low_pass_exact(t: f64, tau: f64, omega: f64) -> f64 {
    let wt = omega * tau;
    ((omega * t).sin() - wt * (omega * t).cos() + wt * (-t / tau).exp()) / (1.0 + wt * wt)
}

/// `akzo_nobel_with! { doc fn name(attributes) { y6 = { value }; statements } }`:
/// the concentrations, rates and rate equations of Akzo Nobel (test set
/// `chemakzo`) as `name`, with `y6` bound to `value` and `statements`
/// after the rate equations: its two forms differ only in how y6 enters.
#[allow(unused_macros)]
macro_rules! akzo_nobel_with {
    ($(#[$($doc:tt)*])* fn $name:ident($($arguments:tt)*) {
        y6 = { $($y6:tt)* };
        $($more:tt)*
    }) => {
$(#[$($doc)*])*
#[dae_model($($arguments)*)]
fn $name() {
    let k1 = param(18.7);
    let k2 = param(0.58);
    let k3 = param(0.09);
    let k4 = param(0.42);
    let kbig = param(34.4);
    let kla = param(3.3);
    let ks = param(115.83);
    let po2 = param(0.9);
    let hen = param(737.0);
    let y1 = state(0.444);
    let y2 = state(0.00123);
    let y3 = state(0.0);
    let y4 = state(0.007);
    let y5 = state(0.0);
    let y6 = $($y6)*;
    let r1 = k1 * y1.powi(4) * sqrt(y2);
    let r2 = k2 * y3 * y4;
    let r3 = k2 / kbig * y1 * y5;
    let r4 = k3 * y1 * y4 * y4;
    let r5 = k4 * y6 * y6 * sqrt(y2);
    let f_in = kla * (po2 / hen - y2);
    der(y1) == -2.0 * r1 + r2 - r3 - r4;
    der(y2) == -0.5 * r1 - r4 - 0.5 * r5 + f_in;
    der(y3) == r1 - r2 + r3;
    der(y4) == -r2 + r3 - 2.0 * r4;
    der(y5) == r2 - r3 + r5;
    $($more)*
}
    };
}

#[allow(unused_macros)]
macro_rules! akzo_nobel_model {
    ($($arguments:tt)*) => {
        akzo_nobel_with! {
            /// The chemical Akzo Nobel problem (test set `chemakzo`), as its authors
            /// write it: five differential equations for the concentrations and one
            /// algebraic, `0 == ks * y1 * y4 - y6`, whose variable enters two rates
            /// squared. An index-1 DAE on t ∈ [0, 180].
            fn akzo_nobel($($arguments)*) {
                y6 = { algebraic(0.444 * 0.007 * 115.83) };
                0.0 == ks * y1 * y4 - y6;
            }
        }
    };
}

#[allow(unused_macros)]
macro_rules! akzo_nobel_by_hand_model {
    ($($arguments:tt)*) => {
        akzo_nobel_with! {
            /// Akzo Nobel with y6 = ks·y1·y4 substituted by hand into the rate that
            /// reads it: the ODE in five concentrations.
            fn akzo_nobel_by_hand($($arguments)*) {
                y6 = { ks * y1 * y4 };
            }
        }
    };
}

/// `chemakzo` at t = 180: y1 … y5, then y6 (the test set's `SOLN`,
/// computed by PSIDE at tolerance 1e-19; Mazzia & Magherini, Test Set for
/// IVP Solvers, release 2.4).
#[allow(dead_code)]
const AKZO_NOBEL_AT_180: [f64; 6] = [
    0.1150794920661702,
    0.1203831471567715e-2,
    0.1611562887407974,
    0.3656156421249283e-3,
    0.1708010885264404e-1,
    0.4873531310307455e-2,
];
