//! The FMUs as an importer meets them: each archive unpacked, its
//! library loaded from the platform directory its FMI version names, and
//! run through the standard's C functions in both interfaces by an
//! importer of the tests' own (`support/importer.rs`). Results equal the
//! native run within the tolerances.

#[path = "support/importer.rs"]
#[allow(dead_code)]
mod importer;
mod support;

use daegen::prelude::*;
use importer::{Instance2, Instance3, Kind, Unpacked};

#[path = "../examples/models/bouncing_ball.rs"]
mod bouncing_ball;
#[path = "../../tests/models/speed_drive.rs"]
mod speed_drive;
#[path = "../examples/models/van_der_pol.rs"]
mod van_der_pol;

fn native<M: Model + Clone + Send + Sync + 'static>(model: M, stop: f64) -> daegen::Solution {
    let options = Options::new().method(Method::Radau5).rtol(1e-12).atol(1e-12);
    model.simulate(0.0, stop, &options).expect("the native run")
}

/// Classical RK4 through `rates`.
fn rk4(x: &mut [f64], t: f64, h: f64, mut rates: impl FnMut(f64, &[f64]) -> Vec<f64>) {
    let shift =
        |x: &[f64], d: &[f64], s: f64| x.iter().zip(d).map(|(x, d)| x + s * d).collect::<Vec<_>>();
    let k1 = rates(t, x);
    let k2 = rates(t + h / 2.0, &shift(x, &k1, h / 2.0));
    let k3 = rates(t + h / 2.0, &shift(x, &k2, h / 2.0));
    let k4 = rates(t + h, &shift(x, &k3, h));
    for i in 0..x.len() {
        x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    }
}

#[test]
fn fmi3_co_simulation_and_model_exchange_of_van_der_pol() {
    let archives = support::fmus("van_der_pol_fmu", "archive-importer-vdp");
    let fmu = Unpacked::new(&archives.fmi3);
    let sol = native(van_der_pol::VanDerPol::default(), 10.0);
    let exact: f64 = sol.at(10.0, "x").unwrap();
    let x_ref = fmu.reference("x");

    // Co-Simulation: the FMU's own Auto at the experiment's tolerance.
    let mut cs = Instance3::co_simulation(&fmu);
    cs.initialize(Some(1e-10), 0.0).unwrap();
    for k in 0..20 {
        let t = k as f64 * 0.5;
        let reached = cs.do_step(t, 0.5).unwrap();
        assert_eq!(reached, t + 0.5, "the step's end");
    }
    let mut x = [0.0];
    cs.get_float64(&[x_ref], &mut x).unwrap();
    assert!((x[0] - exact).abs() < 1e-8, "co-simulation: {} vs {exact}", x[0]);
    cs.terminate().unwrap();

    // Model Exchange: RK4 with h = 1e-3 from the FMU's rates (global
    // error of order h⁴ ≈ 1e-12 times the solution's derivatives).
    let mut me = Instance3::model_exchange(&fmu);
    me.initialize(None, 0.0).unwrap();
    me.update_discrete_states().unwrap();
    me.enter_continuous_time_mode().unwrap();
    let mut state = vec![0.0; 2];
    me.get_continuous_states(&mut state).unwrap();
    let h = 1e-3;
    for k in 0..10_000 {
        rk4(&mut state, k as f64 * h, h, |t, x| {
            me.set_time(t).unwrap();
            me.set_continuous_states(x).unwrap();
            let mut dx = vec![0.0; 2];
            me.get_derivatives(&mut dx).unwrap();
            dx
        });
    }
    assert!((state[0] - exact).abs() < 1e-8, "model exchange: {} vs {exact}", state[0]);
    me.terminate().unwrap();
}

#[test]
fn fmi2_co_simulation_of_the_speed_drive() {
    let archives = support::fmus("speed_drive_fmu", "archive-importer-drive");
    let fmu = Unpacked::new(&archives.fmi2);
    let sol = native(speed_drive::SpeedDrive::default(), 1.0);
    let mut cs = Instance2::new(&fmu, Kind::CoSimulation);
    cs.setup_experiment(Some(1e-10), 0.0).unwrap();
    cs.initialize().unwrap();
    let names = ["motor.rotor.w", "motor.winding.i", "controller.x"];
    let vrs: Vec<u32> = names.iter().map(|n| fmu.reference(n)).collect();
    for k in 0..10 {
        let t = k as f64 * 0.1;
        cs.do_step(t, 0.1).unwrap();
        let mut values = vec![0.0; 3];
        cs.get_real(&vrs, &mut values).unwrap();
        for (name, v) in names.iter().zip(&values) {
            let exact: f64 = sol.at(t + 0.1, name).unwrap();
            assert!(
                (v - exact).abs() < 1e-7 * (1.0 + exact.abs()),
                "{name} at {}: {v} vs {exact}",
                t + 0.1
            );
        }
    }
    cs.terminate().unwrap();
}

#[test]
fn fmi2_model_exchange_of_the_bouncing_ball() {
    let archives = support::fmus("bouncing_ball_fmu", "archive-importer-ball");
    let fmu = Unpacked::new(&archives.fmi2);
    let mut me = Instance2::new(&fmu, Kind::ModelExchange);
    me.setup_experiment(None, 0.0).unwrap();
    me.initialize().unwrap();
    me.new_discrete_states().unwrap();
    me.enter_continuous_time_mode().unwrap();
    let mut x = vec![0.0; 2];
    me.get_continuous_states(&mut x).unwrap();
    let mut g = [0.0];
    me.get_event_indicators(&mut g).unwrap();
    let h = 1e-4;
    let mut impacts = Vec::new();
    for k in 0..20_000 {
        let t = k as f64 * h;
        rk4(&mut x, t, h, |t, x| {
            me.set_time(t).unwrap();
            me.set_continuous_states(x).unwrap();
            let mut dx = vec![0.0; 2];
            me.get_derivatives(&mut dx).unwrap();
            dx
        });
        me.set_time(t + h).unwrap();
        me.set_continuous_states(&x).unwrap();
        let mut g_new = [0.0];
        me.get_event_indicators(&mut g_new).unwrap();
        let step_event = me.completed_integrator_step().unwrap();
        if (g[0] > 0.0) != (g_new[0] > 0.0) || step_event {
            me.enter_event_mode().unwrap();
            let info = me.new_discrete_states().unwrap();
            if info.values_changed != 0 {
                me.get_continuous_states(&mut x).unwrap();
                impacts.push((t + h, x[1]));
            }
            me.enter_continuous_time_mode().unwrap();
            me.get_event_indicators(&mut g_new).unwrap();
        }
        g = g_new;
    }
    // Impacts at t₁(1 + 2e(1 − e^(k−1))/(1 − e)) with speed e^k √(2g),
    // t₁ = √(2/g): each located to within a step.
    let (gravity, e) = (9.81f64, 0.8f64);
    let t1 = (2.0 / gravity).sqrt();
    assert_eq!(impacts.len(), 3, "{impacts:?}");
    for (k, &(t, v)) in impacts.iter().enumerate() {
        let k = k as i32 + 1;
        let exact = t1 * (1.0 + 2.0 * e * (1.0 - e.powi(k - 1)) / (1.0 - e));
        assert!((t - exact).abs() <= k as f64 * h, "impact {k}: {t} vs {exact}");
        assert!((v - e.powi(k) * (2.0 * gravity).sqrt()).abs() < 1e-2, "impact {k}: {v}");
    }
    me.terminate().unwrap();
    let _ = bouncing_ball::BouncingBall::default();
}

#[test]
fn fmi3_model_exchange_announces_the_load_step_as_a_time_event() {
    // The speed drive's load torque steps at t = 0.3: an importer's
    // integrator is told to stop there, as at a clock's instant.
    let archives = support::fmus("speed_drive_fmu", "archive-importer-time-event");
    let fmu = Unpacked::new(&archives.fmi3);
    let mut me = Instance3::model_exchange(&fmu);
    me.initialize(None, 0.0).unwrap();
    let update = me.update_discrete_states().unwrap();
    assert!(update.next_event_time_defined);
    assert_eq!(update.next_event_time, 0.3);
    me.terminate().unwrap();
}
