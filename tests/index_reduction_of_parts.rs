//! Index reduction of connected parts: library parts joined as a Modelica
//! user joins them, whose connections relate states through potentials
//! and flows (capacitors in parallel, a source across a capacitor, a gear
//! between an inertia and a compliant coupling). Each compiles, keeps the
//! states of the physics, and follows the exact solution or the same
//! physics written flat.

use daegen::prelude::*;

/// 1 V through R = 1 Ω into C1 = 1 F and C2 = 2 F in parallel: one state,
/// `v = 1 − e^(−t/3)`.
#[dae_model]
fn parallel_capacitors() {
    let source = constant_voltage(1.0);
    let r = resistor(1.0);
    connect(source.p, r.p);
    let c1 = capacitor(1.0);
    let c2 = capacitor(2.0);
    connect(r.n, c1.p, c2.p);
    let gnd = ground();
    connect(c1.n, c2.n, source.n, gnd.p);
}

#[test]
fn two_capacitors_in_parallel_are_one_state() {
    assert_eq!(<ParallelCapacitors as Model>::INFO.states, ["c1.v"]);
    // `describe()` says why the other is no state.
    let described = ParallelCapacitors::default().describe();
    let why = "Not a state: the connections tie it to the states kept, `c1.v`.";
    assert!(described.lines().any(|l| l.contains("c2.v") && l.contains(why)), "{described}");
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = ParallelCapacitors::default().simulate(0.0, 5.0, &opts).unwrap();
    for &t in &[0.5f64, 1.0, 3.0, 5.0] {
        let v = 1.0 - (-t / 3.0).exp();
        let rate = (-t / 3.0).exp() / 3.0;
        let (v1, v2): (f64, f64) = (sol.at(t, "c1.v").unwrap(), sol.at(t, "c2.v").unwrap());
        assert!((v1 - v).abs() < 1e-8 && (v2 - v).abs() < 1e-8, "t = {t}: {v1}, {v2} vs {v}");
        // Each capacitor's current is its own C dv/dt.
        let (i1, i2): (f64, f64) = (sol.at(t, "c1.i").unwrap(), sol.at(t, "c2.i").unwrap());
        assert!((i1 - rate).abs() < 1e-8 && (i2 - 2.0 * rate).abs() < 1e-8, "t = {t}: {i1}, {i2}");
    }
}

/// A sine source of 1 V at 1 Hz directly across C = 2 F.
#[dae_model]
fn source_across_a_capacitor() {
    let source = sine_voltage(amplitude = 1.0, f = 1.0);
    let c = capacitor(2.0);
    let gnd = ground();
    connect(source.p, c.p);
    connect(c.n, source.n, gnd.p);
}

#[test]
fn a_source_across_a_capacitor_drives_its_current_by_its_derivative() {
    // No state is left: the capacitor's voltage is the source's.
    assert!(<SourceAcrossACapacitor as Model>::INFO.states.is_empty());
    // Every method runs a model without states: its error is zero.
    let w = 2.0 * std::f64::consts::PI;
    for method in
        Method::ALL.into_iter().filter(|m| m.refusal::<SourceAcrossACapacitor>().is_none())
    {
        let opts = Options::new().method(method).rtol(1e-10).atol(1e-12).step(1e-2);
        let sol = SourceAcrossACapacitor::default().simulate(0.0, 1.0, &opts).unwrap();
        for &t in &[0.1f64, 0.3, 0.55, 0.9] {
            let (v, i): (f64, f64) = (sol.at(t, "c.v").unwrap(), sol.at(t, "c.i").unwrap());
            assert!((v - (w * t).sin()).abs() < 1e-12, "{method:?} t = {t}: v = {v}");
            assert!((i - 2.0 * w * (w * t).cos()).abs() < 1e-12, "{method:?} t = {t}: i = {i}");
            let source_i: f64 = sol.at(t, "source.i").unwrap();
            assert!((source_i + i).abs() < 1e-12, "t = {t}: the source's current {source_i}");
        }
    }
}

/// `geared_coupling!(name, coupling(arguments))`: a torque of 1 N m on a
/// rotor (J = 1 kg m²) behind a 10:1 gear, coupled to a load (J = 3 kg m²)
/// by `coupling`, nothing between the gear and the coupling.
macro_rules! geared_coupling {
    ($name:ident, $coupling:ident($($arguments:tt)*)) => {
        #[dae_model]
        fn $name() {
            let drive = torque_source(1.0);
            let rotor = inertia(j = 1.0);
            let gear = ideal_gear(10.0);
            let coupling = $coupling($($arguments)*);
            let load = inertia(j = 3.0);
            connect(drive.flange, rotor.flange_a);
            connect(rotor.flange_b, gear.flange_a);
            connect(gear.flange_b, coupling.flange_a);
            connect(coupling.flange_b, load.flange_a);
        }
    };
}

geared_coupling!(geared_damper, damper(2.0));
geared_coupling!(geared_spring_damper, spring_damper(c = 100.0, d = 2.0));

/// The rotor's and the load's speeds behind a gear n with a damper d:
/// with `u = w_load − w_rotor/n`, `u' = −a u − b`, `a = d (1/J_load +
/// 1/(n² J_rotor))`, `b = τ/(n J_rotor)`, from rest.
fn geared_damper_exact(t: f64) -> (f64, f64) {
    let (n, d, j_rotor, j_load, tau) = (10.0, 2.0, 1.0, 3.0, 1.0);
    let a = d * (1.0 / j_load + 1.0 / (n * n * j_rotor));
    let b = tau / (n * j_rotor);
    let u = b / a * ((-a * t).exp() - 1.0);
    let w_load = -d / j_load * b / a * ((1.0 - (-a * t).exp()) / a - t);
    (n * (w_load - u), w_load)
}

#[test]
fn a_gear_then_a_damper_follows_the_exact_speeds() {
    // The damper's relative angle is the load's less the rotor's over the
    // ratio: the states are the two inertias'.
    assert_eq!(
        <GearedDamper as Model>::INFO.states,
        ["rotor.phi", "rotor.w", "load.phi", "load.w"]
    );
    for method in [Method::Radau5, Method::Rodas5P, Method::Dop853] {
        let opts = Options::new().method(method).rtol(1e-10).atol(1e-12);
        let sol = GearedDamper::default().simulate(0.0, 5.0, &opts).unwrap();
        for &t in &[0.5f64, 2.0, 5.0] {
            let (w_rotor, w_load) = geared_damper_exact(t);
            let (r, l): (f64, f64) = (sol.at(t, "rotor.w").unwrap(), sol.at(t, "load.w").unwrap());
            assert!((r - w_rotor).abs() < 1e-7, "{method:?} t = {t}: rotor {r} vs {w_rotor}");
            assert!((l - w_load).abs() < 1e-7, "{method:?} t = {t}: load {l} vs {w_load}");
            // The damper reads the speeds through the gear.
            let tau: f64 = sol.at(t, "coupling.tau").unwrap();
            assert!((tau - 2.0 * (w_load - w_rotor / 10.0)).abs() < 1e-7, "t = {t}: {tau}");
        }
    }
}

/// The geared spring-damper written flat: the rotor's angle and speed,
/// the load's angle and speed, the coupling's torque from their
/// difference through the gear.
#[dae_model]
fn geared_spring_damper_flat() {
    let n = param(10.0);
    let phi = state(0.0);
    let w = state(0.0);
    let phi_load = state(0.0);
    let w_load = state(0.0);
    let tau = 100.0 * (phi_load - phi / n) + 2.0 * (w_load - w / n);
    der(phi) == w;
    der(w) == 1.0 + tau / n;
    der(phi_load) == w_load;
    3.0 * der(w_load) == -tau;
}

#[test]
fn a_gear_then_a_spring_damper_follows_the_flat_model() {
    assert_eq!(
        <GearedSpringDamper as Model>::INFO.states,
        ["rotor.phi", "rotor.w", "load.phi", "load.w"]
    );
    let opts = Options::new().method(Method::Radau5).rtol(1e-11).atol(1e-13);
    let parts = GearedSpringDamper::default().simulate(0.0, 3.0, &opts).unwrap();
    let flat = GearedSpringDamperFlat::default().simulate(0.0, 3.0, &opts).unwrap();
    for &t in &[0.3f64, 1.0, 2.2, 3.0] {
        for (name, flat_name) in [("rotor.w", "w"), ("load.w", "w_load"), ("load.phi", "phi_load")]
        {
            let (a, b): (f64, f64) = (parts.at(t, name).unwrap(), flat.at(t, flat_name).unwrap());
            assert!((a - b).abs() < 1e-8 * (1.0 + b.abs()), "t = {t}: {name} {a} vs {b}");
        }
        let phi_rel: f64 = parts.at(t, "coupling.phi_rel").unwrap();
        let (phi, phi_load): (f64, f64) =
            (flat.at(t, "phi").unwrap(), flat.at(t, "phi_load").unwrap());
        assert!((phi_rel - (phi_load - phi / 10.0)).abs() < 1e-8, "t = {t}: {phi_rel}");
    }
}

/// MSL's `Modelica.Electrical.Analog.Examples.CauerLowPassAnalog`, as a
/// Modelica user connects it: a fifth-order low-pass filter of five
/// library capacitors and two inductors behind R1 = 1 Ω, loaded by
/// R2 = 1 Ω, a 1 V step at t = 1. C1–C2–C3 and C3–C4–C5 are loops of
/// capacitors.
#[dae_model]
fn cauer_low_pass() {
    let l1 = param(1.304);
    let l2 = param(0.8586);
    let v = step_voltage(height = 1.0, start_time = 1.0);
    let g = ground();
    let r1 = resistor(1.0);
    let r2 = resistor(1.0);
    let c1 = capacitor(1.072);
    let c2 = capacitor(1.0 / (1.704992 * 1.704992 * l1));
    let c3 = capacitor(1.682);
    let c4 = capacitor(1.0 / (1.179945 * 1.179945 * l2));
    let c5 = capacitor(0.7262);
    let ind1 = inductor(l1);
    let ind2 = inductor(l2);
    connect(v.p, r1.p);
    connect(r1.n, c1.p, ind1.p, c2.p);
    connect(ind1.n, c2.n, c3.p, c4.p, ind2.p);
    connect(ind2.n, c4.n, c5.p, r2.p);
    connect(v.n, g.p, c1.n, c3.n, c5.n, r2.n);
    // MSL's `C1(v(start = 0, fixed = true))` and the like.
    init(c1.v, 0.0);
    init(c3.v, 0.0);
    init(c5.v, 0.0);
    init(ind1.i, 0.0);
    init(ind2.i, 0.0);
}

/// The Cauer filter by nodal analysis, written by hand: the node
/// voltages and the inductors' currents, the capacitances between the
/// nodes a mass matrix.
#[dae_model]
fn cauer_low_pass_nodal() {
    let t = time();
    let l1 = 1.304;
    let l2 = 0.8586;
    let c1 = 1.072;
    let c3 = 1.682;
    let c5 = 0.7262;
    let c2 = 1.0 / (1.704992 * 1.704992 * l1);
    let c4 = 1.0 / (1.179945 * 1.179945 * l2);
    let v1 = state(0.0);
    let v2 = state(0.0);
    let v3 = state(0.0);
    let i1 = state(0.0);
    let i2 = state(0.0);
    let source = heaviside(t - 1.0);
    c1 * der(v1) + c2 * (der(v1) - der(v2)) + i1 == source - v1;
    c2 * (der(v2) - der(v1)) + c3 * der(v2) + c4 * (der(v2) - der(v3)) - i1 + i2 == 0.0;
    c4 * (der(v3) - der(v2)) + c5 * der(v3) - i2 + v3 == 0.0;
    l1 * der(i1) == v1 - v2;
    l2 * der(i2) == v2 - v3;
}

#[test]
fn the_cauer_filter_of_library_capacitors_keeps_five_states_and_follows_nodal_analysis() {
    // Seven storage elements less two loops of capacitors: five states,
    // those whose starts are set, as Dymola keeps.
    let states = <CauerLowPass as Model>::INFO.states;
    assert_eq!(states, ["c1.v", "c3.v", "c5.v", "ind1.i", "ind2.i"]);
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let parts = CauerLowPass::default().simulate(0.0, 60.0, &opts).unwrap();
    let nodal = CauerLowPassNodal::default().simulate(0.0, 60.0, &opts).unwrap();
    for &t in &[0.5f64, 1.5, 3.0, 7.0, 15.0, 30.0, 60.0] {
        for (name, node) in [("c1.v", "v1"), ("c3.v", "v2"), ("r2.v", "v3"), ("ind1.i", "i1")] {
            let (a, b): (f64, f64) = (parts.at(t, name).unwrap(), nodal.at(t, node).unwrap());
            assert!((a - b).abs() < 1e-7, "t = {t}: {name} {a} vs {b}");
        }
        // The loop's capacitor reads the difference of its neighbours.
        let (c2, c1, c3): (f64, f64, f64) = (
            parts.at(t, "c2.v").unwrap(),
            parts.at(t, "c1.v").unwrap(),
            parts.at(t, "c3.v").unwrap(),
        );
        assert!((c2 - (c1 - c3)).abs() < 1e-12, "t = {t}");
    }
}

/// An accelerometer as a user writes one: the flange's angle and its
/// second derivative.
#[component]
fn accelerometer() {
    let flange = flange();
    let a = real_output();
    let phi = state(0.0).avoid();
    phi == flange.phi;
    flange.tau == 0.0;
    a == der(der(phi));
}

/// A rotor spinning at 10 rad/s, braked by a damper to the housing, its
/// acceleration measured.
#[dae_model]
fn measured_rotor() {
    let rotor = inertia(j = 1.0, w0 = 10.0);
    let brake = damper(0.5);
    let housing = fixed();
    let sensor = accelerometer();
    connect(rotor.flange_a, sensor.flange);
    connect(rotor.flange_b, brake.flange_a);
    connect(brake.flange_b, housing.flange);
}

#[test]
fn an_accelerometer_keeps_the_rotors_start() {
    // The sensor's `der(der(phi))` makes the rotor's angle a state of
    // order two: its speed is the slot `der(rotor.phi)`, started at w0.
    assert_eq!(<MeasuredRotor as Model>::INFO.states, ["rotor.phi", "der(rotor.phi)"]);
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = MeasuredRotor::default().simulate(0.0, 4.0, &opts).unwrap();
    for &t in &[0.0f64, 1.0, 4.0] {
        // w = 10 e^(−t/2), a = −5 e^(−t/2).
        let (w, a): (f64, f64) = (sol.at(t, "rotor.w").unwrap(), sol.at(t, "sensor.a").unwrap());
        assert!((w - 10.0 * (-t / 2.0).exp()).abs() < 1e-8 * 10.0, "t = {t}: w = {w}");
        assert!((a + 5.0 * (-t / 2.0).exp()).abs() < 1e-8 * 5.0, "t = {t}: a = {a}");
    }
}

/// A compliant coupling as a user writes one, differentiating its
/// algebraic relative speed: `w_rel = der(phi_rel)`, `a_rel = der(w_rel)`.
#[component]
fn coupling_with_rates() {
    let c = param(100.0);
    let d = param(2.0);
    let flange_a = flange();
    let flange_b = flange();
    let phi_rel = state(0.0).avoid();
    let w_rel = algebraic(0.0);
    let a_rel = algebraic(0.0);
    let tau = algebraic(0.0);
    phi_rel == flange_b.phi - flange_a.phi;
    w_rel == der(phi_rel);
    a_rel == der(w_rel);
    flange_b.tau == tau;
    flange_a.tau == -tau;
    tau == c * phi_rel + d * w_rel;
}

geared_coupling!(geared_coupling_with_rates, coupling_with_rates());

#[test]
fn the_derivative_of_an_algebraic_variable_is_the_derivative_of_what_ties_it() {
    // `w_rel`, differentiated, is tied to the speeds through the gear and
    // goes with `phi_rel`: the states are the inertias'.
    assert_eq!(
        <GearedCouplingWithRates as Model>::INFO.states,
        ["rotor.phi", "rotor.w", "load.phi", "load.w"]
    );
    let opts = Options::new().method(Method::Radau5).rtol(1e-11).atol(1e-13);
    let parts = GearedCouplingWithRates::default().simulate(0.0, 3.0, &opts).unwrap();
    let flat = GearedSpringDamperFlat::default().simulate(0.0, 3.0, &opts).unwrap();
    for &t in &[0.3f64, 1.0, 2.2, 3.0] {
        for (name, flat_name) in [("rotor.w", "w"), ("load.w", "w_load")] {
            let (a, b): (f64, f64) = (parts.at(t, name).unwrap(), flat.at(t, flat_name).unwrap());
            assert!((a - b).abs() < 1e-8 * (1.0 + b.abs()), "t = {t}: {name} {a} vs {b}");
        }
        // a_rel is the load's acceleration less the rotor's over the ratio,
        // each from its inertia's balance in the flat model.
        let (phi, w, phi_load, w_load): (f64, f64, f64, f64) = (
            flat.at(t, "phi").unwrap(),
            flat.at(t, "w").unwrap(),
            flat.at(t, "phi_load").unwrap(),
            flat.at(t, "w_load").unwrap(),
        );
        let tau = 100.0 * (phi_load - phi / 10.0) + 2.0 * (w_load - w / 10.0);
        let (rotor_acceleration, load_acceleration) = (1.0 + tau / 10.0, -tau / 3.0);
        let a_rel: f64 = parts.at(t, "coupling.a_rel").unwrap();
        let expected = load_acceleration - rotor_acceleration / 10.0;
        assert!(
            (a_rel - expected).abs() < 1e-7 * (1.0 + expected.abs()),
            "t = {t}: {a_rel} vs {expected}"
        );
    }
}

/// A nonlinear capacitor as a user writes one, its charge the state:
/// `v = q/c0 + k q³`.
#[component]
fn varactor() {
    let c0 = param(1.0);
    let k = param(0.1);
    let p = pin();
    let n = pin();
    p.i + n.i == 0.0;
    let q = state(0.0);
    der(q) == p.i;
    let v = algebraic(0.0);
    v == p.v - n.v;
    v == q / c0 + k * q * q * q;
}

/// 1 V through 1 Ω into two varactors in parallel (c0 = 1 F and 2 F):
/// their voltages are one, a nonlinear relation between their charges.
#[dae_model]
fn parallel_varactors() {
    let source = constant_voltage(1.0);
    let r = resistor(1.0);
    connect(source.p, r.p);
    let a = varactor(c0 = 1.0);
    let b = varactor(c0 = 2.0);
    connect(r.n, a.p, b.p);
    let gnd = ground();
    let charge = state(0.0);
    connect(a.n, b.n, source.n, gnd.p);
    der(charge) == r.i;
}

#[test]
fn a_nonlinear_tie_is_a_constraint_the_run_holds() {
    // Both charges stay states, tied by a.v = b.v, which index reduction
    // differentiates and the run projects onto.
    assert_eq!(<ParallelVaractors as Model>::INFO.states, ["a.q", "b.q", "charge"]);
    let opts = Options::new().method(Method::Radau5).rtol(1e-10).atol(1e-12);
    let sol = ParallelVaractors::default().simulate(0.0, 40.0, &opts).unwrap();
    for &t in &[0.5f64, 2.0, 10.0, 40.0] {
        let (va, vb): (f64, f64) = (sol.at(t, "a.v").unwrap(), sol.at(t, "b.v").unwrap());
        assert!((va - vb).abs() < 1e-9, "t = {t}: {va} vs {vb}");
        // The charge the resistor delivered is the two capacitors'.
        let (qa, qb, q): (f64, f64, f64) =
            (sol.at(t, "a.q").unwrap(), sol.at(t, "b.q").unwrap(), sol.at(t, "charge").unwrap());
        assert!((qa + qb - q).abs() < 1e-8, "t = {t}: {qa} + {qb} vs {q}");
    }
    // At rest both sit at 1 V: q/c0 + 0.1 q³ = 1, by Newton's method.
    let at_one_volt = |c0: f64| {
        let mut q = c0;
        for _ in 0..50 {
            q -= (q / c0 + 0.1 * q * q * q - 1.0) / (1.0 / c0 + 0.3 * q * q);
        }
        q
    };
    let (qa, qb): (f64, f64) = (sol.last("a.q").unwrap(), sol.last("b.q").unwrap());
    assert!((qa - at_one_volt(1.0)).abs() < 1e-7, "{qa}");
    assert!((qb - at_one_volt(2.0)).abs() < 1e-7, "{qb}");
}

/// A massless rod of length `l` from the origin to the point whose
/// coordinates are the positions of the flanges `x` and `y`, as a user
/// writes one: it pulls along itself, `f = λ (x, y)`.
#[component]
fn pendulum_rod() {
    let l = param(1.0);
    let x = translational_flange();
    let y = translational_flange();
    let lambda = algebraic(0.0);
    x.s * x.s + y.s * y.s == l * l;
    x.f == lambda * x.s;
    y.f == lambda * y.s;
}

/// The planar pendulum from parts: a 1 kg mass free to move in x and
/// one in y (the same bob's coordinates), its weight on y, the rod
/// joining them to the origin. Released at rest from (1, 0).
#[dae_model]
fn pendulum_of_parts() {
    let horizontal = mass(m = 1.0, s0 = 1.0);
    let vertical = mass(m = 1.0, s0 = 0.0);
    let weight = force_source(-9.81);
    let tie = pendulum_rod(l = 1.0);
    connect(horizontal.flange_a, tie.x);
    connect(vertical.flange_a, tie.y, weight.flange);
}

/// K(k) = π / (2 AGM(1, √(1 − k²))), the complete elliptic integral.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..30 {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

#[test]
fn a_pendulum_of_parts_keeps_both_coordinates_where_no_one_would_do() {
    // The rod ties the positions by x² + y² = l², whose gradient (2x, 2y)
    // loses its x part at x = 0 and its y part at y = 0: neither position
    // can be solved for along the whole swing (where a Modelica tool
    // selects states dynamically). Both stay states, the rod a
    // constraint the run projects onto.
    let info = <PendulumOfParts as Model>::INFO;
    assert_eq!(info.states, ["horizontal.s", "horizontal.v", "vertical.s", "vertical.v"]);
    let described = PendulumOfParts::default().describe();
    let why = "Kept: the connections tie it to `vertical.s` by";
    assert!(
        described.lines().any(|l| l.contains("horizontal.s") && l.contains(why)),
        "{described}"
    );
    // Released horizontally (θ0 = π/2 from the lowest point), the bob is
    // back at (1, 0) after the exact period T = 4 √(l/g) K(sin(θ0/2)), at
    // (−1, 0) after T/2, passing under the pivot at T/4.
    let period = 4.0 * (1.0f64 / 9.81).sqrt() * elliptic_k((std::f64::consts::FRAC_PI_4).sin());
    for method in [Method::Radau5, Method::Rodas5P, Method::Dop853] {
        let opts = Options::new().method(method).rtol(1e-10).atol(1e-10);
        let sol = PendulumOfParts::default().simulate(0.0, period, &opts).unwrap();
        for (t, x, y) in [(0.25 * period, 0.0, -1.0), (0.5 * period, -1.0, 0.0), (period, 1.0, 0.0)]
        {
            let (xs, ys): (f64, f64) =
                (sol.at(t, "horizontal.s").unwrap(), sol.at(t, "vertical.s").unwrap());
            assert!(
                (xs - x).abs() < 1e-6 && (ys - y).abs() < 1e-6,
                "{method:?} t = {t}: ({xs}, {ys}) vs ({x}, {y})"
            );
        }
        // The rod holds at every step, and the energy m g y + ½ m v² stays 0.
        assert!(sol.max_constraint_residual() <= 1e-9, "{method:?}");
        for &t in sol.times() {
            let (vx, vy, y): (f64, f64, f64) = (
                sol.at(t, "horizontal.v").unwrap(),
                sol.at(t, "vertical.v").unwrap(),
                sol.at(t, "vertical.s").unwrap(),
            );
            let energy = 0.5 * (vx * vx + vy * vy) + 9.81 * y;
            assert!(energy.abs() < 1e-6, "{method:?} t = {t}: energy {energy:e}");
        }
    }
}
