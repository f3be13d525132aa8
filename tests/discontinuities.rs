//! Discontinuities: switches in the time alone (the library's steps),
//! which every method steps to exactly; event functions that leave zero;
//! relations on model variables (`if`, `min`, `max`, `sign`) held between
//! events and switched where they cross, as Modelica's relations are.

use daegen::prelude::*;

/// A rotor (J = 2 kg m²) braked by a damper (d = 1 N m s), a torque of
/// 1 N m switched on at t = 0.4 by a step block.
#[dae_model]
fn torque_step() {
    let rotor = inertia(j = 2.0);
    let brake = damper(1.0);
    let housing = fixed();
    let drive = signal_torque();
    let command = step(height = 1.0, start_time = 0.4);
    connect(command.y, drive.u);
    connect(drive.flange, rotor.flange_a);
    connect(rotor.flange_b, brake.flange_a);
    connect(brake.flange_b, housing.flange);
}

/// `method` at rtol 1e-10, atol 1e-12.
fn tight(method: Method) -> Options {
    Options::new().method(method).rtol(1e-10).atol(1e-12)
}

/// Checks that `name` stays within `bound` of `exact` at `times`.
fn assert_follows(sol: &Solution, name: &str, exact: fn(f64) -> f64, times: &[f64], bound: f64) {
    let method = sol.stats().method;
    for &t in times {
        let (v, want): (f64, f64) = (sol.at(t, name).unwrap(), exact(t));
        assert!((v - want).abs() < bound, "{method} t = {t}: {name} = {v} vs {want}");
    }
}

/// The rotor's speed: at rest until 0.4, then `1 − e^(−(t − 0.4)/2)`.
fn torque_step_exact(t: f64) -> f64 {
    if t <= 0.4 {
        0.0
    } else {
        1.0 - (-(t - 0.4) / 2.0).exp()
    }
}

#[test]
fn a_step_in_time_is_stepped_to_by_every_adaptive_method() {
    let adaptive = [Method::Auto, Method::Dopri5, Method::Dop853, Method::Radau5, Method::Rodas5P];
    for method in adaptive {
        let tol = 1e-6;
        let opts = Options::new().method(method).rtol(tol).atol(tol);
        let sol = TorqueStep::default().simulate(0.0, 3.0, &opts).unwrap();
        assert_follows(&sol, "rotor.w", torque_step_exact, &[0.3, 0.4, 0.45, 1.0, 3.0], 10.0 * tol);
    }
}

/// A step from 0 to 1 at t = 0.4 watched by an event on its rise, and a
/// state counting the events.
#[dae_model]
fn step_watched() {
    let s = step(height = 1.0, start_time = 0.4);
    let x = state(0.0);
    der(x) == -x;
    let rise = event(s.y).rising().reinit(x, x + 1.0);
}

#[test]
fn an_event_on_a_function_that_leaves_zero_fires() {
    for method in [Method::Dopri5, Method::Radau5] {
        let opts = Options::new().method(method).rtol(1e-8).atol(1e-10);
        let sol = StepWatched::default().simulate(0.0, 1.0, &opts).unwrap();
        let fired: Vec<f64> = sol.events().iter().map(|e| e.t).collect();
        assert_eq!(fired.len(), 1, "{method:?}: {fired:?}");
        assert!((fired[0] - 0.4).abs() < 1e-12, "{method:?}: {fired:?}");
        // x = e^(−(t − 0.4)) after the event.
        let x: f64 = sol.at(1.0, "x").unwrap();
        assert!((x - (-0.6f64).exp()).abs() < 1e-7, "{method:?}: x = {x}");
    }
}

/// C = 2 F discharging from 3 V through a piecewise-linear conductor:
/// `i = 2 (v − 1) + 0.5` above 1 V, `0.5 v` below, written as an `if` on
/// the voltage.
#[dae_model]
fn piecewise_discharge() {
    let v = state(3.0);
    let i = if v > 1.0 { 2.0 * (v - 1.0) + 0.5 } else { 0.5 * v };
    2.0 * der(v) == -i;
}

/// Its exact voltage: `0.75 + 2.25 e^(−t)` down to 1 V at `t₁ = ln 9`,
/// then `e^(−(t − t₁)/4)`.
fn piecewise_discharge_exact(t: f64) -> f64 {
    let t1 = 9f64.ln();
    if t <= t1 {
        0.75 + 2.25 * (-t).exp()
    } else {
        (-(t - t1) / 4.0).exp()
    }
}

#[test]
fn an_if_on_a_variable_switches_where_its_relation_crosses() {
    let methods = [Method::Auto, Method::Taylor, Method::Dopri5, Method::Dop853, Method::Radau5];
    for method in methods.into_iter().chain([Method::Rodas5P]) {
        let tol = 1e-8;
        let opts = Options::new().method(method).rtol(tol).atol(tol);
        let sol = PiecewiseDischarge::default().simulate(0.0, 6.0, &opts).unwrap();
        // The relation's two events: it turns false once, at ln 9.
        let fired: Vec<(&str, f64)> = sol.events().iter().map(|e| (e.name, e.t)).collect();
        assert_eq!(fired.len(), 1, "{method:?}: {fired:?}");
        assert_eq!(fired[0].0, "!(v > 1.0)");
        // Located on the method's continuous output, as accurate as it.
        assert!((fired[0].1 - 9f64.ln()).abs() < 1e-6, "{method:?}: {fired:?}");
        // RADAU5 meets 0.1·rtol^(2/3), the tolerance it turns rtol into
        // (`radau5.f`): about 10·tol here, before the switch as after it.
        assert_follows(
            &sol,
            "v",
            piecewise_discharge_exact,
            &[1.0, 2.0, 2.5, 4.0, 6.0],
            20.0 * tol,
        );
    }
}

/// `min`, `max` and `sign` on variables: x rises at rate 1 until it
/// meets 2 − x, then follows it; y integrates `sign(2 − t)`; z counts the
/// time x spends above 1 by an `if` statement on `x`.
#[dae_model]
fn switching_functions() {
    let t = time();
    let x = state(0.0);
    let y = state(0.0);
    let z = state(0.0);
    der(x) == max(0.0, min(1.0, 2.0 - x));
    der(y) == sign(2.0 - t);
    if x > 1.0 {
        der(z) == 1.0;
    } else {
        der(z) == 0.0;
    }
}

#[test]
fn min_max_sign_and_if_statements_switch_at_their_relations() {
    let sol = SwitchingFunctions::default().simulate(0.0, 4.0, &tight(Method::Dop853)).unwrap();
    // The three relations on x switch together at t = 1; sign's two at 2.
    let fired: Vec<(&str, f64)> = sol.events().iter().map(|e| (e.name, e.t)).collect();
    let names: Vec<&str> = fired.iter().map(|f| f.0).collect();
    assert_eq!(names, ["!(1.0 < 2.0 - x)", "(x > 1.0)", "!(2.0 - t > 0)", "(2.0 - t < 0)"]);
    for (name, t) in fired {
        let at = if name.contains('x') { 1.0 } else { 2.0 };
        assert!((t - at).abs() < 1e-14, "{name} at {t}");
    }
    for &t in &[0.5f64, 1.5, 2.5, 4.0] {
        // x = t to 1, then 2 − e^(−(t − 1)); y = t to 2, then 4 − t;
        // z = the time since x passed 1 (at t = 1).
        let x = if t <= 1.0 { t } else { 2.0 - (-(t - 1.0)).exp() };
        let y = if t <= 2.0 { t } else { 4.0 - t };
        let z = (t - 1.0).max(0.0);
        for (name, exact) in [("x", x), ("y", y), ("z", z)] {
            let v: f64 = sol.at(t, name).unwrap();
            assert!((v - exact).abs() < 1e-8, "t = {t}: {name} = {v} vs {exact}");
        }
    }
}

/// `chua!(name { statements })`: MSL's
/// `Modelica.Electrical.Analog.Examples.ChuaCircuit` (L = 18 H,
/// Ro = 12.5 mΩ, G = 0.565 S, C1 = 10 F, C2 = 100 F), the nonlinear
/// resistor's current `nr` defined by `statements`.
macro_rules! chua {
    ($(#[$doc:meta])* $name:ident { $($resistor:tt)* }) => {
        $(#[$doc])*
        #[dae_model]
        fn $name() {
            let ga = param(-0.757576);
            let gb = param(-0.409091);
            let ve = param(1.0);
            let il = state(0.0);
            let v1 = state(4.0);
            let v2 = state(0.0);
            $($resistor)*
            18.0 * der(il) == -v2 - 12.5e-3 * il;
            10.0 * der(v1) == 0.565 * (v2 - v1) - nr;
            100.0 * der(v2) == 0.565 * (v1 - v2) + il;
        }
    };
}

chua!(
    /// The resistor written as Modelica writes it, an `if` on its voltage.
    chua_with_if {
        let nr = if v1 < -ve {
            gb * (v1 + ve) - ga * ve
        } else if v1 > ve {
            gb * (v1 - ve) + ga * ve
        } else {
            ga * v1
        };
    }
);

chua!(
    /// The resistor's segment in two booleans set by hand by four directed
    /// events, its start segment (v1 = 4 > Ve) set by hand.
    chua_by_hand {
        let below = discrete(false);
        let above = discrete(true);
        event(v1 + ve).falling().reinit(below, 1.0);
        event(v1 + ve).rising().reinit(below, 0.0);
        event(v1 - ve).rising().reinit(above, 1.0);
        event(v1 - ve).falling().reinit(above, 0.0);
        let nr = if below {
            gb * (v1 + ve) - ga * ve
        } else if above {
            gb * (v1 - ve) + ga * ve
        } else {
            ga * v1
        };
    }
);

#[test]
fn chuas_resistor_as_an_if_follows_the_hand_made_events() {
    let opts = Options::new().method(Method::Radau5).rtol(1e-11).atol(1e-12);
    let with_if = ChuaWithIf::default().simulate(0.0, 3000.0, &opts).unwrap();
    let by_hand = ChuaByHand::default().simulate(0.0, 3000.0, &opts).unwrap();
    // The segments switch at the same instants.
    let switches = |s: &Solution| s.events().iter().map(|e| e.t).collect::<Vec<f64>>();
    let (a, b) = (switches(&with_if), switches(&by_hand));
    assert!(a.len() >= 4 && a.len() == b.len(), "{} vs {} switches", a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() < 1e-6, "{x} vs {y}");
    }
    for &t in &[50.0f64, 150.0, 300.0] {
        for name in ["v1", "v2", "il"] {
            let (x, y): (f64, f64) = (with_if.at(t, name).unwrap(), by_hand.at(t, name).unwrap());
            assert!((x - y).abs() < 1e-6 * (1.0 + y.abs()), "t = {t}: {name} {x} vs {y}");
        }
    }
}

/// A gearbox whose integer mode is set by an expression of a relation: at
/// w = 1 it shifts into second gear before t = 5 and into third after.
#[dae_model]
fn shifting_gearbox() {
    let t = time();
    let w = state(0.0);
    let gear = discrete(1);
    let shift = event(w - 1.0).rising().reinit(gear, if t < 5.0 { 2 } else { 3 });
    if gear == 1 {
        der(w) == 1.0;
    } else if gear == 2 {
        der(w) == 0.5;
    } else {
        der(w) == 0.25;
    }
}

#[test]
fn an_integer_mode_is_set_by_an_expression_of_a_relation() {
    let sol = ShiftingGearbox::default().simulate(0.0, 3.0, &tight(Method::Dopri5)).unwrap();
    // w = t to 1, then in second gear w = 1 + (t − 1)/2.
    let (w, gear): (f64, f64) = (sol.at(3.0, "w").unwrap(), sol.at(3.0, "gear").unwrap());
    assert_eq!(gear, 2.0);
    assert!((w - 2.0).abs() < 1e-9, "{w}");
}

/// A clutch of three booleans, as a user writes one: disengaged it passes
/// no torque; engaged and locked, its sides turn together; engaged and
/// slipping, it passes its friction torque from `flange_a` on to
/// `flange_b` (forward) or back.
#[component]
fn three_state_clutch() {
    let friction = param(1.0);
    let engaged0 = param(1.0);
    let locked0 = param(1.0);
    let forward0 = param(1.0);
    let flange_a = flange();
    let flange_b = flange();
    let engaged = discrete(engaged0);
    let locked = discrete(locked0);
    let forward = discrete(forward0);
    let phi_rel = state(0.0).avoid();
    let tau = algebraic(0.0);
    phi_rel == flange_b.phi - flange_a.phi;
    flange_a.tau == -tau;
    flange_b.tau == tau;
    if !engaged {
        tau == 0.0;
    } else if locked {
        der(der(phi_rel)) == 0.0;
    } else if forward {
        tau == -friction;
    } else {
        tau == friction;
    }
}

/// Five inertias (1, 2, 3, 4, 5 kg m²) in a row joined by four clutches,
/// 10 N m on the first.
#[dae_model]
fn four_clutches() {
    let drive = torque_source(10.0);
    let j = (0..5).map(|k| inertia(j = k as f64 + 1.0));
    let c = [three_state_clutch(); 4];
    connect(drive.flange, j[0].flange_a);
    for k in 0..4 {
        connect(j[k].flange_b, c[k].flange_a);
        connect(c[k].flange_b, j[k + 1].flange_a);
    }
}

#[test]
fn four_clutches_of_three_booleans_compile_into_one_system() {
    // 4096 combinations of the twelve booleans: each clutch's branches
    // blended into one equation, the drivetrain analysed once, its block
    // solved at run time in whatever modes the clutches are in.
    let speeds = |model: FourClutches| {
        let opts = tight(Method::Radau5);
        let sol = model.simulate(0.0, 1.0, &opts).unwrap();
        ["j[0].w", "j[1].w", "j[2].w", "j[3].w", "j[4].w"].map(|n| sol.last(n).unwrap())
    };
    let check = |speeds: [f64; 5], expected: [f64; 5]| {
        for (w, e) in speeds.iter().zip(expected) {
            assert!((w - e).abs() < 1e-9, "{speeds:?} vs {expected:?}");
        }
    };
    let d = FourClutches::default();
    // All locked: one rigid body, 10 N m over 15 kg m².
    check(speeds(d), [10.0 / 15.0; 5]);
    // Clutch c[k] joins j[k] and j[k + 1]; below, j1 is j[0] and so on.
    // The second disengaged: j1 and j2 together (10/3), the rest at rest.
    let split = FourClutches { c_1_engaged0: 0.0, ..d };
    check(speeds(split), [10.0 / 3.0, 10.0 / 3.0, 0.0, 0.0, 0.0]);
    // The third slipping forward: 1 N m passes on to j4 and j5 (1/9),
    // j1–j3 keep the rest (9/6).
    let slipping = FourClutches { c_2_locked0: 0.0, ..d };
    check(speeds(slipping), [1.5, 1.5, 1.5, 1.0 / 9.0, 1.0 / 9.0]);
    // The first disengaged, the last slipping back: j1 alone; 1 N m from
    // j5 back to j2–j4 (1/9 forward, j5 −1/5).
    let mixed = FourClutches { c_0_engaged0: 0.0, c_3_locked0: 0.0, c_3_forward0: 0.0, ..d };
    check(speeds(mixed), [10.0, 1.0 / 9.0, 1.0 / 9.0, 1.0 / 9.0, -1.0 / 5.0]);
}
