//! Initialization as its own system: equations that hold at the start only
//! (`initial(..)`, Modelica's `initial equation`) decide start values,
//! solved before the first step; `init(part.x, v)` starts a part's state.

use daegen::prelude::*;

/// `drive!(name { statements })`: a DC drive (R = 1 Ω, L = 0.5 mH,
/// k = 0.05 V s, J = 1e-4 kg m²) under a PI speed controller (kp = 0.02,
/// ki = 0.5) set to 100 rad/s, the rotor's free flange and the rest
/// given by `statements`.
macro_rules! drive {
    ($(#[$doc:meta])* $name:ident { $($rest:tt)* }) => {
        $(#[$doc])*
        #[dae_model]
        fn $name() {
            // From the supply along the armature to the shaft, then the loop.
            let gnd = ground();
            let supply = signal_voltage();
            let armature = resistor(1.0);
            connect(supply.p, armature.p);
            let winding = inductor(0.5e-3);
            connect(armature.n, winding.p);
            let emf = emf(0.05);
            connect(winding.n, emf.p);
            connect(emf.n, supply.n, gnd.p);
            let rotor = inertia(j = 1e-4);
            let sensor = speed_sensor();
            connect(emf.flange, rotor.flange_a, sensor.flange);
            let controller = pi_controller(kp = 0.02, ki = 0.5);
            connect(sensor.w, controller.u_m);
            connect(controller.y, supply.u);
            let reference = constant(100.0);
            connect(reference.y, controller.u_s);
            $($rest)*
        }
    };
}

drive!(
    /// The drive with friction (1e-5 N m s) against a load of 0.02 N m,
    /// started in its steady state (MSL's `initType = SteadyState`).
    drive_in_steady_state {
        let friction = damper(1e-5);
        let housing = fixed();
        let load = torque_source(-0.02);
        connect(rotor.flange_b, friction.flange_a, load.flange);
        connect(friction.flange_b, housing.flange);
        initial(der(winding.i) == 0.0);
        initial(der(rotor.w) == 0.0);
        initial(der(controller.x) == 0.0);
    }
);

#[test]
fn a_steady_state_start_is_the_exact_operating_point() {
    // At rest in speed: w = 100; the torque k i = d w + 0.02 gives
    // i = 0.42 A; the voltage R i + k w = 5.42 V is the integral part
    // (the error is zero).
    let (w, i, x) = (100.0, 0.42, 5.42);
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = DriveInSteadyState::default().simulate(0.0, 1.0, &opts).unwrap();
    for &t in &[0.0f64, 0.5, 1.0] {
        let (rotor_w, winding_i, controller_x): (f64, f64, f64) = (
            sol.at(t, "rotor.w").unwrap(),
            sol.at(t, "winding.i").unwrap(),
            sol.at(t, "controller.x").unwrap(),
        );
        assert!((rotor_w - w).abs() < 1e-8, "t = {t}: w = {rotor_w}");
        assert!((winding_i - i).abs() < 1e-10, "t = {t}: i = {winding_i}");
        assert!((controller_x - x).abs() < 1e-10, "t = {t}: x = {controller_x}");
    }
    // What initialization chose, from the starts the parts give (zero).
    let mut moved: Vec<&str> = sol.initial_corrections().iter().map(|c| c.name).collect();
    moved.sort_unstable();
    assert_eq!(moved, ["controller.x", "rotor.w", "winding.i"], "{moved:?}");
    // Strict starts allow the values the initial equations decide.
    let strict = opts.clone().strict_initial_values(true);
    assert!(DriveInSteadyState::default().simulate(0.0, 0.1, &strict).is_ok());
}

drive!(
    /// The drive from a standstill, unloaded, its controller's integral
    /// part started at −10 V.
    drive_with_a_wound_up_controller {
        init(controller.x, -10.0);
    }
);

#[test]
fn init_starts_a_parts_state() {
    let opts = Options::new().rtol(1e-10).atol(1e-12);
    let sol = DriveWithAWoundUpController::default().simulate(0.0, 1e-3, &opts).unwrap();
    let x0: f64 = sol.at(0.0, "controller.x").unwrap();
    assert_eq!(x0, -10.0);
    // The voltage at the start: kp·100 − 10 = −8 V.
    let v0: f64 = sol.at(0.0, "supply.v").unwrap();
    assert!((v0 + 8.0).abs() < 1e-12, "{v0}");
}
