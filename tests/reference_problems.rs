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
    // Each table pins the problem's statistics for every method: steps,
    // rejections and evaluations (tests/snapshots/reference_problems__*.snap).
    for (name, table) in &tables {
        println!("{name}\n{table}");
        insta::assert_snapshot!(*name, table);
    }
}

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
