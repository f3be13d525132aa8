//! Every method on every reference problem, through the harness of
//! `support::harness`: a table of problems, each with its tolerances, its
//! reference (exact, or published: ../shared/notes/reference-problems.md),
//! its error bound and its time scale and stiffness, and every method of
//! `Method::ALL` run on each, meeting its bound, failing as documented or
//! refused with its reason.
//!
//! The bound is the problem's condition, not the method's: a sound error
//! controller keeps the global error within a problem-dependent multiple
//! of the tolerance (Shampine's tolerance proportionality; HNW I §II.4),
//! large where the problem amplifies errors (eccentric orbits, a chaotic
//! flow) and small where it damps them (stiff problems). Each problem's
//! solver statistics are pinned by an inline snapshot, so a change in the
//! steps any method takes, or in which methods fail or refuse, is reviewed
//! like a change in code.

use daegen::prelude::*;

include!("models/arenstorf.rs");
include!("models/kepler.rs");
include!("models/lorenz.rs");
include!("models/pendulum.rs");
include!("models/stiff.rs");

arenstorf_model!();
// With the economic Taylor scheme to order 4, so that `TaylorFixed` of
// `Method::ALL` runs on it.
kepler_model!(taylor = 4);
lorenz_model!([-8.0, 8.0, 27.0],);
cash_pendulum_model!();
van_der_pol_model!();
robertson_model!();
hires_model!();
low_pass_model!();
akzo_nobel_model!();

mod support;

use support::harness::{run_every_method, Problem};

/// max |y − ref| / max(1, |ref|) over the components.
fn mixed_error(y: &[f64], reference: &[f64]) -> f64 {
    support::mixed_error(y, reference, 1.0)
}

/// max |y − ref| / |ref|: for components far below 1 (chemistry).
fn relative_error(y: &[f64], reference: &[f64]) -> f64 {
    support::mixed_error(y, reference, 0.0)
}

/// Every method on every problem, each within its bound, failing as
/// documented, or refused; the table of every run, for the snapshots.
// One block a problem: the blocks share their shape by design.
fn run_all() -> Vec<(&'static str, String)> {
    let mut tables = Vec::new();
    let mut beyond = Vec::new();
    let mut add = |(table, mut wrong): (String, Vec<String>), name| {
        tables.push((name, table));
        beyond.append(&mut wrong);
    };
    add(
        run_every_method(&Problem {
            name: "kepler",
            model: Kepler::default(),
            t1: 2.0 * std::f64::consts::PI,
            error: |s| mixed_error(s.final_state(), &kepler_exact(2.0 * std::f64::consts::PI)),
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // An eccentric orbit (e = 0.9): the pericentre passage, 19 times
            // faster than the apocentre, amplifies the local errors and an
            // energy error shifts the phase along the orbit (10²–10⁵).
            bound: 1e5,
            // At the pericentre r = a(1 − e) = 0.1: the local period
            // r^(3/2) = 0.032, and ρ(J) = √(2/r³) = 45.
            time_scale: 0.032,
            settled_time_scale: None,
            stiffness: 45.0,
            gmres: false,
        }),
        "kepler",
    );
    add(
        run_every_method(&Problem {
            name: "arenstorf",
            model: Arenstorf::default(),
            t1: ARENSTORF_T,
            error: |s| mixed_error(s.final_state(), &ARENSTORF_Y0),
            tolerances: &[1e-7, 1e-9, 1e-11],
            atol_scale: 1.0,
            // Two close approaches to the Moon per period.
            bound: 1e5,
            // Each close approach passes the Moon within about 0.01 time
            // units, where ρ(J) is of the order of its inverse.
            time_scale: 0.01,
            settled_time_scale: None,
            stiffness: 100.0,
            gmres: false,
        }),
        "arenstorf",
    );
    add(
        run_every_method(&Problem {
            name: "lorenz",
            model: Lorenz::default(),
            t1: 16.0,
            error: |s| mixed_error(s.final_state(), &LORENZ_HNW_AT_16),
            tolerances: &[1e-8, 1e-10, 1e-12],
            atol_scale: 1.0,
            // Chaotic: errors grow as e^(0.9 t), 2e6 by t = 16, times the
            // local error constant of each step.
            bound: 1e8,
            // σ + 1 = 11 and the eigenvalue −22.8 at the origin: ρ(J) ≈ 20,
            // the flow turning on time scales of 1/20.
            time_scale: 0.05,
            settled_time_scale: None,
            stiffness: 20.0,
            gmres: false,
        }),
        "lorenz",
    );
    add(
        run_every_method(&Problem {
            name: "cash_pendulum",
            model: CashPendulum::default(),
            t1: 10.0,
            error: |s| {
                let y = s.final_state();
                let lambda = s.last("lambda").unwrap_or(f64::NAN);
                mixed_error(&[y[0], y[1], y[2], y[3], lambda], &CASH_PENDULUM_AT_10)
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // A pendulum over ten swings, projected onto its constraints.
            bound: 1e3,
            // g = l = 1: ω = 1.
            time_scale: 1.0,
            settled_time_scale: None,
            stiffness: 1.0,
            gmres: false,
        }),
        "cash_pendulum",
    );
    add(
        run_every_method(&Problem {
            name: "van_der_pol",
            model: VanDerPol::default(),
            t1: 2.0,
            error: |s| mixed_error(s.final_state(), &VDP_AT_2),
            tolerances: &[1e-5, 1e-7, 1e-9],
            atol_scale: 1.0,
            // Stiff: the slow manifold damps errors, even across the jump
            // between its branches before t = 2.
            bound: 1e1,
            // ρ(J) ≈ (y1² − 1)/ε = 3e6 at y1 = 2, ε = 1e-6; the jump
            // between the branches takes a few hundredths.
            time_scale: 0.01,
            settled_time_scale: None,
            stiffness: 3e6,
            gmres: true,
        }),
        "van_der_pol",
    );
    add(
        run_every_method(&Problem {
            name: "robertson",
            model: Robertson::default(),
            t1: 1e11,
            error: |s| relative_error(s.final_state(), &ROBER_AT_1E11),
            tolerances: &[1e-6, 1e-8, 1e-10],
            // y2 falls to 1e-13: its absolute tolerance lies far below it.
            atol_scale: 1e-10,
            bound: 1e1,
            // ρ(J) ≈ 1e4 (k3·y3 + 2·k2·y2 + k1) once y3 grows, while the
            // concentrations change over decades of time from t ≈ 1 on.
            time_scale: 1.0,
            settled_time_scale: None,
            stiffness: 1e4,
            gmres: true,
        }),
        "robertson",
    );
    add(
        run_every_method(&Problem {
            name: "hires",
            model: Hires::default(),
            t1: 321.8122,
            error: |s| relative_error(s.final_state(), &HIRES_AT_END),
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1e-4,
            bound: 1e2,
            // ρ(J) ≥ 280·y6 + 0.43 ≈ 1e2 once y6 has grown, while the
            // solution settles over tens of time units.
            time_scale: 10.0,
            settled_time_scale: None,
            stiffness: 1e2,
            gmres: true,
        }),
        "hires",
    );
    add(
        run_every_method(&Problem {
            name: "low_pass",
            model: LowPass::default(),
            t1: 0.5,
            error: |s| {
                let m = LowPass::default();
                let exact = low_pass_exact(0.5, m.tau, m.omega);
                mixed_error(s.final_state(), &[exact])
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            atol_scale: 1.0,
            // Stiff and damped: the error forgets its past.
            bound: 1e2,
            // The drive's 1/ω = 0.032; ρ = 1/τ = 5e3.
            time_scale: 0.032,
            settled_time_scale: None,
            stiffness: 5e3,
            gmres: true,
        }),
        "low_pass",
    );
    add(
        run_every_method(&Problem {
            name: "akzo_nobel",
            model: AkzoNobel::default(),
            t1: 180.0,
            error: |s| {
                let y = s.final_state();
                let y6 = s.last("y6").unwrap_or(f64::NAN);
                relative_error(&[y[0], y[1], y[2], y[3], y[4], y6], &AKZO_NOBEL_AT_180)
            },
            tolerances: &[1e-6, 1e-8, 1e-10],
            // y4 falls to 4e-4.
            atol_scale: 1e-4,
            // Written with its algebraic variable; solved with y6 from its
            // equation, as an ODE in five concentrations, damped.
            bound: 1e3,
            // y2 settles within a tenth of a time unit (ρ(J) ≈ 8.5 at the
            // start: r1/(4 y2) + klA), a step longer than that takes it
            // below zero under its square root; then the concentrations
            // drift over tens of time units while ρ(J) stays near 3.4 (the
            // explicit pairs' stiffness test measures h·ρ ≈ 3.3 at h ≈ 1).
            time_scale: 0.1,
            settled_time_scale: Some(50.0),
            stiffness: 10.0,
            gmres: false,
        }),
        "akzo_nobel",
    );
    assert!(beyond.is_empty(), "{}", beyond.join("\n"));
    tables
}

#[test]
fn every_method_meets_every_reference_within_its_bound() {
    let tables = run_all();
    for (name, table) in &tables {
        println!("{name}\n{table}");
    }
    let table = |name: &str| {
        tables.iter().find(|(n, _)| *n == name).map(|(_, t)| t.clone()).unwrap_or_default()
    };
    insta::assert_snapshot!(table("kepler"), @r"
Auto (Dopri5)         1e-6      52 steps   17 rejected    416 f    0 J
Auto (Dop853)         1e-8      42 steps   17 rejected    836 f    0 J
Auto (Dop853)         1e-10     70 steps   30 rejected   1412 f    0 J
Taylor                1e-6      58 steps    0 rejected     58 f    0 J
Taylor                1e-8      54 steps    0 rejected     54 f    0 J
Taylor                1e-10     47 steps    0 rejected     47 f    0 J
TaylorFixed           h       1000 steps    0 rejected   1000 f    0 J
Euler                 h       1000 steps    0 rejected   1000 f    0 J
BackwardEuler         h      Error::StepSizeUnderflow at t = 5.165e0
Rk4                   h       1000 steps    0 rejected   4000 f    0 J
Rk38                  h       1000 steps    0 rejected   4000 f    0 J
Midpoint              h       1000 steps    0 rejected   2000 f    0 J
Heun                  h       1000 steps    0 rejected   2000 f    0 J
Ralston               h       1000 steps    0 rejected   2000 f    0 J
Dopri5                1e-6      52 steps   17 rejected    416 f    0 J
Dopri5                1e-8     118 steps    9 rejected    764 f    0 J
Dopri5                1e-10    294 steps    1 rejected   1772 f    0 J
Dop853                1e-6      27 steps   11 rejected    539 f    0 J
Dop853                1e-8      42 steps   17 rejected    836 f    0 J
Dop853                1e-10     70 steps   30 rejected   1412 f    0 J
Radau5                1e-6      87 steps    0 rejected    597 f   82 J
Radau5                1e-8     182 steps    1 rejected   1268 f   72 J
Radau5                1e-10    390 steps    0 rejected   2718 f   42 J
Rodas5P               1e-6      78 steps    1 rejected    631 f   78 J
Rodas5P               1e-8     181 steps    0 rejected   1448 f  181 J
Rodas5P               1e-10    442 steps    0 rejected   3536 f  442 J
    ");
    insta::assert_snapshot!(table("arenstorf"), @r"
Auto (Dopri5)         1e-7     216 steps   24 rejected   1442 f    0 J
Auto (Dop853)         1e-9     136 steps   50 rejected   2642 f    0 J
Auto (Dop853)         1e-11    229 steps   69 rejected   4265 f    0 J
Taylor                1e-7     124 steps    0 rejected    124 f    0 J
Taylor                1e-9     130 steps    0 rejected    130 f    0 J
Taylor                1e-11    136 steps    0 rejected    136 f    0 J
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h       1001 steps    0 rejected   1001 f    0 J
BackwardEuler         h      Error::StepSizeUnderflow at t = 1.341e1
Rk4                   h       1001 steps    0 rejected   4004 f    0 J
Rk38                  h       1001 steps    0 rejected   4004 f    0 J
Midpoint              h       1001 steps    0 rejected   2002 f    0 J
Heun                  h       1001 steps    0 rejected   2002 f    0 J
Ralston               h       1001 steps    0 rejected   2002 f    0 J
Dopri5                1e-7     216 steps   24 rejected   1442 f    0 J
Dopri5                1e-9     530 steps    5 rejected   3212 f    0 J
Dopri5                1e-11   1333 steps    2 rejected   8012 f    0 J
Dop853                1e-7      83 steps   33 rejected   1643 f    0 J
Dop853                1e-9     136 steps   50 rejected   2642 f    0 J
Dop853                1e-11    229 steps   69 rejected   4265 f    0 J
Radau5                1e-7     303 steps    0 rejected   2112 f  265 J
Radau5                1e-9     650 steps    0 rejected   4544 f  241 J
Radau5                1e-11   1409 steps    0 rejected   9857 f  135 J
Rodas5P               1e-7     340 steps    2 rejected   2734 f  340 J
Rodas5P               1e-9     836 steps    0 rejected   6688 f  836 J
Rodas5P               1e-11   2083 steps    0 rejected  16664 f 2083 J
    ");
    insta::assert_snapshot!(table("lorenz"), @r"
Auto (Dop853)         1e-8     401 steps  112 rejected   7361 f    0 J
Auto (Dop853)         1e-10    693 steps   62 rejected  11141 f    0 J
Auto (Dop853)         1e-12   1228 steps   46 rejected  18974 f    0 J
Taylor                1e-8     392 steps    0 rejected    392 f    0 J
Taylor                1e-10    330 steps    0 rejected    330 f    0 J
Taylor                1e-12    341 steps    0 rejected    341 f    0 J
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h       1000 steps    0 rejected   1000 f    0 J
BackwardEuler         h       1787 steps  929 rejected  10040 f 6276 J
Rk4                   h       1000 steps    0 rejected   4000 f    0 J
Rk38                  h       1000 steps    0 rejected   4000 f    0 J
Midpoint              h       1000 steps    0 rejected   2000 f    0 J
Heun                  h       1000 steps    0 rejected   2000 f    0 J
Ralston               h       1000 steps    0 rejected   2000 f    0 J
Dopri5                1e-8    1713 steps    3 rejected  10298 f    0 J
Dopri5                1e-10   4279 steps    0 rejected  25676 f    0 J
Dopri5                1e-12  10731 steps    0 rejected  64388 f    0 J
Dop853                1e-8     401 steps  112 rejected   7361 f    0 J
Dop853                1e-10    693 steps   62 rejected  11141 f    0 J
Dop853                1e-12   1228 steps   46 rejected  18974 f    0 J
Radau5                1e-8    2070 steps    2 rejected  14508 f 1080 J
Radau5                1e-10   4492 steps    0 rejected  31435 f  691 J
Radau5                1e-12   9741 steps    0 rejected  68178 f  365 J
Rodas5P               1e-8    2452 steps    3 rejected  19637 f 2452 J
Rodas5P               1e-10   6144 steps    1 rejected  49159 f 6144 J
Rodas5P               1e-12  15432 steps    1 rejected 123463 f 15432 J
    ");
    insta::assert_snapshot!(table("cash_pendulum"), @r"
Auto (Dopri5)         1e-6      60 steps    4 rejected    446 f    0 J
Auto (Dop853)         1e-8      37 steps    6 rejected    666 f    0 J
Auto (Dop853)         1e-10     63 steps   10 rejected   1130 f    0 J
Taylor                1e-6      48 steps    0 rejected     48 f    0 J
Taylor                1e-8      40 steps    0 rejected     40 f    0 J
Taylor                1e-10     33 steps    0 rejected     33 f    0 J
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h       1000 steps    0 rejected   1000 f    0 J
BackwardEuler         h       1027 steps   31 rejected   3323 f 2112 J
Rk4                   h       1000 steps    0 rejected   4000 f    0 J
Rk38                  h       1000 steps    0 rejected   4000 f    0 J
Midpoint              h       1000 steps    0 rejected   2000 f    0 J
Heun                  h       1000 steps    0 rejected   2000 f    0 J
Ralston               h       1000 steps    0 rejected   2000 f    0 J
Dopri5                1e-6      60 steps    4 rejected    446 f    0 J
Dopri5                1e-8     144 steps    0 rejected   1010 f    0 J
Dopri5                1e-10    359 steps    0 rejected   2515 f    0 J
Dop853                1e-6      22 steps    6 rejected    426 f    0 J
Dop853                1e-8      37 steps    6 rejected    666 f    0 J
Dop853                1e-10     63 steps   10 rejected   1130 f    0 J
Radau5                1e-6      93 steps    0 rejected    636 f   86 J
Radau5                1e-8     192 steps    0 rejected   1329 f  163 J
Radau5                1e-10    410 steps    0 rejected   2858 f  111 J
Rodas5P               1e-6      95 steps    2 rejected    774 f   95 J
Rodas5P               1e-8     218 steps    3 rejected   1765 f  218 J
Rodas5P               1e-10    530 steps    0 rejected   4240 f  530 J
    ");
    insta::assert_snapshot!(table("van_der_pol"), @r"
Auto (Dopri5⇄Radau5)  1e-5     264 steps   50 rejected   2552 f   62 J
Auto (Dopri5⇄Radau5)  1e-7     623 steps   19 rejected   4758 f  114 J
Auto (Dop853⇄Radau5)  1e-9     522 steps   86 rejected   7781 f  269 J
Taylor                1e-5   Error::MaxSteps at t = 8.794e-2
Taylor                1e-7   Error::MaxSteps at t = 1.155e-1
Taylor                1e-9   Error::MaxSteps at t = 1.296e-1
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h      Error::NonFinite at t = 1.400e-2
BackwardEuler         h       1869 steps  877 rejected  15896 f 6771 J
Rk4                   h      Error::NonFinite at t = 4.000e-3
Rk38                  h      Error::NonFinite at t = 4.000e-3
Midpoint              h      Error::NonFinite at t = 6.000e-3
Heun                  h      Error::NonFinite at t = 6.000e-3
Ralston               h      Error::NonFinite at t = 6.000e-3
Dopri5                1e-5   Error::Stiff at t = 2.818e-5
Dopri5                1e-7   Error::Stiff at t = 3.180e-5
Dopri5                1e-9   Error::Stiff at t = 2.712e-5
Dop853                1e-5   Error::Stiff at t = 4.053e-5
Dop853                1e-7   Error::Stiff at t = 4.053e-5
Dop853                1e-9   Error::Stiff at t = 4.624e-5
Radau5                1e-5     339 steps    8 rejected   2962 f  222 J
Radau5                1e-7     711 steps    8 rejected   5735 f  434 J
Radau5                1e-9    1538 steps    4 rejected  11908 f  530 J
Rodas5P               1e-5     350 steps   20 rejected   2954 f  350 J
Rodas5P               1e-7    1097 steps   11 rejected   8867 f 1097 J
Rodas5P               1e-9    3665 steps   11 rejected  29418 f 3665 J
Rodas5P GMRES         1e-5     351 steps   17 rejected   2941 f  351 J  2929 GMRES it
Rodas5P GMRES         1e-7    1097 steps   13 rejected   8881 f 1097 J  8868 GMRES it
Rodas5P GMRES         1e-9    3666 steps   12 rejected  29433 f 3666 J 29429 GMRES it
    ");
    insta::assert_snapshot!(table("robertson"), @r"
Auto (Dopri5→Radau5)  1e-6     299 steps    1 rejected   2189 f  253 J
Auto (Dop853→Radau5)  1e-8     566 steps    4 rejected   4552 f  357 J
Auto (Dop853→Radau5)  1e-10   1193 steps    3 rejected   9369 f  485 J
Taylor                1e-6   Error::MaxSteps at t = 7.786e1
Taylor                1e-8   Error::MaxSteps at t = 9.616e1
Taylor                1e-10  Error::MaxSteps at t = 1.138e2
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h      Error::NonFinite at t = 4.000e8
BackwardEuler         h      Error::StepSizeUnderflow at t = 0.000e0
Rk4                   h      Error::NonFinite at t = 1.000e8
Rk38                  h      Error::NonFinite at t = 1.000e8
Midpoint              h      Error::NonFinite at t = 2.000e8
Heun                  h      Error::NonFinite at t = 2.000e8
Ralston               h      Error::NonFinite at t = 2.000e8
Dopri5                1e-6   Error::Stiff at t = 3.811e-2
Dopri5                1e-8   Error::Stiff at t = 5.531e0
Dopri5                1e-10  Error::Stiff at t = 4.102e1
Dop853                1e-6   Error::Stiff at t = 6.063e-2
Dop853                1e-8   Error::Stiff at t = 6.147e-2
Dop853                1e-10  Error::Stiff at t = 7.960e0
Radau5                1e-6     299 steps    2 rejected   2222 f  279 J
Radau5                1e-8     620 steps    2 rejected   4655 f  376 J
Radau5                1e-10   1326 steps    2 rejected   9960 f  499 J
Rodas5P               1e-6     284 steps    2 rejected   2286 f  284 J
Rodas5P               1e-8     723 steps    3 rejected   5805 f  723 J
Rodas5P               1e-10   2405 steps    9 rejected  19303 f 2405 J
Rodas5P GMRES         1e-6     284 steps    2 rejected   2286 f  284 J  2284 GMRES it
Rodas5P GMRES         1e-8     723 steps    3 rejected   5805 f  723 J  5807 GMRES it
Rodas5P GMRES         1e-10   2406 steps   10 rejected  19318 f 2406 J 19328 GMRES it
    ");
    insta::assert_snapshot!(table("hires"), @r"
Auto (Dopri5→Radau5)  1e-6     328 steps    2 rejected   2299 f   24 J
Auto (Dop853→Radau5)  1e-8     181 steps    4 rejected   2089 f   79 J
Auto (Dop853→Radau5)  1e-10    473 steps    6 rejected   5692 f  124 J
Taylor                1e-6    6793 steps    0 rejected   6793 f    0 J
Taylor                1e-8    5241 steps    0 rejected   5241 f    0 J
Taylor                1e-10   4270 steps    0 rejected   4270 f    0 J
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h      Error::NonFinite at t = 3.858e0
BackwardEuler         h       1909 steps  920 rejected  11068 f 7931 J
Rk4                   h      Error::NonFinite at t = 1.286e0
Rk38                  h      Error::NonFinite at t = 1.286e0
Midpoint              h      Error::NonFinite at t = 1.929e0
Heun                  h      Error::NonFinite at t = 1.929e0
Ralston               h      Error::NonFinite at t = 1.929e0
Dopri5                1e-6   Error::Stiff at t = 6.596e0
Dopri5                1e-8   Error::Stiff at t = 1.585e1
Dopri5                1e-10  19199 steps    0 rejected 115196 f    0 J
Dop853                1e-6   Error::Stiff at t = 3.549e0
Dop853                1e-8   Error::Stiff at t = 5.656e0
Dop853                1e-10  Error::Stiff at t = 9.788e0
Radau5                1e-6     117 steps    2 rejected   1140 f   73 J
Radau5                1e-8     235 steps    1 rejected   2050 f  134 J
Radau5                1e-10    501 steps    1 rejected   4110 f  229 J
Rodas5P               1e-6     212 steps    1 rejected   1703 f  212 J
Rodas5P               1e-8     787 steps    4 rejected   6324 f  787 J
Rodas5P               1e-10   2854 steps    4 rejected  22860 f 2854 J
Rodas5P GMRES         1e-6     212 steps    1 rejected   1703 f  212 J  3642 GMRES it
Rodas5P GMRES         1e-8     787 steps    4 rejected   6324 f  787 J 13679 GMRES it
Rodas5P GMRES         1e-10   2854 steps    4 rejected  22860 f 2854 J 49637 GMRES it
    ");
    insta::assert_snapshot!(table("low_pass"), @r"
Auto (Dopri5→Radau5)  1e-6      61 steps    9 rejected    352 f   10 J
Auto (Dop853→Radau5)  1e-8     100 steps    7 rejected    709 f    8 J
Auto (Dop853→Radau5)  1e-10    222 steps    4 rejected   1418 f    5 J
Taylor                1e-6     498 steps    0 rejected    498 f    0 J
Taylor                1e-8     386 steps    0 rejected    386 f    0 J
Taylor                1e-10    315 steps    0 rejected    315 f    0 J
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h       1000 steps    0 rejected   1000 f    0 J
BackwardEuler         h       1399 steps  401 rejected   5319 f 3518 J
Rk4                   h       1000 steps    0 rejected   4000 f    0 J
Rk38                  h       1000 steps    0 rejected   4000 f    0 J
Midpoint              h       1000 steps    0 rejected   2000 f    0 J
Heun                  h       1000 steps    0 rejected   2000 f    0 J
Ralston               h       1000 steps    0 rejected   2000 f    0 J
Dopri5                1e-6    1361 steps    4 rejected   8192 f    0 J
Dopri5                1e-8    3116 steps    6 rejected  18734 f    0 J
Dopri5                1e-10   7504 steps    7 rejected  45068 f    0 J
Dop853                1e-6     485 steps   54 rejected   7925 f    0 J
Dop853                1e-8    1317 steps    8 rejected  19853 f    0 J
Dop853                1e-10   2953 steps    6 rejected  44369 f    0 J
Radau5                1e-6      45 steps    7 rejected    238 f    8 J
Radau5                1e-8      97 steps    8 rejected    493 f    9 J
Radau5                1e-10    222 steps    8 rejected   1127 f    9 J
Rodas5P               1e-6      83 steps    5 rejected    699 f   83 J
Rodas5P               1e-8     275 steps    4 rejected   2228 f  275 J
Rodas5P               1e-10    830 steps    4 rejected   6668 f  830 J
Rodas5P GMRES         1e-6      82 steps    4 rejected    684 f   82 J   683 GMRES it
Rodas5P GMRES         1e-8     275 steps    4 rejected   2228 f  275 J  2228 GMRES it
Rodas5P GMRES         1e-10    830 steps    5 rejected   6675 f  830 J  6677 GMRES it
    ");
    insta::assert_snapshot!(table("akzo_nobel"), @r"
Auto (Dopri5→Radau5)  1e-6      69 steps    0 rejected    505 f   34 J
Auto (Dop853→Radau5)  1e-8      90 steps    5 rejected    924 f   57 J
Auto (Dop853→Radau5)  1e-10    182 steps    5 rejected   1704 f   94 J
Taylor                1e-6     147 steps    0 rejected    147 f    0 J
Taylor                1e-8     117 steps    0 rejected    117 f    0 J
Taylor                1e-10     98 steps    0 rejected     98 f    0 J
TaylorFixed           refused: TaylorFixed of order 4 needs the model expanded with #[dae_model(taylor = 4)] or higher; it has 0
Euler                 h      Error::NonFinite at t = 1.800e-1
BackwardEuler         h       1067 steps   69 rejected   3758 f 2578 J
Rk4                   h      Error::NonFinite at t = 0.000e0
Rk38                  h      Error::NonFinite at t = 0.000e0
Midpoint              h      Error::NonFinite at t = 0.000e0
Heun                  h      Error::NonFinite at t = 0.000e0
Ralston               h      Error::NonFinite at t = 0.000e0
Dopri5                1e-6   Error::Stiff at t = 1.772e2
Dopri5                1e-8     655 steps    1 rejected   3938 f    0 J
Dopri5                1e-10   1544 steps    1 rejected   9272 f    0 J
Dop853                1e-6   Error::Stiff at t = 8.444e1
Dop853                1e-8     251 steps    6 rejected   3839 f    0 J
Dop853                1e-10    584 steps    7 rejected   8846 f    0 J
Radau5                1e-6      61 steps    0 rejected    463 f   51 J
Radau5                1e-8     121 steps    0 rejected    931 f   84 J
Radau5                1e-10    254 steps    0 rejected   1934 f  119 J
Rodas5P               1e-6     102 steps    2 rejected    830 f  102 J
Rodas5P               1e-8     303 steps    0 rejected   2424 f  303 J
Rodas5P               1e-10    869 steps    1 rejected   6959 f  869 J
    ");
}

/// Course notes, Example 1.1's system has no closed form; its reference
/// is SciPy's DOP853 at rtol 1e-13 (tests/models.rs). The fixed-step
/// methods converge on the oscillator x'' = −x, whose solution is cos t,
/// at their orders: the error falls by 2^p as the step halves. The step
/// grows with the order so that the error stays far above rounding; the
/// Taylor scheme runs at order 6 too (the oscillator is expanded to 6).
#[test]
fn every_fixed_step_method_converges_at_its_order() {
    use support::harness::{fixed_step_methods, kind, Kind};
    use support::Oscillator;
    let sixth = Method::TaylorFixed { order: 6, step: 0.0 };
    for method in fixed_step_methods().chain([sixth]) {
        let order = match (method, kind(method)) {
            (Method::TaylorFixed { order, .. }, _) => order as i32,
            (_, Kind::FixedStep { order, .. }) => order,
            (other, _) => unreachable!("{other:?} takes no fixed step"),
        };
        let h = match order {
            1 => 1e-3,
            2 => 5e-3,
            4 => 2e-2,
            _ => 1e-1,
        };
        let error = |h: f64| {
            let opts = match method {
                Method::TaylorFixed { order, .. } => {
                    Options::new().method(Method::TaylorFixed { order, step: h })
                }
                m => Options::new().method(m).step(h),
            };
            let sol = Oscillator::default().simulate(0.0, 2.0, &opts).unwrap();
            (sol.last("x").unwrap() - 2f64.cos()).abs()
        };
        let rate = (error(h) / error(h / 2.0)).log2();
        assert!(
            (rate - order as f64).abs() < 0.15,
            "{method:?}: observed order {rate:.3}, expected {order}"
        );
    }
}
